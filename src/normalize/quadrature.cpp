#include "specula/normalize/quadrature.h"

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <numbers>

namespace specula::normalize {
namespace {

constexpr double kRvTruncation = 40;  // e^(−2u) < 1.9e-35 beyond
constexpr double kTolerance = 1e-13;  // on |K31 − G15|, far above the rule's true error
constexpr unsigned kMaxDepth = 15;

double weight(Form form, double u) noexcept {
  const double e2 = std::exp(-2 * u);
  return form == Form::rv ? e2 : (2 * e2 - 1) * 4 * e2;
}

template <class L>
Integral integrate(const L& lobe, Form form) {
  const double form_end = form == Form::rv ? kRvTruncation : std::numbers::ln2 / 2;
  const double end = std::min(form_end, lobe.support_log_cos());
  // Integrate in s = u/width so that every piece is O(1) in length and in value, whatever n is:
  // Boost's error control misbehaves on pieces of length 1e-9.
  const double width = std::min(lobe.half_max_log_cos(), end);
  const double s_end = end / width;
  auto integrand = [&](double s) {
    const double u = s * width;
    return lobe.at_log_cos(u) * weight(form, u);
  };

  Integral total;
  for (double a = 0, b = 1; a < s_end; a = b, b *= 4) {
    b = std::min(b, s_end);
    double error = 0;
    total.value += boost::math::quadrature::gauss_kronrod<double, 31>::integrate(
        integrand, a, b, kMaxDepth, kTolerance, &error);
    total.error_estimate += error;
  }
  const double scale = 2 * std::numbers::pi * width;
  return {total.value * scale, total.error_estimate * scale};
}

}  // namespace

Integral normal_incidence_albedo(const lobes::Lobe& lobe, Form form) {
  return std::visit([form](const auto& l) { return integrate(l, form); }, lobe);
}

double quadrature(const lobes::Lobe& lobe, Form form) {
  return 1 / normal_incidence_albedo(lobe, form).value;
}

}  // namespace specula::normalize
