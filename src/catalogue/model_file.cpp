// Model files (TOML, by toml++) and inline definitions: user-defined models as ModelInfo
// (catalogue/model_file.h, docs/models.md).
#include "specula/catalogue/model_file.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <limits>
#include <set>
#include <toml++/toml.h>

#include "specula/exceptions.h"
#include "specula/io/files.h"
#include "specula/normalize/quadrature.h"

namespace specula {
namespace {

using Impl = ModelImpl;
constexpr std::size_t kMaxModelsPerFile = 1000;
constexpr std::size_t kMaxIdLength = 64;
constexpr std::size_t kMaxTextLength = 1000;  // names, sources, meanings

const std::set<std::string_view> kModelKeys{"id",   "name", "source", "summary", "kind",          "form",
                                            "lobe", "lobe_u", "brdf", "let",     "normalization", "params"};
const std::set<std::string_view> kParamKeys{"default", "min", "max", "min_exclusive", "meaning"};

std::vector<std::string> lobe_inputs() {
  return {std::string(lobes::FormulaDefinition::kInputs[0]), std::string(lobes::FormulaDefinition::kInputs[1])};
}
std::vector<std::string> brdf_inputs() {
  return {FormulaBrdf::kInputs.begin(), FormulaBrdf::kInputs.end()};
}

std::string known(const std::set<std::string_view>& keys) { return fmt::format("{}", fmt::join(keys, ", ")); }

// Errors at a place in the file.
class Reader {
 public:
  explicit Reader(std::string_view filename) : file_(filename) {}

  [[noreturn]] void fail(const toml::source_region& where, std::string_view message) const {
    throw InvalidArgument(one_line(fmt::format("{}:{}: {}", file_, where.begin.line, message)));
  }
  [[noreturn]] void fail_at(const toml::source_region& where, std::size_t column, std::string_view message) const {
    throw InvalidArgument(one_line(fmt::format("{}:{}: column {}: {}", file_, where.begin.line, column, message)));
  }
  std::string origin(const toml::source_region& where) const { return fmt::format("{}:{}", file_, where.begin.line); }

  std::string text(const toml::table& t, std::string_view key, bool required, std::string fallback = {}) const {
    const toml::node* node = t.get(key);
    if (!node) {
      if (required) fail(t.source(), fmt::format("missing key '{}'", key));
      return fallback;
    }
    const auto* s = node->as_string();
    if (!s) fail(node->source(), fmt::format("key '{}' must be a string", key));
    if (s->get().size() > (key == "lobe" || key == "lobe_u" || key == "brdf" || key == "normalization"
                               ? expr::kMaxFormulaLength
                               : kMaxTextLength))
      fail(node->source(), fmt::format("key '{}' is too long ({} characters)", key, s->get().size()));
    return s->get();
  }

  double number(const toml::table& t, std::string_view key, std::string_view param) const {
    const toml::node* node = t.get(key);
    if (!node) fail(t.source(), fmt::format("parameter '{}' lacks key '{}'{}", param, key,
                                            key == "default" ? "" : " (every parameter has a range)"));
    const auto value = node->value<double>();
    if (!node->is_number() || !value || std::isnan(*value))
      fail(node->source(), fmt::format("parameter '{}': key '{}' must be a number", param, key));
    return *value;
  }

  /// Parses `text` (the string at `node`) as a step of `program`: `name` empty for the result.
  void formula(expr::Program& program, const toml::node& node, std::string_view key, std::string_view name,
               std::string_view text, std::size_t offset) const {
    try {
      if (name.empty()) program.set_result(text);
      else program.let(std::string(name), text);
    } catch (const expr::ParseError& e) {
      fail_at(node.source(), node.source().begin.column + offset + e.column(),
              fmt::format("{}: {}", key, e.reason()));
    } catch (const InvalidArgument& e) {
      fail(node.source(), fmt::format("{}: {}", key, e.what()));
    }
  }

  void check_keys(const toml::table& t, const std::set<std::string_view>& allowed, std::string_view what) const {
    for (const auto& [key, value] : t)
      if (!allowed.count(key.str()))
        fail(key.source(), fmt::format("unknown key '{}' in {} (known: {})", key.str(), what, known(allowed)));
  }

