// The designer's pipeline (include/specula/design/design.h): enumerate shapes by the cost model,
// screen each on a few parameter values, fit the promising ones on a finer grid, give their
// constants laws in the parameter, measure each finished lobe over the whole domain, time the
// front and the references as native code in one harness, and keep the Pareto front.
#include "specula/design/design.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <map>
#include <mutex>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>
#include <unordered_set>

#include "fitting.h"
#include "laws.h"
#include "precision.h"
#include "native.h"
#include "process.h"
#include "seeds.h"
#include "shapes.h"
#include "specula/catalogue/catalogue.h"
#include "specula/glsl/glsl.h"
#include "specula/interrupt/interrupt.h"
#include "specula/simd/lobes.h"
#include "certify.h"
#include "checks.h"
#include "spirv.h"
#include "verify.h"

namespace specula::design {

namespace {

constexpr std::size_t kScreenGrid = 5;   // parameter values every shape is fitted at
constexpr std::size_t kFineGrid = 17;    // … and the promising ones
constexpr std::size_t kPerCost = 3;      // shapes kept per cost that do not improve the front
constexpr double kKeepWithin = 1.5;      // … when within this factor of the front's best so far
constexpr std::size_t kMaxCandidates = 40;
static_assert(2 * kMaxCandidates <= Ranges::front_members, "a front (each candidate fitted for both objectives) is what --merge reads");
constexpr std::size_t kChunk = 64;       // shapes screened between budget checks

using Clock = std::chrono::steady_clock;

class Stopper {
 public:
  explicit Stopper(const Settings& s) : s_(s), start_(Clock::now()) {}
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  bool cancelled() const { return stop_requested() != 0 || (s_.cancel && s_.cancel->load()); }
  bool out_of_time() const { return seconds() >= s_.time_s; }

