#include "endpoints.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "fields.h"
#include "specula/exceptions.h"
#include <cmath>

#include "specula/catalogue/model_meta.h"
#include "specula/glsl/glsl.h"
#include "specula/brdf/ggx.h"
#include "specula/design/design.h"
#include "specula/queries/compensation.h"
#include "specula/queries/queries.h"
#include "specula/render/scene.h"
#include "specula/render/scene_shader.h"
#include "specula/sampling/check.h"
#include "specula/sampling/sampler.h"
#include "specula/sampling/seeds.h"

namespace specula::serve {
namespace {

constexpr auto kKey = queries::Spelling::key;

[[noreturn]] void fail(std::string_view field, const std::string& message) {
  throw InvalidField(std::string(field), message);
}

/// The cap on n values: fewer when each is a search of its own (the strict condition).
std::size_t n_cap(queries::Condition condition, const Limits& limits) {
  return condition == queries::Condition::strict ? limits.max_strict_n : limits.max_n;
}

}  // namespace

std::string models_endpoint() { return queries::models_json(); }

std::string terms_endpoint() {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const design::Term& t : design::terms()) {
    nlohmann::ordered_json references = nlohmann::ordered_json::array();
    for (const design::TermReference& r : design::term_references())
      if (r.term == t.id) references.push_back({{"id", r.id}, {"formula", r.formula}, {"source", r.source}});
    out.push_back({{"id", t.id}, {"formula", t.formula}, {"variables", design::default_variables(t.id)},
                   {"param", t.param}, {"range", {t.lo, t.hi}}, {"summary", t.summary}, {"references", references}});
  }
  return out.dump() + "\n";
}

std::string eval_endpoint(std::string_view body, const Limits& limits) {
  const Fields f(body, {"model", "params", "form", "coef", "cos", "lobe", "theta_i", "theta_o", "phi_o"});
  const Model m = queries::make(f.model(), kKey);
  if (f.has("cos")) {
    if (f.has("theta_i") || f.has("theta_o"))
      fail("cos", "give cos (lobe models) or theta_i and theta_o (any model), not both");
    return io::to_json(queries::eval_at_cosines(m, f.values("cos", limits.max_eval_points), f.flag_or("lobe", false), kKey));
  }
  if (!f.has("theta_i") && !f.has("theta_o")) fail("cos", "give cos (lobe models) or theta_i and theta_o (any model)");
  if (f.has("lobe")) fail("lobe", "lobe applies to cos only");
  const double theta_i = f.number("theta_i");
  const auto theta_o = f.values("theta_o", limits.max_eval_points);
  return io::to_json(queries::eval_at_directions(m, theta_i, theta_o, f.number_or("phi_o", 0), kKey));
}

std::string slice_endpoint(std::string_view body, const Limits& limits) {
  const Fields f(body, {"model", "params", "form", "coef", "theta_h", "theta_d", "phi_d"});
  const Model m = queries::make(f.model(), kKey);
  const auto theta_h = f.values("theta_h", limits.max_eval_points);
  const auto theta_d = f.values("theta_d", limits.max_eval_points);
  if (theta_h.size() * theta_d.size() > limits.max_eval_points)
    fail("theta_d", fmt::format("{} × {} angles exceed {} points per request", theta_h.size(), theta_d.size(),
                                limits.max_eval_points));
  return io::to_json(queries::eval_half_difference(m, theta_h, theta_d, f.number_or("phi_d", 90), kKey));
}