 private:
  std::string file_;
};

std::vector<ParamInfo> read_params(const Reader& r, const toml::table& model) {
  std::vector<std::pair<toml::source_position, ParamInfo>> found;
  const toml::node* node = model.get("params");
  if (!node) return {};
  const toml::table* params = node->as_table();
  if (!params) r.fail(node->source(), "key 'params' must be a table ([model.params.NAME])");
  for (const auto& [key, value] : *params) {
    const std::string name(key.str());
    const toml::table* p = value.as_table();
    if (!p) r.fail(key.source(), fmt::format("parameter '{}' must be a table with default, min and max", name));
    r.check_keys(*p, kParamKeys, fmt::format("parameter '{}'", name));
    try {
      expr::require_slot_name(name, "parameter");
    } catch (const InvalidArgument& e) {
      r.fail(key.source(), e.what());
    }
    ParamInfo info{name, r.number(*p, "default", name), r.number(*p, "min", name), r.number(*p, "max", name), false,
                   r.text(*p, "meaning", false)};
    if (const toml::node* exclusive = p->get("min_exclusive")) {
      const auto* flag = exclusive->as_boolean();
      if (!flag) r.fail(exclusive->source(), fmt::format("parameter '{}': min_exclusive must be true or false", name));
      info.min_exclusive = flag->get();
    }
    if (!(info.min <= info.max) || (info.min_exclusive && info.min == info.max))
      r.fail(p->source(), fmt::format("parameter '{}': the range {} is empty", name, info.range_text()));
    if (!std::isfinite(info.default_value) || !info.accepts(info.default_value))
      r.fail(p->get("default")->source(), fmt::format("parameter '{}': default {} is outside its range {}", name,
                                                      info.default_value, info.range_text()));
    found.emplace_back(key.source().begin, std::move(info));
  }
  // The file's order (a TOML table is unordered): the order of `params` in Model and shaders.
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
    return a.first.line != b.first.line ? a.first.line < b.first.line : a.first.column < b.first.column;
  });
  std::vector<ParamInfo> out;
  for (auto& f : found) out.push_back(std::move(f.second));
  return out;
}

std::vector<std::string> names_of(const std::vector<ParamInfo>& params) {
  std::vector<std::string> names;
  for (const auto& p : params) names.push_back(p.name);
  return names;
}

/// The let steps and result of `key` in a program over `inputs` and the parameters.
std::shared_ptr<const expr::Program> read_program(const Reader& r, const toml::table& model, std::string_view key,
                                                  std::vector<std::string> inputs, const std::vector<ParamInfo>& params) {
  std::shared_ptr<expr::Program> program;
  try {  // a parameter named like an input of this kind (c, u; nl, nv, …)
    program = std::make_shared<expr::Program>(std::move(inputs), names_of(params));
  } catch (const InvalidArgument& e) {
    r.fail(model.get("params")->source(), e.what());
  }
  if (const toml::node* lets = model.get("let")) {
    const toml::array* list = lets->as_array();
    if (!list) r.fail(lets->source(), "key 'let' must be an array of strings \"NAME = FORMULA\"");
    for (const toml::node& item : *list) {
      const auto* s = item.as_string();
      if (!s) r.fail(item.source(), "each let is a string \"NAME = FORMULA\"");
      const std::string& text = s->get();
      const auto equals = text.find('=');
      if (equals == std::string::npos) r.fail(item.source(), fmt::format("let '{}' has no '=' (NAME = FORMULA)", text));
      std::string name = text.substr(0, equals);
      name.erase(0, name.find_first_not_of(' '));
      name.erase(name.find_last_not_of(' ') + 1);
      r.formula(*program, item, "let", name.empty() ? "?" : name, std::string_view(text).substr(equals + 1), equals + 1);
    }
  }
  const toml::node* node = model.get(key);
  r.formula(*program, *node, key, {}, r.text(model, key, true), 0);
  return program;
}

/// k for a lobe model: none, quadrature, or a formula in the parameters.
struct Coefficient {
  Normalization normalization = Normalization::none;
  std::shared_ptr<const expr::Program> formula;
};

Coefficient read_coefficient(const Reader& r, const toml::table& model, const std::vector<ParamInfo>& params) {
  const std::string text = r.text(model, "normalization", true);
  if (text == "none") return {};
  if (text == "quadrature") return {Normalization::quadrature, nullptr};
  auto program = std::make_shared<expr::Program>(std::vector<std::string>{}, names_of(params));
  r.formula(*program, *model.get("normalization"), "normalization", {}, text, 0);
  return {Normalization::formula, program};
}

