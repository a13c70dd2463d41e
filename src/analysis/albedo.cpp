#include "specula/analysis/albedo.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <vector>

#include "../numeric/piecewise.h"
#include "specula/analysis/fresnel.h"
#include "specula/analysis/parallel.h"
#include "specula/exceptions.h"
#include "specula/interrupt/interrupt.h"

namespace specula::analysis {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLogCosEnd = 40;  // α with cos α = e^(−40): the rest weighs < 1e-17
// Relative tolerances on |K31 − G15|, which overstates the error of K31 by orders of magnitude:
// these give 12+ digits (measured against tests/reference/albedo.csv: ≤ 2e-13 apart). The inner
// one is tighter because inner noise stalls the outer error control.
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
  return {k * e.value, k * e.error, e.evaluations};
}

/// ρ = 2 ∫₀^{θ_h,max} sin θ_h ∫₀^{φ_max(θ_h)} 4 (L·H)(N·V) f(L, V) dφ dθ_h; the factor 2 and
/// φ ∈ [0, π] use the symmetry of isotropic BRDFs about the plane of incidence.
/// f_at(l, v, theta_h) evaluates the BRDF.
/// Geometry of the half-vector parametrization: the lobe's width and support in θ_h, and whether
/// f has Cook & Torrance's V-cavity G, whose min() has kinks at known φ_h.
struct HalfVectorShape {
  double width;
  double support = std::numbers::pi / 2;  ///< f is 0 beyond, or below 1e-18 of its integral
  bool vcavity = false;
  std::vector<double> fresnel_kinks = {};  ///< the V·H where F bends (analysis::fresnel_kinks)
};

/// The φ_h where L·H = V·H is `lh`, for L at θ_i and H at θ_h; −1 for none.
double phi_where_lh(double lh, double ci, double si, double ch, double sh) {
  const double x = (lh - ci * ch) / (si * sh);
  return x > -1 && x < 1 ? std::acos(x) : -1.0;
}

/// The φ_h where G's min() switches, for L at θ_i and H at θ_h (V·H = L·H): up to θ_h = 45°,
/// where 2(N·H)(N·L) = V·H and where 2(N·H)(N·V) = V·H (each term reaches 1 while the other is
/// above it); beyond, where N·V = N·L (the two terms cross below 1); −1 for none.
std::vector<double> vcavity_kinks(double ci, double si, double ch, double sh) {
  const double q = 4 * ch * ch - 1;
  if (2 * ch * ch < 1) return {phi_where_lh(ci / ch, ci, si, ch, sh)};
  return {phi_where_lh(2 * ch * ci, ci, si, ch, sh), phi_where_lh(2 * ch * ci / q, ci, si, ch, sh)};
}

/// The θ_h in (0, upper) where the outer integrand bends because a Fresnel kink at V·H = c enters
/// or leaves the φ_h range: where L·H at φ_h = 0 or π, cos(θ_i ∓ θ_h), is c.
std::vector<double> fresnel_bends(double theta_i, double upper, const std::vector<double>& kink_cosines) {
  std::vector<double> bends;
  for (const double c : kink_cosines)
    for (const double theta_h : {std::acos(c) - theta_i, std::acos(c) + theta_i, theta_i - std::acos(c)})
      if (theta_h > 0 && theta_h < upper) bends.push_back(theta_h);
  return bends;
}

/// Appends the roots of gap(θ_h) in (lo, hi): a scan for sign changes, then bisection.
template <class Gap>
void append_roots(const Gap& gap, double lo, double hi, std::vector<double>& roots) {
  constexpr int kScan = 128;
  for (int k = 0; k < kScan; ++k) {
    double a = lo + (hi - lo) * k / kScan, b = lo + (hi - lo) * (k + 1) / kScan;
    if ((gap(a) > 0) == (gap(b) > 0)) continue;
    while (b - a > 1e-15 * b) {
      const double mid = (a + b) / 2;
      ((gap(mid) > 0) == (gap(a) > 0) ? a : b) = mid;
    }
    roots.push_back(a);
  }
}

