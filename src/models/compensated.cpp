// The energy table's interpolation, Kulla & Conty's multiple-scattering lobe with its Fresnel and
// Turquin's scale (models/compensated.h); the table's values come from analysis/energy.h.
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

double EnergyTable::lost_average() const noexcept {
  static constexpr double x[] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  static constexpr double w[] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  double total = 0;
  for (std::size_t piece = 0; piece < kNodes; ++piece) {
    const double a = static_cast<double>(piece) / kNodeCount, b = static_cast<double>(piece + 1) / kNodeCount;
    for (int k = 0; k < 4; ++k) {
      const double s = (a + b) / 2 + (b - a) / 2 * x[k];
      total += (b - a) / 2 * w[k] * std::max(0.0, 1 - at(s * s * s)) * 6 * std::pow(s, 5);
    }
  }
  return total;
}

double EnergyTable::multiple_scattering(double mu_i, double mu_o) const noexcept {
  if (!(e_avg < 1)) return 0;
  const double lost_i = std::max(0.0, 1 - at(mu_i)), lost_o = std::max(0.0, 1 - at(mu_o));
  return lost_i * lost_o / (std::numbers::pi * (1 - e_avg));
}

double kulla_conty_fresnel(double f_avg, double e_avg) noexcept {
  const double stays = 1 - f_avg * (1 - e_avg);  // ≥ E_avg: 0 only for F_avg = 1, E_avg = 0
  return stays > 0 ? f_avg * f_avg * e_avg / stays : 1;
}

double cycles_fresnel(double f_avg, double e_avg) noexcept {
  const double stays = 1 - f_avg * (1 - e_avg);  // ≥ E_avg: 0 only for F_avg = 1, E_avg = 0
  return stays > 0 ? f_avg * e_avg / stays : 1;
}

double Compensated::multiple_scattering(double mu_i, double mu_o) const noexcept {
  return fresnel_scale * table->multiple_scattering(mu_i, mu_o);
}

double Compensated::scale(double mu_o) const noexcept {
  const double e = table->at(mu_o);
  if (!(e > 0)) return 1;  // nothing reflected to scale
  const double f = fresnel ? (*fresnel)(mu_o) : fresnel_scale;
  return 1 + f * std::max(0.0, 1 - e) / e;
}

double Compensated::albedo(double base_albedo, double mu) const noexcept {
  if (scales(scheme)) return base_albedo * scale(mu);
  return base_albedo + fresnel_scale * std::max(0.0, 1 - table->at(mu)) * table->ms_scale;
}

namespace {

/// The index of the suffix `id` ends with (after a base id of at least one character), or
/// kCompensationSchemeCount.
std::size_t suffix_index(std::string_view id) noexcept {
  for (std::size_t k = 0; k < kCompensationSchemeCount; ++k)
    if (id.size() > kCompensationSuffixes[k].size() && id.ends_with(kCompensationSuffixes[k])) return k;
  return kCompensationSchemeCount;
}

}  // namespace

std::string_view compensated_base_id(std::string_view id) noexcept {
  const std::size_t k = suffix_index(id);
  return k < kCompensationSchemeCount ? id.substr(0, id.size() - kCompensationSuffixes[k].size()) : std::string_view{};
}

CompensationScheme compensation_scheme_of(std::string_view id) noexcept {
  const std::size_t k = suffix_index(id);
  return k < kCompensationSchemeCount ? static_cast<CompensationScheme>(k) : CompensationScheme::shipped;
}

}  // namespace specula