 private:
  const Settings& s_;
  Clock::time_point start_;
};

struct Screened {
  std::size_t shape;
  GridFit fit;
};

std::vector<Samples> samples_over(const Settings& s, std::size_t count) {
  std::vector<Samples> out;
  for (double p : param_grid(s.lo, s.hi, count)) out.push_back(samples_at(s, p));
  return out;
}

// Shapes worth the fine grid: each that lowers the best error of every cheaper shape, and up to
// kPerCost more per cost within kKeepWithin of it.
std::vector<std::size_t> promising(const std::vector<Shape>& shapes, const std::vector<Screened>& screened) {
  std::vector<const Screened*> order;
  for (const auto& x : screened)
    if (x.fit.ok()) order.push_back(&x);
  std::ranges::stable_sort(order, [&](auto* a, auto* b) {
    const int ca = shapes[a->shape].cost, cb = shapes[b->shape].cost;
    return ca < cb || (ca == cb && a->fit.worst < b->fit.worst);
  });
  std::vector<std::size_t> out;
  double best = INFINITY;
  std::map<int, std::size_t> kept_at_cost;
  for (const Screened* x : order) {
    const int cost = shapes[x->shape].cost;
    const bool improves = x->fit.worst < best * (1 - 1e-3);
    if (improves || (x->fit.worst < best * kKeepWithin && kept_at_cost[cost] < kPerCost)) {
      out.push_back(x->shape);
      ++kept_at_cost[cost];
    }
    best = std::min(best, x->fit.worst);
  }
  // The most promising first when there are too many: those that improve the front come first by cost.
  if (out.size() > kMaxCandidates) out.resize(kMaxCandidates);
  return out;
}

double objective_error(const Lobe& l, Objective o) {
  return o == Objective::max_rel ? l.max_rel : l.max_abs;
}

// Whether a is at least as good as b on cost and every objective and better on one.
bool dominates(const Lobe& a, const Lobe& b, Objective o, bool timed) {
  const double ca = timed ? a.ns_per_eval : a.model_cost, cb = timed ? b.ns_per_eval : b.model_cost;
  std::vector<std::pair<double, double>> axes{{ca, cb}};
  if (o != Objective::max_rel) axes.emplace_back(a.max_abs, b.max_abs);
  if (o != Objective::max_abs) axes.emplace_back(a.max_rel, b.max_rel);
  bool better = false;
  for (auto [x, y] : axes) {
    if (x > y) return false;
    better |= x < y;
  }
  return better;
}

std::vector<Lobe> pareto(std::vector<Lobe> lobes, Objective o, bool timed) {
  std::vector<Lobe> out;
  for (const auto& a : lobes)
    if (std::ranges::none_of(lobes, [&](const Lobe& b) { return dominates(b, a, o, timed); })) out.push_back(a);
  std::ranges::stable_sort(out, [&](const Lobe& a, const Lobe& b) {
    return (timed ? a.ns_per_eval < b.ns_per_eval : a.model_cost < b.model_cost);
  });
  return out;
}

void set_errors(Lobe& l, const DomainError& e) {
  l.max_abs = e.max_abs;
  l.argmax_c = e.argmax_c;
  l.argmax_param = e.argmax_param;
  l.max_rel = e.max_rel;
}

// The shape fitted on the fine grid, its constants given laws, its error measured over the whole
// domain; nullopt where a fit fails or a stop came first.
std::optional<Lobe> finished_lobe(const Shape& shape, std::span<const Samples> fine, const Settings& s,
                                  const std::function<bool()>& stop) {
  const GridFit fitted = fit_over_grid(shape, fine, s);
  if (!fitted.ok()) return std::nullopt;
  const auto lawful = constant_laws(shape, fine, fitted, s, stop);
  if (!lawful || !std::isfinite(lawful->grid_error) || stop()) return std::nullopt;
  Lobe l;
  l.formula = expr::to_infix(lawful->lobe);
  l.shape = shape.key;
  l.model_cost = shape.cost;
  set_errors(l, domain_error(l, s, stop));
  if (stop()) return std::nullopt;  // a measurement cut short understates
  return l;
}

// The members of a target of several outputs made of each output's own: every output designed
// alone (output_targets; its share of the time, untimed), and each tuple of their fronts' members
// — at most kJoinedTuples, the fronts thinned evenly from cheapest to most accurate — as one
// formula (stacked_formula), measured over the whole target. Shares nothing between the outputs
// but what the compiler finds common; the search over the whole finds what a formula can share.
constexpr std::size_t kJoinedTuples = 100;

// Whether a function target's formula reads its range parameter.
bool reads_range_parameter(const Settings& s) {
  Settings without = s;
  without.param.clear();
  try {
    (void)function_expression(without);
    return false;  // parses without it as a variable: it does not read it
  } catch (const InvalidArgument&) {
    return true;
  }
}

std::vector<Lobe> joined_members(const Settings& s, const Stopper& stopper) {
  const std::vector<std::string> targets = output_targets(s.target);
  std::vector<std::vector<Lobe>> fronts;
  for (const std::string& target : targets) {
    Settings alone = s;
    alone.target = target;
    alone.variables.pop_back();  // the output index
    alone.time_s = s.time_s / static_cast<double>(targets.size() + 1);
    alone.measure_cost = false;
    alone.gpu_timer = {};
    alone.precision = Precision::f64;
    if (!s.param.empty() && !reads_range_parameter(alone)) {  // a part without the range parameter
      alone.param.clear();
      alone.lo = alone.hi = 1;
    }
    const Result r = design(alone);
    if (r.cancelled || stopper.cancelled()) return {};
    fronts.push_back(r.front);
  }
  const auto per_front = static_cast<std::size_t>(
      std::max(1.0, std::floor(std::pow(static_cast<double>(kJoinedTuples), 1.0 / static_cast<double>(fronts.size())))));
  for (auto& front : fronts)
    if (front.size() > per_front) {
      std::vector<Lobe> thinned;
      for (std::size_t j = 0; j < per_front; ++j)
        thinned.push_back(front[per_front == 1 ? front.size() - 1 : j * (front.size() - 1) / (per_front - 1)]);
      front = std::move(thinned);
    }
  std::vector<Lobe> out;
  std::vector<std::size_t> pick(fronts.size(), 0);
  for (;;) {
    std::vector<std::string> formulas, shapes;
    Lobe l;
    for (std::size_t i = 0; i < fronts.size(); ++i) {
      const Lobe& part = fronts[i][pick[i]];
      formulas.push_back(part.formula);
      shapes.push_back(part.shape);
      l.model_cost += part.model_cost;
    }
    l.formula = stacked_formula(formulas);
    l.shape = "each output alone: " + fmt::format("{}", fmt::join(shapes, " | "));
    l.model_cost = std::min(l.model_cost, Ranges::member_cost);
    set_errors(l, domain_error(l, s, [&] { return stopper.cancelled(); }));
    if (stopper.cancelled()) return {};
    if (std::isfinite(objective_error(l, s.objective))) out.push_back(std::move(l));
    std::size_t i = 0;
    while (i < pick.size() && ++pick[i] == fronts[i].size()) pick[i++] = 0;
    if (i == pick.size()) break;
  }
  return out;
}

// The built-in bare lobes with the range parameter (one per family), and the spherical Gaussian
// e^(n(c − 1)) where the parameter is n.
std::vector<Lobe> reference_lobes(const Settings& s) {
  std::vector<Lobe> out;
  if (is_function_target(s.target)) {  // a term's: the engines' approximations and the term itself
    ParamValues fixed = s.params;  // the target's other parameters, given or at their defaults
    const auto info = model_definition("lobe: " + (is_tabulated(s.target) ? std::string("c") : function_formula(s.target)));
    for (const ParamInfo& p : info->params)  // a lobe formula's free names: the per-pixel variables are not parameters
      if (p.name != s.param && std::ranges::find(s.variables, p.name) == s.variables.end()) fixed.emplace(p.name, p.default_value);
    for (const TermReference& r : term_references()) {
      if (r.term != s.target) continue;
      Lobe l;
      l.id = r.id;
      l.reference = l.evaluable = true;
      l.formula = with_values(r.formula, fixed);
      out.push_back(std::move(l));
    }
    return out;
  }
  for (const ModelInfo& info : models()) {
    if (!info.is_builtin() || info.kind != ModelKind::lobe || info.normalization != Normalization::none) continue;
    const ParamInfo* p = info.find_param(s.param);
    if (!p || !p->accepts(s.lo) || !p->accepts(s.hi)) continue;
    Lobe l;
    l.id = info.id;
    l.reference = true;
    l.formula = info.summary;
    out.push_back(std::move(l));
  }
  if (s.param == "n") {
    Lobe l;
    l.id = "spherical-gaussian";
    l.reference = true;
    l.evaluable = true;
    l.formula = "exp(n * (c - 1))";
    out.push_back(std::move(l));
  }
  return out;
}

// Times every lobe in one harness: formulas compiled as native kernels, built-ins through the
// benchmark's kernels at their fastest tier. Returns a note on how.
std::string time_lobes(std::vector<Lobe*> lobes, const Settings& s, const Stopper& stopper) {
  const double p = timing_param(s);
  std::vector<NativeLobe> natives;
  std::vector<Lobe*> native_lobes, builtin_lobes;
  for (Lobe* l : lobes) {
    if (is_formula(*l)) {
      natives.push_back({is_function_target(s.target) ? shader_expression(s, l->formula) : expr::parse(l->formula, formula_variables(s)),
                         p, shader_variables(s)});
      native_lobes.push_back(l);
    } else {
      builtin_lobes.push_back(l);
    }
  }
  std::vector<cost::FloatKernel> kernels;
  std::vector<std::pair<Lobe*, std::string>> timed;
  std::string note;
  const ScratchDirectory work;
  std::optional<NativeKernels> compiled;
  try {
    compiled.emplace(natives, work.path(), [&] { return stopper.cancelled(); });
    for (std::size_t i = 0; i < natives.size(); ++i) {
      native_lobes[i]->ops = compiled->operations()[i];
      if (kernel_deviation(compiled->kernels()[i], natives[i]) > 1e-4) continue;  // not the formula: untimed
      kernels.push_back(compiled->kernels()[i]);
      timed.emplace_back(native_lobes[i], "native Highway kernel, float");
    }
    note = fmt::format("native kernels compiled by {} -O2 -march=native; built-ins by specula bench's kernels; "
                       "ns per value in cache, one core, float{}",
                       native_compiler(), s.param.empty() ? std::string() : fmt::format(", at {} = {:g}", s.param, p));
  } catch (const Interrupted&) {
    throw;
  } catch (const std::runtime_error& e) {
    note = fmt::format("formula lobes not timed ({}): their cost is the cost model's", e.what());
  }
  for (Lobe* l : builtin_lobes) {
    const lobes::Lobe lobe = lobe_at(*l, s)(p).lobe();
    for (cost::Path path : {cost::Path::exact, cost::Path::fast}) {
      kernels.push_back(cost::lobe_kernel(lobe, path));
      timed.emplace_back(l, fmt::format("specula bench kernel, {} tier, float", cost::to_string(path)));
    }
  }
  cost::Settings harness = cost::Settings::quick();
  harness.trials = 7;
  const std::vector<double> ns = cost::time_in_cache(kernels, harness);
  for (std::size_t i = 0; i < timed.size(); ++i) {
    Lobe* l = timed[i].first;
    if (std::isnan(l->ns_per_eval) || ns[i] < l->ns_per_eval) {
      l->ns_per_eval = ns[i];
      l->timing = timed[i].second;
    }
  }
  return note;
}

// A lobe or function as `float specula_term(variables…, parameter)` for the GPU axis at
// timing_param: a formula through its expression's GLSL with the parameter's value written in (its
// subexpressions then fold at compile time, as a renderer's uniforms are computed once per
// material: not per pixel), a built-in lobe through its model's lobe function; nullopt for a
// built-in whose GLSL has no lobe function of c and the parameter.
std::optional<GpuFunction> gpu_function(const Lobe& l, const Settings& s) {
  const double p = timing_param(s);
  GpuFunction f{{}, static_cast<int>(shader_variables(s)), !s.param.empty(), p};
  std::string arguments;
  for (const auto& name : formula_variables(s))
    if (name != kOutputVariable || output_count(s.target) == 1) arguments += (arguments.empty() ? "float " : ", float ") + name;
  if (is_formula(l)) {
    Settings at_p = s;
    if (!s.param.empty()) at_p.params[s.param] = p;
    at_p.param.clear();
    f.glsl = fmt::format("float specula_term({}) {{\n  return {};\n}}\n", arguments,
                         expr::to_glsl(shader_expression(at_p, l.formula)));
    return f;
  }
  // The model's lobe function, `float specula_<family or id>_lobe(float c[, float n])` (a family's
  // is named after the family: phong's is specula_power_lobe).
  const std::string model = glsl::model_glsl(lobe_at(l, s)(p));
  const std::size_t at = model.find("_lobe(float c");
  const std::size_t start = model.rfind("float specula_", at);
  if (at == std::string::npos || start == std::string::npos) return std::nullopt;
  const std::string name = model.substr(start + 6, at + 5 - start - 6);
  const std::string parameters = model.substr(at + 13, model.find(')', at) - at - 13);  // "" or ", float n"
  if (parameters.empty() == f.has_param || std::ranges::count(parameters, ',') > 1) return std::nullopt;
  f.glsl = fmt::format("{}float specula_term({}) {{\n  return {}({});\n}}\n", model, arguments, name,
                       f.has_param ? "c, " + s.param : std::string("c"));
  return f;
}

// The front and the references timed on the GPU (Settings::gpu_timer), and each member's place on
// the front of GPU cost against error among the front's members; the note names the device.
std::string time_on_gpu(Result& result) {
  const Settings& s = result.settings;
  std::vector<Lobe*> lobes;
  std::vector<GpuFunction> functions;
  for (auto* list : {&result.front, &result.references})
    for (Lobe& l : *list)
      if (const auto f = gpu_function(l, s)) {
        lobes.push_back(&l);
        functions.push_back(*f);
      }
  const GpuTiming timing = s.gpu_timer(functions);
  if (timing.ps.size() != functions.size()) return "GPU not timed: " + timing.device;
  for (std::size_t i = 0; i < lobes.size(); ++i) lobes[i]->gpu_ps_per_eval = timing.ps[i];
  for (Lobe& m : result.front)
    m.gpu_front = std::isfinite(m.gpu_ps_per_eval) && std::ranges::none_of(result.front, [&](const Lobe& o) {
      return &o != &m && std::isfinite(o.gpu_ps_per_eval) && o.gpu_ps_per_eval <= m.gpu_ps_per_eval &&
             objective_error(o, s.objective) < objective_error(m, s.objective);
    });
  return fmt::format("GPU: ps per evaluation beyond F = {}'s, a fragment shader over 256² pixels × 64 evaluations, "
                     "float, on {}", s.variables.front(), timing.device);
}

// Each member's and evaluable reference's error bounded by interval arithmetic (certify.h); where
// a box's centre shows a larger error than the measurement found, that is the claim.
void certify_errors(Result& result, const std::function<bool()>& stop) {
  const Settings& s = result.settings;
  std::vector<Lobe*> lobes;
  for (auto* list : {&result.front, &result.references})
    for (Lobe& l : *list)
      if (is_formula(l)) lobes.push_back(&l);
  tbb::task_arena arena(s.threads > 0 ? s.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, lobes.size(), [&](std::size_t i) {
      if (stop()) return;
      Lobe& l = *lobes[i];
      const Certified c = certify(s, l.formula, l.max_abs, stop);
      if (stop()) return;  // cut short: no bound
      l.max_abs_bound = c.bound;
      if (c.found > l.max_abs) {
        l.max_abs = c.found;
        l.argmax_c = c.where[0];
        if (!s.param.empty()) l.argmax_param = c.where.back();
      }
    });
  });
}