std::string hemisphere_endpoint(std::string_view body, const Limits& limits) {
  const Fields f(body, {"model", "params", "form", "coef", "theta_i", "theta_o", "phi_o"});
  const Model m = queries::make(f.model(), kKey);
  const double theta_i = f.number_or("theta_i", 30);
  const auto theta_o = f.values_or("theta_o", "0:90@46", limits.max_eval_points);
  const auto phi_o = f.values_or("phi_o", "0:355@72", limits.max_eval_points);
  if (theta_o.size() * phi_o.size() > limits.max_eval_points)
    fail("phi_o", fmt::format("{} × {} directions exceed {} points per request", theta_o.size(), phi_o.size(),
                              limits.max_eval_points));
  // f over the outgoing hemisphere, one row of φ_o values per θ_o (the 3-D lobe's surface).
  nlohmann::json values = nlohmann::json::array();
  for (std::size_t t = 0; t < theta_o.size(); ++t) values.push_back(nlohmann::json::array());
  for (const double phi : phi_o) {
    const io::Table column = queries::eval_at_directions(m, theta_i, theta_o, phi, kKey);
    for (std::size_t t = 0; t < theta_o.size(); ++t) {
      const double v = column.rows[t].back();
      values[t].push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json());
    }
  }
  return nlohmann::json{{"model", std::string(m.id())}, {"theta_i_deg", theta_i}, {"theta_o_deg", theta_o},
                        {"phi_o_deg", phi_o}, {"values", std::move(values)}}.dump();
}

std::string compensation_endpoint(std::string_view body, const Limits& limits) {
  const Fields f(body, {"model", "params", "form", "coef", "mu", "paths", "seed"});
  const Model m = queries::make(f.model(), kKey);
  const Model& base = m.compensated() ? *m.compensated()->base : m;
  const Ggx* ggx = base.is_lobe() || base.compensated() ? nullptr : std::get_if<Ggx>(&base.brdf());
  if (!ggx)
    fail("model", fmt::format("{} is not a GGX model: the compensations are measured against the random walk on GGX "
                              "microsurfaces (ggx, ggx-schlick, ggx-f82, ggx-dielectric, ggx-conductor)", m.id()));
  queries::VerdictSettings s;
  s.alpha = {ggx->alpha};
  s.mu = f.values_or("mu", "0.05,0.1,0.2,0.35,0.5,0.7,0.85,1", 32);
  for (const double mu : s.mu)
    if (!(mu > 0 && mu <= 1)) fail("mu", fmt::format("mu {} is outside (0, 1]", mu));
  s.fresnels = {{std::string(base.id()), std::string(base.id()), ggx->fresnel}};
  s.paths = static_cast<std::uint64_t>(f.integer_or("paths", 32768, 32768, static_cast<std::int64_t>(limits.max_walk_paths)));
  s.seed = static_cast<std::uint64_t>(f.integer_or("seed", 1, 0, std::int64_t{1} << 53));
  io::Table cells = queries::verdict(s).cells;
  cells.meta.emplace_back("model", std::string(m.id()));
  cells.meta.emplace_back("compensations", fmt::format("{}", fmt::join(queries::kCompensationNames, ",")));
  return io::to_json(cells);
}