/// The θ_h in (0, upper) where the outer integrand bends because a kink of vcavity_kinks enters or
/// leaves the φ_h range, where L·H is cos(θ_i ∓ θ_h) at φ_h = 0, π: at 45°, where the kinks
/// change; at 90° − θ_i, where the first one crosses φ_h = 0; and where the second crosses φ_h = 0
/// or π, cos(θ_i ∓ θ_h)(4cos²θ_h − 1) = 2 cos θ_h cos θ_i, or the third, cos(θ_i ∓ θ_h) cos θ_h =
/// cos θ_i.
std::vector<double> vcavity_bends(double theta_i, double upper) {
  const double ci = std::cos(theta_i), quarter = kPi / 4;
  std::vector<double> bends{quarter};
  if (theta_i >= quarter) bends.push_back(kPi / 2 - theta_i);
  for (const double sign : {-1.0, 1.0}) {
    auto lh = [&](double theta_h) { return std::cos(theta_i + sign * theta_h); };
    auto second = [&](double t) { return lh(t) * (4 * std::cos(t) * std::cos(t) - 1) - 2 * std::cos(t) * ci; };
    append_roots(second, 0, std::min(quarter, upper), bends);
    if (upper > quarter) append_roots([&](double t) { return lh(t) * std::cos(t) - ci; }, quarter, upper, bends);
  }
  return bends;
}

/// ∫ g over [a, b] split at `breaks`: 31-point Kronrod rules on one piece, 15-point ones on several
/// (pieces between G's kinks are short and smooth: 15 points take them at the same tolerance in
/// half the evaluations, where one long piece would need bisection).
template <class G>
numeric::Estimate integrate_inner(const G& g, double a, double b, const std::vector<double>& breaks) {
  const bool split = std::any_of(breaks.begin(), breaks.end(), [&](double x) { return x > a && x < b; });
  return split ? numeric::integrate_pieces<15>(g, a, b, b - a, breaks, kInnerTolerance, kInnerMaxDepth)
               : numeric::integrate_pieces<31>(g, a, b, b - a, breaks, kInnerTolerance, kInnerMaxDepth);
}

/// ∫₀^end g(φ) dφ with kinks at `kinks` (< 0: none). Where the horizon cuts (end < π), N·V ∝
/// end − φ near the end, and a BRDF with a power of N·V (Ward's 1/√(N·V)) has a root
/// singularity there that bisection refines to its depth limit: φ = end·u(2 − u), end − φ =
/// end·(1 − u)², makes it smooth in u.
template <class G>
numeric::Estimate integrate_azimuth(const G& g, double end, const std::vector<double>& kinks) {
  if (!(end > 0)) return {};
  if (end >= kPi) return integrate_inner(g, 0, end, kinks);
  auto in_u = [&](double u) { return g(end * u * (2 - u)) * 2 * end * (1 - u); };
  std::vector<double> kinks_u;
  for (const double phi : kinks)
    if (phi > 0 && phi < end) kinks_u.push_back(1 - std::sqrt(1 - phi / end));
  return integrate_inner(in_u, 0, 1, kinks_u);
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
  std::size_t inner_evaluations = 0;
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
    std::vector<double> kinks = shape.vcavity && si * sh > 0 ? vcavity_kinks(ci, si, ch, sh) : std::vector<double>{};
    if (si * sh > 0)
      for (const double c : shape.fresnel_kinks) kinks.push_back(phi_where_lh(c, ci, si, ch, sh));
    const auto e = integrate_azimuth(inner, end, kinks);
    inner_evaluations += e.evaluations;
    return sh * e.value;
  };
  const double upper = (kPi / 2 + theta_i) / 2;      // beyond, V is below the horizon for every φ_h
  const double horizon_starts = (kPi / 2 - theta_i) / 2;
  // With a V-cavity G the outer integrand also bends where G's kinks enter or leave the φ range
  // (vcavity_bends) and, at normal incidence, at θ_h = 30°.
  std::vector<double> breaks = fresnel_bends(theta_i, upper, shape.fresnel_kinks);
  breaks.insert(breaks.end(), {horizon_starts, shape.support});
  if (shape.vcavity && si > 0) {
    for (const double theta_h : vcavity_bends(theta_i, upper)) breaks.push_back(theta_h);
  } else if (shape.vcavity) {
    breaks.push_back(kPi / 6);
  }
  // Smoothed ends: at the horizon's start and end, φ_max moves as a root of θ_h, and so does a kink
  // entering the φ range, which puts a (θ_h − θ₀)^(3/2) into the outer integrand there.
  const auto e = numeric::integrate_pieces(outer, 0, std::min(upper, shape.support), shape.width, breaks,
                                           kOuterTolerance, 10, numeric::Ends::smoothed);
  return {2 * e.value, 2 * e.error, inner_evaluations};
}

