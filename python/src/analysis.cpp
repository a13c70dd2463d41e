// specula.normalize, albedo, check, error, glsl and export: the queries the CLI's commands and
// the server compute (queries/queries.h), on NumPy arrays, the long ones off the GIL and stopped
// by Ctrl-C.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "binding.h"
#include "specula/catalogue/fresnel_spec.h"
#include "specula/exports/exports.h"
#include "specula/queries/queries.h"
#include "specula/walk/walk.h"

namespace specula::python {

py::array real_array(const py::handle& x, std::string_view name) {
  const py::array a = py::isinstance<py::array>(x) ? py::reinterpret_borrow<py::array>(x)
                                                   : py::module_::import("numpy").attr("asarray")(x).cast<py::array>();
  const char kind = a.dtype().kind();
  if (kind != 'b' && kind != 'i' && kind != 'u' && kind != 'f')
    throw py::type_error(fmt::format("{} must be real numbers, got an array of {}", name, std::string(py::str(a.dtype()))));
  return a;
}

std::vector<double> values_of(const py::object& x, const char* name) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(real_array(x, name));
  if (!a) throw py::type_error(fmt::format("{} must be a number or an array of numbers", name));
  return {a.data(), a.data() + a.size()};
}

namespace {

using queries::Spelling;

py::array_t<double> column(const io::Table& table, std::string_view name) {
  const auto at = std::find(table.columns.begin(), table.columns.end(), name);
  const auto k = static_cast<std::size_t>(at - table.columns.begin());
  py::array_t<double> out(static_cast<py::ssize_t>(table.rows.size()));
  for (std::size_t i = 0; i < table.rows.size(); ++i) out.mutable_data()[i] = table.rows[i][k];
  return out;
}

/// Parameters of a model but n: normalize and error take n as their own argument.
ParamValues without_n(const PyModel& m) {
  ParamValues out = m.params;
  out.erase("n");
  return out;
}

py::array_t<double> normalize(const py::object& model, const py::object& n, const std::string& method) {
  std::optional<PyModel> storage;
  const PyModel& m = model_argument(model, storage);
  queries::NormalizeQuery q;
  q.model = queries::ModelRef(m.id);
  q.params = without_n(m);
  q.form = m.form;
  q.n = values_of(n, "n");
  q.method = queries::normalize_method_named(method, Spelling::key);
  if (q.method == queries::NormalizeMethod::both) throw InvalidField("method", "method must be auto, exact or quadrature");
  return column(run_interruptible([&] { return queries::normalize_table(q, Spelling::key); }), "coef");
}

py::array_t<double> albedo(const py::object& model, const py::object& theta, const std::string& method,
                           std::uint64_t samples, std::uint64_t seed) {
  std::optional<PyModel> storage;
  const PyModel& m = model_argument(model, storage);
  queries::AlbedoQuery q;
  q.theta_deg = values_of(theta, "theta");
  q.method = queries::albedo_method_named(method, Spelling::key);
  q.samples = samples;
  q.seed = seed;
  return column(run_interruptible([&] { return queries::albedo_table(m.model, q, Spelling::key); }), "albedo");
}

py::dict error(const py::object& model, const std::string& reference, const py::object& n, double zone) {
  std::optional<PyModel> storage;
  const PyModel& m = model_argument(model, storage);
  queries::ErrorQuery q;
  q.model = queries::ModelRef(m.id);
  q.params = without_n(m);
  q.reference = queries::ModelRef(reference);
  q.n = values_of(n, "n");
  q.zone = zone;
  const io::Table t = run_interruptible([&] { return queries::error_table(q, Spelling::key); });
  py::dict out;
  for (const auto& name : t.columns) out[py::str(name)] = column(t, name);
  return out;
}

analysis::CheckResult check(const py::object& model, std::size_t pairs, std::uint64_t seed, double step,
                            const std::vector<double>& grazing) {
  std::optional<PyModel> storage;
  const PyModel& m = model_argument(model, storage);
  queries::CheckQuery q;
  q.model = {queries::ModelRef(m.id), m.params, m.form, m.coef};
  q.options.reciprocity_pairs = pairs;
  q.options.seed = seed;
  q.options.grid_step_deg = step;
  q.options.grazing_deg = grazing;
  return run_interruptible([&] { return queries::check_cases(q, Spelling::key); }).front().result;
}

// The walk's estimates as arrays: one row per channel, the orders 1, 2, 3, ≥ 4 in columns.
py::dict walk_dict(const std::vector<walk::Albedo>& channels) {
  const auto n = static_cast<py::ssize_t>(channels.size());
  py::array_t<double> order({n, py::ssize_t{walk::kOrders}}), order_se({n, py::ssize_t{walk::kOrders}});
  py::array_t<double> total(n), total_se(n), multiple(n), multiple_se(n);
  for (py::ssize_t c = 0; c < n; ++c) {
    const walk::Albedo& a = channels[std::size_t(c)];
    for (int k = 0; k < walk::kOrders; ++k) {
      order.mutable_at(c, k) = a.order[k].value;
      order_se.mutable_at(c, k) = a.order[k].error;
    }
    total.mutable_at(c) = a.total.value, total_se.mutable_at(c) = a.total.error;
    multiple.mutable_at(c) = a.multiple.value, multiple_se.mutable_at(c) = a.multiple.error;
  }
  py::dict d;
  d["order"] = order, d["order_se"] = order_se, d["total"] = total, d["total_se"] = total_se;
  d["multiple"] = multiple, d["multiple_se"] = multiple_se;
  return d;
}

py::dict walk_albedo(double alpha, double theta, const std::vector<std::string>& fresnel, const std::string& distribution,
                     std::uint64_t paths, std::uint64_t seed, std::optional<double> dielectric) {
  if (distribution != "ggx" && distribution != "beckmann")
    throw InvalidField("distribution", fmt::format("distribution must be 'ggx' or 'beckmann', got '{}'", distribution));
  if (!(theta >= 0 && theta < 90)) throw InvalidField("theta", fmt::format("theta = {} is outside [0, 90)", theta));
  const walk::Microsurface surface{distribution == "ggx" ? walk::Distribution::ggx : walk::Distribution::beckmann, alpha};
  walk::Options options;
  options.paths = paths;
  options.seed = seed;
  const double mu = std::cos(theta * std::numbers::pi / 180);
  if (dielectric) {
    if (!fresnel.empty()) throw InvalidField("fresnel", "a dielectric walk takes no fresnel channels");
    const walk::DielectricAlbedo d =
        run_interruptible([&] { return walk::dielectric_albedo(surface, *dielectric, mu, options); });
    return walk_dict({d.reflection, d.transmission, d.energy});
  }
  std::vector<fresnel::Channel> channels;
  for (const auto& spec : fresnel) channels.push_back(parse_fresnel(spec));
  if (channels.empty()) channels.push_back({});
  return walk_dict(run_interruptible([&] { return walk::conductor_albedo(surface, channels, mu, options); }));
}

std::string check_repr(const analysis::CheckResult& r) {
  return fmt::format("CheckResult(conserves_energy={}, reciprocal={}, non_negative={}, albedo_normal={:.9g}, "
                     "max_albedo={:.9g} at {:.4g}°, max_asymmetry={:.3g}, min_value={:.3g})",
                     r.conserves_energy ? "True" : "False", r.reciprocal ? "True" : "False",
                     r.non_negative ? "True" : "False", r.albedo_normal, r.max_albedo.value, r.max_albedo.theta_deg,
                     r.max_asymmetry, r.min_value);
}

}  // namespace

