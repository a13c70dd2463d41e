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

const char* to_string(ModelKind kind) noexcept { return kind == ModelKind::lobe ? "lobe" : "brdf"; }

const char* to_string(Normalization normalization) noexcept {
  switch (normalization) {
    case Normalization::none: return "none";
    case Normalization::exact: return "exact";
    case Normalization::formula: return "formula";
    case Normalization::quadrature: return "quadrature";
  }
  return "none";
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

Model make_model(std::shared_ptr<const ModelInfo> info, const ParamValues& params, std::optional<Form> form) {
  Model model;
  model.info_ = std::move(info);
  const ModelInfo& def = *model.info_;
  const std::string_view id = def.id;
  for (const auto& p : def.params) model.values_.push_back(p.default_value);
  for (const auto& [name, value] : params) {
    const ParamInfo* p = def.find_param(name);
    if (!p)
      throw InvalidArgument(fmt::format("model '{}' has no parameter '{}' (its parameters: {})", id,
                                        name, param_names(def)));
    if (std::isnan(value) || !p->accepts(value))
      throw InvalidArgument(fmt::format("parameter {} = {} is out of range for model '{}': valid {}",
                                        name, value, id, p->range_text()));
    model.values_[static_cast<std::size_t>(p - def.params.data())] = value;
  }
  model.impl_ = def.make(model.values_);
  if (form) {
    auto* lobe_model = std::get_if<LobeModel>(&model.impl_);
    if (!lobe_model)
      throw InvalidArgument(fmt::format("model '{}' is a full BRDF and has no form", id));
    lobe_model->form = *form;
  }
  return model;
}

Form parse_form(std::string_view text) {
  if (text == "rv") return Form::rv;
  if (text == "nh") return Form::nh;
  throw InvalidArgument(fmt::format("unknown form '{}' (expected rv or nh)", text));
}

}  // namespace specula