std::string sampling_endpoint(std::string_view body, const Limits& limits) {
  const Fields f(body, {"model", "params", "form", "coef", "theta", "samples", "seed", "bins", "points"});
  const Model m = queries::make(f.model(), kKey);
  sampling::SamplingCheckOptions o;
  const double theta = f.number_or("theta", 30);
  if (!(theta >= 0 && theta < 90)) fail("theta", fmt::format("{} is outside [0, 90) degrees", theta));
  o.theta_deg = {theta};
  o.samples = static_cast<std::size_t>(f.integer_or("samples", 100'000, 1000, static_cast<std::int64_t>(limits.max_sampling_samples)));
  o.seed = static_cast<std::uint64_t>(f.integer_or("seed", 1, 0, std::int64_t{1} << 53));
  o.cos_bins = static_cast<int>(f.integer_or("bins", 16, 4, 64));
  const auto points = static_cast<std::size_t>(f.integer_or("points", 1000, 0, 10'000));
  const sampling::Sampler sampler(m);
  const sampling::AngleCheck a = sampling::check_sampling(sampler, o).angles.at(0);
  nlohmann::json out{{"method", sampler.description()}, {"theta_deg", theta},   {"samples", o.samples},
                     {"chi2", a.chi2},                  {"dof", a.dof},         {"p_value", a.p_value},
                     {"alpha", a.alpha},                {"chi2_passes", a.chi2_passes()}, {"passes", a.passes()},
                     {"mean_weight", a.mean_weight},    {"standard_error", a.standard_error}, {"albedo", a.albedo},
                     {"cos_bins", o.cos_bins},          {"observed", a.observed}, {"expected", a.expected}};
  // The first `points` directions the sampler draws (a stream of their own), for the hemisphere view.
  sampling::SplitMixStream random(sampling::stream_key(o.seed, 1u << 20));
  const Vec3 wi = from_spherical(radians(theta), 0.0);
  nlohmann::json drawn = nlohmann::json::array();
  for (std::size_t k = 0; k < points; ++k) {
    const double u1 = random.uniform(), u2 = random.uniform();
    if (const sampling::Sample s = sampler.sample(wi, u1, u2); s.valid()) drawn.push_back({s.wo.x, s.wo.y, s.wo.z});
  }
  out["points"] = std::move(drawn);
  return out.dump();
}

std::string normalize_endpoint(std::string_view body, const Limits& limits) {
  const Fields f(body, {"model", "params", "form", "n", "method", "compare", "condition", "step"});
  queries::NormalizeQuery q;
  q.model = f.model_ref("model");
  q.params = f.params();
  if (f.has("form")) q.form = queries::form_named(f.text("form"), kKey);
  q.method = queries::normalize_method_named(f.text_or("method", to_string(q.method)), kKey);
  q.condition = queries::condition_named(f.text_or("condition", to_string(q.condition)), kKey);
  if (f.has("n")) q.n = f.values("n", n_cap(q.condition, limits));
  if (f.has("compare")) q.compare = f.model_ref("compare");
  q.step = f.number_or("step", q.step);
  return io::to_json(queries::normalize_table(q, kKey));
}

std::string albedo_endpoint(std::string_view body, const Limits& limits) {
  const Fields f(body, {"model", "params", "form", "coef", "theta", "method", "samples", "seed"});
  const Model m = queries::make(f.model(), kKey);
  queries::AlbedoQuery q;
  q.theta_deg = f.values_or("theta", "0:80:10,85,89", limits.max_albedo_angles);
  q.method = queries::albedo_method_named(f.text_or("method", to_string(q.method)), kKey);
  q.samples = static_cast<std::uint64_t>(f.integer_or("samples", 100'000, 1, 1'000'000'000));
  q.seed = static_cast<std::uint64_t>(f.integer_or("seed", 1, 0, std::int64_t{1} << 53));
  if (queries::samples(q.method) && q.samples * q.theta_deg.size() > limits.max_monte_carlo_samples)
    fail("samples", fmt::format("samples × angles = {} exceeds {} per request",
                                q.samples * q.theta_deg.size(), limits.max_monte_carlo_samples));
  return io::to_json(queries::albedo_table(m, q, kKey));
}

std::string check_endpoint(std::string_view body, const Limits& limits) {
  const Fields f(body, {"model", "params", "form", "coef", "n", "sweep", "values", "pairs", "seed", "step", "grazing"});
  if (f.has("n") && f.has("sweep")) fail("sweep", "give n or sweep and values, not both");
  if (f.has("values") && !f.has("sweep")) fail("values", "values needs sweep (the parameter they are for)");
  // n: [...] is sweep "n" over those values.
  const std::string sweep = f.has("n") ? std::string(1, 'n') : f.text_or("sweep", "");
  queries::CheckQuery q{f.model(), sweep, {}, {}};
  if (!sweep.empty()) q.values = f.values(f.has("n") ? "n" : "values", limits.max_check_cases);
  q.options.reciprocity_pairs = static_cast<std::size_t>(
      f.integer_or("pairs", static_cast<std::int64_t>(q.options.reciprocity_pairs), 1,
                   static_cast<std::int64_t>(limits.max_check_pairs)));
  q.options.seed = static_cast<std::uint64_t>(f.integer_or("seed", 1, 0, std::int64_t{1} << 53));
  q.options.grid_step_deg = f.number_or("step", q.options.grid_step_deg);
  if (f.has("grazing")) q.options.grazing_deg = f.values("grazing", 10);
  return queries::check_json(queries::check_cases(q, kKey));
}

std::string error_endpoint(std::string_view body, const Limits& limits) {
  const Fields f(body, {"model", "params", "reference", "n", "zone"});
  queries::ErrorQuery q;
  q.model = f.model_ref("model");
  q.params = f.params();
  if (f.has("reference")) q.reference = f.model_ref("reference");
  q.n = f.values_or("n", "1:1000@50:log", limits.max_n);
  q.zone = f.number_or("zone", q.zone);
  return io::to_json(queries::error_table(q, kKey));
}

namespace {

/// The default comparison scene (render/scene.h: a unit sphere, one directional light) with the
/// light toward `light` if given, at `size` pixels, in display values (sRGB, no tone map): its
/// uniforms by name (render::SceneUniforms::visit, the names the shader declares).
nlohmann::ordered_json scene_json(const Model& m, const Fields& f, const Limits& limits) {
  render::SceneDescription description;
  if (f.has("light")) {
    const auto light = f.values("light", 3);
    if (light.size() != 3 || (light[0] == 0 && light[1] == 0 && light[2] == 0))
      fail("light", "light must be a non-zero direction [x, y, z] toward the light");
    render::Light lamp;
    lamp.direction = {light[0], light[1], light[2]};
    description.lights = {lamp};
  }
  const render::Scene scene = render::make_scene(m, std::move(description));
  const auto size = f.values_or("size", "256,256", 2);
  if (size.size() != 2 || size[0] != std::floor(size[0]) || size[1] != std::floor(size[1]) ||
      size[0] < 1 || size[1] < 1 || size[0] > static_cast<double>(limits.max_image_side) ||
      size[1] > static_cast<double>(limits.max_image_side))
    fail("size", fmt::format("size must be [width, height], whole numbers in [1, {}]", limits.max_image_side));
  const render::SceneUniforms u = render::scene_uniforms(
      scene, {static_cast<int>(size[0]), static_cast<int>(size[1])}, render::Display{});
  nlohmann::ordered_json uniforms = nlohmann::ordered_json::object();
  u.visit([&](const render::SceneUniform& uniform, const auto& value) { uniforms[uniform.name] = value; });
  return uniforms;
}

}  // namespace

std::string glsl_endpoint(std::string_view body, const Limits& limits) {
  const Fields f(body, {"model", "params", "form", "coef", "dialect", "shader", "light", "size"});
  const Model m = queries::make(f.model(), kKey);
  const glsl::Dialect dialect = queries::dialect_named(f.text_or("dialect", glsl::to_string(glsl::Dialect::webgl2)));
  nlohmann::ordered_json out;
  for (const auto& [key, value] : model_meta(m)) out[key] = value;
  out["dialect"] = glsl::to_string(dialect);
  out["entry"] = "specula_brdf";
  out["entry_params"] = glsl::model_params(m);
  out["version_header"] = glsl::version_header(dialect);
  out["function"] = queries::glsl_function(m, dialect);
  const bool shader = f.flag_or("shader", false);
  if (!shader && (f.has("light") || f.has("size"))) fail(f.has("light") ? "light" : "size", "light and size go with shader: true");
  if (shader) {
    // The comparison sphere as `specula render --backend gl` draws it (render/scene_shader.h).
    out["vertex_shader"] = render::scene_vertex_shader(dialect);
    out["fragment_shader"] = render::scene_fragment_shader(m, dialect, render::SceneGeometry::spheres);
    out["uniforms"] = scene_json(m, f, limits);
  }
  return out.dump(2) + "\n";
}

}  // namespace specula::serve
