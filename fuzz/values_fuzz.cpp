// Fuzzes the list and range parser every command and the server take (io::parse_values,
// include/specula/io/values.h): "1:7", "1:1000@50:log", "0:1@11", "paper50", "0.5,1:4".
// Input: the spec. Properties, each a finding when broken:
//   - parse_values() returns or throws InvalidArgument, nothing else;
//   - what it returns is non-empty, within the cap on values, and every value is finite;
//   - a cap below the count is refused (InvalidArgument), never expanded past;
//   - parse_number() of the whole input returns a finite number or throws InvalidArgument;
//   - split() cuts at every separator and its parts join back to the input.
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "specula/io/values.h"

namespace {

using namespace specula;

// Small enough that the largest accepted spec runs in well under a millisecond.
constexpr std::size_t kMaxValues = 4096;

void check_values(std::string_view spec, const std::vector<double>& values, std::size_t cap) {
  const std::string quoted = fmt::format("'{}'", spec);
  fuzz::require(!values.empty(), "parse_values returned no values for " + quoted);
  fuzz::require(values.size() <= cap, "parse_values returned " + std::to_string(values.size()) +
                                          " values, over the cap of " + std::to_string(cap) + ", for " + quoted);
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      fuzz::finding("parse_values returned a non-finite value (" + std::to_string(values[i]) + ", value " +
                    std::to_string(i) + ") for " + quoted);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view spec = fuzz::text_of(data, size);
  std::vector<double> values;
  if (fuzz::accepted("parse_values", [&] { values = io::parse_values(spec, kMaxValues); })) {
    check_values(spec, values, kMaxValues);
    // One value fewer than it expands to must be refused.
    const std::size_t below = values.size() - 1;
    if (below > 0 && fuzz::accepted("parse_values (cap below the count)", [&] { (void)io::parse_values(spec, below); }))
      fuzz::finding("parse_values accepted '" + std::string(spec) + "' under a cap of " + std::to_string(below) +
                    " though it expands to " + std::to_string(values.size()) + " values");
  }
  double number = 0;
  if (fuzz::accepted("parse_number", [&] { number = io::parse_number(spec, "fuzz"); }))
    fuzz::require(std::isfinite(number), "parse_number returned a non-finite number for '" + std::string(spec) + "'");

  const auto parts = io::split(spec, ',');
  std::string joined;
  for (std::size_t i = 0; i < parts.size(); ++i) joined += fmt::format("{}{}", i ? "," : "", parts[i]);
  fuzz::require(joined == spec, "split(',') parts do not join back to the input");
  return 0;
}