double evaluate_coefficient(const Coefficient& coef, const lobes::Formula& lobe, Form form,
                            std::span<const double> values, std::string_view id) {
  double k = 1;
  if (coef.normalization == Normalization::quadrature) {
    k = normalize::quadrature(lobe, form);
  } else if (coef.formula) {
    std::array<double, expr::kMaxSlots> slots;
    std::copy(values.begin(), values.end(), slots.begin());
    k = coef.formula->evaluate(std::span<double>(slots.data(), coef.formula->slot_names().size()));
  }
  if (!(k > 0) || !std::isfinite(k))
    throw InvalidArgument(fmt::format("model '{}': its normalization gives k = {} at these parameters "
                                      "(k must be finite and > 0)", id, k));
  return k;
}

void check_id(const Reader& r, const toml::table& model, const std::string& id) {
  const bool valid = !id.empty() && id.size() <= kMaxIdLength && std::isalnum(static_cast<unsigned char>(id[0])) &&
                     std::all_of(id.begin(), id.end(), [](char c) {
                       return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
                     });
  if (!valid)
    r.fail(model.get("id")->source(), fmt::format("model id '{}' must be 1–{} letters, digits, '-', '_' or '.', "
                                                  "starting with a letter or digit", id, kMaxIdLength));
}

ModelInfo lobe_info(ModelInfo info, std::shared_ptr<const lobes::FormulaDefinition> definition, Coefficient coef) {
  const Form form = info.form;
  const std::string id = info.id;
  info.make = [definition, coef, form, id](std::span<const double> values) -> Impl {
    lobes::Formula lobe(definition, {values.begin(), values.end()});
    const double k = evaluate_coefficient(coef, lobe, form, values, id);
    return LobeModel{std::move(lobe), form, k};
  };
  return info;
}

ModelInfo brdf_info(ModelInfo info, std::shared_ptr<const expr::Program> program) {
  info.make = [program](std::span<const double> values) -> Impl {
    return FullBrdf{FormulaBrdf{program, {values.begin(), values.end()}}};
  };
  return info;
}

ModelInfo read_model(const Reader& r, const toml::table& model) {
  r.check_keys(model, kModelKeys, "a model");
  ModelInfo info{};
  info.id = r.text(model, "id", true);
  check_id(r, model, info.id);
  info.name = r.text(model, "name", true);
  info.source = r.text(model, "source", false, "user-defined");
  info.origin = {OriginKind::file, r.origin(model.source())};
  const std::string kind = r.text(model, "kind", true);
  info.params = read_params(r, model);
  auto reject = [&](std::string_view key, std::string_view why) {
    if (const toml::node* n = model.get(key)) r.fail(n->source(), fmt::format("key '{}' {}", key, why));
  };
  if (kind == "lobe") {
    reject("brdf", "belongs to kind = \"brdf\" (a lobe has lobe = or lobe_u =)");
    info.kind = ModelKind::lobe;
    const std::string form = r.text(model, "form", true);  // outside the try: a missing key is its own error
    try {
      info.form = parse_form(form);
    } catch (const InvalidArgument& e) {
      r.fail(model.get("form")->source(), e.what());
    }
    if (!model.get("lobe") && !model.get("lobe_u")) r.fail(model.source(), "missing key 'lobe' (or 'lobe_u')");
    auto definition = std::make_shared<lobes::FormulaDefinition>();
    if (model.get("lobe")) definition->in_cos = read_program(r, model, "lobe", lobe_inputs(), info.params);
    if (model.get("lobe_u")) definition->in_log_cos = read_program(r, model, "lobe_u", lobe_inputs(), info.params);
    Coefficient coef = read_coefficient(r, model, info.params);
    info.normalization = coef.normalization;
    info.coef_program = coef.formula;
    info.coef_formula = coef.normalization == Normalization::quadrature ? "1/albedo(0) by quadrature"
                                                                        : r.text(model, "normalization", true);
    if (coef.normalization == Normalization::none) info.coef_formula = "1";
    info.summary = r.text(model, "summary", false,
                          "F = " + r.text(model, model.get("lobe") ? "lobe" : "lobe_u", true));
    return lobe_info(std::move(info), std::move(definition), std::move(coef));
  }
  if (kind == "brdf") {
    for (const char* key : {"lobe", "lobe_u", "form", "normalization"})
      reject(key, "belongs to kind = \"lobe\"");
    info.kind = ModelKind::brdf;
    info.form = Form::rv;
    info.normalization = Normalization::none;
    info.coef_formula = "1";
    info.summary = r.text(model, "summary", false, "f = " + r.text(model, "brdf", true));
    return brdf_info(std::move(info), read_program(r, model, "brdf", brdf_inputs(), info.params));
  }
  r.fail(model.get("kind")->source(), fmt::format("kind '{}' is neither \"lobe\" nor \"brdf\"", kind));
}

}  // namespace