// SPIR-V instructions of every member and reference (spirv.h); the note says how, or why not.
std::string count_spirv(Result& result, const std::function<bool()>& stop) {
  const Settings& s = result.settings;
  const bool function = is_function_target(s.target);
  const ScratchDirectory work("spirv");
  std::string why;
  const auto count = [&](Lobe& l) {
    if (!why.empty()) return;
    const auto n = function ? function_spirv_instructions(shader_expression(s, l.formula), shader_variables(s), work.path(), stop, why)
                            : lobe_spirv_instructions(lobe_at(l, s)(timing_param(s)), work.path(), stop, why);
    if (n) l.spirv_instructions = *n;
  };
  for (auto& l : result.front) count(l);
  for (auto& l : result.references) count(l);
  if (!why.empty()) return "SPIR-V not counted: " + why;
  return function ? fmt::format("SPIR-V: instructions of the function beyond F = {}'s, glslangValidator -V (no optimizer)",
                                s.variables.front())
                  : "SPIR-V: instructions of the lobe beyond F = c's, glslangValidator -V (no optimizer)";
}

// The Pareto front of `candidates` with every member passing `specula check` normalized: a member
// that fails leaves for `refused` (its check says why) and the front is taken again without it,
// until none fails. A function of c is not a lobe: nothing to normalize or check ("-").
std::vector<Lobe> passing_front(std::vector<Lobe> candidates, std::vector<Lobe>& refused, const Settings& s, bool timed,
                                const std::function<bool()>& stop) {
  for (;;) {
    std::vector<Lobe> front = pareto(candidates, s.objective, timed);
    std::vector<std::string> failing;
    for (Lobe& m : front) {
      const auto it = std::ranges::find(candidates, m.formula, &Lobe::formula);
      if (it->check.empty()) is_function_target(s.target) ? void(it->check = "-") : normalize_and_check(*it, s, stop);
      m = *it;
      if (m.check != "pass" && m.check != "-") failing.push_back(m.formula);
    }
    if (failing.empty()) return front;
    for (const std::string& formula : failing) {
      const auto it = std::ranges::find(candidates, formula, &Lobe::formula);
      refused.push_back(std::move(*it));
      candidates.erase(it);
    }
  }
}

