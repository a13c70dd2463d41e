// F_avg of a Fresnel channel: closed forms where they hold, adaptive quadrature split at the kinks
// otherwise (docs/fresnel.md).
#include "specula/analysis/fresnel.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "../numeric/piecewise.h"
#include "specula/exceptions.h"

namespace specula::analysis {

namespace {

using fresnel::Kind;

// Where g changes sign in (0, 1): sign changes over a grid of 4096 cells, each bisected to the
// last bit. A pair of roots closer than a cell (a tangency) is missed; what the clamp cuts off
// there is below 1e-12 of F_avg for the parameters of the domain. A root within 1e-9 of an end is
// rounding (F82 is exactly 1 at c = 0), not a kink.
template <class G>
void add_roots(const G& g, std::vector<double>& roots) {
  constexpr int kCells = 4096;
  double a = 0, ga = g(0.0);
  for (int i = 1; i <= kCells; ++i) {
    const double b = double(i) / kCells, gb = g(b);
    if ((ga < 0) != (gb < 0)) {
      double lo = a, hi = b;
      for (int k = 0; k < 80 && hi - lo > 1e-17; ++k) {
        const double mid = (lo + hi) / 2;
        ((g(mid) < 0) == (ga < 0) ? lo : hi) = mid;
      }
      const double root = (lo + hi) / 2;
      if (root > 1e-9 && root < 1 - 1e-9) roots.push_back(root);
    }
    a = b, ga = gb;
  }
}

bool in_unit(double x) { return x >= 0 && x <= 1 && std::isfinite(x); }

}  // namespace

std::string fresnel_domain_error(const fresnel::Channel& f) {
  auto outside = [](const char* name, double v, double lo, double hi) {
    return std::isfinite(v) && v >= lo && v <= hi ? std::string()
                                                  : fmt::format("{} = {} is outside [{}, {}]", name, v, lo, hi);
  };
  std::string e;
  switch (f.kind) {
    case Kind::one: return "";
    case Kind::schlick:
      e = outside("f0", f.f0, 0, 1);
      if (e.empty()) e = outside("f90", f.f90, 0, 1);
      if (e.empty()) e = outside("exponent", f.exponent, 0.5, 50);
      return e;
    case Kind::f82_tint:
      e = outside("f0", f.f0, 0, 1);
      if (e.empty()) e = outside("tint", f.tint, 0, 1);
      return e;
    case Kind::dielectric: return outside("eta", f.eta, 1e-3, 1e3);
    case Kind::conductor:
      e = outside("eta", f.eta, 1e-3, 1e3);
      if (e.empty()) e = outside("kappa", f.kappa, 0, 1e3);
      return e;
  }
  return "";
}

std::vector<double> fresnel_kinks(const fresnel::Channel& f) {
  std::vector<double> kinks;
  if (f.kind == Kind::dielectric && f.eta < 1) kinks.push_back(std::sqrt(1 - f.eta * f.eta));
  if (f.kind == Kind::f82_tint) {
    const double b = fresnel::f82_tint_b(f.f0, f.tint);
    add_roots([&](double c) { return fresnel::f82_tint_unclamped(c, f.f0, b); }, kinks);
    add_roots([&](double c) { return fresnel::f82_tint_unclamped(c, f.f0, b) - 1; }, kinks);
  }
  std::sort(kinks.begin(), kinks.end());
  return kinks;
}

FresnelAverage fresnel_average(const fresnel::Channel& f) {
  if (const std::string e = fresnel_domain_error(f); !e.empty()) throw InvalidArgument("Fresnel: " + e);
  const std::vector<double> kinks = fresnel_kinks(f);
  switch (f.kind) {
    case Kind::one: return {1, 0, true};
    case Kind::schlick: return {fresnel::schlick_average(f.f0, f.f90, f.exponent), 0, true};
    case Kind::f82_tint: {
      const double b = fresnel::f82_tint_b(f.f0, f.tint);
      if (kinks.empty() && in_unit(fresnel::f82_tint_unclamped(0.5, f.f0, b)))
        return {fresnel::f82_tint_average_unclamped(f.f0, f.tint), 0, true};
      break;
    }
    case Kind::dielectric:
    case Kind::conductor: break;
  }
  // Smoothed ends: F has a square-root edge at the critical cosine (1 − F ∝ √(c − c_crit)).
  const auto estimate = numeric::integrate_pieces([&](double mu) { return 2 * f(mu) * mu; }, 0.0, 1.0, 1.0,
                                                  kinks, 1e-14, 20, numeric::Ends::smoothed);
  return {estimate.value, estimate.error, false};
}

}  // namespace specula::analysis