std::vector<ModelInfo> parse_model_file(std::string_view text, std::string_view filename) {
  const Reader r(filename);
  toml::table root;
  try {
    root = toml::parse(text, filename);
  } catch (const toml::parse_error& e) {
    r.fail_at(e.source(), e.source().begin.column, e.description());
  }
  for (const auto& [key, value] : root)
    if (key.str() != "model")
      r.fail(key.source(), fmt::format("unknown top-level key '{}' (a model file holds [[model]] tables)", key.str()));
  const toml::node* list = root.get("model");
  if (!list) throw InvalidArgument(fmt::format("{}: no [[model]] table", filename));
  const toml::array* models = list->as_array();
  if (!models) r.fail(list->source(), "'model' must be an array of tables: write [[model]]");
  if (models->size() > kMaxModelsPerFile)
    r.fail(list->source(), fmt::format("{} models in one file (at most {})", models->size(), kMaxModelsPerFile));
  std::vector<ModelInfo> out;
  for (const toml::node& item : *models) {
    const toml::table* model = item.as_table();
    if (!model) r.fail(item.source(), "each model is a table: write [[model]]");
    out.push_back(read_model(r, *model));
  }
  return out;
}

std::vector<ModelInfo> load_model_file(const std::string& path) {
  return parse_model_file(io::read_file(path), path);
}

void register_model_file(const std::string& path) { register_models(load_model_file(path)); }

bool is_inline_model(std::string_view id) noexcept { return id.starts_with("lobe:") || id.starts_with("brdf:"); }

std::shared_ptr<const ModelInfo> inline_model(std::string_view spec, const ParamValues& values) {
  const bool lobe = spec.starts_with("lobe:");
  const std::string_view text = spec.substr(5);
  std::vector<std::string> inputs = lobe ? lobe_inputs() : brdf_inputs();
  // The parameters: the identifiers that are neither inputs nor constants, in order of use.
  std::vector<ParamInfo> params;
  try {
    const expr::Expression parsed = expr::parse(text);
    for (const auto& name : parsed.variables()) {
      if (std::find(inputs.begin(), inputs.end(), name) != inputs.end() || name == "pi" || name == "e") continue;
      const auto value = values.find(name);
      const double given = value == values.end() || !std::isfinite(value->second) ? 1.0 : value->second;
      constexpr double kMax = std::numeric_limits<double>::max();
      params.push_back(ParamInfo{name, given, -kMax, kMax, false, "inline parameter"});
    }
  } catch (const expr::ParseError& e) {
    throw InvalidField("model", fmt::format("column {}: {}", e.column() + 5, e.reason()));
  }
  auto program = std::make_shared<expr::Program>(std::move(inputs), names_of(params));
  try {
    program->set_result(text);
  } catch (const expr::ParseError& e) {
    throw InvalidField("model", fmt::format("column {}: {}", e.column() + 5, e.reason()));
  } catch (const InvalidArgument& e) {
    throw InvalidField("model", e.what());
  }
  ModelInfo info{};
  info.id = std::string(spec);
  info.name = lobe ? "inline lobe" : "inline BRDF";
  info.summary = std::string(spec);
  info.source = "inline";
  info.origin = {OriginKind::inline_formula, ""};
  info.params = std::move(params);
  info.coef_formula = "1";
  info.normalization = Normalization::none;
  info.form = Form::rv;
  if (!lobe) {
    info.kind = ModelKind::brdf;
    return std::make_shared<const ModelInfo>(brdf_info(std::move(info), std::move(program)));
  }
  info.kind = ModelKind::lobe;
  auto definition = std::make_shared<lobes::FormulaDefinition>();
  definition->in_cos = std::move(program);
  return std::make_shared<const ModelInfo>(lobe_info(std::move(info), std::move(definition), {}));
}

}  // namespace specula
