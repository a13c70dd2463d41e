// The compensations measured against the random walk (compensation.h).
#include "specula/queries/compensation.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "specula/analysis/albedo.h"
#include "specula/analysis/energy.h"
#include "specula/analysis/fresnel.h"
#include "specula/catalogue/catalogue.h"
#include "specula/catalogue/fresnel_spec.h"
#include "specula/exceptions.h"
#include "specula/interrupt/interrupt.h"
#include "specula/models/compensated.h"

namespace specula::queries {

namespace {

using fresnel::Channel;
using fresnel::Kind;

// The GGX model whose Fresnel is `f` (families/ggx.h: one model per kind), at α.
Model ggx_with(const Channel& f, double alpha, std::string_view suffix) {
  const auto named = [&](std::string id, ParamValues p) {
    p["alpha"] = alpha;
    return make_model(id + std::string(suffix), p);
  };
  switch (f.kind) {
    case Kind::one: return named("ggx", {{"f0", 1}});
    case Kind::schlick:
      if (f.is_schlick_f0()) return named("ggx", {{"f0", f.f0}});
      return named("ggx-schlick", {{"f0", f.f0}, {"f90", f.f90}, {"exponent", f.exponent}});
    case Kind::f82_tint: return named("ggx-f82", {{"f0", f.f0}, {"tint", f.tint}});
    case Kind::dielectric: return named("ggx-dielectric", {{"eta", f.eta}});
    case Kind::conductor: return named("ggx-conductor", {{"eta", f.eta}, {"kappa", f.kappa}});
  }
  unreachable();
}

// A metal's F82-tint from its complex index: F0 = F(1), tint = F(1/7) / Schlick(1/7) (clamped to
// the channel's [0, 1]).
Channel f82_of_metal(double eta, double kappa) {
  const double f0 = fresnel::conductor(1.0, eta, kappa);
  const double tint = fresnel::conductor(1.0 / 7, eta, kappa) / fresnel::schlick(1.0 / 7, f0, 1.0, 5.0);
  return Channel{Kind::f82_tint, f0, 1, 5, std::clamp(tint, 0.0, 1.0)};
}

}  // namespace

double compensated_albedo(Compensation c, const CompensationInputs& in) noexcept {
  const double missing = in.e > 0 ? (1 - in.e) / in.e : 0;  // (1 − E)/E
  switch (c) {
    case Compensation::none: return in.e_f;
    case Compensation::kulla_conty:
      // f_ms's albedo is 1 − E(μ) (f_ms = (1 − E(μ_i))(1 − E(μ_o))/(π(1 − E_avg))), times F_avg F_ms:
      // what M+ms ships (models/compensated.h).
      return in.e_f + (1 - in.e) * kulla_conty_fresnel(in.f_avg, in.e_avg);
    case Compensation::turquin_f0: return in.e_f * (1 + in.f0 * missing);
    case Compensation::turquin_fresnel: return in.e_f * (1 + in.f_mu * missing);
    case Compensation::turquin_average: return in.e_f * (1 + in.f_avg * missing);
    case Compensation::cycles: return in.e_f * (1 + cycles_fresnel(in.f_avg, in.e_avg) * missing);
    case Compensation::walk_fit: {
      const double single = in.e > 0 ? in.e_f / in.e : 0;  // the Fresnel of the first bounce, averaged
      const double first = std::max(single, in.f_avg), later = (single + in.f_avg) / 2;
      const double leave = std::pow(in.e_avg, 0.7);
      return in.e_f + (1 - in.e) * first * later * leave / (1 - later * (1 - leave));
    }
    case Compensation::shipped: return in.shipped;
  }
  return in.e_f;
}

std::vector<VerdictFresnel> verdict_fresnels() {
  std::vector<VerdictFresnel> out;
  for (double f0 : {0.04, 0.2, 0.5, 0.9}) {
    const Channel c{Kind::schlick, f0, 1, 5};
    out.push_back({"schlick", to_spec(c), c});
  }
  for (double eta : {1.1, 1.5, 2.5}) {
    const Channel c{Kind::dielectric, 1, 1, 5, 1, eta};
    out.push_back({"dielectric", to_spec(c), c});
  }
  // Complex indices at the sRGB primaries' wavelengths (about 650, 550 and 450 nm), as many
  // renderers tabulate them.
  struct Metal {
    const char* name;
    std::array<double, 3> eta, kappa;
  };
  for (const Metal& m : {Metal{"gold", {0.143, 0.374, 1.442}, {3.983, 2.385, 1.603}},
                         Metal{"copper", {0.200, 0.924, 1.102}, {3.912, 2.452, 2.142}},
                         Metal{"aluminium", {1.657, 0.880, 0.521}, {9.224, 6.270, 4.837}}})
    for (int rgb = 0; rgb < 3; ++rgb) {
      const Channel c = f82_of_metal(m.eta[rgb], m.kappa[rgb]);
      out.push_back({m.name, fmt::format("{} {}: {}", m.name, "RGB"[rgb], to_spec(c)), c});
    }
  return out;
}

Verdict verdict(const VerdictSettings& s) {
  if (s.alpha.empty() || s.mu.empty() || s.fresnels.empty()) throw InvalidArgument("the verdict needs α, μ and Fresnel values");
  if (s.distribution != walk::Distribution::ggx) throw InvalidArgument("the verdict measures GGX only");
  // F = 1 first, never read: Russian roulette follows a path's largest weight, so with it every
  // Fresnel channel rides on the paths of the white walk (the same paths whatever the Fresnels).
  std::vector<Channel> channels{Channel{}};
  for (const auto& f : s.fresnels) channels.push_back(f.channel);
  std::vector<double> f_avg;
  for (const auto& f : s.fresnels) f_avg.push_back(analysis::fresnel_average(f.channel).value);

  Verdict v;
  v.cells.columns = {"alpha", "mu", "fresnel", "F", "F0", "F_avg", "E", "E_avg", "E_F", "E_F_se", "E_ms", "E_ms_se"};
  for (auto name : kCompensationNames) v.cells.columns.push_back(fmt::format("albedo_{}", name));
  v.cells.key_columns = 3;
  v.cells.meta = {{"truth", "random walk on the GGX microsurface (walk/walk.h)"},
                  {"paths", std::to_string(s.paths)},
                  {"seed", std::to_string(s.seed)}};
  for (std::size_t k = 0; k < s.fresnels.size(); ++k) v.cells.meta.emplace_back(fmt::format("fresnel {}", k), s.fresnels[k].label);

  struct Errors {
    double max = 0, sum2 = 0, max_relative = 0, max_walk = 0;
    std::size_t n = 0;
  };
  std::vector<std::array<Errors, kCompensationCount>> errors(s.fresnels.size());
  const std::size_t total = s.alpha.size() * s.mu.size();
  std::size_t done = 0;
  for (double alpha : s.alpha) {
    const Model ggx = make_model("ggx", {{"alpha", alpha}, {"f0", 1.0}});
    const double e_avg = analysis::average_albedo(ggx).value;
    for (double mu : s.mu) {
      check_interrupt();
      const double e = analysis::albedo(ggx, std::acos(mu)).value;
      walk::Options options;
      options.paths = s.paths;
      options.seed = s.seed;
      const auto walked = walk::conductor_albedo({s.distribution, alpha}, channels, mu, options);
      for (std::size_t k = 0; k < s.fresnels.size(); ++k) {
        const walk::Albedo& w = walked[k + 1];
        const Channel& f = s.fresnels[k].channel;
        CompensationInputs in{e, e_avg, w.order[0].value, f(mu), f(1.0), f_avg[k]};
        in.shipped = analysis::albedo(ggx_with(f, alpha, "+ms"), std::acos(mu)).value;
        const double truth = w.total.value;
        std::vector<double> row{alpha, mu, double(k), in.f_mu, in.f0, in.f_avg, e, e_avg, w.order[0].value,
                                w.order[0].error, w.multiple.value, w.multiple.error};
        for (std::size_t c = 0; c < kCompensationCount; ++c) {
          const double a = compensated_albedo(Compensation(c), in);
          row.push_back(a);
          if (std::isnan(a)) continue;  // does not apply here
          Errors& err = errors[k][c];
          const double d = std::abs(a - truth);
          err.max = std::max(err.max, d);
          err.sum2 += d * d;
          if (w.multiple.value > 1e-3) err.max_relative = std::max(err.max_relative, d / w.multiple.value);
          err.max_walk = std::max(err.max_walk, w.multiple.error);
          ++err.n;
        }
        v.cells.rows.push_back(std::move(row));
      }
      if (s.progress) s.progress(++done, total);
    }
  }
  // The families, in the order they first appear, each over all its channels' cells.
  std::vector<std::string> families;
  for (const auto& f : s.fresnels)
    if (std::find(families.begin(), families.end(), f.family) == families.end()) families.push_back(f.family);
  for (const auto& family : families)
    for (std::size_t c = 0; c < kCompensationCount; ++c) {
      VerdictSummary sum{family, Compensation(c)};
      double sum2 = 0;
      for (std::size_t k = 0; k < s.fresnels.size(); ++k) {
        if (s.fresnels[k].family != family) continue;
        const Errors& e = errors[k][c];
        sum.max_error = std::max(sum.max_error, e.max);
        sum.max_relative_ms = std::max(sum.max_relative_ms, e.max_relative);
        sum.max_walk_error = std::max(sum.max_walk_error, e.max_walk);
        sum2 += e.sum2;
        sum.cells += e.n;
      }
      if (sum.cells == 0) sum.max_error = sum.rms_error = sum.max_relative_ms = sum.max_walk_error = NAN;
      else sum.rms_error = std::sqrt(sum2 / double(sum.cells));
      v.summary.push_back(sum);
    }
  return v;
}

io::Table summary_table(const Verdict& v) {
  io::Table t;
  t.columns = {"family", "compensation", "max_error", "rms_error", "max_relative_ms", "max_walk_se", "cells"};
  t.key_columns = 2;
  std::vector<std::string> families;
  for (const auto& s : v.summary) {
    auto at = std::find(families.begin(), families.end(), s.family);
    if (at == families.end()) {
      t.meta.emplace_back(fmt::format("family {}", families.size()), s.family);
      at = families.insert(families.end(), s.family);
    }
    t.rows.push_back({double(at - families.begin()), double(s.compensation), s.max_error, s.rms_error,
                      s.max_relative_ms, s.max_walk_error, double(s.cells)});
  }
  for (std::size_t c = 0; c < kCompensationCount; ++c) t.meta.emplace_back(fmt::format("compensation {}", c), kCompensationNames[c]);
  return t;
}

}  // namespace specula::queries
