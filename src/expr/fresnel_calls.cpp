// The Fresnel calls of a formula (expr.h: is_fresnel_call), each defined in the ops a formula has,
// written as named steps over its arguments; brdf/fresnel.h holds the same Fresnels for the
// built-in models, and tests/expr checks the two against each other.
#include <algorithm>
#include <array>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <span>
#include <string>
#include <utility>

#include "specula/expr/expr.h"

namespace specula::expr {
namespace {

struct Step {
  std::string_view name, text;
};

struct FresnelCall {
  std::string_view name;
  std::array<std::string_view, 4> args;  ///< its variables, "" past the last
  std::span<const Step> steps;           ///< named terms over the arguments and earlier steps
  std::string_view result;
};

constexpr Step kF82[] = {{"m", "1 - c"},
                         {"b", "(f0 + (1 - f0) * (6 / 7)^5) * (1 - tint) * 7 / (6 / 7)^6"}};
// Cook & Torrance 1982, eq. 8; g = 0 where g² ≤ 0 (total internal reflection) gives F = 1.
constexpr Step kDielectric[] = {{"g", "sqrt(max(eta^2 - 1 + c^2, 0))"}};
// Born & Wolf §13.2 in real arithmetic (as pbrt-v3's FrConductor).
constexpr Step kConductor[] = {{"s2", "1 - c^2"},
                               {"t0", "eta^2 - kappa^2 - s2"},
                               {"ab", "sqrt(t0^2 + 4 * eta^2 * kappa^2)"},
                               {"a", "sqrt(max((ab + t0) / 2, 0))"},
                               {"t1", "ab + c^2"},
                               {"t2", "2 * a * c"},
                               {"rs", "(t1 - t2) / (t1 + t2)"},
                               {"t3", "c^2 * ab + s2^2"},
                               {"t4", "t2 * s2"}};

constexpr FresnelCall kCalls[] = {
    {"fresnel_schlick", {"c", "f0"}, {}, "f0 + (1 - f0) * (1 - c)^5"},
    {"fresnel_schlick", {"c", "f0", "f90", "p"}, {}, "f0 + (f90 - f0) * (1 - c)^p"},
    {"fresnel_f82", {"c", "f0", "tint"}, kF82, "min(max(f0 + (1 - f0) * m^5 - b * c * m^6, 0), 1)"},
    {"fresnel_dielectric", {"c", "eta"}, kDielectric,
     "((g - c) / (g + c))^2 * (1 + ((c * (g + c) - 1) / (c * (g - c) + 1))^2) / 2"},
    {"fresnel_conductor", {"c", "eta", "kappa"}, kConductor, "(rs + rs * (t3 - t4) / (t3 + t4)) / 2"},
};

std::size_t arity(const FresnelCall& call) {
  return static_cast<std::size_t>(std::count_if(call.args.begin(), call.args.end(), [](auto a) { return !a.empty(); }));
}

/// `text` over `names`, each variable replaced by the nodes of its value.
std::vector<Node> substituted(std::string_view text, const std::vector<std::string>& names,
                              std::span<const std::vector<Node>> values) {
  const Expression body = parse(text, names);
  std::vector<Node> out;
  for (const Node& node : body.nodes())
    if (node.op == Op::variable)
      out.insert(out.end(), values[node.var].begin(), values[node.var].end());
    else
      out.push_back(node);
  return out;
}

}  // namespace

bool is_fresnel_call(std::string_view name) {
  return std::any_of(std::begin(kCalls), std::end(kCalls), [&](const FresnelCall& c) { return c.name == name; });
}

std::vector<Node> expand_fresnel_call(std::string_view name, std::span<const std::vector<Node>> arguments) {
  std::vector<std::size_t> counts;
  for (const FresnelCall& call : kCalls) {
    if (call.name != name) continue;
    if (arity(call) != arguments.size()) {
      counts.push_back(arity(call));
      continue;
    }
    std::vector<std::string> names(call.args.begin(), call.args.begin() + static_cast<std::ptrdiff_t>(arity(call)));
    std::vector<std::vector<Node>> values(arguments.begin(), arguments.end());
    for (const Step& step : call.steps) {
      values.push_back(substituted(step.text, names, values));
      names.emplace_back(step.name);
    }
    return substituted(call.result, names, values);
  }
  throw InvalidArgument(fmt::format("'{}' takes {} arguments but was given {}", name, fmt::join(counts, " or "),
                                    arguments.size()));
}

}  // namespace specula::expr
