// specula.lut and specula.render: energy-compensation tables (analysis/energy.h, as specula lut)
// and the CPU renderer's linear images (render/render.h, render/environment.h, as specula render),
// as NumPy arrays.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>

#include "binding.h"
#include "specula/analysis/energy.h"
#include "specula/io/values.h"
#include "specula/render/environment.h"
#include "specula/render/render.h"

namespace specula::python {

namespace {

// --- lut ---

void require_increasing(const char* name, const std::vector<double>& v) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) throw InvalidField(name, fmt::format("{}: {} is not a finite number", name, v[i]));
    if (i > 0 && !(v[i] > v[i - 1]))
      throw InvalidField(name, fmt::format("{}: values must increase ({} after {})", name, v[i], v[i - 1]));
  }
}

/// The sweep {name: values}: the table's parameter axis (none: one row at the model's values).
std::pair<std::string, std::vector<double>> sweep_of(const py::object& sweep) {
  if (sweep.is_none()) return {"", {0.0}};
  if (!py::isinstance<py::dict>(sweep) || py::len(sweep) != 1)
    throw InvalidField("sweep", "sweep must be a dict of one parameter and its values, e.g. {'alpha': [0.1, 0.5]}");
  const auto [key, values] = *sweep.cast<py::dict>().begin();
  if (!py::isinstance<py::str>(key)) throw InvalidField("sweep", "sweep's key must be a parameter name");
  std::vector<double> p = values_of(py::reinterpret_borrow<py::object>(values), "sweep");
  if (p.empty() || p.size() > analysis::kMaxLutAxisValues)
    throw InvalidField("sweep", fmt::format("sweep: 1 to {} values, got {}", analysis::kMaxLutAxisValues, p.size()));
  require_increasing("sweep", p);
  return {key.cast<std::string>(), std::move(p)};
}

py::object lut(const py::object& model, const py::object& mu_arg, const py::object& sweep_arg, bool average) {
  std::optional<PyModel> storage;
  const PyModel& m = model_argument(model, storage);
  const auto [name, p] = sweep_of(sweep_arg);
  const std::vector<double> mu = mu_arg.is_none() ? io::parse_values("0.03125:1@32") : values_of(mu_arg, "mu");
  if (mu.empty() || mu.size() > analysis::kMaxLutAxisValues)
    throw InvalidField("mu", fmt::format("mu: 1 to {} values, got {}", analysis::kMaxLutAxisValues, mu.size()));
  require_increasing("mu", mu);
  if (mu.front() < analysis::kMinMu || mu.back() > 1)
    throw InvalidField("mu", fmt::format("mu: values must lie in [{:g}, 1]", analysis::kMinMu));
  if (p.size() * mu.size() > analysis::kMaxLutCells)
    throw InvalidField("mu", fmt::format("{} x {} cells is more than {}", p.size(), mu.size(), analysis::kMaxLutCells));
  if (average && p.size() > analysis::kMaxLutAverages)
    throw InvalidField("sweep", fmt::format("average: {} values of {} is more than {} (each E_avg costs 100-400 cells)",
                                            p.size(), name, analysis::kMaxLutAverages));
  const analysis::ModelAt at = [&m, name = name](double value) {
    if (name.empty()) return m.model;
    ParamValues params = m.params;
    params[name] = value;
    return make_py_model(m.id, params, m.form ? std::optional<std::string>(to_string(*m.form)) : std::nullopt, m.coef)
        .model;
  };
  at(p.front());  // a bad parameter fails before any work
  const analysis::AlbedoLut table = run_interruptible([&] { return analysis::albedo_lut(at, p, mu, average); });
  std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(mu.size())};
  if (!name.empty()) shape.insert(shape.begin(), static_cast<py::ssize_t>(p.size()));
  py::array_t<double> e(shape);
  std::copy(table.e.begin(), table.e.end(), e.mutable_data());
  if (!average) return e;
  py::array_t<double> e_avg(static_cast<py::ssize_t>(table.e_avg.size()));
  std::copy(table.e_avg.begin(), table.e_avg.end(), e_avg.mutable_data());
  return py::make_tuple(e, name.empty() ? py::object(py::float_(table.e_avg.front())) : py::object(e_avg));
}

