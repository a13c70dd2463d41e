#pragma once
// A model defined in a request: a JSON object with a model file's keys (docs/models.md), read by
// parse_model_file so that its rules and numerics are exactly a model file's.
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "specula/models/model.h"

namespace specula::serve {

/// The model `definition` holds: {"kind": "lobe", "form": "rv", "lobe": "c^n",
/// "normalization": "quadrature", "params": {"n": {"default": 20, "min": 0, "max": 1e6}}}, id
/// and name optional ("user", "user-defined model"). It is the request's own: never registered,
/// whatever its id. InvalidField naming the key at fault below `field`: "model.lobe",
/// "model.let[1]", "model.params.n.default", with the model file's message without its file and
/// line ("column 9: unknown variable 'x' …", the column counted in the formula's string).
std::shared_ptr<const ModelInfo> definition_model(const nlohmann::json& definition, const std::string& field);

}  // namespace specula::serve