// The members placed against the references, measured in the same run: the references' errors,
// every lobe timed, the Pareto front with its ids.
template <class Tell>
void finish_front(std::vector<Lobe> members, Result& result, const Stopper& stopper, const Tell& tell) {
  const Settings& s = result.settings;
  const auto stop = [&] { return stopper.cancelled(); };
  if (s.precision != Precision::f64 && !result.cancelled) {
    tell("rounding constants", 0, static_cast<std::int64_t>(members.size()), nullptr);
    const std::vector<Samples> rows = samples_over(s, kFineGrid);
    tbb::task_arena arena(s.threads > 0 ? s.threads : tbb::task_arena::automatic);  // the search's threads, no more
    arena.execute([&] {
      tbb::parallel_for(std::size_t{0}, members.size(), [&](std::size_t i) {
        if (stop()) return;
        round_member(members[i], rows, s, objective_error(members[i], s.objective));
        set_errors(members[i], domain_error(members[i], s, stop));
      });
    });
    if (stop()) result.cancelled = true;
    std::erase_if(members, [&](const Lobe& m) { return !std::isfinite(objective_error(m, s.objective)); });
  }
  // Every finished lobe stays a candidate (not only the cost model's front): one that a refused
  // member dominated may enter the front in its place.
  result.references = reference_lobes(s);
  if (!result.cancelled) {
    try {
      for (auto& r : result.references) set_errors(r, domain_error(r, s, stop));
    } catch (const Interrupted&) {
      result.cancelled = true;
    }
  }
  if (result.cancelled || stop()) {
    result.cancelled = true;
    result.references.clear();  // not measured: nothing to place the front against
  }
  if (s.measure_cost && !result.cancelled) {
    std::vector<Lobe*> all_lobes;
    for (auto& m : members) all_lobes.push_back(&m);
    for (auto& r : result.references) all_lobes.push_back(&r);
    tell("timing", 0, static_cast<std::int64_t>(all_lobes.size()), nullptr);
    try {
      result.cost_note = time_lobes(all_lobes, s, stopper);
    } catch (const Interrupted&) {
      result.cancelled = true;
      result.cost_note = "not timed (stopped): cost is the cost model's";
    }
  } else {
    result.cost_note = "not timed: cost is the cost model's";
  }
  const bool timed = std::ranges::all_of(members, [](const Lobe& m) { return std::isfinite(m.ns_per_eval); });
  const std::string prefix = s.target.find(':') == std::string::npos ? s.target
                             : std::string(is_function_target(s.target) ? "expr" : "lobe");
  const auto name = [&](std::vector<Lobe>& lobes, std::string_view kind) {
    for (std::size_t i = 0; i < lobes.size(); ++i) lobes[i].id = fmt::format("{}-{}{}", prefix, kind, i + 1);
  };
  if (result.cancelled) {  // not checked: the front as it stands
    result.front = pareto(std::move(members), s.objective, timed);
    name(result.front, "d");
  } else {
    tell("checking", 0, static_cast<std::int64_t>(members.size()), nullptr);
    try {
      result.front = passing_front(std::move(members), result.refused, s, timed, stop);
      name(result.front, "d");
      name(result.refused, "refused");
      if (s.certify && certifiable(s)) {
        tell("certifying", 0, static_cast<std::int64_t>(result.front.size() + result.references.size()), nullptr);
        certify_errors(result, stop);
      }
      result.spirv_note = s.measure_cost ? count_spirv(result, stop) : "SPIR-V not counted: no cost measured (--no-timing)";
      if (s.gpu_timer && s.measure_cost && !stop()) result.gpu_note = time_on_gpu(result);
    } catch (const Interrupted&) {
      result.cancelled = true;
    }
    if (stop()) result.cancelled = true;
  }
  result.seconds = stopper.seconds();
  tell("done", 1, 1, &result.front);
}