// --- render ---

std::vector<double> numbers(const py::handle& x, const char* name, std::size_t count) {
  std::vector<double> v = values_of(py::reinterpret_borrow<py::object>(x), name);
  if (v.size() != count) throw InvalidField(name, fmt::format("{} must be {} numbers, got {}", name, count, v.size()));
  return v;
}

Vec3 vec3(const py::handle& x, const char* name) {
  const auto v = numbers(x, name, 3);
  return {v[0], v[1], v[2]};
}

render::Rgb rgb(const py::handle& x, const char* name) {
  const auto v = numbers(x, name, 3);
  return {v[0], v[1], v[2]};
}

/// A light as a dict: {'direction': (x, y, z)} toward a directional light, or {'position': (x, y,
/// z)} of a point light, with 'color' (r, g, b) and 'intensity' optional.
render::Light light_of(const py::handle& item, std::size_t index) {
  if (!py::isinstance<py::dict>(item))
    throw InvalidField("lights", "lights must be a list of dicts like {'direction': (x, y, z)}");
  const auto d = item.cast<py::dict>();
  for (const auto& [key, value] : d) {
    const std::string k = py::str(key);
    if (k != "direction" && k != "position" && k != "color" && k != "intensity")
      throw InvalidField("lights", fmt::format("lights[{}]: unknown key '{}' (direction, position, color, intensity)",
                                               index, k));
  }
  if (d.contains("direction") == d.contains("position"))
    throw InvalidField("lights", fmt::format("lights[{}]: give a direction or a position, one of them", index));
  render::Light light;
  if (d.contains("direction")) {
    light.direction = vec3(d["direction"], "lights");
  } else {
    light.kind = render::LightKind::point;
    light.position = vec3(d["position"], "lights");
  }
  if (d.contains("color")) light.colour = rgb(d["color"], "lights");
  if (d.contains("intensity")) light.intensity = numbers(d["intensity"], "lights", 1)[0];
  render::check_light(light, fmt::format("lights[{}]", index));
  return light;
}

/// A lat-long environment image (H, W, 3) of linear radiance.
render::Environment environment_image(const py::object& env) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(env);
  if (!a || a.ndim() != 3 || a.shape(2) != 3)
    throw InvalidField("env", "env must be None, 'white', an image file or an (H, W, 3) array of radiance");
  render::Image image(static_cast<int>(std::min<py::ssize_t>(a.shape(1), render::kMaxImageSide + 1)),
                      static_cast<int>(std::min<py::ssize_t>(a.shape(0), render::kMaxImageSide + 1)));
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) image.set(x, y, {a.at(y, x, 0), a.at(y, x, 1), a.at(y, x, 2)});
  return render::Environment::lat_long(image);
}

std::optional<render::Environment> environment_of(const py::object& env) {
  if (env.is_none()) return std::nullopt;
  if (py::isinstance<py::str>(env)) {
    const auto text = env.cast<std::string>();
    if (text == "white") return render::Environment::uniform({1, 1, 1});
    return render::read_environment(text);
  }
  return environment_image(env);
}

render::RenderSettings size_of(const py::object& size) {
  const std::vector<double> v = values_of(size, "size");
  if (v.size() != 1 && v.size() != 2) throw InvalidField("size", "size must be a number of pixels or (width, height)");
  for (const double x : v)
    if (!(x >= 1 && x <= render::kMaxImageSide) || x != std::floor(x))
      throw InvalidField("size", fmt::format("size must be whole numbers in [1, {}]", render::kMaxImageSide));
  render::RenderSettings s;
  s.width = static_cast<int>(v.front());
  s.height = static_cast<int>(v.back());
  return s;
}

