// specula.fit and specula.design: symbolic regression over NumPy columns (fit/fit.h, as specula
// fit) and the lobe designer (design/design.h, as specula design), off the GIL, stopped by Ctrl-C.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <atomic>
#include <tuple>
#include <cmath>

#include "binding.h"
#include "specula/design/design.h"
#include "specula/design/output.h"
#include "specula/expr/expr.h"
#include "specula/fit/emit.h"
#include "specula/fit/fit.h"
#include "specula/queries/queries.h"

namespace specula::python {

namespace {

/// A formula of a fit's front: callable on the data's variables.
struct Formula {
  expr::Expression formula;
  int size = 0;
  double train_error = 0;
  std::optional<double> test_error;
};

/// The formula over columns in the order of its variables (the Python side picks them).
py::array_t<double> evaluate_columns(const Formula& f, const std::vector<py::array_t<double, py::array::c_style | py::array::forcecast>>& columns) {
  if (columns.size() != f.formula.variables().size())
    throw InvalidField("X", fmt::format("the formula takes {} variables, got {} columns", f.formula.variables().size(),
                                        columns.size()));
  const py::ssize_t rows = columns.empty() ? 1 : columns.front().size();
  std::vector<std::span<const double>> spans;
  for (const auto& c : columns) {
    if (c.ndim() != 1 || c.size() != rows) throw InvalidField("X", "every variable must be a column of as many rows");
    spans.emplace_back(c.data(), static_cast<std::size_t>(rows));
  }
  py::array_t<double> out(rows);
  double* values = out.mutable_data();
  for_chunks(static_cast<std::size_t>(rows), kMaxChunkValues, [&](std::size_t begin, std::size_t end) {
    std::vector<std::span<const double>> chunk;
    for (const auto& column : spans) chunk.push_back(column.subspan(begin, end - begin));
    expr::evaluate_batch(f.formula, chunk, std::span<double>(values + begin, end - begin));
  });
  return out;
}

std::string shown(const Formula& f) { return expr::to_infix(fit::rounded(f.formula, 6)); }

struct FitResult {
  std::vector<Formula> front;
  std::size_t chosen = 0;
  std::int64_t evaluations = 0, generations = 0;
  double seconds = 0;
  std::string stopped_by;
};

template <class T>
std::optional<T> optional_of(const py::object& x, std::string_view name) {
  return x.is_none() ? std::nullopt : std::optional<T>(argument<T>(x, name));
}

FitResult fit_columns(std::vector<std::string> variables, std::vector<std::vector<double>> columns,
                      std::vector<double> target, const py::dict& kwargs) {
  fit::Data data{std::move(variables), std::move(columns), std::move(target)};
  fit::Options o;
  o.operators = fit::parse_operators(argument<std::string>(kwargs["ops"], "ops"));
  o.constants = fit::parse_constants(argument<std::string>(kwargs["constants"], "constants"));
  o.max_size = argument<int>(kwargs["max_size"], "max_size");
  o.weights = fit::SizeWeights::parse(argument<std::string>(kwargs["size_weights"], "size_weights"));
  o.metric = fit::parse_metric(argument<std::string>(kwargs["metric"], "metric"));
  o.test_fraction = argument<double>(kwargs["test_fraction"], "test_fraction");
  const std::string split = argument<std::string>(kwargs["split"], "split");
  const std::optional<fit::Split> s = fit::split_named(split);
  if (!s) throw InvalidField("split", fmt::format("split must be random or last, got '{}'", split));
  o.split = *s;
  o.seed = argument<std::uint64_t>(kwargs["seed"], "seed");
  o.time_limit_s = argument<double>(kwargs["time"], "time");
  o.max_generations = optional_of<std::int64_t>(kwargs["generations"], "generations");
  o.max_evaluations = optional_of<std::int64_t>(kwargs["evaluations"], "evaluations");
  o.target_error = optional_of<double>(kwargs["target_error"], "target_error");
  o.threads = argument<int>(kwargs["threads"], "threads");
  o.islands = argument<int>(kwargs["islands"], "islands");
  o.population = argument<int>(kwargs["population"], "population");
  o.enumerate_max_size = argument<int>(kwargs["enumerate_size"], "enumerate_size");
  o.choice = fit::parse_choice(argument<std::string>(kwargs["choose"], "choose"));
  o.choose_factor = argument<double>(kwargs["choose_factor"], "choose_factor");
  o.snap = argument<bool>(kwargs["snap"], "snap");
  o.starts = argument<std::vector<std::string>>(kwargs["starts"], "starts");
  const fit::Result r = run_interruptible([&] { return fit::search(data, o); });
  FitResult out{{}, r.chosen, r.evaluations, r.generations, r.seconds, std::string(fit::to_string(r.stopped_by))};
  for (const auto& c : r.front) out.front.push_back({c.formula, c.size, c.train_error, c.test_error});
  return out;
}

}  // namespace
}  // namespace specula::python

