#pragma once
// The model catalogue: every model by its id — the built-in ones (one per model of each family,
// families/), those registered from model files (catalogue/model_file.h), and "M+ms" for any of
// them (models/compensated.h) — and making a model from an id or an inline definition. Above
// analysis, which builds M+ms's energy table; nothing below it looks a model up by id.
#include <deque>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "specula/brdf/fresnel.h"
#include "specula/models/model.h"

namespace specula {

/// Every model, in the order the CLI lists them: the built-in ones, then those registered.
/// References stay valid while models are registered.
const std::deque<ModelInfo>& models();
/// nullptr if unknown. "M+ms" for a known M (not itself compensated) is M's compensated model
/// (models/compensated.h): not in models(), made on first lookup and kept.
const ModelInfo* find_model(std::string_view id) noexcept;
/// Adds user-defined models (catalogue/model_file.h) to models(). Throws InvalidArgument, adding
/// none, if an id is already taken (by a built-in model or an earlier registration) or repeated.
/// Not thread-safe against concurrent lookups: register before the work starts.
void register_models(std::vector<ModelInfo> infos);
/// Removes every registered model (tests).
void clear_registered_models();

/// The definition `id` names: a model's id (built-in or registered), or an inline definition,
/// "lobe: FORMULA" or "brdf: FORMULA" (catalogue/model_file.h), whose parameters are the
/// formula's other identifiers, each defaulting to its value in `params`. Throws InvalidField
/// "model" for an unknown id or a bad inline formula.
std::shared_ptr<const ModelInfo> model_definition(std::string_view id, const ParamValues& params = {});

/// The model `id` names (model_definition) with the given parameters (others at their defaults),
/// in `form` if given (lobe models only; k stays the model's own). Throws InvalidField naming the
/// field at fault: "model" (model_definition), "params" or "form" (make_model of a ModelInfo).
Model make_model(std::string_view id, const ParamValues& params = {}, std::optional<Form> form = std::nullopt);

/// The Fresnel of a built-in microfacet model with its F0 (the parameter "f0"): Schlick's for GGX
/// and Cook-Torrance, the exact dielectric's with η from F0 for Cook-Torrance 1982. None for the
/// other models (F ≡ 1, or a user's formula, whose parameters say nothing of a Fresnel) and for a
/// compensated one.
std::optional<fresnel::Channel> fresnel_of(const Model& model);

}  // namespace specula
