// specula_lobe_bench: the benchmark that settles the lobes' speed claims (what `make bench` runs
// first, and `specula bench` from the shipped binary): every lobe through the scalar lobe (libm)
// and the SIMD exact and fast tiers, in cache and streaming, on one core and all, against the
// machine's compute and memory limits. The measurements are the library's (cost/lobe_cost.h);
// docs/simd.md explains the table. Usage: specula_lobe_bench [--quick] [--json]
#include <cstdio>
#include <string_view>

#include "specula/cost/lobe_cost.h"

int main(int argc, char** argv) {
  bool quick = false, json = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--quick") quick = true;
    else if (arg == "--json") json = true;
    else {
      std::fprintf(stderr, "usage: specula_lobe_bench [--quick] [--json]\n");
      return 2;
    }
  }
  using specula::cost::Settings;
  const auto result = specula::cost::run(quick ? Settings::quick() : Settings::full(), [](std::string_view phase) {
    std::fprintf(stderr, "bench: %.*s\n", int(phase.size()), phase.data());
  });
  const std::string text = json ? specula::cost::to_json(result) : specula::cost::to_table(result);
  std::fwrite(text.data(), 1, text.size(), stdout);
  return 0;
}