// Formula and FitResult check their instance like every bound class (binding.h).
template <>
struct pybind11::detail::type_caster<specula::python::Formula>
    : specula::python::ConstructedCaster<specula::python::Formula> {};
template <>
struct pybind11::detail::type_caster<specula::python::FitResult>
    : specula::python::ConstructedCaster<specula::python::FitResult> {};

namespace specula::python {
namespace {

std::string formula_repr(const Formula& f) {
  return fmt::format("Formula({}, size={}, train_error={:.6g})", python_repr(shown(f)), f.size, f.train_error);
}

py::object number_or_none(double x) { return std::isnan(x) ? py::object(py::none()) : py::object(py::float_(x)); }

py::dict lobe_dict(const design::Lobe& l) {
  py::dict d;
  d["id"] = l.id;
  d["formula"] = l.formula;
  d["shape"] = l.shape;
  d["max_abs"] = l.max_abs;
  d["argmax_c"] = l.argmax_c;
  d["argmax_param"] = l.argmax_param;
  d["max_rel"] = l.max_rel;
  d["max_abs_bound"] = number_or_none(l.max_abs_bound);
  d["ops"] = l.ops;
  d["model_cost"] = l.model_cost;
  d["ns_per_eval"] = number_or_none(l.ns_per_eval);
  d["timing"] = l.timing;
  d["spirv_instructions"] = number_or_none(l.spirv_instructions);
  if (!l.reference) {
    d["k"] = number_or_none(l.k);
    d["k_formula"] = l.k_formula;
    d["check"] = l.check;
    d["precision_error"] = l.precision_error;
    d["precision_note"] = l.precision_note;
  }
  return d;
}

py::list lobe_list(const std::vector<design::Lobe>& lobes) {
  py::list out;
  for (const auto& l : lobes) out.append(lobe_dict(l));
  return out;
}

py::dict design_run(const py::dict& kwargs) {
  design::Settings s;
  s.target = argument<std::string>(kwargs["target"], "target");
  for (const auto& [key, value] : kwargs["params"].cast<py::dict>()) s.params[py::str(key)] = argument<double>(value, "params");
  if (!kwargs["form"].is_none()) s.form = queries::form_named(argument<std::string>(kwargs["form"], "form"), Spelling::key);
  s.variables = design::target_variables(
      s.target, kwargs["vars"].is_none() ? std::vector<std::string>{} : argument<std::vector<std::string>>(kwargs["vars"], "vars"));
  if (kwargs["param"].is_none() && kwargs["range"].is_none()) {  // the target's own range
    const design::DefaultRange r = design::default_range(s.target, s.variables);
    std::tie(s.param, s.lo, s.hi) = std::tie(r.param, r.lo, r.hi);
  } else {
    s.param = kwargs["param"].is_none() ? std::string("n") : argument<std::string>(kwargs["param"], "param");
    const auto range = values_of(kwargs["range"], "range");
    if (range.size() != 2) throw InvalidField("range", "range must be (lo, hi), two numbers");
    s.lo = range[0];
    s.hi = range[1];
  }
  s.objective = choice_named<design::Objective, design::kObjectiveCount>("objective", argument<std::string>(kwargs["objective"], "objective"),
                                                                         Spelling::key);
  s.zone = argument<double>(kwargs["zone"], "zone");
  s.operations = design::parse_operations(argument<std::string>(kwargs["ops"], "ops"));
  s.max_cost = argument<int>(kwargs["max_cost"], "max_cost");
  s.max_forms = optional_of<std::int64_t>(kwargs["max_forms"], "max_forms");
  s.time_s = argument<double>(kwargs["time"], "time");
  s.seed = argument<std::uint64_t>(kwargs["seed"], "seed");
  s.threads = argument<int>(kwargs["threads"], "threads");
  s.measure_cost = argument<bool>(kwargs["measure_cost"], "measure_cost");
  s.precision = choice_named<design::Precision, design::kPrecisionCount>("precision", argument<std::string>(kwargs["precision"], "precision"),
                                                                         Spelling::key);
  design::validate(s);
  const design::Result r = run_interruptible([&] {
    design::Settings with_cancel = s;
    with_cancel.cancel = current_limit().cancel;  // Ctrl-C stops the search
    return design::design(with_cancel);
  });
  py::dict out;
  out["front"] = lobe_list(r.front);
  out["references"] = lobe_list(r.references);
  out["refused"] = lobe_list(r.refused);
  out["toml"] = design::models_toml(r);
  out["csv"] = design::front_csv(r);
  out["table"] = design::front_table(r);
  out["json"] = design::design_json(r);
  out["forms_screened"] = r.forms_screened;
  out["forms_total"] = r.forms_total;
  out["forms_same"] = r.forms_same;
  out["seconds"] = r.seconds;
  out["cancelled"] = r.cancelled;
  out["cost_note"] = r.cost_note;
  return out;
}

}  // namespace

void bind_search(py::module_& m) {
  py::class_<Formula> formula(m, "Formula",
                              "A formula of a fit's front: its text, size and errors; call it on data like X.");
  formula.def_property_readonly("formula", [](const Formula& f) { return expr::to_infix(f.formula); },
                                "The formula with its constants at full precision (parses back bit-identically).")
      .def_property_readonly("text", &shown, "The formula with 6 significant digits, as specula fit prints it.")
      .def_property_readonly("variables", [](const Formula& f) { return f.formula.variables(); })
      .def_readonly("size", &Formula::size)
      .def_readonly("train_error", &Formula::train_error)
      .def_readonly("test_error", &Formula::test_error)
      .def("code", [](const Formula& f, const std::string& language, const std::string& name) {
        if (language != "cpp" && language != "glsl" && language != "latex" && language != "python")
          throw InvalidField("language", fmt::format("language must be cpp, glsl, latex or python, got '{}'", language));
        fit::check_emittable(f.formula.variables(), language);
        return fit::emit_function(f.formula, language, name, fmt::format("specula.fit: size {}, train error {:.6g}",
                                                                          f.size, f.train_error));
      }, py::arg("language"), py::arg("name") = "y",
           "The formula as a function in 'cpp', 'glsl', 'latex' or 'python' (specula fit --emit).")
      .def("_evaluate", &evaluate_columns)
      .def("__str__", &shown)
      .def("__repr__", &formula_repr);
  refuse_pickling(formula);
  py::class_<FitResult> fit_result(m, "FitResult",
                                    "The Pareto front of a fit: formulas by size, each more accurate.");
  fit_result.def_readonly("front", &FitResult::front)
      .def_readonly("chosen", &FitResult::chosen)
      .def_property_readonly("best", [](const FitResult& r) { return r.front.at(r.chosen); },
                             "The chosen formula (choose=…): front[chosen].")
      .def_readonly("evaluations", &FitResult::evaluations)
      .def_readonly("generations", &FitResult::generations)
      .def_readonly("seconds", &FitResult::seconds)
      .def_readonly("stopped_by", &FitResult::stopped_by)
      .def("__repr__", [](const FitResult& r) {
        return fmt::format("FitResult({} formulas, best {}, stopped by {})", r.front.size(),
                           formula_repr(r.front.at(r.chosen)), r.stopped_by);
      });
  refuse_pickling(fit_result);
  m.def("_fit", &fit_columns);
  m.def("_design", &design_run);
}

}  // namespace specula::python
