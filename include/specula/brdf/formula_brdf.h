#pragma once
// A full BRDF written as a formula (a user-defined model, catalogue/model_file.h) in the dot
// products of docs/math.md §1 — nl = N·L, nv = N·V, nh = N·H, vh = V·H, lv = L·V — and its
// parameters, with named intermediate terms (expr::Program's lets), so that Cook-Torrance, GGX or
// Ward can be written as a paper writes them. Zero below the horizon (N·L ≤ 0 or N·V ≤ 0), as
// every full BRDF.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <span>
#include <string_view>
#include <vector>

#include "specula/brdf/directions.h"
#include "specula/expr/program.h"

namespace specula {

struct FormulaBrdf {
  /// The inputs every BRDF formula has, in slot order.
  static constexpr std::array<std::string_view, 5> kInputs{"nl", "nv", "nh", "vh", "lv"};

  std::shared_ptr<const expr::Program> program;
  std::vector<double> params;  ///< in the program's parameter order

  double operator()(const Vec3& n, const Vec3& l, const Vec3& v) const noexcept {
    const double nl = dot(n, l), nv = dot(n, v);
    if (nl <= 0 || nv <= 0) return 0;
    const Vec3 h = half_vector(l, v);
    return at(nl, nv, dot(n, h), dot(v, h), dot(l, v));
  }

  /// f at the given dot products.
  double at(double nl, double nv, double nh, double vh, double lv) const noexcept {
    std::array<double, expr::kMaxSlots> slots;
    slots[0] = nl, slots[1] = nv, slots[2] = nh, slots[3] = vh, slots[4] = lv;
    std::copy(params.begin(), params.end(), slots.begin() + kInputs.size());
    return program->evaluate(std::span<double>(slots.data(), program->slot_names().size()));
  }

  /// The lobe's width in θ_h (radians), a scale for the analysis's integrals: the θ_h where f at
  /// normal incidence (L = N, V at 2θ_h) first falls to half its value at θ_h = 0, to 1e-3 relative
  /// (θ_h ∈ [1e-6, π/4]; π/4 if it never does, or if f(0) ≤ 0: no peak, whose "half" a negative f
  /// would fall below at once).
  double width() const noexcept {
    constexpr double kQuarter = std::numbers::pi / 4;
    auto f = [&](double theta_h) {
      const double c = std::cos(theta_h), c2 = std::cos(2 * theta_h);
      return at(1, c2, c, c, c2);
    };
    const double half = f(0) / 2;
    if (!(half > 0)) return kQuarter;
    double lo = 1e-6, hi = lo;
    while (hi < kQuarter && !(f(hi) < half)) lo = hi, hi = std::min(hi * 1.5, kQuarter);
    if (!(f(hi) < half)) return kQuarter;
    while (hi - lo > 1e-3 * hi) {
      const double mid = (lo + hi) / 2;
      (f(mid) < half ? hi : lo) = mid;
    }
    return hi;
  }

  /// True if the formula has a min, max or abs: its kinks are unknown to the analysis, which
  /// then splits its integrals where a V-cavity's min(1, …) bends as well.
  bool has_switches() const noexcept {
    auto switches = [](const expr::Expression& e) {
      for (const expr::Node& node : e.nodes())
        if (node.op == expr::Op::min || node.op == expr::Op::max || node.op == expr::Op::abs) return true;
      return false;
    };
    for (const auto& step : program->lets())
      if (switches(step)) return true;
    return switches(program->result());
  }
};

}  // namespace specula
