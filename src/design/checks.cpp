#include "checks.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <optional>

#include "closed_form.h"
#include "specula/analysis/check.h"
#include "specula/catalogue/catalogue.h"
#include "specula/expr/expr.h"
#include "specula/normalize/normalize.h"

namespace specula::design {

namespace {

constexpr std::size_t kReciprocityPairs = 2000;
constexpr double kClosedFormAgreement = 1e-9;  // relative, closed form against quadrature

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
  const std::function<Model(double)> model_at = lobe_at(l, s);
  const std::optional<std::string> closed = closed_form_k(l.formula, s);
  const std::optional<expr::Expression> k_of_p = closed ? std::optional(expr::parse(*closed, {s.param})) : std::nullopt;
  l.k_formula.clear();
  bool closed_holds = k_of_p.has_value();
  std::vector<std::string> failed;
  for (double p : check_params(s)) {
    if (stop()) return;
    const Model bare = model_at(p);
    const double quadrature = normalize::coefficient(bare.lobe(), bare.form(), normalize::Method::quadrature);
    const double exact = k_of_p ? expr::evaluate(*k_of_p, std::vector<double>{p}) : NAN;
    // The closed form is k itself: it must agree with quadrature (≥ 13 digits) to be shipped.
    closed_holds = closed_holds && std::abs(exact - quadrature) <= kClosedFormAgreement * std::abs(quadrature);
    const double k = closed_holds ? exact : quadrature;
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
  if (closed_holds) l.k_formula = *closed;
  l.check = failed.empty() ? "pass" : fmt::format("fail: {}", fmt::join(failed, "; "));
}

}  // namespace specula::design
