// specula check: does a model conserve energy at every angle, is it reciprocal and non-negative?
// Exit 0 when every property holds for every parameter value, 1 when one fails.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <iostream>

#include "cli.h"
#include "specula/analysis/check.h"
#include "specula/exceptions.h"
#include "specula/render/heatmap.h"
#include "specula/render/image_io.h"
#include "specula/sampling/check.h"

namespace specula::cli {
namespace {

// The documented caps: a case is one albedo curve (up to ~15 s for GGX at --step 0.01), a pair
// two evaluations; Ctrl-C stops any of them.
constexpr std::size_t kMaxCases = 1000, kMaxGrazing = 100;
constexpr int kMaxPairs = 10'000'000;
// --sampling: sampling/check.h's caps.
using sampling::kMaxSamplingAngles, sampling::kMaxSamplingTotal;

struct CheckCliOptions {
  ModelOptions model;
  std::string n;
  std::string sweep;
  analysis::CheckOptions check;
  std::string grazing = "89.5,89.9";
  bool json = false;
  std::string out;
  bool sampling = false;
  std::string sampling_theta = "0,30,60,80,89";
  sampling::SamplingCheckOptions sampling_options;
};

/// The parameter to sweep and its values: --n RANGE is --sweep n=RANGE.
std::pair<std::string, std::vector<double>> sweep_of(const CheckCliOptions& o) {
  if (!o.n.empty() && !o.sweep.empty()) throw InvalidArgument("give --n or --sweep, not both");
  if (!o.n.empty()) return {"n", option_values("--n", o.n, kMaxCases)};
  if (o.sweep.empty()) return {};
  const auto eq = o.sweep.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InvalidArgument(fmt::format("malformed --sweep '{}': expected NAME=RANGE", o.sweep));
  return {o.sweep.substr(0, eq), option_values("--sweep", std::string_view(o.sweep).substr(eq + 1), kMaxCases)};
}

std::string describe(const Model& m) {
  std::string text(m.id());
  for (std::size_t i = 0; i < m.params().size(); ++i)
    text += fmt::format("{}{}={}", i ? ", " : " (", m.info().params[i].name, m.params()[i]);
  if (!m.params().empty()) text += ")";
  if (m.is_lobe()) text += fmt::format(", {} form, k = {}", to_string(m.form()), m.coef());
  return text;
}

std::string verdict(bool holds) { return holds ? "holds" : "FAILS"; }

std::string text_report(const std::vector<queries::CheckCase>& cases, double last_probe_deg) {
  std::string out;
  for (const auto& [m, r] : cases) {
    out += describe(m) + "\n";
    out += fmt::format("  albedo at normal incidence  {:.10g}\n", r.albedo_normal);
    out += fmt::format("  max albedo                  {:.10g} at θ_i = {:.6g}° (θ_i probed up to {:.6g}°)\n",
                       r.max_albedo.value, r.max_albedo.theta_deg, last_probe_deg);
    out += fmt::format("  energy conservation         {}", verdict(r.conserves_energy));
    if (!r.conserves_energy)
      out += fmt::format(": reflects {:.4g} % more than it receives at θ_i = {:.6g}°",
                         100 * (r.max_albedo.value - 1), r.max_albedo.theta_deg);
    const Compensated* compensated = m.compensated();
    if (compensated && !compensated->table->compensates())
      out += "\n  energy compensation         does not apply: the base model reflects more than it receives";
    else if (compensated && compensated->table->from_walk)
      out += fmt::format("\n  energy compensation         the random walk's multiple scattering (F0 < 1), within {:.2g} of the walk",
                         r.compensation_error);
    else if (compensated && scales(compensated->scheme))
      out += fmt::format("\n  energy compensation         Turquin's scale 1 + F_s (1 − E)/E at N·V, {}; not reciprocal: the albedo is the viewer's",
                         compensated->fresnel ? "F_s = F(N·V)" : fmt::format("F_s = {:.4g}", compensated->fresnel_scale));
    else if (compensated && compensated->fresnel_scale != 1)
      out += fmt::format("\n  energy compensation         Kulla-Conty's, F_ms = {:.4g} (F0 < 1: the albedo stays below 1)",
                         compensated->fresnel_scale);
    else if (compensated)
      out += fmt::format("\n  energy compensation         albedo 1 within the table's error {:.2g}: max |ρ − 1| = {:.2g} on the θ_i grid",
                         r.compensation_error, r.max_deviation_from_one);
    out += fmt::format("\n  reciprocity                 {}: max relative |f(l,v) − f(v,l)| = {:.3g} over {} pairs\n",
                       verdict(r.reciprocal), r.max_asymmetry, r.pairs);
    out += fmt::format("  non-negativity              {}: min f = {:.6g}\n", verdict(r.non_negative), r.min_value);
  }
  return out;
}

std::string sampling_text(const Model& m, const sampling::SamplingCheck& c) {
  std::string out = fmt::format("{}\n  sampled by {}", describe(m), c.method);
  if (c.table_error > 0) out += fmt::format(" (table's L1 error {:.2g})", c.table_error);
  out += fmt::format("\n  {:>6} {:>9} {:>10} {:>5} {:>9} {:>8} {:>10} {:>12} {:>10} {:>12} {:>9}  {}\n", "θ_i", "samples",
                     "χ²", "dof", "p", "α_θ", "∫pdf", "mean weight", "± se", "albedo", "max wt", "verdict");
  for (const sampling::AngleCheck& a : c.angles) {
    if (a.non_finite_samples) {
      out += fmt::format("  {:>5}° FAILS: f is inf or NaN at {} samples: the model is not finite; the check stops here\n",
                         a.theta_deg, a.non_finite_samples);
      continue;
    }
    if (a.negative_samples) {
      out += fmt::format("  {:>5}° FAILS: f < 0 at {} samples (min f = {:.6g}): the model is negative; the check stops here\n",
                         a.theta_deg, a.negative_samples, a.min_f);
      continue;
    }
    std::string problems;
    if (!a.chi2_passes()) problems += " χ²";
    if (!a.albedo_agrees()) problems += fmt::format(" mean weight ≠ albedo ({:.2f} se)", std::abs(a.mean_weight - a.albedo) / a.standard_error);
    if (!a.pdf_normalized()) problems += " ∫pdf > 1";
    if (a.outside) problems += fmt::format(" {} samples outside the hemisphere or with a bad pdf", a.outside);
    if (a.weight_mismatches) problems += fmt::format(" {} weights ≠ f·cos/pdf", a.weight_mismatches);
    if (a.uncovered_nodes) problems += fmt::format(" pdf = 0 where f > 0 at {} points", a.uncovered_nodes);
    out += fmt::format("  {:>5}° {:>9} {:>10.4g} {:>5} {:>9.3g} {:>8.2g} {:>10.7f} {:>12.7f} {:>10.2g} {:>12.7f} {:>9.3g}  {}\n",
                       a.theta_deg, a.valid_samples, a.chi2, a.dof, a.p_value, a.alpha, a.pdf_integral, a.mean_weight,
                       a.standard_error, a.albedo, a.max_weight, problems.empty() ? "passes" : "FAILS:" + problems);
  }
  return out;
}

/// A JSON number, or null for inf and NaN (which JSON has no number for).
std::string json_number(double x) { return std::isfinite(x) ? fmt::format("{}", x) : "null"; }

std::string sampling_json(const Model& m, const sampling::SamplingCheck& c) {
  std::string out = fmt::format("{{\"model\": \"{}\", \"method\": \"{}\", \"table_error\": {}, \"passes\": {}, \"angles\": [",
                                describe(m), c.method, c.table_error, c.passes());
  for (std::size_t i = 0; i < c.angles.size(); ++i) {
    const sampling::AngleCheck& a = c.angles[i];
    out += fmt::format("{}\n  {{\"theta_deg\": {}, \"samples\": {}, \"chi2\": {}, \"dof\": {}, \"p_value\": {}, "
                       "\"alpha\": {}, \"pdf_integral\": {}, \"mean_weight\": {}, \"standard_error\": {}, "
                       "\"albedo\": {}, \"max_weight\": {}, \"outside\": {}, \"weight_mismatches\": {}, "
                       "\"uncovered\": {}, \"in_empty_cells\": {}, \"negative\": {}, \"min_f\": {}, "
                       "\"non_finite\": {}, \"passes\": {}}}",
                       i ? "," : "", a.theta_deg, a.valid_samples, json_number(a.chi2), a.dof, json_number(a.p_value),
                       a.alpha, json_number(a.pdf_integral), json_number(a.mean_weight), json_number(a.standard_error),
                       json_number(a.albedo), json_number(a.max_weight), a.outside, a.weight_mismatches,
                       a.uncovered_nodes, a.unexpected_samples, a.negative_samples, json_number(a.min_f),
                       a.non_finite_samples, a.passes());
  }
  return out + "\n]}\n";
}

void run_sampling_check(CheckCliOptions& o) {
  if (!o.n.empty() || !o.sweep.empty())
    throw InvalidArgument("--sampling checks one parameter set: give the parameters with -p NAME=VALUE");
  o.sampling_options.theta_deg = option_values("--theta-i", o.sampling_theta, kMaxSamplingAngles);
  const std::size_t angles = o.sampling_options.theta_deg.size();
  if (o.sampling_options.samples > kMaxSamplingTotal / angles)
    throw InvalidArgument(fmt::format("--samples {} at {} angles is {} samples, more than the {} a check may draw",
                                      o.sampling_options.samples, angles, o.sampling_options.samples * angles,
                                      kMaxSamplingTotal));
  o.sampling_options.seed = o.check.seed;
  const Model model = o.model.make();
  const sampling::SamplingCheck c = sampling::check_sampling(sampling::Sampler(model), o.sampling_options);
  std::cout << (o.json ? sampling_json(model, c) : sampling_text(model, c)) << std::flush;
  if (!o.out.empty()) render::write_png(o.out, render::sampling_heatmap(c));
  if (!c.passes()) throw CheckFailed();
}

}  // namespace

void add_check_command(CLI::App& app) {
  auto o = std::make_shared<CheckCliOptions>();
  auto* cmd = app.add_subcommand("check", "Check energy conservation at every angle, reciprocity and non-negativity");
  o->model.add_to(*cmd);
  o->model.add_coef_to(*cmd);
  cmd->add_option("--n", o->n, "Check at each of these n (list or range, at most 1000 values)");
  cmd->add_option("--sweep", o->sweep,
                  "Check at each value of another parameter: NAME=RANGE (e.g. alpha=0.05:0.5@4; at most 1000 values)");
  cmd->add_option("--pairs", o->check.reciprocity_pairs, "Random direction pairs for reciprocity, [1, 1e7]")
      ->capture_default_str()->check(CLI::Range(1, kMaxPairs));
  cmd->add_option("--seed", o->check.seed, "Seed of the direction pairs")->capture_default_str();
  cmd->add_option("--step", o->check.grid_step_deg, "θ_i grid step in degrees before refinement")
      ->capture_default_str()->check(CLI::Range(0.01, 45.0));
  cmd->add_option("--grazing", o->grazing,
                  "Grazing angles (degrees, < 90) probed beyond the grid, e.g. 89.99,89.999 to see "
                  "divergence at grazing (seconds per angle for Cook-Torrance)")
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Print JSON instead of text");
  cmd->add_option("--out,-o", o->out, "Write to FILE (atomically) instead of stdout; with --sampling, the heat map (PNG)");
  cmd->add_flag("--sampling", o->sampling,
                "Check the model's importance sampler instead: χ² goodness of fit, weights, coverage, ∫pdf ≤ 1 and "
                "the mean weight against the albedo, at each --theta-i (docs/sampling.md)");
  cmd->add_option("--theta-i", o->sampling_theta, "--sampling: incidence angles in degrees, [0, 90), at most 20")
      ->capture_default_str();
  cmd->add_option("--samples", o->sampling_options.samples, "--sampling: samples per angle, [1e3, 3e7], at most 3e7 over all angles (about a minute)")
      ->capture_default_str()->check(CLI::Range(std::size_t{1000}, kMaxSamplingTotal));
  cmd->add_option("--bins", o->sampling_options.cos_bins,
                  "--sampling: grid cells in cos θ_o (φ_o has twice as many), [4, 128]")
      ->capture_default_str()->check(CLI::Range(4, 128));
  cmd->footer(
      "For each parameter value: the albedo ρ(θ_i) at normal incidence and its maximum over θ_i\n"
      "(energy conservation: max ρ ≤ 1), reciprocity f(l,v) = f(v,l) and f ≥ 0 over seeded random\n"
      "direction pairs. Exit 0 when all hold, 1 when one fails, 2 on usage errors. Examples:\n"
      "  specula check --model log-normalized --n 1,20,1000\n"
      "  specula check --model cook-torrance-1982            # reflects ~4× what it receives\n"
      "  specula check --model ggx -p alpha=0.1 --sampling -o ggx-chi2.png   # the sampler, by χ²\n"
      "  specula check --model log-normalized -p n=20 --form nh   # k made for rv breaks in nh\n"
      "  specula check --model log -p n=20 --form nh --coef $(specula normalize --model log --form nh --n 20 | tail -1 | cut -d, -f2)");
  cmd->callback([o] {
    if (o->sampling) return run_sampling_check(*o);
    o->check.grazing_deg = option_values("--grazing", o->grazing, kMaxGrazing);
    auto [sweep, values] = sweep_of(*o);
    const auto cases = queries::check_cases({o->model.spec(), sweep, values, o->check}, queries::Spelling::option);
    const double last_probe = std::max(89.0, *std::max_element(o->check.grazing_deg.begin(), o->check.grazing_deg.end()));
    write_output(o->out, o->json ? queries::check_json(cases) : text_report(cases, last_probe));
    for (const auto& c : cases)
      if (!c.result.all_hold()) throw CheckFailed();
  });
}

}  // namespace specula::cli
