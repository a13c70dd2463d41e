#pragma once
// The full BRDFs as one type: the built-in ones and a user's formula. A model that is not a lobe
// holds one (models/model.h), unless it is a compensated model M+ms (models/compensated.h).
#include <variant>

#include "specula/brdf/beckmann.h"
#include "specula/brdf/cook_torrance.h"
#include "specula/brdf/formula_brdf.h"
#include "specula/brdf/ggx.h"
#include "specula/brdf/lambert.h"
#include "specula/brdf/ward.h"

namespace specula {

using FullBrdf = std::variant<Ward, CookTorrance1982, CookTorrance, Ggx, Beckmann, Lambert, FormulaBrdf>;

}  // namespace specula
