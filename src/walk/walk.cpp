// The random walk on the Smith microsurface of a conductor and of a dielectric interface (walk.h;
// Heitz et al. 2016, §5–6 and the supplemental code's MicrosurfaceConductor and
// MicrosurfaceDielectric, with the two changes docs/random-walk.md explains: leaving is taken in
// expectation and paths end by Russian roulette).
#include "specula/walk/walk.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "microsurface.h"
#include "sobol.h"
#include "specula/analysis/fresnel.h"
#include "specula/analysis/parallel.h"
#include "specula/exceptions.h"
#include "specula/sampling/seeds.h"

namespace specula::walk {

namespace {

using detail::lambda;
using sampling::SplitMixStream;

// Statistics per channel: the orders, then every order, then 2 or more.
constexpr int kStats = kOrders + 2;
// Russian roulette: a path whose largest channel weight falls below this survives with the
// probability weight/kRoulette and, if it does, carries kRoulette on.
constexpr double kRoulette = 0.05;
// A guard against a path that would never leave: past it the path's remaining weight is dropped.
// Russian roulette ends paths long before (no test reaches it).
constexpr int kMaxBounces = 1 << 16;

// Per channel: the sums of the blocks' means and of their squares, statistic by statistic.
struct Sums {
  std::array<double, kStats> sum{}, sum2{};
};

// A path's uniform numbers: the first two bounces' height and normal from the block's shifted
// Sobol' net (sobol.h), the rest from the block's stream.
class Draws {
 public:
  Draws(const detail::SobolNet& net, const std::array<std::uint32_t, detail::kSobolDimensions>& shift,
        SplitMixStream& rng) noexcept
      : net_(net), shift_(shift), rng_(rng) {}
  void start_path(std::uint32_t index) noexcept { index_ = index; }

  /// Draw `slot` (0 the height, 1–2 the normal, 3 the dielectric's choice) of bounce `bounce` (1, 2, …).
  double at(int bounce, int slot) noexcept {
    const int d = bounce == 1 && slot < 4 ? slot : bounce == 2 && slot < 3 ? 4 + slot : -1;
    return d < 0 ? rng_.uniform() : net_.at(index_, d, shift_[d]);
  }
  double uniform() noexcept { return rng_.uniform(); }

 private:
  const detail::SobolNet& net_;
  const std::array<std::uint32_t, detail::kSobolDimensions>& shift_;
  SplitMixStream& rng_;
  std::uint32_t index_ = 0;
};

constexpr detail::SobolNet kNet;

// The next height, given that a ray along `ray` from log u meets the surface again (Heitz et
// al. 2016, eq. 22 with u for C₁(h)): up, from U uniform on [0, 1 − G₁); down, always. Λ is the
// masking surface's.
double next_log_u(const Microsurface& masking, const Vec3& ray, double log_u, double uniform) noexcept {
  const double l = lambda(masking, ray);
  if (ray.z > 0) return log_u - std::log1p(std::expm1(l * log_u) * uniform) / l;
  return log_u + std::log1p(-uniform) / -l;
}

// The chance G₁ = u^Λ that a ray along w (upward) leaves from height log u: e^(Λ log u).
double leaves(const Microsurface& masking, const Vec3& w, double log_u) noexcept {
  if (w.z <= 0) return 0;
  return std::exp(lambda(masking, w) * log_u);
}

// Russian roulette on a path's weights: false when the path ends, else the survivors reweighted.
bool roulette(std::vector<double>& weight, double largest, Draws& draws, const Faults& faults) {
  if (largest <= 0) return false;
  if (largest >= kRoulette) return true;
  const double survive = largest / kRoulette;
  if (draws.uniform() >= survive) return false;
  if (!faults.roulette_unweighted)
    for (double& w : weight) w /= survive;
  return true;
}

// A conductor's walk: what every path shares.
struct Walk {
  const Microsurface& surface;
  std::span<const fresnel::Channel> channels;
  const Faults& faults;
  Vec3 wi;
  const Vec3* next_event = nullptr;  // ω_o of conductor_brdf_cos; null for the albedo
  Microsurface masking{surface.distribution, surface.alpha * faults.masking_alpha_scale};  // G₁'s: `surface`

  std::size_t outputs() const noexcept { return channels.size(); }

  double fresnel(std::size_t c, int bounce, double cos_d) const noexcept {
    return bounce == faults.drop_fresnel_at_bounce ? 1.0 : channels[c](std::clamp(cos_d, 0.0, 1.0));
  }

