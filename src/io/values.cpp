#include "specula/io/values.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <string>

#include "specula/exceptions.h"

namespace specula::io {
namespace {

[[noreturn]] void malformed(std::string_view item, std::string_view why) {
  throw InvalidArgument(fmt::format("malformed range '{}': {}", item, why));
}

// `count` more values after the `already` there are must stay within `max_values`.
void check_count(std::string_view item, double count, std::size_t already, std::size_t max_values) {
  if (!(count <= static_cast<double>(max_values - already)))
    malformed(item, fmt::format("more than {} values", max_values));
}

// The steps from a to b, (b − a) / step, also where b − a overflows (a and b of opposite signs
// near the ends of the range of a double: -1e308:1e308:1e308 is 3 values).
double steps_between(double a, double b, double step) {
  const double span = b - a;
  return std::isfinite(span) ? span / step : b / step - a / step;
}

// The value a fraction f of the way from a to b: a + (b − a)·f, or a·(1 − f) + b·f where b − a
// overflows (-1e308:1e308@3 would otherwise start with inf·0 = nan).
double linear_at(double a, double b, double f) {
  const double span = b - a;
  return std::isfinite(span) ? a + span * f : a * (1 - f) + b * f;
}

// The same on a log scale (a, b > 0): a·(b/a)^f, or a^(1−f)·b^f where b/a overflows or underflows
// (1e-300:1e300@3:log would otherwise give inf in the middle), kept within [a, b].
double log_at(double a, double b, double f) {
  const double ratio = b / a;
  if (std::isfinite(ratio) && ratio > 0) return a * std::pow(ratio, f);
  return std::clamp(std::pow(a, 1 - f) * std::pow(b, f), std::min(a, b), std::max(a, b));
}

void append_stepped(std::string_view item, double a, double b, double step, std::size_t max_values,
                    std::vector<double>& out) {
  if (!(step > 0)) malformed(item, "the step must be > 0");
  if (b < a) malformed(item, "the end is below the start");
  const double count = std::floor(steps_between(a, b, step) * (1 + 1e-12)) + 1;
  check_count(item, count, out.size(), max_values);
  for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i)  // ≤ b; b itself despite round-off
    out.push_back(std::abs(b - (a + step * i)) <= 1e-9 * step ? b : std::min(b, a + step * i));
}

// The same evenly spaced in x^(1/k) (a, b ≥ 0, k > 0).
double power_at(double a, double b, double k, double f) {
  return std::clamp(std::pow(linear_at(std::pow(a, 1 / k), std::pow(b, 1 / k), f), k), std::min(a, b), std::max(a, b));
}

// K of a spacing "powK", or 0 when `spacing` is not one.
double power_of(std::string_view spacing) {
  if (!spacing.starts_with("pow")) return 0;
  double k = 0;
  const auto [ptr, ec] = std::from_chars(spacing.data() + 3, spacing.data() + spacing.size(), k);
  return ec == std::errc() && ptr == spacing.data() + spacing.size() && std::isfinite(k) && k > 0 && spacing.size() > 3 ? k : 0;
}

void append_counted(std::string_view item, double a, double b, std::string_view count_text,
                    std::size_t max_values, std::vector<double>& out) {
  const auto at = split(count_text, ':');
  const bool log = at.size() == 2 && at[1] == "log";
  const double power = at.size() == 2 ? power_of(at[1]) : 1;
  if (at.size() > 2 || (at.size() == 2 && !log && power == 0))
    malformed(item, "expected a:b@count, a:b@count:log or a:b@count:powK (K > 0)");
  const double count = parse_number(at[0], fmt::format("the count of '{}'", item));
  if (count < 1 || count != std::floor(count)) malformed(item, "the count must be a whole number ≥ 1");
  check_count(item, count, out.size(), max_values);
  if (log && !(a > 0 && b > 0)) malformed(item, "log spacing needs a > 0 and b > 0");
  if (power != 1 && !(a >= 0 && b >= 0)) malformed(item, "pow spacing needs a ≥ 0 and b ≥ 0");
  const auto n = static_cast<std::size_t>(count);
  for (std::size_t i = 0; i < n; ++i) {
    const double f = n == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(n - 1);
    if (i + 1 == n && n > 1) out.push_back(b);  // the end exactly, free of round-off
    else if (log) out.push_back(log_at(a, b, f));
    else out.push_back(power != 1 ? power_at(a, b, power, f) : linear_at(a, b, f));
  }
}

void append_item(std::string_view item, std::size_t max_values, std::vector<double>& out) {
  if (item == "paper50") {
    const auto p = paper50();
    out.insert(out.end(), p.begin(), p.end());
    return;
  }
  const auto at = item.find('@');
  const auto parts = split(item.substr(0, at), ':');
  if (parts.size() == 1 && at == std::string_view::npos) {
    out.push_back(parse_number(item, "value"));
    return;
  }
  if (parts.size() < 2 || parts.size() > 3) malformed(item, "expected a:b, a:b:step or a:b@count");
  const double a = parse_number(parts[0], fmt::format("the start of '{}'", item));
  const double b = parse_number(parts[1], fmt::format("the end of '{}'", item));
  if (at != std::string_view::npos) {
    if (parts.size() != 2) malformed(item, "a step and a count cannot both be given");
    append_counted(item, a, b, item.substr(at + 1), max_values, out);
  } else if (parts.size() == 3) {
    append_stepped(item, a, b, parse_number(parts[2], fmt::format("the step of '{}'", item)), max_values,
                   out);
  } else {
    if (a != std::floor(a) || b != std::floor(b)) malformed(item, "a:b takes integers (use a:b:step)");
    append_stepped(item, a, b, 1, max_values, out);
  }
}

}  // namespace

double parse_number(std::string_view text, std::string_view what) {
  double value = 0;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (text.size() > 1 && text[0] == '+' && text[1] != '-') ++first;  // "+1", not "+-1"
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (text.empty() || ec != std::errc() || ptr != last)
    throw InvalidArgument(fmt::format("{}: '{}' is not a number", what, text));
  if (!std::isfinite(value)) throw InvalidArgument(fmt::format("{}: '{}' is not finite", what, text));
  return value;
}

std::vector<double> parse_values(std::string_view spec, std::size_t max_values) {
  if (spec.empty()) throw InvalidArgument("empty list of values");
  std::vector<double> values;
  for (const auto item : split(spec, ',')) {
    if (item.empty()) malformed(spec, "empty item between commas");
    append_item(item, max_values, values);
    if (values.size() > max_values) malformed(spec, fmt::format("more than {} values", max_values));
  }
  return values;
}

double spacing_power(std::string_view spec) noexcept {
  if (spec.find(',') != std::string_view::npos) return 1;
  const auto at = spec.find('@');
  if (at == std::string_view::npos) return 1;
  const auto colon = spec.find(':', at);
  if (colon == std::string_view::npos) return 1;
  const double k = power_of(spec.substr(colon + 1));
  return k > 0 ? k : 1;
}

std::vector<double> paper50() {
  std::vector<double> n{1};
  for (int i = 1; i < 50; ++i)
    n.push_back(std::max(n.back() + 1, std::round(std::pow(1000.0, i / 49.0))));
  return n;
}

std::vector<std::string_view> split(std::string_view text, char separator) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= text.size(); ++i) {
    if (i == text.size() || text[i] == separator) {
      parts.push_back(text.substr(start, i - start));
      start = i + 1;
    }
  }
  return parts;
}

}  // namespace specula::io