// A function target on its fits' rows at every value of the measurement's grid: finite, ≥ 0 and
// at most Ranges::target_max.
void validate_function_values(const Settings& s) {
  for (double p : param_grid(s.lo, s.hi, kVerifyGrid)) {
    const Samples rows = function_rows(s, p);
    for (std::size_t r = 0; r < rows.value.size(); ++r) {
      const double v = rows.value[r];
      if (std::isfinite(v) && v >= 0 && v <= Ranges::target_max) continue;
      std::string at;
      for (std::size_t i = 0; i < s.variables.size(); ++i) at += fmt::format("{}{} = {:.6g}", i ? ", " : "", s.variables[i], rows.x[i][r]);
      if (!s.param.empty()) at += fmt::format(", {} = {:.6g}", s.param, p);
      throw InvalidField("target", fmt::format("the target '{}' is {} at {} ({:g}): a target must be finite, ≥ 0 and at most "
                                               "{:g} over the box", s.target, !std::isfinite(v) ? "not finite" : v < 0 ? "negative" : "too large",
                                               at, v, Ranges::target_max));
    }
  }
}

// The target on the probe at every value of the measurement's grid: finite, ≥ 0 and at most
// Ranges::target_max, as the fits and the measurement need it.
void validate_target_values(const Settings& s) {
  if (is_function_target(s.target)) return validate_function_values(s);
  for (double p : param_grid(s.lo, s.hi, kVerifyGrid)) {
    const lobes::Lobe target = target_at(s, p).lobe();
    for (double u : probe_log_cos()) {
      const double v = lobes::at_log_cos(target, u);
      if (std::isfinite(v) && v >= 0 && v <= Ranges::target_max) continue;
      const std::string what = !std::isfinite(v) ? "not finite" : v < 0 ? "negative" : "too large";
      const std::string at_param = s.param.empty() ? std::string() : fmt::format(", {} = {:.6g}", s.param, p);
      throw InvalidField("target", fmt::format("the target '{}' is {} at c = {:.6g}{} ({:g}): a target must be "
                                               "finite, ≥ 0 and at most {:g} for every c in (0, 1] over the range",
                                               s.target, what, std::exp(-u), at_param, v, Ranges::target_max));
    }
  }
}

// Where a shard came from, for messages.
std::string source_of(const Result& shard, std::size_t index) {
  return shard.source.empty() ? fmt::format("shard {}", index + 1) : shard.source;
}

std::string params_text(const ParamValues& params) {
  std::vector<std::string> out;
  for (const auto& [name, value] : params) out.push_back(fmt::format("{}={}", name, value));
  return out.empty() ? std::string("none") : fmt::format("{}", fmt::join(out, ","));
}

// The settings that make shards one search, each as text at full precision.
std::vector<std::pair<std::string_view, std::string>> search_keys(const Settings& s) {
  return {{"target", s.target},
          {"variables", fmt::format("{}", fmt::join(s.variables, ","))},
          {"parameters", params_text(s.params)},
          {"form", s.form ? to_string(*s.form) : "(the target's own)"},
          {"range", fmt::format("{}={}:{}", s.param, s.lo, s.hi)},
          {"objective", to_string(s.objective)},
          {"zone", fmt::format("{}", s.zone)},
          {"precision", to_string(s.precision)}};
}

// InvalidField "merge" naming the first setting on which a shard's search differs from the first
// shard's, with both values.
void check_one_search(const std::vector<Result>& shards) {
  const auto first = search_keys(shards.front().settings);
  for (std::size_t i = 1; i < shards.size(); ++i) {
    const auto keys = search_keys(shards[i].settings);
    for (std::size_t k = 0; k < keys.size(); ++k)
      if (keys[k].second != first[k].second)
        throw InvalidField("merge", fmt::format("merge: {}: {} {} differs from {}'s {} {}: shards of one search share "
                                                "their target, parameters, form, range, objective and zone",
                                                source_of(shards[i], i), keys[k].first, keys[k].second,
                                                source_of(shards.front(), 0), first[k].first, first[k].second));
  }
}

// A member of the union, and where it was read.
struct Merged {
  Lobe lobe;
  std::string origin;  // "FILE: 'members'[I]"
};

// Each member measured again over the whole domain as design() measures a finished lobe, the
// claimed errors replaced. A member that is not finite somewhere, or whose objective error is not,
// is refused (design() keeps no such lobe); those a stop cut short are left out (a measurement cut
// short understates).
template <class Tell>
std::vector<Lobe> measured_again(std::vector<Merged> members, const Settings& s, const Stopper& stopper,
                                 const Tell& tell) {
  const auto stop = [&] { return stopper.cancelled(); };
  std::vector<std::optional<DomainError>> measured(members.size());
  std::mutex telling;
  std::int64_t done = 0;
  const auto total = static_cast<std::int64_t>(members.size());
  tell("measuring members", 0, total, nullptr);
  tbb::task_arena arena(s.threads > 0 ? s.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, members.size(), [&](std::size_t i) {
      if (stop()) return;
      try {
        const DomainError e = domain_error(members[i].lobe, s, stop);
        if (!stop()) measured[i] = e;
      } catch (const Interrupted&) {
        return;
      }
      const std::lock_guard lock(telling);
      tell("measuring members", ++done, total, nullptr);
    });
  });
  std::vector<Lobe> out;
  for (std::size_t i = 0; i < members.size(); ++i) {
    if (!measured[i]) continue;
    Lobe& l = members[i].lobe;
    const DomainError& e = *measured[i];
    if (!e.finite)
      throw InvalidField("merge", fmt::format("merge: {}: the lobe '{}' is not finite at c = {:g}, {} = {:g}", members[i].origin,
                                              l.formula, e.argmax_c, s.param, e.argmax_param));
    set_errors(l, e);
    if (!std::isfinite(objective_error(l, s.objective)))
      throw InvalidField("merge", fmt::format("merge: {}: the lobe '{}' has no finite {} over the domain", members[i].origin,
                                              l.formula, to_string(s.objective)));
    l.ns_per_eval = NAN;  // timed again, beside the rest, on this machine
    out.push_back(std::move(l));
  }
  return out;
}

}  // namespace

