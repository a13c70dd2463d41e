// The model types (models/model.h): parameters, kinds, and making a Model from its definition.
#include "specula/models/model.h"

#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "specula/exceptions.h"

namespace specula {
namespace {

std::string param_names(const ModelInfo& info) {
  std::vector<std::string_view> names;
  for (const auto& p : info.params) names.push_back(p.name);
  return fmt::format("{}", fmt::join(names, ", "));
}

}  // namespace

std::string ParamInfo::range_text() const {
  return fmt::format("{}{:g}, {:g}]", min_exclusive ? '(' : '[', min, max);
}

namespace {

// The kinds' and normalizations' names, the one list to_string reads ("" outside the enum).
constexpr const char* name_of(ModelKind kind) noexcept {
  switch (kind) {
    case ModelKind::lobe: return "lobe";
    case ModelKind::brdf: return "brdf";
  }
  return "";
}
static_assert(names_complete<ModelKind, kModelKindCount>([](ModelKind k) { return name_of(k); }));

constexpr const char* name_of(Normalization normalization) noexcept {
  switch (normalization) {
    case Normalization::none: return "none";
    case Normalization::exact: return "exact";
    case Normalization::formula: return "formula";
    case Normalization::quadrature: return "quadrature";
  }
  return "";
}
static_assert(names_complete<Normalization, kNormalizationCount>([](Normalization n) { return name_of(n); }));

}  // namespace

const char* to_string(ModelKind kind) noexcept { return name_of(kind); }

const char* to_string(Normalization normalization) noexcept { return name_of(normalization); }

std::string to_string(const ModelOrigin& origin) {
  return origin.kind == OriginKind::file ? origin.file_line : to_string(origin.kind);
}

const ParamInfo* ModelInfo::find_param(std::string_view name) const noexcept {
  for (const auto& p : params)
    if (p.name == name) return &p;
  return nullptr;
}

double Model::param(std::string_view name) const {
  for (std::size_t i = 0; i < info_->params.size(); ++i)
    if (info_->params[i].name == name) return values_[i];
  throw InvalidArgument(fmt::format("model '{}' has no parameter '{}'", id(), name));
}

Model Model::with_coef(double k) const {
  auto* lobe_model = std::get_if<LobeModel>(&impl_);
  if (!lobe_model) throw InvalidArgument(fmt::format("model '{}' is a full BRDF and has no coefficient", id()));
  if (!(k > 0) || !std::isfinite(k))
    throw InvalidArgument(fmt::format("coefficient {} for model '{}' must be finite and > 0", k, id()));
  Model copy = *this;
  std::get<LobeModel>(copy.impl_).k = k;
  return copy;
}

namespace {

/// The definition's implementation at `values`; a definition that cannot be made there names the
/// parameters when some were given, else the model.
ModelImpl implementation(const ModelInfo& def, std::span<const double> values, const ParamValues& given) {
  try {
    return def.make(values);
  } catch (const InvalidField&) {
    throw;
  } catch (const InvalidArgument& e) {
    throw InvalidField(given.empty() ? "model" : "params", e.what());
  }
}

}  // namespace

Model make_model(std::shared_ptr<const ModelInfo> info, const ParamValues& params, std::optional<Form> form) {
  Model model;
  model.info_ = std::move(info);
  const ModelInfo& def = *model.info_;
  const std::string_view id = def.id;
  for (const auto& p : def.params) model.values_.push_back(p.default_value);
  for (const auto& [name, value] : params) {
    const ParamInfo* p = def.find_param(name);
    if (!p)
      throw InvalidParameter(name, fmt::format("model '{}' has no parameter '{}' (its parameters: {})", id, name,
                                               param_names(def)));
    if (std::isnan(value) || !p->accepts(value))
      throw InvalidParameter(name, fmt::format("parameter {} = {} is out of range for model '{}': valid {}", name,
                                               value, id, p->range_text()));
    model.values_[static_cast<std::size_t>(p - def.params.data())] = value;
  }
  model.impl_ = implementation(def, model.values_, params);
  if (auto* lobe_model = std::get_if<LobeModel>(&model.impl_)) {
    model.own_coef_ = lobe_model->k;
    if (form) lobe_model->form = *form;
  } else if (form) {
    throw InvalidField("form", fmt::format("model '{}' is a full BRDF and has no form", id));
  }
  return model;
}

Form parse_form(std::string_view text) {
  if (const auto form = form_named(text)) return *form;
  throw InvalidArgument(fmt::format("unknown form '{}' (expected {})", text, names_listed<Form, kFormCount>(ToString{})));
}

}  // namespace specula
