// specula.models(), specula.model(), specula.load_models() and the Model object: evaluation of
// lobes over arrays of cosines and of models over arrays of directions, through the SIMD batch
// paths of specula bench (simd/lobes.h, simd/brdf.h) with the GIL released.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <span>
#include <vector>

#include "binding.h"
#include "specula/catalogue/model_file.h"
#include "specula/exceptions.h"
#include "specula/io/table.h"
#include "specula/queries/queries.h"
#include "specula/simd/brdf.h"
#include "specula/simd/lobes.h"

namespace specula::python {

namespace {

simd::Tier tier_named(const std::string& text) {
  return choice_named<simd::Tier, simd::kTierCount>("tier", text, Spelling::key);
}

py::dict param_info(const ParamInfo& p) {
  py::dict d;
  d["name"] = p.name;
  d["default"] = p.default_value;
  d["min"] = p.min;
  d["max"] = p.max;
  d["min_exclusive"] = p.min_exclusive;
  d["meaning"] = p.meaning;
  return d;
}

py::dict info_dict(const ModelInfo& info) {
  py::dict d;
  d["id"] = info.id;
  d["name"] = info.name;
  d["kind"] = to_string(info.kind);
  d["summary"] = info.summary;
  d["source"] = info.source;
  if (info.kind == ModelKind::lobe) {
    d["form"] = to_string(info.form);
    d["normalization"] = to_string(info.normalization);
    d["coef_formula"] = info.coef_formula;
  }
  py::list params;
  for (const auto& p : info.params) params.append(param_info(p));
  d["params"] = params;
  d["origin"] = to_string(info.origin);
  return d;
}

/// The array to write into: a new one of c's shape, or `out` when it is a C-contiguous writable
/// array of that shape and type (TypeError/ValueError otherwise).
template <class T>
py::array_t<T> output_for(const py::array& c, const py::object& out) {
  const std::vector<py::ssize_t> shape(c.shape(), c.shape() + c.ndim());
  if (out.is_none()) return py::array_t<T>(shape);
  if (!py::isinstance<py::array_t<T>>(out))
    throw py::type_error(fmt::format("out must be a {} array like c", std::string(py::str(py::dtype::of<T>()))));
  auto a = out.cast<py::array_t<T>>();
  if (!std::equal(shape.begin(), shape.end(), a.shape(), a.shape() + a.ndim()) || a.ndim() != c.ndim())
    throw InvalidField("out", "out must have c's shape");
  if (!a.writeable() || !(a.flags() & py::array::c_style)) throw InvalidField("out", "out must be writable and C-contiguous");
  return a;
}

template <class T>
py::array lobe_batch(const Model& model, simd::Tier tier, const py::handle& input, const py::object& out_arg) {
  const auto c = py::array_t<T>::ensure(input);  // an array of T as it is, strides and all
  if (!c) throw py::type_error(fmt::format("c must be an array of numbers, got {}", std::string(py::str(py::type::of(input)))));
  py::array_t<T> out = output_for<T>(c, out_arg);
  Elements<T> cosines(c, out_arg);
  T* values = out.mutable_data();
  const simd::LobeSpec spec = simd::spec_of(model.lobe());
  for_chunks(cosines.size(), kMaxChunkValues, [&](std::size_t begin, std::size_t end) {
    simd::eval_batch(spec, tier, cosines.chunk(begin, end), std::span<T>(values + begin, end - begin));
  });
  return out;
}

/// F(c), the bare lobe, over an array of cosines of any shape: float32 in float32 out, anything
/// else as float64.
py::array lobe_values(const PyModel& m, const py::object& c, const std::string& tier, const py::object& out) {
  if (!m.model.is_lobe())
    throw InvalidField("c", fmt::format("'{}' is a full BRDF, not a lobe model: evaluate it at directions, m(l, v)", m.id));
  const py::array values = real_array(c, "c");
  if (py::isinstance<py::array_t<float>>(values)) return lobe_batch<float>(m.model, tier_named(tier), values, out);
  return lobe_batch<double>(m.model, tier_named(tier), values, out);
}

/// f(N, L, V) for the 3-vectors of l, v and n, arrays of shape (..., 3) of as many vectors (the
/// Python side broadcasts them: broadcast views, read through their strides, not copied), written
/// into `out_arg` (a C-contiguous float64 array of one value per vector) or a new array, through
/// the batch path over rows a chunk at a time.
py::array_t<double> direction_values(const PyModel& m, const py::array_t<double>& l, const py::array_t<double>& v,
                                     const std::optional<py::array_t<double>>& n, const std::string& tier_name,
                                     const py::object& out_arg) {
  const std::size_t count = vector_count(l, "l");
  if (vector_count(v, "v") != count || (n && vector_count(*n, "n") != count))
    throw InvalidField("v", "l, v and n must hold as many directions");
  const simd::Tier tier = tier_named(tier_name);
  if (!out_arg.is_none() && !py::isinstance<py::array_t<double>>(out_arg)) throw py::type_error("out must be a float64 array");
  py::array_t<double> out = out_arg.is_none() ? py::array_t<double>(static_cast<py::ssize_t>(count))
                                              : py::reinterpret_borrow<py::array_t<double>>(out_arg);
  if (out.size() != static_cast<py::ssize_t>(count) || !out.writeable() || !(out.flags() & py::array::c_style))
    throw InvalidField("out", "out must be a writable C-contiguous array of the directions' shape");
  Elements<double> lights(l, out_arg), views(v, out_arg);
  std::optional<Elements<double>> normals;
  if (n) normals.emplace(*n, out_arg);
  double* values = out.mutable_data();
  for_chunks(count, kMaxChunkRows, [&](std::size_t begin, std::size_t end) {
    const simd::DirectionRows rows{normals ? normals->chunk(3 * begin, 3 * end) : std::span<const double>{},
                                   lights.chunk(3 * begin, 3 * end), views.chunk(3 * begin, 3 * end)};
    simd::eval_batch(m.model, tier, rows, std::span<double>(values + begin, end - begin));
  });
  return out;
}

std::string repr(const PyModel& m) {
  std::string out = fmt::format("specula.model({}", python_repr(m.id));
  for (const auto& [name, value] : m.params) out += fmt::format(", {}={}", name, io::format_number(value));
  if (m.form) out += fmt::format(", form={}", python_repr(to_string(*m.form)));
  if (m.coef) out += fmt::format(", coef={}", io::format_number(*m.coef));
  return out + ")";
}

py::tuple pickled(const PyModel& m) {
  py::dict params;
  for (const auto& [name, value] : m.params) params[py::str(name)] = value;
  return py::make_tuple(m.id, params, m.form ? py::object(py::str(to_string(*m.form))) : py::object(py::none()),
                        m.coef ? py::object(py::float_(*m.coef)) : py::object(py::none()));
}

/// What pickle saves of a Model at any protocol: copyreg.__newobj__(type(self)), then
/// __setstate__(pickled(self)), the very pickle protocol 2 makes by default.
py::tuple reduced(const py::object& self) {
  return py::make_tuple(py::module_::import("copyreg").attr("__newobj__"), py::make_tuple(py::type::of(self)),
                        pickled(self.cast<const PyModel&>()));
}

ParamValues params_of(const py::kwargs& kwargs) {
  ParamValues out;
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    if (!py::isinstance<py::float_>(value) && !py::isinstance<py::int_>(value))
      throw InvalidField("params", fmt::format("parameter {} must be a number, got {}", name,
                                               std::string(py::str(py::type::of(value)))));
    out[name] = value.cast<double>();
  }
  return out;
}

}  // namespace

