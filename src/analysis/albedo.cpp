#include "specula/analysis/albedo.h"

#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "../numeric/piecewise.h"
#include "specula/analysis/parallel.h"
#include "specula/exceptions.h"
#include "specula/interrupt/interrupt.h"

namespace specula::analysis {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLogCosEnd = 40;  // α with cos α = e^(−40): the rest weighs < 1e-17
// Relative tolerances on |K31 − G15|, which overstates the error of K31 by orders of magnitude:
// these give 10+ digits (measured against a run at 1e-10/1e-12: ≤ 7e-11 apart). The inner one is
// tighter because inner noise stalls the outer error control.
constexpr double kOuterTolerance = 1e-9;
constexpr double kInnerTolerance = 1e-11;
constexpr unsigned kInnerMaxDepth = 8;

/// ∫₀^{2π} max(0, A + B cos φ) dφ for B ≥ 0.
double clipped_azimuthal(double a, double b) noexcept {
  if (a >= b) return 2 * kPi * a;
  if (a <= -b) return 0;
  const double x = -a / b;
  return 2 * (a * std::acos(x) + b * std::sqrt(1 - x * x));
}

/// u = −ln cos θ without cancellation for small θ.
double log_cos_of_angle(double theta) noexcept {
  const double s = std::sin(theta / 2);
  return -std::log1p(-2 * s * s);
}

template <class L>
Albedo rv_albedo(const L& lobe, double k, double theta_i) {
  const double ci = std::cos(theta_i), si = std::sin(theta_i);
  auto integrand = [&](double u) {
    const double c = std::exp(-u), s = std::sqrt(-std::expm1(-2 * u));
    return lobe.at_log_cos(u) * c * clipped_azimuthal(c * ci, s * si);
  };
  const double end = std::min(kLogCosEnd, lobe.support_log_cos());
  const double horizon = si > 0 ? -std::log(si) : end;
  std::vector<double> breaks{horizon};
  for (const double kink : lobes::kinks_log_cos(lobe)) breaks.push_back(kink);
  const auto e = numeric::integrate_pieces(integrand, 0, end, lobe.half_max_log_cos(), breaks, kOuterTolerance);
  return {k * e.value, k * e.error};
}

/// ρ = 2 ∫₀^{θ_h,max} sin θ_h ∫₀^{φ_max(θ_h)} 4 (L·H)(N·V) f(L, V) dφ dθ_h; the factor 2 and
/// φ ∈ [0, π] use the symmetry of isotropic BRDFs about the plane of incidence.
/// f_at(l, v, theta_h) evaluates the BRDF.
/// Geometry of the half-vector parametrization: the lobe's width and support in θ_h, and whether
/// f has Cook & Torrance's V-cavity G, whose min() has kinks at known φ_h.
struct HalfVectorShape {
  double width;
  double support = std::numbers::pi / 2;
  bool vcavity = false;
};

/// The φ_h where G's min() switches, for L at θ_i and H at θ_h: where 2(N·H)(N·L) = V·H and
/// where 2(N·H)(N·V) = V·H (V·H = L·H).
std::pair<double, double> vcavity_kinks(double ci, double si, double ch, double sh) {
  auto phi_where_lh = [&](double lh) {
    const double x = (lh - ci * ch) / (si * sh);
    return x > -1 && x < 1 ? std::acos(x) : -1.0;
  };
  const double q = 4 * ch * ch - 1;
  return {phi_where_lh(2 * ch * ci), q > 0 ? phi_where_lh(2 * ch * ci / q) : -1.0};
}

template <class F>
Albedo half_vector_albedo(const F& f_at, double theta_i, const HalfVectorShape& shape) {
  const double ci = std::cos(theta_i), si = std::sin(theta_i);
  const Vec3 l{si, 0, ci};
  auto phi_max = [&](double ch, double sh) {
    if (si * sh == 0) return 2 * ch * ch > 1 ? kPi : 0.0;  // N·V = cos 2θ_h at normal incidence
    const double kappa = (ci / (2 * ch) - ci * ch) / (si * sh);
    return kappa >= 1 ? 0.0 : (kappa <= -1 ? kPi : std::acos(kappa));
  };
  auto outer = [&](double theta_h) {
    check_interrupt();  // per outer node: each is an inner adaptive integral over φ_h
    const double ch = std::cos(theta_h), sh = std::sin(theta_h);
    const double end = phi_max(ch, sh);
    auto inner = [&](double phi) {
      const Vec3 h{sh * std::cos(phi), sh * std::sin(phi), ch};
      const double lh = dot(l, h);
      Vec3 v = h * (2 * lh) - l;
      // N·V = sin θ_i sin 2θ_h (cos φ − κ) cancels near the horizon; written without
      // subtraction: a product of sines when the horizon cuts (κ = cos φ_max), otherwise
      // sin θ_i sin 2θ_h (1 + cos φ) + cos(θ_i + 2θ_h), a sum of two non-negative terms.
      const double s2 = si * 2 * sh * ch;
      if (end < kPi) {
        v.z = -2 * s2 * std::sin((phi + end) / 2) * std::sin((phi - end) / 2);
      } else {
        const double c = std::cos(phi / 2);
        v.z = s2 * 2 * c * c + std::cos(theta_i + 2 * theta_h);
      }
      return v.z > 0 && lh > 0 ? 4 * lh * v.z * f_at(l, v, theta_h) : 0.0;
    };
    const auto [g1, g2] = shape.vcavity && si * sh > 0 ? vcavity_kinks(ci, si, ch, sh) : std::pair{-1.0, -1.0};
    return sh * numeric::integrate_pieces(inner, 0, end, end, {g1, g2}, kInnerTolerance, kInnerMaxDepth).value;
  };
  const double upper = (kPi / 2 + theta_i) / 2;      // beyond, V is below the horizon for every φ_h
  const double horizon_starts = (kPi / 2 - theta_i) / 2;
  // With a V-cavity G the outer integrand also bends where G's kinks enter the φ range: at
  // θ_h = 90° − θ_i (2(N·H)(N·L) = V·H reaches φ = 0) and, at normal incidence, θ_h = 30°.
  const double g_kink = shape.vcavity ? (si > 0 ? kPi / 2 - theta_i : kPi / 6) : -1.0;
  const auto e = numeric::integrate_pieces(outer, 0, upper, shape.width, {horizon_starts, shape.support, g_kink},
                                           kOuterTolerance, 10);
  return {2 * e.value, 2 * e.error};
}

/// A formula BRDF's width: the θ_h where f at normal incidence (L = N, V at 2θ_h) first falls to
/// half its value at θ_h = 0, to 1e-3 relative (θ_h ∈ [1e-6, π/4]; π/4 if it never does).
double formula_brdf_width(const FormulaBrdf& b) {
  auto f = [&](double theta_h) {
    const double c = std::cos(theta_h), c2 = std::cos(2 * theta_h);
    return b.at(1, c2, c, c, c2);
  };
  const double half = f(0) / 2;
  double lo = 1e-6, hi = lo;
  while (hi < kPi / 4 && !(f(hi) < half)) lo = hi, hi = std::min(hi * 1.5, kPi / 4);
  if (!(f(hi) < half)) return kPi / 4;
  while (hi - lo > 1e-3 * hi) {
    const double mid = (lo + hi) / 2;
    (f(mid) < half ? hi : lo) = mid;
  }
  return hi;
}

double brdf_width(const FullBrdf& brdf) {
  return std::visit(
      [](const auto& b) -> double {
        using B = std::decay_t<decltype(b)>;
        if constexpr (std::is_same_v<B, Ward> || std::is_same_v<B, Ggx>) return b.alpha;
        else if constexpr (std::is_same_v<B, Lambert>) return kPi / 2;
        else if constexpr (std::is_same_v<B, FormulaBrdf>) return formula_brdf_width(b);
        else if constexpr (std::is_same_v<B, Compensated>) return angular_width(*b.base);
        else return b.m;
      },
      brdf);
}

/// ρ of M + f_ms is ρ_M plus f_ms's own albedo, which is separable and known exactly from the table
/// (EnergyTable::ms_scale): (1 − E(μ_i))₊ · ms_scale.
Albedo compensated_albedo(const Compensated& model, double theta_i) {
  const Albedo base = albedo(*model.base, theta_i);
  const double lost = std::max(0.0, 1 - model.table->at(std::cos(theta_i)));
  return {base.value + lost * model.table->ms_scale, base.error_estimate};
}

}  // namespace

