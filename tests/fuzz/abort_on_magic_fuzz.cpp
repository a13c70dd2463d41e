// The negative control of the corpus replay (tests/fuzz/CMakeLists.txt): a harness that reports
// a finding, as the real ones do (fuzz/fuzz_support.h), on one magic input and accepts the rest.
#include <cstdint>

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  specula::fuzz::require(!specula::fuzz::text_of(data, size).starts_with("specula-fuzz-magic"),
                         "the magic input of the negative control");
  return 0;
}