  // One path: its contributions per channel and order into `value` (channels × kOrders).
  void path(Draws& draws, std::vector<double>& weight, std::vector<double>& value) const;
};

void Walk::path(Draws& draws, std::vector<double>& weight, std::vector<double>& value) const {
  const std::size_t n = channels.size();
  std::fill(weight.begin(), weight.end(), 1.0);
  std::fill(value.begin(), value.end(), 0.0);
  // Entering from above (u = 1) downward: the first height is u = (1 − U)^(1/(1 + Λ(ω_i))).
  Vec3 ray = -wi;
  double log_u = next_log_u(masking, ray, 0, draws.at(1, 0));
  for (int bounce = 1; bounce <= kMaxBounces; ++bounce) {
    const Vec3 in = -ray;
    const int order = std::min(bounce, kOrders) - 1;
    if (next_event) {
      Vec3 half;
      const double p = detail::phase_function(surface, in, *next_event, half) * leaves(masking, *next_event, log_u);
      if (p > 0)
        for (std::size_t c = 0; c < n; ++c) value[c * kOrders + order] += weight[c] * fresnel(c, bounce, dot(in, half)) * p;
    }
    const Vec3 m = detail::sample_visible_normal(surface, in, draws.at(bounce, 1), draws.at(bounce, 2));
    const double cos_d = dot(in, m);
    ray = m * (2 * cos_d) - in;
    const double escape = leaves(masking, ray, log_u);
    double largest = 0;
    for (std::size_t c = 0; c < n; ++c) {
      const double reflected = weight[c] * fresnel(c, bounce, cos_d);
      if (!next_event) value[c * kOrders + order] += reflected * escape;
      weight[c] = reflected * (1 - escape);
      largest = std::max(largest, weight[c]);
    }
    if (escape >= 1 || !roulette(weight, largest, draws, faults)) return;
    log_u = next_log_u(masking, ray, log_u, draws.at(bounce + 1, 0));
  }
}

// A rough dielectric interface's walk (Heitz et al. 2016, §6: MicrosurfaceDielectric): a path
// reflects at a facet with the probability F of the exact dielectric Fresnel, else refracts to the
// other side, where the surface is seen from below. Each side is walked in its own frame, the
// other side's being the point reflection v → −v, in which the heights are u → 1 − u. Outputs: 0
// reflection, 1 transmission, 2 both (their sum, path by path, for its standard error).
struct DielectricWalk {
  const Microsurface& surface;
  double eta;  // n below / n above
  const Faults& faults;
  Vec3 wi;
  Microsurface masking{surface.distribution, surface.alpha * faults.masking_alpha_scale};

