// The energy table's interpolation and Kulla & Conty's multiple-scattering lobe
// (models/compensated.h); the table's values come from analysis/energy.h.
#include "specula/models/compensated.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace specula {
namespace {

constexpr double kNodeCount = static_cast<double>(EnergyTable::kNodes);

}  // namespace

double EnergyTable::node_mu(std::size_t j) noexcept {
  const double s = static_cast<double>(j + 1) / kNodeCount;
  return s * s * s;
}

double EnergyTable::midpoint_mu(std::size_t j) noexcept {
  const double s = (static_cast<double>(j) + 0.5) / kNodeCount;
  return s * s * s;
}

double EnergyTable::at(double mu) const noexcept {
  // s·kNodes − 1 is the node index as a real number; below node 0 the first segment extends.
  const double t = std::cbrt(std::clamp(mu, 0.0, 1.0)) * kNodeCount - 1;
  const auto j = static_cast<std::size_t>(std::clamp(std::floor(t), 0.0, kNodeCount - 2));
  const double w = t - static_cast<double>(j);
  return e[j] + w * (e[j + 1] - e[j]);
}

bool EnergyTable::compensates() const noexcept {
  return e_avg < 1 && std::all_of(e.begin(), e.end(), [](double x) { return x <= 1 + 1e-7; });
}

double EnergyTable::multiple_scattering(double mu_i, double mu_o) const noexcept {
  if (!(e_avg < 1)) return 0;
  const double lost_i = std::max(0.0, 1 - at(mu_i)), lost_o = std::max(0.0, 1 - at(mu_o));
  return lost_i * lost_o / (std::numbers::pi * (1 - e_avg));
}

std::string_view compensated_base_id(std::string_view id) noexcept {
  if (id.size() <= kCompensatedSuffix.size() || !id.ends_with(kCompensatedSuffix)) return {};
  return id.substr(0, id.size() - kCompensatedSuffix.size());
}

}  // namespace specula