void bind_analysis(py::module_& m) {
  m.def("normalize", &normalize, py::arg("model"), py::arg("n"), py::arg("method") = "auto",
        "k per value of n: the coefficient that makes the albedo at normal incidence 1 (specula\n"
        "normalize). method: 'auto' (the closed form where known, else quadrature), 'exact' or\n"
        "'quadrature'.\n\n>>> specula.normalize('log', n=[1, 20])\narray([0.48274948, 4.19275612])");
  m.def("albedo", &albedo, py::arg("model"), py::arg("theta"), py::arg("method") = "cubature",
        py::arg("samples") = 1'000'000, py::arg("seed") = 1,
        "The directional albedo ρ(θ_i) at each angle in degrees (specula albedo): adaptive cubature,\n"
        "or method='monte-carlo' with `samples` per angle.\n\n"
        ">>> specula.albedo(specula.model('phong-normalized', n=20), [0, 60])\narray([1.       , 0.5005095])");
  m.def("error", &error, py::arg("model"), py::arg("reference") = "phong", py::arg("n") = std::vector<double>{20},
        py::arg("zone") = 0.5,
        "The largest error of the bare lobe against a reference lobe at each n (specula error): a dict\n"
        "of arrays n, max_abs, argmax_abs_deg, max_rel_epicenter, max_rel_attenuation.\n\n"
        ">>> specula.error('log', n=[20])['max_abs']\narray([0.125])");
  m.def("walk", &walk_albedo, py::arg("alpha"), py::arg("theta"), py::arg("fresnel") = std::vector<std::string>{},
        py::arg("distribution") = "ggx", py::arg("paths") = std::uint64_t{1} << 20, py::arg("seed") = 1,
        py::arg("dielectric") = py::none(),
        "The random walk on the Smith microsurface (specula walk, docs/random-walk.md): the directional\n"
        "albedo at theta (degrees) of a rough conductor with each Fresnel channel ('one',\n"
        "'schlick:f0=0.04', 'f82:f0=..,tint=..', 'dielectric:eta=..', 'conductor:eta=..,kappa=..'), or of\n"
        "a dielectric interface of index `dielectric` (rows: reflection, transmission, their sum). A dict\n"
        "of arrays, a row per channel: order (orders 1, 2, 3, >= 4), total, multiple, each with its _se.\n\n"
        ">>> specula.walk(1.0, 0, paths=32768)['order'].round(3)  # alpha = 1 at normal incidence, F = 1\n"
        "array([[0.307, 0.322, 0.211, 0.16 ]])");
  py::class_<analysis::CheckResult> check_result(m, "CheckResult",
                                                 "What specula check finds: the verdicts and their margins.");
  check_result.def_readonly("albedo_normal", &analysis::CheckResult::albedo_normal)
      .def_property_readonly("max_albedo", [](const analysis::CheckResult& r) { return r.max_albedo.value; })
      .def_property_readonly("max_albedo_theta", [](const analysis::CheckResult& r) { return r.max_albedo.theta_deg; })
      .def_readonly("max_asymmetry", &analysis::CheckResult::max_asymmetry)
      .def_readonly("pairs", &analysis::CheckResult::pairs)
      .def_readonly("min_value", &analysis::CheckResult::min_value)
      .def_readonly("conserves_energy", &analysis::CheckResult::conserves_energy)
      .def_readonly("reciprocal", &analysis::CheckResult::reciprocal)
      .def_readonly("non_negative", &analysis::CheckResult::non_negative)
      .def_property_readonly("all_hold", &analysis::CheckResult::all_hold)
      .def("__bool__", &analysis::CheckResult::all_hold)
      .def("__repr__", &check_repr);
  refuse_pickling(check_result);
  m.def("check", &check, py::arg("model"), py::arg("pairs") = 10'000, py::arg("seed") = 1, py::arg("step") = 1.0,
        py::arg("grazing") = std::vector<double>{89.5, 89.9},
        "Energy conservation at every angle, reciprocity and non-negativity (specula check).\n\n"
        ">>> bool(specula.check(specula.model('phong-normalized', n=20)))\nTrue");
  m.def(
      "glsl",
      [](const py::object& model, const std::string& dialect) {
        std::optional<PyModel> storage;
        return queries::glsl_function(model_argument(model, storage).model, queries::dialect_named(dialect));
      },
      py::arg("model"), py::arg("dialect") = "glsl330",
      "The model as a self-contained GLSL function (specula glsl); dialect 'glsl330', 'gles300' or\n'webgl2'.\n\n"
      ">>> specula.glsl('ggx').splitlines()[0]\n'// specula glsl: model=ggx alpha=0.3 f0=1'");
  m.def(
      "export",
      [](const py::object& model, const std::string& format) {
        std::optional<PyModel> storage;
        exports::Format f{};
        try {
          f = exports::parse_format(format);
        } catch (const InvalidArgument& e) {
          throw InvalidField("format", e.what());
        }
        return exports::export_model(model_argument(model, storage).model, f);
      },
      py::arg("model"), py::arg("format"),
      "The model as source code (specula export): format 'hlsl', 'msl', 'brdf' (BRDF Explorer) or 'cpp'.\n\n"
      ">>> specula.export('ggx', 'hlsl').splitlines()[0]\n'// specula export --format hlsl: model=ggx alpha=0.3 f0=1'");
}

}  // namespace specula::python