std::string python_repr(const std::string& text) { return py::repr(py::str(text)); }

std::size_t vector_count(const py::array_t<double>& a, const char* name) {
  if (a.ndim() == 0 || a.shape(a.ndim() - 1) != 3)
    throw InvalidField(name, fmt::format("{} must be an array of 3-vectors, shape (..., 3)", name));
  return static_cast<std::size_t>(a.size() / 3);
}

std::shared_mutex& catalogue_mutex() {
  static std::shared_mutex mutex;
  return mutex;
}

namespace {

/// The catalogue's lock for a change, waited for with the GIL released (a long call's worker
/// holds it shared and needs no GIL; its caller needs the GIL to return).
std::unique_lock<std::shared_mutex> changing_catalogue() {
  const py::gil_scoped_release release;
  return std::unique_lock(catalogue_mutex());
}

}  // namespace

PyModel make_py_model(const std::string& id, const ParamValues& params, std::optional<std::string> form,
                      std::optional<double> coef) {
  PyModel m{id, std::nullopt, coef, params, make_model(id, params), {}};
  if (form) {
    m.form = queries::form_named(*form, Spelling::key);
    m.model = make_model(id, params, m.form);
  }
  if (coef) m.model = m.model.with_coef(*coef);
  return m;
}

const PyModel& model_argument(const py::object& argument, std::optional<PyModel>& storage) {
  if (py::isinstance<PyModel>(argument)) return argument.cast<const PyModel&>();
  if (py::isinstance<py::str>(argument)) return storage.emplace(make_py_model(argument.cast<std::string>(), {}, {}, {}));
  throw py::type_error(fmt::format("a model must be a specula.Model or a model id, got {}",
                                   std::string(py::str(py::type::of(argument)))));
}

