#pragma once
// Importance sampling of every model (docs/sampling.md): a direction ω_o drawn for a given ω_i with
// its density and its Monte-Carlo weight, and the density of any pair — the `sample` / `pdf` /
// `eval_pdf` triple that a path tracer's BSDF interface asks for (pbrt-v4's BxDF, Mitsuba 3's BSDF).
//
// Frame: the normal N = +z; ω_i points toward the light (L of docs/math.md §1), ω_o toward the
// viewer (V); f(ω_i, ω_o) is the model's f(N, L, V). Densities are per unit solid angle of ω_o.
// A scaled compensation (models/compensated.h), which is not reciprocal, is sampled the other way
// round, as a renderer holds the viewer fixed: ω_i is V and f(ω_i, ω_o) is f(N, ω_o, ω_i)
// (Model::from_fixed); its scale is constant over ω_o, so M's sampler samples it.
//
// Each model is sampled by the method its family states (models/sampling_method.h): about R for lobes in
// `rv` form, over the half vector H for lobes in `nh` form (ω_o = 2(ω_i·H)H − ω_i, pdf(ω_o) =
// pdf(H)/(4 ω_o·H)), a microfacet distribution for full BRDFs. Tabulated methods mix a share of
// cosine-weighted sampling in (one-sample mixture: pdf = (1 − s)·pdf_lobe + s·cos θ_o/π), so that
// pdf > 0 wherever f·cos θ_o > 0 and the weight stays bounded in the tails.
//
// A sample that leaves the hemisphere (θ_o ≥ 90°) is returned with pdf = weight = 0 — the
// renderer's "no sample" — and pdf() of a direction below the horizon is 0, so the density of the
// samples that count integrates to at most 1.
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "specula/models/model.h"
#include "specula/models/sampling_method.h"

namespace specula::sampling {

struct Sample {
  Vec3 wo;
  double pdf = 0;     ///< density of ω_o per solid angle; 0: no sample
  double weight = 0;  ///< f(ω_i, ω_o)·cos θ_o / pdf; 0 when pdf = 0

  bool valid() const noexcept { return pdf > 0; }
};

struct ValuePdf {
  double f = 0;
  double pdf = 0;
};

class Sampler {
 public:
  /// The sampler of `model` (tables are built here: a few ms). Never throws for a valid model.
  explicit Sampler(const Model& model);
  ~Sampler();
  Sampler(Sampler&&) noexcept;
  Sampler& operator=(Sampler&&) noexcept;

  /// ω_o from two uniform numbers in [0, 1); ω_i a unit vector with ω_i·N > 0.
  Sample sample(const Vec3& wi, double u1, double u2) const noexcept;
  /// The density sample() draws ω_o with.
  double pdf(const Vec3& wi, const Vec3& wo) const noexcept;
  /// f(ω_i, ω_o) and pdf(ω_i, ω_o) together (one half vector).
  ValuePdf eval_pdf(const Vec3& wi, const Vec3& wo) const noexcept;

  const Model& model() const noexcept;
  Method method() const noexcept;
  /// What is sampled, e.g. "power-cosine (closed form) about R".
  std::string description() const;
  /// The share of cosine-weighted samples mixed in (0 for closed-form methods). For M+ms it
  /// depends on ω_i, 1 − E(μ_i) (the base model's share within the rest); this returns M's.
  double cosine_share() const noexcept;
  /// A tabulated method's error: the L1 distance between the table's density and the lobe's
  /// normalized density (0 for the exact methods).
  double table_error() const noexcept;

  /// A tabulated method's table, for code that re-creates this sampler (exports::export_model):
  /// the radial density is piecewise constant in y = −ln cos on cells with edges
  /// y_j = width·(e^(j·ds) − 1), j < cells, and y_end last; cumulative[j] = P(y < y_j). Empty
  /// cumulative for the other methods (and where the table found nothing to sample).
  struct Table {
    double width = 0, y_end = 0, ds = 0;
    std::span<const double> cumulative;
  };
  Table table() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Seeded sample sequences come in blocks of this many, each from its own generator.
inline constexpr std::size_t kSeedBlock = std::size_t{1} << 16;

/// sample(ω_i, u1, u2): a Sampler's, or a stand-in's (the tests break one on purpose).
using SampleFunction = std::function<Sample(const Vec3& wi, double u1, double u2)>;

/// Samples [block·kSeedBlock, block·kSeedBlock + count) of the sequence `seed` at ω_i (count ≤
/// kSeedBlock): u1, u2 from a mt19937_64 seeded by a hash of (seed, block), 53 bits each.
std::vector<Sample> draw_block(const SampleFunction& sample, const Vec3& wi, std::uint64_t seed, std::size_t block,
                               std::size_t count);
/// The first `count` samples of the sequence `seed`, blocks in parallel: the same for any thread
/// count.
std::vector<Sample> draw_samples(const Sampler& sampler, const Vec3& wi, std::size_t count, std::uint64_t seed);

}  // namespace specula::sampling
