#include "specula/analysis/monte_carlo.h"

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include "specula/analysis/albedo.h"
#include "specula/interrupt/interrupt.h"
#include "specula/simd/brdf.h"

namespace specula::analysis {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLobeShare = 0.8;

/// pdf (m + 1)/(2π) cos^m θ about an axis; m from the lobe's width: cos^m = ½ at the width.
struct PowerLobe {
  double m;
  double pdf(double cos_theta) const { return cos_theta > 0 ? (m + 1) / (2 * kPi) * std::pow(cos_theta, m) : 0; }
  double sample_cos(double xi) const { return std::pow(xi, 1 / (m + 1)); }
};

Vec3 to_world(const Frame& frame, double cos_theta, double phi) {
  return frame.to_world(cos_theta, std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta)), phi);
}

PowerLobe matched_power_lobe(const Model& model) {
  const double width = std::min(angular_width(model), 1.4);
  return {std::max(1.0, std::log(0.5) / std::log(std::cos(width)))};
}

/// Samples above the horizon waiting for their BRDF values, evaluated as one SIMD batch
/// (simd/brdf.h, exact tier) per block; the sums run in sample order, as one at a time would.
/// N = +z and L are the same for every sample: their columns are filled once.
class SampleBlock {
 public:
  static constexpr std::size_t kSize = 1024;

  /// `viewer`: the fixed direction is V and the samples are L (the albedo of a model that is not
  /// reciprocal, a scaled compensation's, is the viewer's: models/compensated.h).
  SampleBlock(const Model& model, const Vec3& l, bool viewer) : model_(model), viewer_(viewer) {
    const double fixed[6] = {0, 0, 1, l.x, l.y, l.z};
    for (std::size_t k = 0; k < 6; ++k) fixed_[k].assign(kSize, fixed[k]);
    for (auto& c : v_) c.reserve(kSize);
    pdf_.reserve(kSize);
  }

  /// A sample V with its pdf; samples that count 0 (below the horizon, pdf 0) come with pdf 0.
  void add(const Vec3& v, double pdf) {
    v_[0].push_back(v.x);
    v_[1].push_back(v.y);
    v_[2].push_back(v.z);
    pdf_.push_back(pdf);
    if (pdf_.size() == kSize) flush();
  }

  /// Evaluates the pending samples and adds value and value² to the sums.
  void flush() {
    check_interrupt();  // once per block of kSize samples
    const std::size_t count = pdf_.size();
    const auto first = [count](const std::vector<double>& column) { return std::span<const double>(column.data(), count); };
    f_.resize(count);
    const std::span<const double> sampled[3] = {v_[0], v_[1], v_[2]};
    const std::span<const double> fixed[3] = {first(fixed_[3]), first(fixed_[4]), first(fixed_[5])};
    const std::span<const double>* l = viewer_ ? sampled : fixed;
    const std::span<const double>* v = viewer_ ? fixed : sampled;
    simd::eval_batch(model_, simd::Tier::exact,
                     {first(fixed_[0]), first(fixed_[1]), first(fixed_[2]), l[0], l[1], l[2], v[0], v[1], v[2]}, f_);
    for (std::size_t i = 0; i < count; ++i) {
      const double value = pdf_[i] > 0 ? f_[i] * v_[2][i] / pdf_[i] : 0;  // f (N·V) / pdf
      sum += value;
      sum_sq += value * value;
    }
    for (auto& c : v_) c.clear();
    pdf_.clear();
  }

  double sum = 0, sum_sq = 0;

 private:
  const Model& model_;
  bool viewer_;
  std::array<std::vector<double>, 6> fixed_;  ///< N and L by component
  std::array<std::vector<double>, 3> v_;
  std::vector<double> pdf_, f_;
};

}  // namespace

MonteCarloEstimate albedo_monte_carlo(const Model& model, double theta_i, std::size_t samples,
                                      std::uint64_t seed) {
  const Vec3 n{0, 0, 1};
  const Vec3 l = from_spherical(theta_i, 0.0);
  const bool around_r = model.is_lobe() && model.form() == Form::rv;
  const Frame lobe_frame(around_r ? reflect(l, n) : n);
  const Frame normal_frame(n);
  const PowerLobe lobe = matched_power_lobe(model);

  // pdf of V under the lobe strategy.
  auto lobe_pdf = [&](const Vec3& v) {
    if (around_r) return lobe.pdf(dot(lobe_frame.w, v));
    const Vec3 h = half_vector(l, v);
    const double vh = dot(v, h);
    return vh > 0 ? lobe.pdf(h.z) / (4 * vh) : 0.0;
  };

  check_interrupt();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  SampleBlock block(model, l, model.fixes_viewer());
  for (std::size_t i = 0; i < samples; ++i) {
    const double choice = uniform(rng), xi1 = uniform(rng), xi2 = uniform(rng);
    Vec3 v;
    if (choice < kLobeShare) {
      const Vec3 axis_dir = to_world(lobe_frame, lobe.sample_cos(xi1), 2 * kPi * xi2);
      v = around_r ? axis_dir : reflect(l, axis_dir);
    } else {
      v = to_world(normal_frame, std::sqrt(xi1), 2 * kPi * xi2);  // cosine-weighted
    }
    const double pdf = v.z > 0 ? kLobeShare * lobe_pdf(v) + (1 - kLobeShare) * v.z / kPi : 0;
    block.add(v, pdf);
  }
  block.flush();
  const double count = static_cast<double>(samples);
  const double mean = block.sum / count;
  const double variance = std::max(0.0, block.sum_sq / count - mean * mean);
  return {mean, std::sqrt(variance / count), samples};
}

}  // namespace specula::analysis
