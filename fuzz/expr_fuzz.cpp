// Fuzzes the expression parser and its printers (include/specula/expr/expr.h).
// Input: infix text. Properties, each a finding when broken:
//   - parse() accepts it or throws InvalidArgument (ParseError), nothing else;
//   - to_infix() of what it accepts parses again, with the same variables in the same order, and
//     evaluates bit-identically (or NaN where the original is NaN) at a few sample points;
//   - to_infix() is canonical: printing the re-parsed expression gives the same text;
//   - evaluate_batch() agrees bit for bit with evaluate() (row by row, and on the SIMD path);
//   - the other printers (C++, GLSL, LaTeX, Python: not meant to be read back) do not fail;
//   - parse() with a fixed variable list accepts or rejects with InvalidArgument;
//   - simplify() of what parse() accepts ends, throws nothing, keeps the variables, prints, and
//     at most doubles the size; on the sample points it agrees with the original wherever
//     agrees_on() says the two agree (agrees_on is what the fit trusts to keep a rewrite).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "specula/expr/expr.h"
#include "specula/expr/simplify.h"

namespace {

using namespace specula;

bool same_value(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) || std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// Row r of variable i: ordinary values, zero, signed zero, negatives, large and tiny numbers,
// and the awkward ones (1 for pow/log, 0.5 for acos), different for each variable.
double sample(std::size_t row, std::size_t variable) {
  static constexpr double kValues[] = {0.5,  1.75, -2.25, 0.0,    -0.0, 1.0,   3.0,  -1.0,
                                       1e10, 1e-9, 0.25,  -0.125, 7.5,  1e300, 2.0,  -0.75};
  constexpr std::size_t kCount = sizeof(kValues) / sizeof(kValues[0]);
  return kValues[(row * 7 + variable * 3) % kCount];
}

constexpr std::size_t kPoints = 4;    // sample points for the round trip
constexpr std::size_t kSimdRows = 70;  // ≥ the 64 rows from which evaluate_batch goes SIMD

std::vector<std::vector<double>> columns(std::size_t variables, std::size_t rows) {
  std::vector<std::vector<double>> out(variables, std::vector<double>(rows));
  for (std::size_t v = 0; v < variables; ++v)
    for (std::size_t r = 0; r < rows; ++r) out[v][r] = sample(r, v);
  return out;
}

std::vector<double> row(const std::vector<std::vector<double>>& columns, std::size_t r) {
  std::vector<double> values;
  for (const auto& c : columns) values.push_back(c[r]);
  return values;
}

std::string show(double x) {
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

void check_round_trip(const expr::Expression& e) {
  const std::string infix = expr::to_infix(e);
  std::optional<expr::Expression> again;
  if (!fuzz::accepted("parse(to_infix(e))", [&] { again = expr::parse(infix); }))
    fuzz::finding("to_infix printed text that does not parse: " + infix);
  fuzz::require(again->variables() == e.variables(),
                "parse(to_infix(e)) has other variables than e: " + infix);
  const std::string twice = expr::to_infix(*again);
  fuzz::require(twice == infix, "to_infix is not canonical: '" + infix + "' reads back as '" + twice + "'");

  const auto values = columns(e.variables().size(), kPoints);
  for (std::size_t r = 0; r < kPoints; ++r) {
    const auto point = row(values, r);
    const double a = expr::evaluate(e, point);
    const double b = expr::evaluate(*again, point);
    if (!same_value(a, b))
      fuzz::finding("parse(to_infix(e)) evaluates differently at point " + std::to_string(r) + ": " +
                    show(a) + " against " + show(b) + " for " + infix);
  }
}

void check_batch(const expr::Expression& e, std::size_t rows) {
  const auto values = columns(e.variables().size(), rows);
  std::vector<std::span<const double>> spans(values.begin(), values.end());
  std::vector<double> out(rows);
  expr::evaluate_batch(e, spans, out);
  for (std::size_t r = 0; r < rows; ++r) {
    const double one = expr::evaluate(e, row(values, r));
    if (!same_value(one, out[r]))
      fuzz::finding("evaluate_batch (" + std::to_string(rows) + " rows) differs from evaluate in row " +
                    std::to_string(r) + ": " + show(out[r]) + " against " + show(one) + " for " +
                    expr::to_infix(e));
  }
}

void check_simplify(const expr::Expression& e) {
  const expr::Expression s = expr::simplify(e);
  fuzz::require(s.variables() == e.variables(), "simplify changed the variables of " + expr::to_infix(e));
  fuzz::require(s.size() <= 2 * e.size() + 2, "simplify more than doubled " + expr::to_infix(e));
  (void)expr::to_infix(s);
  const auto values = columns(e.variables().size(), kPoints);
  const std::vector<std::span<const double>> spans(values.begin(), values.end());
  if (!expr::agrees_on(e, s, spans)) return;
  for (std::size_t r = 0; r < kPoints; ++r) {
    const auto point = row(values, r);
    const double a = expr::evaluate(e, point), b = expr::evaluate(s, point);
    if (std::isfinite(a) && std::isfinite(b))
      fuzz::require(std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)),
                    "agrees_on accepted a simplification that differs at point " + std::to_string(r) + ": " +
                        expr::to_infix(e) + " against " + expr::to_infix(s));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = fuzz::text_of(data, size);
  std::optional<expr::Expression> e;
  if (fuzz::accepted("parse", [&] { e = expr::parse(text); })) {
    const bool printed = fuzz::accepted("printers and evaluation", [&] {
      check_round_trip(*e);
      check_batch(*e, 3);
      if (e->size() <= 512) check_batch(*e, kSimdRows);  // keeps one input within milliseconds
      (void)expr::to_cpp(*e);
      (void)expr::to_glsl(*e);
      (void)expr::to_latex(*e);
      (void)expr::to_python(*e);
      if (e->size() <= 512) check_simplify(*e);
    });
    fuzz::require(printed, "a printer or evaluate threw InvalidArgument for an expression parse() accepted");
  }
  fuzz::accepted("parse with variables x, n", [&] { (void)expr::parse(text, {"x", "n"}); });
  return 0;
}