int operation_cost(Operation op) {
  switch (op) {
    case Operation::fma:
    case Operation::mul:
    case Operation::add:
    case Operation::max: return 1;
    case Operation::div:
    case Operation::sqrt: return 4;
    case Operation::exp:
    case Operation::log2: return 10;
  }
  unreachable();
}

std::vector<Operation> parse_operations(std::string_view text) {
  if (text == "all") {
    constexpr auto all = enumerators<Operation, kOperationCount>();
    return std::vector<Operation>(all.begin(), all.end());
  }
  std::vector<Operation> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string_view name = text.substr(start, end - start);
    const auto op = enum_named<Operation, kOperationCount>(name, [](Operation o) { return to_string(o); });
    if (!op)
      throw InvalidField("ops", fmt::format("unknown operation '{}' (known: {}, or all)", name,
                                            names_listed<Operation, kOperationCount>(ToString{}, ", ")));
    if (std::ranges::find(out, *op) == out.end()) out.push_back(*op);
    start = end + 1;
  }
  return out;
}

namespace {

// The range parameter is the target's (or, for a target without parameters, none: lo = hi).
void validate_range(const Settings& s, const ModelInfo& info) {
  if (s.param.empty()) {
    if (!info.params.empty())
      throw InvalidField("range", fmt::format("the target '{}' has parameters: give the range of one with --range", s.target));
    if (s.lo != s.hi) throw InvalidField("range", "a target without parameters has no range: lo = hi");
    return;
  }
  const ParamInfo* p = info.find_param(s.param);
  if (!p) throw InvalidField("range", fmt::format("the target '{}' has no parameter '{}'", s.target, s.param));
  if (!(s.lo < s.hi)) throw InvalidField("range", fmt::format("the range of {} is empty: {:g} to {:g}", s.param, s.lo, s.hi));
  if (!p->accepts(s.lo) || !p->accepts(s.hi))
    throw InvalidField("range", fmt::format("the range {:g}:{:g} is outside {}'s range {}", s.lo, s.hi, s.param, p->range_text()));
}

bool is_identifier(const std::string& name) {
  return !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
         std::ranges::all_of(name, [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; });
}

// A tabulated term: its two variables (μ = N·V, then the roughness, any names; then the output
// index of the pair) and no range.
void validate_tabulated_target(const Settings& s) {
  const std::size_t outputs = output_count(s.target) > 1 ? 1 : 0;
  if (s.variables.size() != 2 + outputs)
    throw InvalidField("vars", fmt::format("the target '{}' takes two per-pixel variables (NoV, r), got {}", s.target,
                                           s.variables.size() - outputs));
  if (!s.param.empty() || s.lo != s.hi)
    throw InvalidField("range", fmt::format("the target '{}' has no parameter: it takes no range", s.target));
}

// A function target: its variables named once each, identifiers, distinct from the parameters and
// each used by the formula; the formula parses in them (any other name is a parameter given its
// value); the range, if any, not empty.
void validate_function_target(const Settings& s) {
  if (s.variables.empty() || s.variables.size() > kMaxVariables)
    throw InvalidField("vars", fmt::format("a target has 1 to {} per-pixel variables, got {}", kMaxVariables, s.variables.size()));
  if (const int outputs = output_count(s.target); outputs > 1) {
    if (outputs > kMaxOutputs)
      throw InvalidField("target", fmt::format("a target has at most {} outputs (parts between ';'), got {}", kMaxOutputs, outputs));
    if (s.variables.size() < 2 || !is_output_variable(s, s.variables.size() - 1))
      throw InvalidField("vars", fmt::format("a target of {} outputs takes its per-pixel variables and then '{}' (the output index)",
                                             outputs, kOutputVariable));
    if (function_formula(s.target).find("*()") != std::string::npos)
      throw InvalidField("target", "an output of the target is empty (nothing between two ';')");
  }
  for (std::size_t i = 0; i < s.variables.size(); ++i) {
    const std::string& v = s.variables[i];
    if (!is_identifier(v)) throw InvalidField("vars", fmt::format("'{}' is not a variable name", v));
    if (std::ranges::count(s.variables, v) > 1) throw InvalidField("vars", fmt::format("the variable {} is named twice", v));
    if (v == s.param || s.params.contains(v))
      throw InvalidField("vars", fmt::format("{} is a parameter and a per-pixel variable at once", v));
  }
  if (is_tabulated(s.target)) return validate_tabulated_target(s);
  const expr::Expression f = [&] {
    try {
      return function_expression(s);
    } catch (const InvalidArgument& e) {
      throw InvalidField("target", fmt::format("the target '{}': {}", s.target, e.what()));
    }
  }();
  for (std::uint32_t i = 0; i < s.variables.size(); ++i)
    if (std::ranges::none_of(f.nodes(), [&](const expr::Node& n) { return n.op == expr::Op::variable && n.var == i; }))
      throw InvalidField("vars", fmt::format("the target does not use the variable {}", s.variables[i]));
  if (s.param.empty()) {
    if (s.lo != s.hi) throw InvalidField("range", "a target without parameters has no range: lo = hi");
    return;
  }
  if (!(s.lo < s.hi) || !std::isfinite(s.lo) || !std::isfinite(s.hi))
    throw InvalidField("range", fmt::format("the range of {} is empty or not finite: {:g} to {:g}", s.param, s.lo, s.hi));
  if (std::ranges::none_of(f.nodes(), [&](const expr::Node& n) { return n.op == expr::Op::variable && n.var == s.variables.size(); }))
    throw InvalidField("range", fmt::format("the target '{}' has no parameter '{}'", s.target, s.param));
}

}  // namespace

