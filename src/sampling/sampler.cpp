#include "specula/sampling/sampler.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <random>
#include <tbb/parallel_for.h>
#include <variant>

#include "radial.h"
#include "specula/analysis/albedo.h"
#include "specula/families/families.h"
#include "specula/interrupt/interrupt.h"
#include "specula/sampling/seeds.h"

namespace specula::sampling {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kBelowOne = 1 - 0x1p-53;
/// Tabulated lobes end at cos = 1e-7 (89.999994° from their axis); the cosine share covers beyond.
constexpr double kTableEnd = 16.118;  // −ln 1e-7
constexpr double kLobeTableCosineShare = 0.1;
constexpr double kBrdfTableCosineShare = 0.3;
const Vec3 kNormal{0, 0, 1};

/// Where the radial density is centred, and how ω_o follows from a direction about it.
enum class Axis {
  reflection,   ///< ω_o itself, about R (lobes in rv form)
  half_vector,  ///< H about N, ω_o = 2(ω_i·H)H − ω_i (lobes in nh form, microfacet BRDFs)
  none,         ///< no radial part (GGX's visible normals, Lambert)
};

using Radial = std::variant<std::monostate, PowerRadial, BeckmannRadial, LogRadial, TableRadial>;

using radial::cosine_direction;
using radial::log_cos_between;
using radial::mirror;

TableRadial lobe_table(const lobes::Lobe& lobe) {
  return std::visit(
      [](const auto& l) {
        const double end = std::min(kTableEnd, l.support_log_cos());
        const double width = std::clamp(l.half_max_log_cos(), 1e-300, end);
        return TableRadial([&](double y) { return l.at_log_cos(y); }, width, end);
      },
      lobe);
}

/// A user's full BRDF over H: the density ∝ f in the retro-reflection configuration L = V = H
/// times cos²θ_H (for a microfacet BRDF, ∝ D·G·F), which puts the samples where a specular lobe's
/// half vectors are.
TableRadial brdf_table(const Model& model) {
  const double width = std::max(1e-9, -std::log(std::cos(std::min(analysis::angular_width(model), 1.5))));
  return TableRadial(
      [&](double y) {
        const PolarAngle a = radial::from_log_cos(y);
        const Vec3 h{a.sin, 0, a.cos};
        return model(kNormal, h, h) * a.cos * a.cos;
      },
      width, kTableEnd);
}

}  // namespace

struct Sampler::Impl {
  Model model;
  Method method = Method::tabulated;
  Axis axis = Axis::none;
  Radial radial;
  double alpha = 0;  ///< GGX visible normals
  double share = 0;  ///< cosine-weighted share
  /// A compensated model (models/compensated.h): M's sampler, and for an added f_ms the energy
  /// table (see base_probability); a scaled one is sampled as M alone, its scale being constant
  /// over the directions sampled (ω_i is its viewer).
  std::unique_ptr<Sampler> base;
  std::shared_ptr<const EnergyTable> table;

  explicit Impl(const Model& m) : model(m) {
    if (const Compensated* compensated = model.compensated()) {
      base = std::make_unique<Sampler>(*compensated->base);
      if (!scales(compensated->scheme)) table = compensated->table;
      method = base->method();
      return;
    }
    const families::Family* family = families::family_of(model.info());
    method = family ? family->sampling : Method::tabulated;
    const std::span<const double> p = model.params();
    if (model.is_lobe()) {
      axis = model.form() == Form::rv ? Axis::reflection : Axis::half_vector;
      if (method == Method::power_cosine) radial = PowerRadial(p[0]);
      else if (method == Method::log_t_space) radial = LogRadial(p[0]);
      else use_table(lobe_table(model.lobe()), kLobeTableCosineShare);
      return;
    }
    switch (method) {
      case Method::beckmann: axis = Axis::half_vector, radial = BeckmannRadial(p[0]); break;
      case Method::ggx_visible_normals: alpha = p[0]; break;
      case Method::cosine: share = 1; break;
      case Method::tabulated:
      case Method::power_cosine:  // lobe methods: a full BRDF stating one is tabulated
      case Method::log_t_space: axis = Axis::half_vector, use_table(brdf_table(model), kBrdfTableCosineShare); break;
    }
  }

