#pragma once
// Lists and ranges of numbers as every command takes them:
//   1,2,5          a list               a:b            the integers a, a+1, …, b
//   a:b:step       a, a+step, … ≤ b     a:b@count      count values, linearly spaced, ends included
//   a:b@count:log  count values, log-spaced (a, b > 0)
//   a:b@count:powK count values evenly spaced in x^(1/K) (K > 0, a, b ≥ 0), ends included: K > 1
//                  crowds them toward a — :pow2 is uniform in √x (roughness), :pow3 in x^(1/3)
//                  (μ toward grazing), :pow4 in x^(1/4) (F0, as Cycles tabulates it)
//   paper50        the 50 integers n₀ = 1, nᵢ = max(nᵢ₋₁ + 1, round(1000^(i/49))) (1…7 like the
//                  paper's Fig. 5 file, up to 1000)
// Items combine with commas: "0.5,1:4,100". Every value is finite.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace specula::io {

/// The most values one spec may expand to.
inline constexpr std::size_t kMaxValues = 10'000'000;

/// Throws InvalidArgument naming the malformed item, or when the spec expands to more than
/// `max_values` values (checked before any range is expanded).
std::vector<double> parse_values(std::string_view spec, std::size_t max_values = kMaxValues);

/// One finite number, all of `text` (no trailing characters); throws InvalidArgument naming `what`.
double parse_number(std::string_view text, std::string_view what);

std::vector<double> paper50();

/// K of a spec that is one range "a:b@count:powK"; 1 for any other spec (a list, a linear or log
/// range): the power an evenly spaced table axis is spaced in.
double spacing_power(std::string_view spec) noexcept;

/// `text` cut at every `separator` ("a,,b" → "a", "", "b"; "" → one empty part).
std::vector<std::string_view> split(std::string_view text, char separator);

}  // namespace specula::io