void require_incidence_deg(double degrees, const char* what) {
  if (!(degrees >= 0 && degrees < 90))
    throw InvalidArgument(fmt::format("{} = {} is outside [0, 90) degrees", what, degrees));
}

double angular_width(const Model& model) {
  if (!model.is_lobe()) return brdf_width(model.brdf());
  const double u = std::visit([](const auto& l) { return l.half_max_log_cos(); }, model.lobe());
  return std::isfinite(u) ? std::acos(std::exp(-u)) : kPi / 2;
}

Albedo albedo(const Model& model, double theta_i) {
  check_interrupt();
  if (!(theta_i >= 0 && theta_i < kPi / 2))
    throw InvalidArgument(fmt::format("incidence angle {} rad is outside [0, π/2)", theta_i));
  if (model.is_lobe() && model.form() == Form::rv)
    return std::visit([&](const auto& l) { return rv_albedo(l, model.coef(), theta_i); }, model.lobe());
  if (const auto* compensated = model.is_lobe() ? nullptr : std::get_if<Compensated>(&model.brdf()))
    return compensated_albedo(*compensated, theta_i);
  HalfVectorShape shape{angular_width(model)};
  if (model.is_lobe()) {
    return std::visit(
        [&](const auto& lobe) {
          const double k = model.coef(), support = lobe.support_log_cos();
          if (std::isfinite(support)) shape.support = std::acos(std::exp(-support));
          return half_vector_albedo(
              [&](const Vec3&, const Vec3&, double theta_h) { return k * lobe.at_log_cos(log_cos_of_angle(theta_h)); },
              theta_i, shape);
        },
        model.lobe());
  }
  // A formula with min/max/abs may have a V-cavity G: split where one would bend as well.
  const auto* formula = std::get_if<FormulaBrdf>(&model.brdf());
  shape.vcavity = std::holds_alternative<CookTorrance>(model.brdf()) ||
                  std::holds_alternative<CookTorrance1982>(model.brdf()) || (formula && formula->has_switches());
  const Vec3 n{0, 0, 1};
  return half_vector_albedo([&](const Vec3& l, const Vec3& v, double) { return model(n, l, v); }, theta_i, shape);
}

std::vector<double> albedo_curve(const Model& model, std::span<const double> theta_i) {
  return parallel_map(theta_i, [&](double theta) { return albedo(model, theta).value; });
}

}  // namespace specula::analysis
