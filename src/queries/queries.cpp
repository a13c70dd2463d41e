#include "specula/queries/queries.h"

#include <algorithm>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "specula/analysis/albedo.h"
#include "specula/analysis/error.h"
#include "specula/analysis/monte_carlo.h"
#include "specula/sampling/estimators.h"
#include "specula/analysis/parallel.h"
#include "specula/brdf/directions.h"
#include "specula/catalogue/catalogue.h"
#include "specula/catalogue/model_file.h"
#include "specula/catalogue/model_meta.h"
#include "specula/exceptions.h"
#include "specula/expr/comment.h"
#include "specula/glsl/glsl.h"
#include "specula/interrupt/interrupt.h"
#include "specula/io/values.h"
#include "specula/normalize/normalize.h"

namespace specula::queries {
namespace {

constexpr std::size_t kRowsPerCheck = 256;  // evaluations of eval's rows between interrupt checks

[[noreturn]] void fail(std::string_view key, const std::string& message) {
  throw InvalidField(std::string(key), message);
}

/// Runs `work`; an InvalidArgument it throws becomes an InvalidField for `key`, same message.
template <class Work>
auto for_field(std::string_view key, Work&& work) {
  try {
    return work();
  } catch (const InvalidField&) {
    throw;
  } catch (const InvalidArgument& e) {
    fail(key, e.what());
  }
}

void require_degrees(std::string_view key, double degrees, double low, double high, Spelling spelling) {
  if (!(degrees >= low && degrees <= high))  // NaN too
    fail(key, fmt::format("{} {} is outside [{}, {}] degrees", spelled(key, spelling), degrees, low, high));
}

normalize::Method method_of(NormalizeMethod method) {
  switch (method) {
    case NormalizeMethod::automatic: return normalize::Method::automatic;
    case NormalizeMethod::exact:
    case NormalizeMethod::both: return normalize::Method::exact;
    case NormalizeMethod::quadrature: return normalize::Method::quadrature;
  }
  unreachable();
}

void require_no_n(const ParamValues& params, Spelling spelling) {
  if (params.contains("n"))
    fail("params", fmt::format("give n with {}, not {}", spelled("n", spelling), spelled("params", spelling)));
}

/// Runs `work`, which makes `ref`'s definition or model: its InvalidField "model" becomes
/// `field`'s, and an inline definition's (a column of the formula) says which field it quotes.
template <class Work>
auto as_field(std::string_view field, const ModelRef& ref, Spelling spelling, Work&& work) {
  try {
    return work();
  } catch (const InvalidField& e) {
    if (e.field() != "model") throw;
    fail(field, ref.is_inline() ? fmt::format("{}: {}", spelled(field, spelling), e.what()) : std::string(e.what()));
  }
}

/// InvalidField `field` unless the definition is a lobe model's (`command` needs one).
void require_lobe(std::string_view field, std::string_view command, const ModelRef& ref, const ModelInfo& definition) {
  if (definition.kind != ModelKind::lobe)
    fail(field, fmt::format("{} works on lobe models; '{}' is a full BRDF", command, ref.name()));
}

/// The default n of a lobe model (InvalidField "model" for a full BRDF or a lobe without n).
double default_n(const ModelRef& ref, Spelling spelling) {
  const auto definition = as_field("model", ref, spelling, [&] { return ref.definition(); });
  require_lobe("model", "normalize", ref, *definition);
  const ParamInfo* n = definition->find_param("n");
  if (!n) fail("model", fmt::format("model '{}' has no parameter 'n'", ref.name()));
  return n->default_value;
}

void check_options(const analysis::CheckOptions& o, Spelling spelling) {
  if (o.reciprocity_pairs < 1 || o.reciprocity_pairs > 100'000'000)
    fail("pairs", fmt::format("{} {} is outside [1, 100000000]", spelled("pairs", spelling), o.reciprocity_pairs));
  if (!(o.grid_step_deg >= 0.01 && o.grid_step_deg <= 45))
    fail("step", fmt::format("{} {} is outside [0.01, 45] degrees", spelled("step", spelling), o.grid_step_deg));
  if (o.grazing_deg.empty()) fail("grazing", fmt::format("{} is empty", spelled("grazing", spelling)));
  for (const double g : o.grazing_deg)
    for_field("grazing", [&] { analysis::require_incidence_deg(g, spelled("grazing", spelling).c_str()); });
}

/// k by `method`; asked for a closed form that the lobe lacks, says how to ask for quadrature.
double coefficient(const Model& m, NormalizeMethod method, Spelling spelling) {
  const normalize::Method how = method_of(method);
  try {
    return normalize::coefficient(m.lobe(), m.form(), how);
  } catch (const InvalidArgument& e) {
    if (how != normalize::Method::exact) fail("method", e.what());
    fail("method", fmt::format("{}; use {} quadrature", e.what(), spelled("method", spelling)));
  }
}

}  // namespace

bool ModelRef::is_inline() const noexcept { return !definition_ && is_inline_model(id_); }

std::shared_ptr<const ModelInfo> ModelRef::definition(const ParamValues& params) const {
  return definition_ ? definition_ : model_definition(id_, params);
}

Model ModelRef::make(const ParamValues& params, std::optional<Form> form) const {
  return make_model(definition(params), params, form);
}

Model make(const ModelSpec& spec, Spelling spelling) {
  Model m = as_field("model", spec.model, spelling, [&] { return spec.model.make(spec.params, spec.form); });
  if (spec.coef) m = for_field("coef", [&] { return m.with_coef(*spec.coef); });
  return m;
}

NormalizeMethod normalize_method_named(std::string_view text, Spelling spelling) {
  return choice_named<NormalizeMethod, kNormalizeMethodCount>("method", text, spelling);
}

Condition condition_named(std::string_view text, Spelling spelling) {
  return choice_named<Condition, kConditionCount>("condition", text, spelling);
}

AlbedoMethod albedo_method_named(std::string_view text, Spelling spelling) {
  return choice_named<AlbedoMethod, kAlbedoMethodCount>("method", text, spelling);
}

Form form_named(std::string_view text, Spelling) {
  return for_field("form", [&] { return parse_form(text); });
}

Model lobe_model_at(std::string_view field, std::string_view command, const ModelRef& ref,
                    ParamValues params, double n, std::optional<Form> form, Spelling spelling) {
  params["n"] = n;
  const auto definition = as_field(field, ref, spelling, [&] { return ref.definition(params); });
  require_lobe(field, command, ref, *definition);
  try {
    return make_model(definition, params, form);
  } catch (const InvalidParameter& e) {
    if (e.param() != "n") throw;
    fail("n", e.what());
  } catch (const InvalidField& e) {  // not made at these values: at this n, when n is all that is given
    if (e.field() != "params" || params.size() > 1) throw;
    fail("n", e.what());
  }
}

io::Table eval_at_cosines(const Model& m, std::span<const double> cosines, bool bare_lobe,
                          Spelling spelling) {
  if (!m.is_lobe())
    fail("cos", fmt::format("model '{}' is a full BRDF: give directions with {} and {}", m.id(),
                            spelled("theta_i", spelling), spelled("theta_o", spelling)));
  io::Table table{{"cos", "value"}, {}, model_meta(m)};
  for (const double c : cosines) {
    if (table.rows.size() % kRowsPerCheck == 0) check_interrupt();
    if (!(c >= -1 && c <= 1))  // NaN too
      fail("cos", fmt::format("{} {} is outside [-1, 1]", spelled("cos", spelling), c));
    table.rows.push_back({c, bare_lobe ? lobes::eval(m.lobe(), c) : m.at_cos(c)});
  }
  return table;
}

io::Table eval_at_directions(const Model& m, double theta_i_deg, std::span<const double> theta_o_deg,
                             double phi_o_deg, Spelling spelling) {
  require_degrees("theta_i", theta_i_deg, 0, 90, spelling);
  require_degrees("phi_o", phi_o_deg, -360, 360, spelling);
  const Vec3 n{0, 0, 1};
  const Vec3 l = from_spherical(radians(theta_i_deg), 0.0);
  io::Table table{{"theta_o_deg", "value"}, {}, model_meta(m)};
  table.meta.emplace_back("theta_i_deg", io::format_number(theta_i_deg));
  table.meta.emplace_back("phi_o_deg", io::format_number(phi_o_deg));
  for (const double theta_o : theta_o_deg) {
    if (table.rows.size() % kRowsPerCheck == 0) check_interrupt();
    require_degrees("theta_o", theta_o, 0, 90, spelling);
    table.rows.push_back({theta_o, m(n, l, from_spherical(radians(theta_o), radians(phi_o_deg)))});
  }
  return table;
}

io::Table eval_half_difference(const Model& m, std::span<const double> theta_h_deg, std::span<const double> theta_d_deg,
                               double phi_d_deg, Spelling spelling) {
  require_degrees("phi_d", phi_d_deg, -360, 360, spelling);
  for (const double t : theta_h_deg) require_degrees("theta_h", t, 0, 90, spelling);
  for (const double t : theta_d_deg) require_degrees("theta_d", t, 0, 90, spelling);
  const Vec3 n{0, 0, 1};
  io::Table table{{"theta_h_deg", "theta_d_deg", "value"}, {}, model_meta(m)};
  table.key_columns = 2;
  table.meta.emplace_back("phi_d_deg", io::format_number(phi_d_deg));
  for (const double theta_h : theta_h_deg)
    for (const double theta_d : theta_d_deg) {
      if (table.rows.size() % kRowsPerCheck == 0) check_interrupt();
      const auto [l, v] = from_half_difference(radians(theta_h), radians(theta_d), radians(phi_d_deg));
      table.rows.push_back({theta_h, theta_d, m(n, l, v)});
    }
  return table;
}

io::Table normalize_table(const NormalizeQuery& q, Spelling spelling) {
  require_no_n(q.params, spelling);
  if (!(q.step >= 0.01 && q.step <= 45))
    fail("step", fmt::format("{} {} is outside [0.01, 45] degrees", spelled("step", spelling), q.step));
  const bool both = q.method == NormalizeMethod::both;
  const bool strict = q.condition == Condition::strict;
  if (strict && (q.method == NormalizeMethod::exact || both))
    fail("method", fmt::format("the strict condition has no closed form: drop {} or use quadrature",
                               spelled("method", spelling)));
  const std::vector<double> ns = q.n.empty() ? std::vector<double>{default_n(q.model, spelling)} : q.n;

  io::Table table{{"n", "coef"},
                  {},
                  {{"model", std::string(q.model.name())},
                   {"method", to_string(q.method)},
                   {"condition", to_string(q.condition)}}};
  if (both) table.columns.insert(table.columns.end(), {"coef_quadrature", "rel_diff"});
  if (!q.compare.empty()) table.columns.insert(table.columns.end(), {"coef_compare", "delta"});
  for (const double n : ns) {
    check_interrupt();
    const Model m = lobe_model_at("model", "normalize", q.model, q.params, n, q.form, spelling);
    if (table.meta.size() == 3) table.meta.emplace_back("form", to_string(m.form()));
    const double coef = strict ? analysis::strict_coefficient(m, q.step) : coefficient(m, q.method, spelling);
    std::vector<double> row{n, coef};
    if (both) {
      const double quadrature = normalize::quadrature(m.lobe(), m.form());
      row.insert(row.end(), {quadrature, (quadrature - coef) / coef});
    }
    if (!q.compare.empty()) {
      const double other =
          lobe_model_at("compare", spelled("compare", spelling), q.compare, {}, n, std::nullopt, spelling).coef();
      row.insert(row.end(), {other, (other - coef) / coef});  // k_other·2π·Int − 1
    }
    table.rows.push_back(std::move(row));
  }
  if (!q.compare.empty()) table.meta.emplace_back("compare", q.compare.name());
  return table;
}

/// The estimator of BRDF Explorer's that a method names (uniform, cosine, sampler, mis).
sampling::Estimator estimator_of(AlbedoMethod method) {
  switch (method) {
    case AlbedoMethod::uniform: return sampling::Estimator::uniform;
    case AlbedoMethod::cosine: return sampling::Estimator::cosine;
    case AlbedoMethod::sampler: return sampling::Estimator::sampler;
    default: return sampling::Estimator::mis;
  }
}

io::Table albedo_table(const Model& m, const AlbedoQuery& q, Spelling spelling) {
  for (const double d : q.theta_deg)
    for_field("theta", [&] { analysis::require_incidence_deg(d, spelled("theta", spelling).c_str()); });
  if (q.samples < 1 || q.samples > 1'000'000'000)
    fail("samples", fmt::format("{} {} is outside [1, 1000000000]", spelled("samples", spelling), q.samples));
  if (q.method != AlbedoMethod::cubature && q.method != AlbedoMethod::monte_carlo && q.samples < 2)
    fail("samples", fmt::format("{} {}: an estimator's standard error needs 2 samples or more",
                                spelled("samples", spelling), q.samples));
  io::Table table{{"theta_deg", "albedo"}, {}, model_meta(m)};
  table.meta.emplace_back("method", to_string(q.method));
  if (samples(q.method)) table.columns.push_back("standard_error");
  const auto rows = analysis::parallel_map(std::span<const double>(q.theta_deg), [&](double deg) {
    switch (q.method) {
      case AlbedoMethod::cubature: return std::vector<double>{deg, analysis::albedo(m, radians(deg)).value};
      case AlbedoMethod::monte_carlo: {
        const auto e = analysis::albedo_monte_carlo(m, radians(deg), q.samples, q.seed);
        return std::vector<double>{deg, e.mean, e.standard_error};
      }
      default: {
        const auto e = sampling::albedo_estimate(m, radians(deg), estimator_of(q.method), q.samples, q.seed);
        return std::vector<double>{deg, e.mean, e.standard_error};
      }
    }
  });
  table.rows.assign(rows.begin(), rows.end());
  return table;
}

io::Table error_table(const ErrorQuery& q, Spelling spelling) {
  require_no_n(q.params, spelling);
  if (!(q.zone > 0 && q.zone < 1))
    fail("zone", fmt::format("{} {} is outside (0, 1)", spelled("zone", spelling), q.zone));
  auto lobe_of = [&](std::string_view field, const ModelRef& ref, const ParamValues& params, double n) {
    return lobe_model_at(field, "error", ref, params, n, std::nullopt, spelling).lobe();
  };
  struct Pair {
    double n;
    lobes::Lobe model, reference;
  };
  std::vector<Pair> pairs;  // made here, where a bad one is an error before any work
  for (const double n : q.n)
    pairs.push_back({n, lobe_of("model", q.model, q.params, n), lobe_of("reference", q.reference, {}, n)});
  io::Table table{{"n", "max_abs", "argmax_abs_deg", "max_rel_epicenter", "max_rel_attenuation"},
                  {},
                  {{"model", std::string(q.model.name())}, {"reference", std::string(q.reference.name())}, {"zone", io::format_number(q.zone)}}};
  const auto rows = analysis::parallel_map(std::span<const Pair>(pairs), [&](const Pair& p) {
    const auto e = analysis::approximation_error(p.model, p.reference, q.zone);
    return std::vector<double>{p.n, e.max_abs, e.argmax_abs_deg, e.max_rel_epicenter, e.max_rel_attenuation};
  });
  table.rows.assign(rows.begin(), rows.end());
  return table;
}

std::vector<CheckCase> check_cases(const CheckQuery& q, Spelling spelling) {
  check_options(q.options, spelling);
  if (q.sweep.empty()) {
    Model m = make(q.model, spelling);
    return {{m, analysis::check(m, q.options)}};
  }
  const ModelRef& ref = q.model.model;
  const auto definition = as_field("model", ref, spelling, [&] { return ref.definition(q.model.params); });
  if (!definition->find_param(q.sweep))
    fail("sweep", fmt::format("model '{}' has no parameter '{}' to sweep", ref.name(), q.sweep));
  if (q.model.params.contains(q.sweep))
    fail("sweep", fmt::format("{} is swept; do not also give it with {}", q.sweep, spelled("params", spelling)));
  std::vector<CheckCase> cases;
  for (const double v : q.values) {
    check_interrupt();
    ModelSpec at = q.model;
    at.params[q.sweep] = v;
    const Model m = make(at, spelling);
    cases.push_back({m, analysis::check(m, q.options)});
  }
  return cases;
}

std::string check_json(const std::vector<CheckCase>& cases) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const auto& [m, r] : cases) {
    nlohmann::ordered_json entry;
    for (const auto& [key, value] : model_meta(m)) entry[key] = value;
    entry["albedo_normal"] = r.albedo_normal;
    entry["max_albedo"] = r.max_albedo.value;
    entry["max_albedo_theta_deg"] = r.max_albedo.theta_deg;
    entry["max_asymmetry"] = r.max_asymmetry;
    entry["pairs"] = r.pairs;
    entry["min_value"] = r.min_value;
    entry["conserves_energy"] = r.conserves_energy;
    entry["reciprocal"] = r.reciprocal;
    entry["non_negative"] = r.non_negative;
    list.push_back(std::move(entry));
  }
  return list.dump(2) + "\n";
}