void validate(const Settings& s) {
  if (is_function_target(s.target)) {
    validate_function_target(s);
  } else {
    std::shared_ptr<const ModelInfo> info;
    try {
      info = model_definition(s.target, s.params);
    } catch (const InvalidField& e) {  // the catalogue names its argument "model": here it is the target
      throw InvalidField(e.field() == "model" ? "target" : e.field(), e.what());
    }
    if (info->kind != ModelKind::lobe) throw InvalidField("target", fmt::format("the target '{}' is not a lobe model", s.target));
    if (s.variables != kLobeVariables) throw InvalidField("vars", "a lobe's one variable is c: --vars is for functions");
    validate_range(s, *info);
  }
  if (s.lo > 0 && s.hi / s.lo > Ranges::range_ratio)
    throw InvalidField("range", fmt::format("the range spans over {:g} times", Ranges::range_ratio));
  if (s.operations.empty()) throw InvalidField("ops", "no operations to build lobes with");
  if (!(s.max_cost >= 1 && s.max_cost <= Ranges::max_cost))
    throw InvalidField("max_cost", fmt::format("max_cost must be in [1, {}], got {}", Ranges::max_cost, s.max_cost));
  if (s.max_forms && !(*s.max_forms >= 1 && *s.max_forms <= Ranges::forms))
    throw InvalidField("max_forms", fmt::format("max_forms must be in [1, {}], got {}", Ranges::forms, *s.max_forms));
  if (!(s.time_s > 0 && s.time_s <= Ranges::time_s))
    throw InvalidField("time", fmt::format("time must be in (0, {:g}] seconds, got {:g}", Ranges::time_s, s.time_s));
  if (!(s.threads >= 0 && s.threads <= Ranges::threads))
    throw InvalidField("threads", fmt::format("threads must be in [0, {}], got {}", Ranges::threads, s.threads));
  if (!(s.shards >= 1 && s.shards <= Ranges::shards && s.shard >= 0 && s.shard < s.shards))
    throw InvalidField("shard", fmt::format("shard must be I/N with 0 ≤ I < N ≤ {}, got {}/{}", Ranges::shards, s.shard, s.shards));
  if (!(s.zone > 0 && s.zone < 1)) throw InvalidField("zone", fmt::format("zone must be in (0, 1), got {:g}", s.zone));
  for (const auto& [name, value] : s.params)
    if (name == s.param) throw InvalidField("params", fmt::format("{} is the range parameter; give its range with --range", name));
  if (!is_function_target(s.target)) (void)target_at(s, s.lo);  // the other parameters are the target's and in range
  validate_target_values(s);
  if (s.measure_cost) {  // a compiler or time limit the user named but cannot have: said now, not after the search
    (void)native_compiler();
    (void)compile_limit();
  }
}

