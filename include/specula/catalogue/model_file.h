#pragma once
// User-defined models: model files in TOML and inline definitions (docs/models.md).
//
//   [[model]]
//   id = "my-log"                 # letters, digits, - _ . ; not a built-in id
//   name = "log lobe, my copy"
//   source = "Romanyuk et al. 2023"   # optional
//   kind = "lobe"                 # "lobe" (f = k·F(c)) or "brdf" (f in the dot products)
//   form = "rv"                   # lobes: "rv" (c = R·V) or "nh" (c = N·H)
//   lobe = "max(0, 1 - 0.5*log2(1 - n*log2(c)))"   # F in c (and/or lobe_u = F in u = −ln c)
//   normalization = "quadrature"  # lobes: "none" | "quadrature" | a formula in the parameters
//   [model.params.n]
//   default = 20
//   min = 0
//   min_exclusive = true          # optional: (min, max] instead of [min, max]
//   max = 1e9
//   meaning = "specular exponent" # optional
//
// A full BRDF has kind = "brdf", brdf = "…" in nl, nv, nh, vh, lv and its parameters, and
// optionally let = ["D = …", "G = …"] (each usable after it is defined; lobes may have lets too).
// Formulas use expr::parse's syntax and the constants pi and e.
//
// Errors are InvalidArgument with one line "FILE:LINE: column N: …" (or "FILE:LINE: …"): a TOML
// syntax error, an unknown or missing key, a wrong type, a bad id, a parameter without a range or
// a default outside it, a formula that does not parse, names an unknown identifier, or nests too
// deep or too long. A formula that is negative, NaN or not 1 at c = 1 is no input error:
// `specula check` reports it.
#include <string>
#include <string_view>
#include <vector>

#include "specula/catalogue/catalogue.h"

namespace specula {

/// The models defined in `text`, read from `filename` (named in errors and in each model's
/// origin: OriginKind::file at "FILE:LINE").
std::vector<ModelInfo> parse_model_file(std::string_view text, std::string_view filename);

/// parse_model_file of the file at `path` (io::read_file's size cap applies).
std::vector<ModelInfo> load_model_file(const std::string& path);

/// load_model_file, then register_models.
void register_model_file(const std::string& path);

/// True for "lobe: FORMULA" and "brdf: FORMULA".
bool is_inline_model(std::string_view id) noexcept;

/// The model an inline definition names: its parameters are the formula's identifiers other
/// than its inputs (c and u, or nl nv nh vh lv) and the constants, each with any finite value,
/// defaulting to its value in `values`, or 1. A lobe is in form rv with k = 1. Throws
/// InvalidField "model" ("column N: …", the column in `spec`) for a bad formula: the interface
/// that asked puts the field's name before it (queries::ModelRef: "--model: column N: …").
std::shared_ptr<const ModelInfo> inline_model(std::string_view spec, const ParamValues& values);

}  // namespace specula