  std::size_t outputs() const noexcept { return 3; }
  void path(Draws& draws, std::vector<double>& weight, std::vector<double>& value) const;
};

// ω refracted at a facet m (in·m > 0, no total internal reflection) into the side of relative
// index eta: −in/η + m (cos θ_i/η − cos θ_t).
Vec3 refract(const Vec3& in, const Vec3& m, double eta) noexcept {
  const double cos_i = dot(in, m);
  const double sin2_t = (1 - cos_i * cos_i) / (eta * eta);
  const double cos_t = std::sqrt(std::max(0.0, 1 - sin2_t));
  return normalized(m * (cos_i / eta - cos_t) - in * (1 / eta));
}

void DielectricWalk::path(Draws& draws, std::vector<double>& weight, std::vector<double>& value) const {
  weight.assign(1, 1.0);
  std::fill(value.begin(), value.end(), 0.0);
  bool above = true;
  Vec3 ray = -wi;  // in the frame of the side the path is on
  double log_u = next_log_u(masking, ray, 0, draws.at(1, 0));
  for (int bounce = 1; bounce <= kMaxBounces; ++bounce) {
    const Vec3 in = -ray;
    const Vec3 m = detail::sample_visible_normal(surface, in, draws.at(bounce, 1), draws.at(bounce, 2));
    const double relative = above ? eta : 1 / eta;
    const double f = bounce == faults.drop_fresnel_at_bounce ? 1.0 : fresnel::dielectric(dot(in, m), relative);
    if (draws.at(bounce, 3) < f) {
      ray = m * (2 * dot(in, m)) - in;
    } else {
      ray = -refract(in, m, relative);                 // seen from the other side
      log_u = std::log(-std::expm1(log_u));            // u → 1 − u
      above = !above;
    }
    const double escape = leaves(masking, ray, log_u);
    const int order = std::min(bounce, kOrders) - 1;
    value[(above ? 0 : kOrders) + order] += weight[0] * escape;
    value[2 * kOrders + order] += weight[0] * escape;
    weight[0] *= 1 - escape;
    if (escape >= 1 || !roulette(weight, weight[0], draws, faults)) return;
    log_u = next_log_u(masking, ray, log_u, draws.at(bounce + 1, 0));
  }
}

// A block's means per output and statistic.
template <class W>
std::vector<std::array<double, kStats>> block_means(const W& walk, std::uint64_t seed, std::uint64_t block) {
  const std::size_t n = walk.outputs();
  std::vector<std::array<double, kStats>> means(n);
  std::vector<double> weight(n), value(n * kOrders);
  SplitMixStream rng(sampling::stream_key(seed, block));
  std::array<std::uint32_t, detail::kSobolDimensions> shift;
  for (auto& x : shift) x = std::uint32_t(rng.uniform() * 0x1p32);
  Draws draws(kNet, shift, rng);
  for (std::uint32_t p = 0; p < kBlockPaths; ++p) {
    draws.start_path(p);
    walk.path(draws, weight, value);
    for (std::size_t c = 0; c < n; ++c)
      for (int k = 0; k < kOrders; ++k) {
        const double x = value[c * kOrders + k];
        means[c][k] += x;
        means[c][kOrders] += x;
        if (k > 0) means[c][kOrders + 1] += x;
      }
  }
  for (auto& m : means)
    for (double& x : m) x /= double(kBlockPaths);
  return means;
}

// The mean of the blocks' means, and its standard error from their spread (the paths of a block
// are stratified, not independent: the blocks are).
Estimate estimate(double sum, double sum2, double blocks) {
  const double mean = sum / blocks;
  const double variance = std::max(0.0, (sum2 / blocks - mean * mean) * blocks / (blocks - 1));
  return {mean, std::sqrt(variance / blocks)};
}

template <class W>
std::vector<Albedo> run(const W& walk, const Options& options) {
  const std::uint64_t blocks = std::max<std::uint64_t>(1, (options.paths + kBlockPaths - 1) / kBlockPaths);
  const std::size_t n = walk.outputs();
  std::vector<Sums> total(n);
  constexpr std::uint64_t kRound = 64;  // blocks per round: progress and the order of the sums
  for (std::uint64_t first = 0; first < blocks; first += kRound) {
    std::vector<std::uint64_t> round(std::min(kRound, blocks - first));
    for (std::size_t i = 0; i < round.size(); ++i) round[i] = first + i;
    const auto results = analysis::parallel_map(std::span<const std::uint64_t>(round), [&](std::uint64_t block) {
      return block_means(walk, options.seed, block);
    });
    for (const auto& block : results)
      for (std::size_t c = 0; c < n; ++c)
        for (int s = 0; s < kStats; ++s) {
          total[c].sum[s] += block[c][s];
          total[c].sum2[s] += block[c][s] * block[c][s];
        }
    if (options.progress) options.progress(double(first + round.size()) / double(blocks));
  }
  std::vector<Albedo> out(n);
  for (std::size_t c = 0; c < n; ++c) {
    std::array<Estimate, kStats> e;
    for (int s = 0; s < kStats; ++s) e[s] = estimate(total[c].sum[s], total[c].sum2[s], double(blocks));
    std::copy_n(e.begin(), kOrders, out[c].order.begin());
    out[c].total = e[kOrders];
    out[c].multiple = e[kOrders + 1];
  }
  return out;
}

void require(const std::string& error) {
  if (!error.empty()) throw InvalidArgument(error);
}

std::string direction_error(const char* name, const Vec3& w) {
  const double norm = length(w);
  if (!std::isfinite(norm) || std::abs(norm - 1) > 1e-9) return fmt::format("{} must be a unit vector", name);
  if (!(w.z > 0)) return fmt::format("{} must point above the surface (z > 0)", name);
  return "";
}

}  // namespace

std::string domain_error(const Microsurface& surface, std::span<const fresnel::Channel> channels, double mu,
                         const Options& options) {
  if (!(surface.alpha >= Microsurface::kMinAlpha && surface.alpha <= Microsurface::kMaxAlpha))
    return fmt::format("alpha must be in [{}, {}] (got {})", Microsurface::kMinAlpha, Microsurface::kMaxAlpha,
                       surface.alpha);
  if (!(mu > 0 && mu <= 1)) return fmt::format("mu = cos theta must be in (0, 1] (got {})", mu);
  if (channels.empty()) return "the walk needs at least one Fresnel channel";
  for (const auto& channel : channels)
    if (auto error = analysis::fresnel_domain_error(channel); !error.empty()) return error;
  if (options.paths < kMinPaths || options.paths > kMaxPaths)
    return fmt::format("paths must be in [{}, {}] (got {})", kMinPaths, kMaxPaths, options.paths);
  return "";
}

std::vector<Albedo> conductor_albedo(const Microsurface& surface, std::span<const fresnel::Channel> channels,
                                     double mu, const Options& options) {
  require(domain_error(surface, channels, mu, options));
  const Walk walk{surface, channels, options.faults, {std::sqrt(std::max(0.0, 1 - mu * mu)), 0, mu}};
  return run(walk, options);
}

DielectricAlbedo dielectric_albedo(const Microsurface& surface, double eta, double mu, const Options& options) {
  const fresnel::Channel interface{fresnel::Kind::dielectric, 1, 1, 5, 1, eta};
  require(domain_error(surface, {&interface, 1}, mu, options));
  const DielectricWalk walk{surface, eta, options.faults, {std::sqrt(std::max(0.0, 1 - mu * mu)), 0, mu}};
  const std::vector<Albedo> sides = run(walk, options);
  return {sides[0], sides[1], sides[2]};
}

std::vector<Albedo> conductor_brdf_cos(const Microsurface& surface, std::span<const fresnel::Channel> channels,
                                       const Vec3& wi, const Vec3& wo, const Options& options) {
  require(direction_error("wi", wi));
  require(direction_error("wo", wo));
  require(domain_error(surface, channels, wi.z, options));
  const Walk walk{surface, channels, options.faults, wi, &wo};
  return run(walk, options);
}

}  // namespace specula::walk