py::class_<PyModel> bind_models(py::module_& m) {
  m.def(
      "models", [] {
        py::list out;
        for (const auto& info : models()) out.append(info_dict(info));
        return out;
      },
      "Every model of the catalogue (built-in, then those loaded) as a dict: id, name, kind, summary,\n"
      "source, params (name, default, min, max, min_exclusive, meaning), and for lobes form,\n"
      "normalization and coef_formula.\n\n"
      ">>> [m['id'] for m in specula.models()][:3]\n['phong', 'phong-normalized', 'phong-lafortune']");

  m.def(
      "load_models",
      [](const std::string& path_or_text) {
        const bool text = path_or_text.find('\n') != std::string::npos || path_or_text.find("[[model]]") != std::string::npos;
        std::vector<ModelInfo> infos = text ? parse_model_file(path_or_text, "<text>") : load_model_file(path_or_text);
        py::list ids;
        for (const auto& info : infos) ids.append(info.id);
        const std::unique_lock changing = changing_catalogue();
        register_models(std::move(infos));
        return ids;
      },
      py::arg("path_or_toml"),
      "Loads a model file (docs/models.md) — a path, or the TOML text itself — and returns the ids it\n"
      "defines; model() then knows them.\n\n"
      ">>> specula.load_models('[[model]]\\nid = \"mine\"\\nname = \"mine\"\\nkind = \"lobe\"\\nform = \"rv\"\\nlobe = \"c^n\"\\n'\n"
      "...                     'normalization = \"quadrature\"\\n[model.params.n]\\ndefault = 20\\nmin = 1\\nmax = 1000\\n')\n"
      "['mine']");

  m.def(
      "clear_models",
      [] {
        const std::unique_lock changing = changing_catalogue();
        clear_registered_models();
      },
      "Forgets every model load_models() loaded (the built-in models stay); Model objects already\n"
      "made keep working.\n\n"
      ">>> specula.clear_models()\n>>> [m['origin'] for m in specula.models()][-1]\n'built-in'");

  py::class_<PyModel> model_class(m, "Model",
                      "A model with its parameter values bound: a lobe model k·F(c) or a full BRDF. Made by\n"
                      "specula.model(); evaluates over NumPy arrays through the SIMD batch path.");
  model_class.def_property_readonly("id", [](const PyModel& p) { return p.id; })
      .def_property_readonly("kind", [](const PyModel& p) { return std::string(to_string(p.model.info().kind)); })
      .def_property_readonly("is_lobe", [](const PyModel& p) { return p.model.is_lobe(); })
      .def_property_readonly("form", [](const PyModel& p) -> py::object {
        return p.model.is_lobe() ? py::object(py::str(to_string(p.model.form()))) : py::object(py::none());
      }, "The lobe's form, 'rv' (R·V) or 'nh' (N·H); None for a full BRDF.")
      .def_property_readonly("coef", [](const PyModel& p) -> py::object {
        return p.model.is_lobe() ? py::object(py::float_(p.model.coef())) : py::object(py::none());
      }, "The lobe's normalizing coefficient k; None for a full BRDF.")
      .def_property_readonly("params", [](const PyModel& p) {
        py::dict d;
        for (std::size_t i = 0; i < p.model.info().params.size(); ++i) d[py::str(p.model.info().params[i].name)] = p.model.params()[i];
        return d;
      }, "Every parameter's value (those not given at their defaults).")
      .def_property_readonly("info", [](const PyModel& p) { return info_dict(p.model.info()); },
                             "The model's definition as specula.models() lists it.")
      .def("lobe", &lobe_values, py::arg("c"), py::arg("tier") = "exact", py::arg("out") = py::none(),
           "F(c), the bare lobe (no k), over an array of cosines of any shape; float32 stays float32.\n"
           "tier: 'exact' (a few ulp) or 'fast' (1e-4 relative where F >= 1e-3), as specula bench.\n"
           "out: an array of c's shape and type to write into (else a new one).\n\n"
           ">>> specula.model('phong', n=2).lobe([1.0, 0.5])\narray([1.  , 0.25])")
      .def("_directions", &direction_values, py::arg("l"), py::arg("v"), py::arg("n"), py::arg("tier"), py::arg("out"))
      .def("__repr__", &repr)
      .def(py::pickle(&pickled, [](const py::tuple& t) {
        if (t.size() != 4) throw std::runtime_error("a pickled specula.Model has four fields");
        ParamValues params;
        for (const auto& [key, value] : t[1].cast<py::dict>()) params[py::str(key)] = value.cast<double>();
        return make_py_model(t[0].cast<std::string>(), params, t[2].cast<std::optional<std::string>>(),
                             t[3].cast<std::optional<double>>());
      }))
      .def("__reduce__", &reduced,
           "Pickles at every protocol as protocol 2 does: Model.__new__, then __setstate__ (protocols 0\n"
           "and 1 would otherwise call pybind11's base type, which aborts the interpreter).");

  m.def(
      "model",
      [](const std::string& id, std::optional<std::string> form, std::optional<double> coef, const py::kwargs& params) {
        return make_py_model(id, params_of(params), std::move(form), coef);
      },
      py::arg("id"), py::kw_only(), py::arg("form") = py::none(), py::arg("coef") = py::none(),
      "The model `id` names — a built-in or loaded id, 'ID+ms' (energy-compensated), or an inline\n"
      "'lobe: FORMULA' / 'brdf: FORMULA' — with its parameters as keywords (others at their\n"
      "defaults), a form ('rv' or 'nh', lobes) and a coefficient k overriding its own.\n\n"
      ">>> specula.model('log-normalized', n=20).coef\n4.192756116851179");
  return model_class;
}

}  // namespace specula::python
