#include "checks.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "specula/analysis/check.h"
#include "specula/catalogue/catalogue.h"
#include "specula/normalize/normalize.h"

namespace specula::design {

namespace {

constexpr std::size_t kReciprocityPairs = 2000;

std::string failures(const analysis::CheckResult& r) {
  std::vector<std::string> out;
  if (!r.conserves_energy)
    out.push_back(fmt::format("energy (ρ = {:.6g} at θ_i = {:.4g}°)", r.max_albedo.value, r.max_albedo.theta_deg));
  if (!r.reciprocal) out.push_back(fmt::format("reciprocity ({:.3g})", r.max_asymmetry));
  if (!r.non_negative) out.push_back(fmt::format("non-negativity (f = {:.3g})", r.min_value));
  return fmt::format("{}", fmt::join(out, ", "));
}

}  // namespace

std::vector<double> check_params(const Settings& s) {
  std::vector<double> out{s.lo, timing_param(s), s.hi};
  std::ranges::sort(out);
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void normalize_and_check(Lobe& l, const Settings& s, const std::function<bool()>& stop) {
  const auto info = model_definition("lobe: " + l.formula, {{s.param, s.lo}});
  std::vector<std::string> failed;
  for (double p : check_params(s)) {
    if (stop()) return;
    ParamValues params;
    if (info->find_param(s.param)) params[s.param] = p;
    ParamValues target_params = s.params;
    target_params[s.param] = p;
    const Form form = s.form ? *s.form : make_model(s.target, target_params).form();
    const Model bare = make_model(info, params, form);
    const double k = normalize::coefficient(bare.lobe(), form, normalize::Method::quadrature);
    if (!(std::isfinite(k) && k > 0)) {
      failed.push_back(fmt::format("{} = {:g}: no finite k", s.param, p));
      continue;
    }
    if (p == timing_param(s)) l.k = k;
    analysis::CheckOptions options;
    options.reciprocity_pairs = kReciprocityPairs;
    const analysis::CheckResult r = analysis::check(bare.with_coef(k), options);
    if (!r.all_hold()) failed.push_back(fmt::format("{} = {:g}: {}", s.param, p, failures(r)));
  }
  l.check = failed.empty() ? "pass" : fmt::format("fail: {}", fmt::join(failed, "; "));
}

}  // namespace specula::design