py::array_t<float> render_image(const py::object& model, const py::object& size, const py::object& lights,
                                const py::object& env, int samples, std::uint64_t seed, const py::object& diffuse,
                                const py::object& specular, const py::object& ambient, const py::object& mesh) {
  std::optional<PyModel> storage;
  const PyModel& m = model_argument(model, storage);
  const render::RenderSettings settings = size_of(size);
  render::SceneDescription d;
  if (!mesh.is_none()) {
    if (!py::isinstance<py::str>(mesh)) throw py::type_error("mesh must be the path of an OBJ file");
    d.mesh = render::load_obj(mesh.cast<std::string>());
  }
  if (!lights.is_none()) {
    if (!py::isinstance<py::sequence>(lights) || py::isinstance<py::str>(lights))
      throw py::type_error("lights must be a list of dicts like {'direction': (x, y, z)}");
    d.lights.emplace();
    std::size_t index = 0;
    for (const auto& item : lights) d.lights->push_back(light_of(item, index++));
  }
  const std::optional<render::Environment> environment = environment_of(env);
  if (environment && !d.lights) d.lights.emplace();  // the environment is the only light
  const bool furnace = py::isinstance<py::str>(env) && env.cast<std::string>() == "white";
  if (!diffuse.is_none()) d.diffuse = rgb(diffuse, "diffuse");
  else if (furnace) d.diffuse = render::Rgb{0, 0, 0};  // the white furnace shows the bare model
  if (!specular.is_none()) d.specular = rgb(specular, "specular");
  else if (furnace) d.specular = render::Rgb{1, 1, 1};
  if (!ambient.is_none()) d.ambient = rgb(ambient, "ambient");
  else if (furnace) d.ambient = render::Rgb{0, 0, 0};
  const render::Scene scene = render::make_scene(m.model, std::move(d));
  if (environment) render::check_samples(settings, {samples, seed}, Spelling::key);
  const render::Image image = run_interruptible([&] {
    return environment ? render::render_environment(scene, *environment, settings, {samples, seed})
                       : render::render_cpu(scene, settings);
  });
  py::array_t<float> out({static_cast<py::ssize_t>(image.height()), static_cast<py::ssize_t>(image.width()), py::ssize_t{3}});
  std::copy(image.samples().begin(), image.samples().end(), out.mutable_data());
  return out;
}

}  // namespace

void bind_pictures(py::module_& m) {
  m.def("lut", &lut, py::arg("model"), py::arg("mu") = py::none(), py::arg("sweep") = py::none(),
        py::arg("average") = false,
        "The directional albedo E(μ) = ρ(acos μ) at each μ = cos θ_i (specula lut), by the deterministic\n"
        "cubature, every cell in parallel: an array over mu, or over (p, mu) with sweep={'NAME': values}\n"
        "(increasing) for one parameter's axis. average=True also returns E_avg = 2∫E(μ)μ dμ (a number,\n"
        "or one per p) as (E, E_avg). mu: increasing, in [1e-9, 1] (default 32 values 1/32 … 1); at most\n"
        "1024 values an axis and 65536 cells.\n\n"
        ">>> specula.lut('lambert', mu=[0.5, 1.0])\narray([1., 1.])");
  m.def("render", &render_image, py::arg("model"), py::arg("size") = 256, py::arg("lights") = py::none(),
        py::arg("env") = py::none(), py::arg("samples") = 64, py::arg("seed") = 0, py::arg("diffuse") = py::none(),
        py::arg("specular") = py::none(), py::arg("ambient") = py::none(), py::arg("mesh") = py::none(),
        "A linear radiance image, an (H, W, 3) float32 array, of a sphere (or the OBJ file `mesh`) shaded\n"
        "with the model on the CPU (specula render). size: pixels or (width, height). lights: dicts\n"
        "{'direction': (x, y, z)} (toward a directional light) or {'position': (x, y, z)}, with 'color'\n"
        "and 'intensity'; default one light from the upper left. env: 'white' (the white furnace: the\n"
        "bare model, specular 1, no diffuse), an EXR/PNG file or an (H, W, 3) lat-long array of radiance,\n"
        "lighting the object alone with `samples` pairs per pixel. diffuse, specular, ambient: (r, g, b).\n\n"
        ">>> specula.render('ggx', size=(4, 3)).shape\n(3, 4, 3)");
}

}  // namespace specula::python
