// The target and the designed and reference lobes as models at a value of the range parameter,
// and the spacing of the range: one place for what the pipeline, the checks, the files and the
// page all evaluate.
#include <cmath>
#include <fmt/format.h>
#include <numeric>

#include "specula/catalogue/catalogue.h"
#include "specula/design/design.h"

namespace specula::design {

bool log_spaced(double lo, double hi) { return lo > 0 && hi / lo >= 4; }

double middle(double lo, double hi) {
  if (!log_spaced(lo, hi)) return std::midpoint(lo, hi);
  const double product = lo * hi;  // below the normal doubles (a subnormal range) or above them: √lo·√hi
  return std::isnormal(product) ? std::sqrt(product) : std::sqrt(lo) * std::sqrt(hi);
}

double timing_param(const Settings& s) {
  if (s.lo <= 20 && 20 <= s.hi) return 20;
  return middle(s.lo, s.hi);
}

Model target_at(const Settings& s, double p) {
  ParamValues params = s.params;
  if (!s.param.empty()) params[s.param] = p;
  Model m = make_model(s.target, params, s.form);
  if (!m.is_lobe()) throw InvalidField("target", fmt::format("the target '{}' is not a lobe model", s.target));
  return m;
}

Form target_form(const Settings& s) {
  if (is_function_target(s.target)) return Form::rv;  // a function of c: its lobe model's form is c's own
  return s.form ? *s.form : target_at(s, s.lo).form();
}

std::vector<std::string> formula_variables(const Settings& s) {
  std::vector<std::string> out = s.variables;
  if (!s.param.empty()) out.push_back(s.param);
  return out;
}

bool is_formula(const Lobe& l) { return !l.reference || l.evaluable; }

std::function<Model(double)> lobe_at(const Lobe& l, const Settings& s) {
  const ParamValues at_lo = s.param.empty() ? ParamValues{} : ParamValues{{s.param, s.lo}};
  const auto info = model_definition(is_formula(l) ? "lobe: " + l.formula : l.id, at_lo);
  const bool reads_param = !s.param.empty() && info->find_param(s.param) != nullptr;  // F = c does not
  return [info, reads_param, param = s.param, form = target_form(s)](double p) {
    ParamValues params;
    if (reads_param) params[param] = p;
    return make_model(info, params, form);
  };
}

}  // namespace specula::design