fit::Data normalization_data(const ModelSpec& spec, std::span<const double> n, std::optional<int> digits,
                             Spelling spelling) {
  if (spec.params.contains("n"))
    fail("params", fmt::format("give n with {}, not {}", spelled("n", spelling), spelled("params", spelling)));
  fit::Data data{{"n"}, {{n.begin(), n.end()}}, {}};
  for (const double x : n) {
    check_interrupt();
    const Model m = lobe_model_at("model", "fit", spec.model, spec.params, x, spec.form, spelling);
    const double k = normalize::coefficient(m.lobe(), m.form());
    data.target.push_back(digits ? std::stod(io::format_number(k, *digits)) : k);
  }
  return data;
}

glsl::Dialect dialect_named(std::string_view text) {
  return for_field("dialect", [&] { return glsl::parse_dialect(text); });
}

std::string glsl_function(const Model& model, glsl::Dialect dialect) {
  std::string params;
  for (const auto& [name, value] : model_meta(model)) params += fmt::format(" {}={}", name, value);
  params = expr::comment_text(params);
  const auto p = glsl::model_params(model);
  const std::string call = fmt::format("vec4({}, {}, {}, {})", glsl::float_literal(p[0]), glsl::float_literal(p[1]),
                                       glsl::float_literal(p[2]), glsl::float_literal(p[3]));
  return fmt::format(
      "// specula glsl:{}\n"
      "// For {} (no #version here: paste into a shader that has one). N, L, V: unit vectors,\n"
      "// L toward the light, V toward the viewer. At these parameters:\n"
      "//   float f = specula_brdf(N, L, V, {});\n{}",
      params,
      dialect == glsl::Dialect::glsl330 ? "GLSL 3.30 core" : glsl::to_string(dialect) + std::string(" (GLSL ES 3.00)"),
      call, glsl::model_glsl(model));
}

std::string models_json() {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const auto& m : models()) {
    nlohmann::ordered_json params = nlohmann::ordered_json::array();
    for (const auto& p : m.params)
      params.push_back({{"name", p.name},
                        {"default", p.default_value},
                        {"min", p.min},
                        {"max", p.max},
                        {"min_exclusive", p.min_exclusive},
                        {"meaning", p.meaning}});
    nlohmann::ordered_json entry = {{"id", m.id},         {"name", m.name},
                                    {"kind", to_string(m.kind)}, {"summary", m.summary},
                                    {"source", m.source}, {"origin", to_string(m.origin)},
                                    {"params", params}};
    if (m.kind == ModelKind::lobe) {
      entry["form"] = to_string(m.form);
      entry["normalization"] = to_string(m.normalization);
      entry["coef"] = m.coef_formula;
    }
    list.push_back(std::move(entry));
  }
  return list.dump(2) + "\n";
}

}  // namespace specula::queries
