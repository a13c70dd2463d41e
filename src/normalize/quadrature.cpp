#include "specula/normalize/quadrature.h"

#include <cmath>
#include <numbers>

#include "../numeric/piecewise.h"
#include "specula/interrupt/interrupt.h"

namespace specula::normalize {
namespace {

constexpr double kRvTruncation = 40;  // e^(−2u) < 1.9e-35 beyond

double weight(Form form, double u) noexcept {
  const double e2 = std::exp(-2 * u);
  return form == Form::rv ? e2 : (2 * e2 - 1) * 4 * e2;
}

template <class L>
Integral integrate(const L& lobe, Form form) {
  const double form_end = form == Form::rv ? kRvTruncation : std::numbers::ln2 / 2;
  const double end = std::min(form_end, lobe.support_log_cos());
  const auto kinks = lobes::kinks_log_cos(lobe);
  const auto estimate = numeric::integrate_pieces(
      [&](double u) { return lobe.at_log_cos(u) * weight(form, u); }, 0, end, lobe.half_max_log_cos(),
      {kinks.begin(), kinks.end()});
  return {2 * std::numbers::pi * estimate.value, 2 * std::numbers::pi * estimate.error};
}

}  // namespace

Integral normal_incidence_albedo(const lobes::Lobe& lobe, Form form) {
  check_interrupt();
  return std::visit([form](const auto& l) { return integrate(l, form); }, lobe);
}

double quadrature(const lobes::Lobe& lobe, Form form) {
  return 1 / normal_incidence_albedo(lobe, form).value;
}

}  // namespace specula::normalize