Result design(const Settings& s, const std::function<void(const Progress&)>& progress) {
  validate(s);
  const Stopper stopper(s);
  const auto stop = [&] { return stopper.cancelled(); };
  Result result;
  result.settings = s;
  const auto tell = [&](std::string_view phase, std::int64_t done, std::int64_t total, const std::vector<Lobe>* front) {
    if (progress) progress({phase, done, total, front, result.forms_screened, result.forms_total});
  };
  tbb::task_arena arena(s.threads > 0 ? s.threads : tbb::task_arena::automatic);

  // 0. A target of several outputs: each output designed alone first (the time shared), their
  // fronts' members joined; then the search over the whole, in the time left, for what they share.
  std::vector<Lobe> joined;
  if (output_count(s.target) > 1) {
    tell("designing each output alone", 0, output_count(s.target), nullptr);
    joined = joined_members(s, stopper);
    if (stopper.cancelled()) result.cancelled = true;
  }

  // 1. The first max_forms shapes (all shards' together), this shard's share, screened on a few
  // parameter values.
  const auto limit = static_cast<std::size_t>(s.max_forms.value_or(Ranges::forms));
  const std::vector<Shape> all =
      enumerate_shapes(s.operations, s.max_cost, limit, [&] { return stopper.cancelled() || stopper.out_of_time(); }, s.variables);
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (static_cast<int>(i % static_cast<std::size_t>(s.shards)) == s.shard) mine.push_back(i);
  result.forms_total = static_cast<std::int64_t>(mine.size());
  tell("screening shapes", 0, result.forms_total, nullptr);
  // The range's middle first: the shapes are told apart there, where a range's end (n = 1, where
  // cⁿ is c) makes many the same.
  std::vector<Samples> screen = samples_over(s, kScreenGrid);
  const auto middle_value = screen.begin() + static_cast<std::ptrdiff_t>(screen.size() / 2);
  std::rotate(screen.begin(), middle_value, middle_value + 1);
  const std::span<const Samples> first_value(screen.data(), 1);
  std::vector<Screened> screened;
  std::unordered_set<std::string> computed;  // value_signature of every shape kept so far
  double best_screened = INFINITY;            // the lowest error over the screening grid so far
  for (std::size_t first = 0; first < mine.size(); first += kChunk) {
    if (stopper.cancelled() || stopper.out_of_time()) {
      result.cancelled = stopper.cancelled();
      break;
    }
    const std::size_t last = std::min(mine.size(), first + kChunk);
    std::vector<Screened> chunk(last - first);
    std::vector<std::string> signatures(last - first);
    // Each shape at the range's middle; one that computes what a cheaper shape computes there
    // (the same signature, decided in the shapes' order: the same for any thread count) goes no
    // further; the others go on over the rest of the screening grid.
    const auto each = [&](auto work) {
      arena.execute([&] {
        tbb::parallel_for(first, last, [&](std::size_t i) {
          if (!stop()) work(i - first, all[mine[i]]);  // a stop ends it at once
        });
      });
    };
    each([&](std::size_t j, const Shape& shape) {
      chunk[j] = {mine[first + j], fit_over_grid(shape, first_value, s)};
      if (chunk[j].fit.ok()) signatures[j] = value_signature(shape, chunk[j].fit.constants[0], screen[0], s);
    });
    std::vector<bool> same(last - first);
    for (std::size_t j = 0; j < chunk.size(); ++j)
      same[j] = !stop() && chunk[j].fit.ok() && !computed.insert(signatures[j]).second;
    // A shape whose error at the middle alone is kKeepWithin times the best of the cheaper shapes
    // screened before it can never be promising (its error over the grid is at least that): the
    // rest of the grid is not fitted. The best is of the chunks before, so the same for any
    // thread count; the promising shapes are those a full screening keeps.
    const double hopeless = kKeepWithin * best_screened;
    each([&](std::size_t j, const Shape& shape) {
      if (same[j]) chunk[j].fit.worst = INFINITY;
      else if (chunk[j].fit.ok() && chunk[j].fit.worst >= hopeless) chunk[j].fit.worst = INFINITY;
      else if (chunk[j].fit.ok()) chunk[j].fit = fit_over_grid(shape, screen, s, {}, &chunk[j].fit);
    });
    for (const Screened& x : chunk) best_screened = std::min(best_screened, x.fit.worst);
    if (stop()) {
      result.cancelled = true;
      break;
    }
    result.forms_same += std::ranges::count(same, true);
    screened.insert(screened.end(), chunk.begin(), chunk.end());
    result.forms_screened = static_cast<std::int64_t>(screened.size());
    tell("screening shapes", result.forms_screened, static_cast<std::int64_t>(mine.size()), nullptr);
  }

  // 2. The promising ones on the fine grid, then laws for their constants and the whole domain;
  // with both objectives, each is fitted once for each (the front then holds either).
  // The engines' forms refitted first (reference_seeds), then the screening's most promising.
  std::vector<Shape> seeds;
  if (s.refit_references)
    for (Seed& seed : reference_seeds(s)) seeds.push_back(std::move(seed.shape));
  std::vector<const Shape*> candidates;
  for (const Shape& seed : seeds) candidates.push_back(&seed);
  for (const std::size_t i : promising(all, screened))
    if (candidates.size() < kMaxCandidates) candidates.push_back(&all[i]);
  std::vector<Settings> fits;
  for (const Objective o : {Objective::max_abs, Objective::max_rel})
    if (s.objective == o || s.objective == Objective::both) {
      fits.push_back(s);
      fits.back().objective = o;
    }
  std::vector<std::vector<Samples>> fine;
  for (const Settings& f : fits) fine.push_back(samples_over(f, kFineGrid));
  const std::size_t tasks = candidates.size() * fits.size();
  std::vector<std::optional<Lobe>> finished(tasks);
  std::mutex finishing;  // guards what follows; progress sees the front of the lobes finished so far
  std::int64_t done = 0;
  std::vector<Lobe> so_far;
  const auto total = static_cast<std::int64_t>(tasks);
  tell("finishing lobes", 0, total, nullptr);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, tasks, [&](std::size_t i) {
      if (stop()) return;
      const std::size_t fit = i % fits.size();
      std::optional<Lobe> lobe;
      try {
        lobe = finished_lobe(*candidates[i / fits.size()], fine[fit], fits[fit], stop);
      } catch (const Interrupted&) {
        return;  // a stop: the lobes finished so far are the result
      }
      const std::lock_guard lock(finishing);
      finished[i] = lobe;
      ++done;
      if (lobe && std::isfinite(objective_error(*lobe, s.objective))) so_far.push_back(*lobe);
      const std::vector<Lobe> front = pareto(so_far, s.objective, false);
      tell("finishing lobes", done, total, &front);
    });
  });
  if (stopper.cancelled()) result.cancelled = true;

  std::vector<Lobe> members = std::move(joined);
  for (auto& l : finished)
    if (l && std::isfinite(objective_error(*l, s.objective))) members.push_back(std::move(*l));
  finish_front(std::move(members), result, stopper, tell);
  return result;
}

Result merge(const std::vector<Result>& shards, const MergeOptions& options,
             const std::function<void(const Progress&)>& progress) {
  if (shards.empty()) throw InvalidField("merge", "nothing to merge");
  check_one_search(shards);
  Result result;
  result.settings = shards.front().settings;
  result.settings.shard = 0;
  result.settings.shards = 1;
  result.settings.measure_cost = options.measure_cost;
  result.settings.threads = options.threads;
  result.settings.cancel = options.cancel;
  validate(result.settings);
  const Stopper stopper(result.settings);
  const auto tell = [&](std::string_view phase, std::int64_t done, std::int64_t total, const std::vector<Lobe>* front) {
    if (progress) progress({phase, done, total, front, result.forms_screened, result.forms_total});
  };
  std::vector<Merged> members;
  std::unordered_set<std::string> formulas;
  for (std::size_t i = 0; i < shards.size(); ++i) {
    const Result& r = shards[i];
    result.forms_screened += r.forms_screened;
    result.forms_total += r.forms_total;
    result.forms_same += r.forms_same;
    result.cancelled |= r.cancelled;
    for (std::size_t j = 0; j < r.front.size(); ++j)
      if (formulas.insert(r.front[j].formula).second)
        members.push_back({r.front[j], fmt::format("{}: 'members'[{}]", source_of(r, i), j)});
  }
  std::vector<Lobe> measured = measured_again(std::move(members), result.settings, stopper, tell);
  result.cancelled |= stopper.cancelled();
  finish_front(std::move(measured), result, stopper, tell);
  return result;
}

}  // namespace specula::design