  void use_table(TableRadial table, double cosine_share) {
    if (table.usable()) {
      radial = std::move(table);
      share = cosine_share;
    } else {
      share = 1;  // nothing the table can sample: cosine-weighted alone
    }
  }

  double radial_density(double y) const noexcept {
    return std::visit(
        [y](const auto& r) -> double {
          if constexpr (std::is_same_v<std::decay_t<decltype(r)>, std::monostate>) return 0;
          else return r.density(y);
        },
        radial);
  }
  PolarAngle radial_sample(double u) const noexcept {
    return std::visit(
        [u](const auto& r) -> PolarAngle {
          if constexpr (std::is_same_v<std::decay_t<decltype(r)>, std::monostate>) return {};
          else return r.sample(u);
        },
        radial);
  }

  /// ω_o by the model's own strategy (not the cosine share); z ≤ 0 when it left the hemisphere.
  Vec3 strategy_sample(const Vec3& wi, double u1, double u2) const noexcept {
    if (method == Method::ggx_visible_normals) return mirror(wi, radial::ggx_visible_normal(alpha, wi, u1, u2));
    const PolarAngle a = radial_sample(u1);
    const double phi = 2 * kPi * u2;
    if (axis == Axis::reflection) return Frame(Vec3{-wi.x, -wi.y, wi.z}).to_world(a.cos, a.sin, phi);
    const Vec3 h{a.sin * std::cos(phi), a.sin * std::sin(phi), a.cos};
    return dot(wi, h) > 0 ? mirror(wi, h) : Vec3{0, 0, -1};
  }

  double strategy_pdf(const Vec3& wi, const Vec3& wo) const noexcept {
    if (method == Method::cosine) return 0;
    if (axis == Axis::reflection) return radial_density(log_cos_between(Vec3{-wi.x, -wi.y, wi.z}, wo));
    const Vec3 sum = wi + wo;
    if (!(dot(sum, sum) > 0)) return 0;
    const Vec3 h = normalized(sum);
    const double wo_h = dot(wo, h);
    if (!(wo_h > 0)) return 0;
    if (method == Method::ggx_visible_normals) return radial::ggx_visible_pdf(alpha, wi, h);
    return radial_density(log_cos_between(kNormal, h)) / (4 * wo_h);
  }

  /// M+ms: a one-sample mixture of M's sampler, with probability E(μ_i) (the energy f_M reflects),
  /// and cosine-weighted sampling, with 1 − E(μ_i) (what f_ms, ∝ (1 − E(μ_o)) cos θ_o, reflects):
  /// each strategy in proportion to the energy of the part it samples.
  double base_probability(const Vec3& wi) const noexcept { return table ? std::clamp(table->at(wi.z), 0.0, 1.0) : 1.0; }

  Vec3 compensated_sample(const Vec3& wi, double u1, double u2) const noexcept {
    const double p = base_probability(wi);
    if (!table) return base->sample(wi, u1, u2).wo;
    if (u1 < p) return base->sample(wi, std::min(u1 / p, kBelowOne), u2).wo;
    return cosine_direction<Vec3>(std::min((u1 - p) / (1 - p), kBelowOne), u2);
  }

  double pdf(const Vec3& wi, const Vec3& wo) const noexcept {
    if (!(wo.z > 0) || !(wi.z > 0)) return 0;
    if (base && !table) return base->pdf(wi, wo);
    if (base) {
      const double p = base_probability(wi);
      return p * base->pdf(wi, wo) + (1 - p) * wo.z / kPi;
    }
    const double lobe = share < 1 ? (1 - share) * strategy_pdf(wi, wo) : 0;
    return lobe + share * wo.z / kPi;
  }
};

Sampler::Sampler(const Model& model) : impl_(std::make_unique<Impl>(model)) {}
Sampler::~Sampler() = default;
Sampler::Sampler(Sampler&&) noexcept = default;
Sampler& Sampler::operator=(Sampler&&) noexcept = default;