/// Beckmann's RMS slope (Cook & Torrance's m, Beckmann-Smith's α), or 0 for another BRDF.
double beckmann_slope(const FullBrdf& brdf) {
  if (const auto* ct = std::get_if<CookTorrance>(&brdf)) return ct->m;
  if (const auto* ct = std::get_if<CookTorrance1982>(&brdf)) return ct->m;
  if (const auto* b = std::get_if<Beckmann>(&brdf)) return b->alpha;
  return 0;
}

/// The cosines V·H where the BRDF's Fresnel has a kink (total internal reflection, F82's clamp).
std::vector<double> fresnel_kinks_of(const FullBrdf& brdf) {
  if (const auto* g = std::get_if<Ggx>(&brdf)) return fresnel_kinks(g->fresnel);
  if (const auto* b = std::get_if<Beckmann>(&brdf)) return fresnel_kinks(b->fresnel);
  return {};
}

/// The θ_h beyond which Beckmann's D = exp(−tan²θ_h / m²) / (π m² cos⁴θ_h) is below e^−50
/// (1 + 50 m²)² ≤ 1e-18 of its peak for m ≤ 1: tan θ_h = m √50. The albedo's outer integral ends
/// there; before, its pieces beyond (where G's kinks still bend the integrand) cost some 40 % of
/// every Cook-Torrance albedo.
double beckmann_support(double m) { return std::atan(m * std::sqrt(50.0)); }

/// ρ of M + F_ms f_ms is ρ_M plus F_ms f_ms's own albedo, which is separable and known exactly from
/// the table (EnergyTable::ms_scale): F_ms (1 − E(μ_i))₊ · ms_scale. A scaled compensation's (the
/// viewer's albedo) is ρ_M times its scale at μ, M being reciprocal.
Albedo compensated_albedo(const Compensated& model, double theta_i) {
  const Albedo base = albedo(*model.base, theta_i);
  const double mu = std::cos(theta_i);
  const double scale = scales(model.scheme) ? model.scale(mu) : 1;
  return {model.albedo(base.value, mu), base.error_estimate * scale, base.evaluations};
}

}  // namespace

void require_incidence_deg(double degrees, const char* what) {
  if (!(degrees >= 0 && degrees < 90))
    throw InvalidArgument(fmt::format("{} = {} is outside [0, 90) degrees", what, degrees));
}

double angular_width(const Model& model) {
  if (const Compensated* compensated = model.compensated()) return angular_width(*compensated->base);
  if (!model.is_lobe()) return std::visit([](const auto& b) { return b.width(); }, model.brdf());
  const double u = std::visit([](const auto& l) { return l.half_max_log_cos(); }, model.lobe());
  return std::isfinite(u) ? std::acos(std::exp(-u)) : kPi / 2;
}

Albedo albedo(const Model& model, double theta_i) {
  check_interrupt();
  if (!(theta_i >= 0 && theta_i < kPi / 2))
    throw InvalidArgument(fmt::format("incidence angle {} rad is outside [0, π/2)", theta_i));
  if (model.is_lobe() && model.form() == Form::rv)
    return std::visit([&](const auto& l) { return rv_albedo(l, model.coef(), theta_i); }, model.lobe());
  if (const Compensated* compensated = model.compensated()) return compensated_albedo(*compensated, theta_i);
  HalfVectorShape shape{.width = angular_width(model)};
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
  if (const double m = beckmann_slope(model.brdf()); m > 0) shape.support = beckmann_support(m);
  shape.fresnel_kinks = fresnel_kinks_of(model.brdf());
  const Vec3 n{0, 0, 1};
  return half_vector_albedo([&](const Vec3& l, const Vec3& v, double) { return model(n, l, v); }, theta_i, shape);
}

std::vector<double> albedo_curve(const Model& model, std::span<const double> theta_i) {
  return parallel_map(theta_i, [&](double theta) { return albedo(model, theta).value; });
}

}  // namespace specula::analysis
