// Fuzzes the Fresnel channels written as text (parse_fresnel, include/specula/catalogue/
// fresnel_spec.h): "schlick:f0=0.04,p=5", "f82:f0=0.9,tint=0.8", "dielectric:eta=1.5",
// "conductor:eta=0.2,kappa=3.1". Input: the spec. Properties, each a finding when broken:
//   - parse_fresnel() returns or throws InvalidArgument, nothing else;
//   - what it returns is inside its kind's domain (analysis::fresnel_domain_error is empty);
//   - F(c) is finite and in [0, 1] at cosines across [0, 1], and F_avg is too;
//   - to_spec() writes it back: parse_fresnel(to_spec(f)) has the same F at those cosines.
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <string>

#include "fuzz_support.h"
#include "specula/analysis/fresnel.h"
#include "specula/catalogue/fresnel_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace specula;
  const std::string_view spec = fuzz::text_of(data, size);
  fresnel::Channel f;
  if (!fuzz::accepted("parse_fresnel", [&] { f = parse_fresnel(spec); })) return 0;
  const std::string quoted = fmt::format("'{}'", spec);  // fmt: GCC 12 warns (-Wrestrict) on "'" + string
  fuzz::require(analysis::fresnel_domain_error(f).empty(), "parse_fresnel accepted a channel outside its domain: " + quoted);
  fresnel::Channel back;
  if (!fuzz::accepted("parse_fresnel(to_spec)", [&] { back = parse_fresnel(to_spec(f)); }))
    fuzz::finding("to_spec wrote '" + to_spec(f) + "', which parse_fresnel refuses, for " + quoted);
  for (double c : {0.0, 1e-9, 0.05, 1.0 / 7, 0.5, 6.0 / 7, 0.999, 1.0}) {
    const double value = f(c);
    fuzz::require(std::isfinite(value) && value >= 0 && value <= 1,
                  "F(" + std::to_string(c) + ") = " + std::to_string(value) + " outside [0, 1] for " + quoted);
    fuzz::require(back(c) == value, "to_spec(" + quoted + ") = '" + to_spec(f) + "' reads back another F");
  }
  double average = -1;
  if (fuzz::accepted("fresnel_average", [&] { average = analysis::fresnel_average(f).value; }))
    fuzz::require(std::isfinite(average) && average >= -1e-12 && average <= 1 + 1e-12,
                  "F_avg = " + std::to_string(average) + " outside [0, 1] for " + quoted);
  else
    fuzz::finding("fresnel_average refused the channel parse_fresnel accepted: " + quoted);
  return 0;
}