Sample Sampler::sample(const Vec3& wi, double u1, double u2) const noexcept {
  const Impl& s = *impl_;
  if (!(wi.z > 0)) return {};
  Vec3 wo;
  if (s.base) {
    wo = s.compensated_sample(wi, u1, u2);
  } else if (u1 < s.share) {
    wo = cosine_direction<Vec3>(std::min(u1 / s.share, kBelowOne), u2);
  } else {
    const double u = s.share > 0 ? std::min((u1 - s.share) / (1 - s.share), kBelowOne) : u1;
    wo = s.strategy_sample(wi, u, u2);
  }
  if (!(wo.z > 0)) return {wo, 0, 0};
  const ValuePdf v = eval_pdf(wi, wo);
  if (!(v.pdf > 0)) return {wo, 0, 0};
  return {wo, v.pdf, v.f * wo.z / v.pdf};
}

double Sampler::pdf(const Vec3& wi, const Vec3& wo) const noexcept { return impl_->pdf(wi, wo); }

ValuePdf Sampler::eval_pdf(const Vec3& wi, const Vec3& wo) const noexcept {
  return {impl_->model.from_fixed(kNormal, wi, wo), impl_->pdf(wi, wo)};
}

const Model& Sampler::model() const noexcept { return impl_->model; }
Method Sampler::method() const noexcept { return impl_->method; }
double Sampler::cosine_share() const noexcept { return impl_->base ? impl_->base->cosine_share() : impl_->share; }

double Sampler::table_error() const noexcept {
  if (impl_->base) return impl_->base->table_error();
  const auto* table = std::get_if<TableRadial>(&impl_->radial);
  return table ? table->l1_error() : 0;
}

Sampler::Table Sampler::table() const noexcept {
  const auto* table = std::get_if<TableRadial>(&impl_->radial);
  if (!table) return {};
  return {table->width(), table->y_end(), table->ds(), table->cumulative()};
}

std::string Sampler::description() const {
  const Impl& s = *impl_;
  if (s.base && !s.table) return s.base->description();
  if (s.base)
    return fmt::format("{} with probability E(mu_i), else cosine-weighted (the multiple-scattering lobe)",
                       s.base->description());
  std::string text = to_string(s.method);
  if (s.axis == Axis::reflection) text += " about R";
  if (s.axis == Axis::half_vector) text += " of the half vector about N";
  if (s.share > 0 && s.share < 1) text += fmt::format(", {:g} % cosine-weighted", 100 * s.share);
  if (s.share == 1 && s.method != Method::cosine) text = "cosine-weighted (the table found nothing to sample)";
  return text;
}

std::vector<Sample> draw_block(const SampleFunction& sample, const Vec3& wi, std::uint64_t seed, std::size_t block,
                               std::size_t count) {
  std::mt19937_64 rng(stream_key(seed, block));
  auto uniform = [&rng] { return double(rng() >> 11) * 0x1p-53; };
  std::vector<Sample> samples(std::min(count, kSeedBlock));
  for (Sample& s : samples) {
    const double u1 = uniform();
    s = sample(wi, u1, uniform());
  }
  return samples;
}

std::vector<Sample> draw_samples(const Sampler& sampler, const Vec3& wi, std::size_t count, std::uint64_t seed) {
  const SampleFunction sample = [&sampler](const Vec3& w, double u1, double u2) { return sampler.sample(w, u1, u2); };
  std::vector<Sample> samples(count);
  const std::size_t blocks = (count + kSeedBlock - 1) / kSeedBlock;
  tbb::parallel_for(std::size_t{0}, blocks, carry_limit([&](std::size_t b) {
                      check_interrupt();
                      const std::vector<Sample> part = draw_block(sample, wi, seed, b, count - b * kSeedBlock);
                      std::copy(part.begin(), part.end(), samples.begin() + std::ptrdiff_t(b * kSeedBlock));
                    }));
  return samples;
}

}  // namespace specula::sampling
