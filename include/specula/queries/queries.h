#pragma once
// The computations behind the analysis commands of the CLI and the endpoints of the server —
// eval, normalize, albedo, error, check, glsl, models — with their validation, in one place so
// that both interfaces give the same numbers under the same rules. Inputs arrive as values
// (each interface parses its own syntax); results are io::Tables or text. Bad input throws
// InvalidField with the field's key ("theta_i", "params", "n", …) and a message that spells the
// field the way the interface does: `--theta-i` for the CLI, `theta_i` for the server's JSON.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "specula/analysis/check.h"
#include "specula/exceptions.h"
#include "specula/fit/fit.h"
#include "specula/glsl/glsl.h"
#include "specula/io/table.h"
#include "specula/models/model.h"

namespace specula::queries {

using specula::Spelling;  // how an interface spells a field's key (exceptions.h)
using specula::spelled;

/// A model as a request names it: an id or an inline definition ("lobe: …", "brdf: …"), or a
/// definition of the request's own, held here only (never registered, never looked up by id).
class ModelRef {
 public:
  ModelRef() = default;
  ModelRef(std::string id) : id_(std::move(id)) {}  ///< implicit: wherever an id was, a ModelRef is
  explicit ModelRef(std::shared_ptr<const ModelInfo> definition) : definition_(std::move(definition)) {}

  bool empty() const noexcept { return !definition_ && id_.empty(); }
  /// The id, or the definition's own id: what output metadata calls the model.
  std::string_view name() const noexcept { return definition_ ? std::string_view(definition_->id) : id_; }
  /// Whether the id is an inline definition ("lobe: …"), whose errors quote a column of it.
  bool is_inline() const noexcept;
  /// The request's definition, or model_definition of the id (InvalidField "model"): an inline
  /// definition's parameters default to their values in `params`.
  std::shared_ptr<const ModelInfo> definition(const ParamValues& params = {}) const;
  /// make_model of the id or of the definition (InvalidField "model", "params" or "form").
  Model make(const ParamValues& params = {}, std::optional<Form> form = std::nullopt) const;

 private:
  std::string id_;
  std::shared_ptr<const ModelInfo> definition_;
};

/// A model with its values: the model, parameter values (others at their defaults), an optional
/// form and an optional coefficient overriding the model's own k.
struct ModelSpec {
  ModelRef model;
  ParamValues params;
  std::optional<Form> form;
  std::optional<double> coef;
};

/// The model, made once; InvalidField "model" (unknown id, bad inline formula), "form" (a form for
/// a full BRDF), "params" (unknown parameter, value out of range) or "coef" (not > 0, or a full
/// BRDF).
Model make(const ModelSpec& spec, Spelling spelling);

/// "rv" or "nh" as a Form; InvalidField "form" otherwise.
Form form_named(std::string_view text, Spelling spelling);

/// The lobe model `ref` at exponent n, other parameters from `params`, made once. InvalidField
/// `field` when `ref` is unknown or a full BRDF (`command` names what needs a lobe), "params" for
/// a bad parameter, "n" for an n out of the model's range (or a model without n).
Model lobe_model_at(std::string_view field, std::string_view command, const ModelRef& ref,
                    ParamValues params, double n, std::optional<Form> form, Spelling spelling);

// ---- eval --------------------------------------------------------------------------------------

/// Columns cos,value: value = k·F(c), or the bare lobe F(c). Lobe models only (else InvalidField
/// "cos"); every c in [-1, 1] (else InvalidField "cos").
io::Table eval_at_cosines(const Model& m, std::span<const double> cosines, bool bare_lobe,
                          Spelling spelling);

/// Columns theta_o_deg,value: f(L, V) with N = +z, L at polar angle theta_i (azimuth 0) and V at
/// (theta_o, phi_o), in degrees. InvalidField "theta_i" or "theta_o" outside [0, 90], "phi_o"
/// outside [-360, 360].
io::Table eval_at_directions(const Model& m, double theta_i_deg, std::span<const double> theta_o_deg,
                             double phi_o_deg, Spelling spelling);

/// Columns theta_h_deg,theta_d_deg,value, θ_h-major: f(L, V) with N = +z and L, V at the
/// half/difference angles (θ_h, θ_d, φ_d) (from_half_difference; 0 where either is below the
/// horizon), in degrees: BRDF Explorer's θ_h and θ_d slices and its θ_h × θ_d image. InvalidField
/// "theta_h" or "theta_d" outside [0, 90], "phi_d" outside [-360, 360].
io::Table eval_half_difference(const Model& m, std::span<const double> theta_h_deg, std::span<const double> theta_d_deg,
                               double phi_d_deg, Spelling spelling);

// ---- normalize ---------------------------------------------------------------------------------

/// How normalize finds k: the closed form where known, else quadrature (automatic); the closed
/// form only; quadrature only; or both, side by side.
enum class NormalizeMethod { automatic, exact, quadrature, both };
inline constexpr std::size_t kNormalizeMethodCount = static_cast<std::size_t>(NormalizeMethod::both) + 1;  // both: the last

/// "auto", "exact", "quadrature" or "both" ("" outside the enum).
constexpr const char* to_string(NormalizeMethod method) noexcept {
  switch (method) {
    case NormalizeMethod::automatic: return "auto";
    case NormalizeMethod::exact: return "exact";
    case NormalizeMethod::quadrature: return "quadrature";
    case NormalizeMethod::both: return "both";
  }
  return "";
}
static_assert(names_complete<NormalizeMethod, kNormalizeMethodCount>([](NormalizeMethod m) { return to_string(m); }));

/// What k makes 1: the albedo at normal incidence (the paper's), or the largest albedo over θ_i.
enum class Condition { normal, strict };
inline constexpr std::size_t kConditionCount = static_cast<std::size_t>(Condition::strict) + 1;  // strict: the last

/// "normal" or "strict" ("" outside the enum).
constexpr const char* to_string(Condition condition) noexcept {
  switch (condition) {
    case Condition::normal: return "normal";
    case Condition::strict: return "strict";
  }
  return "";
}
static_assert(names_complete<Condition, kConditionCount>([](Condition c) { return to_string(c); }));

/// The method named `text`; InvalidField "method" otherwise.
NormalizeMethod normalize_method_named(std::string_view text, Spelling spelling);
/// The condition named `text`; InvalidField "condition" otherwise.
Condition condition_named(std::string_view text, Spelling spelling);

struct NormalizeQuery {
  ModelRef model;
  ParamValues params;              ///< every parameter but n
  std::optional<Form> form;
  std::vector<double> n;           ///< empty: the model's default n
  NormalizeMethod method = NormalizeMethod::automatic;
  ModelRef compare;                ///< another lobe model, or empty
  Condition condition = Condition::normal;
  double step = 1;                 ///< the strict condition's θ_i grid step, [0.01, 45] degrees
};

/// Columns n,coef (+ coef_quadrature,rel_diff for method both, + coef_compare,delta with compare).
io::Table normalize_table(const NormalizeQuery& query, Spelling spelling);

// ---- albedo ------------------------------------------------------------------------------------

/// How albedo integrates: deterministic adaptive cubature; importance-sampled Monte Carlo (the
/// cross-check's mixture, analysis/monte_carlo.h); or Monte Carlo with one of BRDF Explorer's
/// estimators (sampling/estimators.h): uniform, cosine, the model's sampler, or MIS of the two.
enum class AlbedoMethod { cubature, monte_carlo, uniform, cosine, sampler, mis };
inline constexpr std::size_t kAlbedoMethodCount = static_cast<std::size_t>(AlbedoMethod::mis) + 1;  // mis: the last

/// "cubature", "monte-carlo", "uniform", "cosine", "sampler", "mis" ("" outside the enum).
constexpr const char* to_string(AlbedoMethod method) noexcept {
  switch (method) {
    case AlbedoMethod::cubature: return "cubature";
    case AlbedoMethod::monte_carlo: return "monte-carlo";
    case AlbedoMethod::uniform: return "uniform";
    case AlbedoMethod::cosine: return "cosine";
    case AlbedoMethod::sampler: return "sampler";
    case AlbedoMethod::mis: return "mis";
  }
  return "";
}

/// True for the methods that draw samples (every one but cubature).
constexpr bool samples(AlbedoMethod method) noexcept { return method != AlbedoMethod::cubature; }
static_assert(names_complete<AlbedoMethod, kAlbedoMethodCount>([](AlbedoMethod m) { return to_string(m); }));

/// The method named `text`; InvalidField "method" otherwise.
AlbedoMethod albedo_method_named(std::string_view text, Spelling spelling);

struct AlbedoQuery {
  std::vector<double> theta_deg;     ///< each in [0, 90)
  AlbedoMethod method = AlbedoMethod::cubature;
  std::uint64_t samples = 1'000'000;  ///< the sampling methods: per angle, [1, 1e9] (estimators: ≥ 2)
  std::uint64_t seed = 1;
};

/// Columns theta_deg,albedo (+ standard_error for the sampling methods), angles computed in parallel.
io::Table albedo_table(const Model& m, const AlbedoQuery& query, Spelling spelling);

// ---- error -------------------------------------------------------------------------------------

struct ErrorQuery {
  ModelRef model;
  ParamValues params;  ///< every parameter but n
  ModelRef reference{"phong"};
  std::vector<double> n;
  double zone = 0.5;   ///< (0, 1)
};

/// Columns n,max_abs,argmax_abs_deg,max_rel_epicenter,max_rel_attenuation of the bare lobes.
io::Table error_table(const ErrorQuery& query, Spelling spelling);

// ---- check -------------------------------------------------------------------------------------

struct CheckQuery {
  ModelSpec model;
  std::string sweep;           ///< a parameter to sweep over `values`, or empty: one case
  std::vector<double> values;
  analysis::CheckOptions options;
};

struct CheckCase {
  Model model;
  analysis::CheckResult result;
};

/// One case per swept value (the swept parameter may not also be in model.params).
/// InvalidField "sweep" (unknown parameter, also given in params), "pairs", "step", "grazing".
std::vector<CheckCase> check_cases(const CheckQuery& query, Spelling spelling);

/// The cases as a JSON array of objects (model metadata, albedos, verdicts).
std::string check_json(const std::vector<CheckCase>& cases);

// ---- fit ---------------------------------------------------------------------------------------

/// A lobe model's coefficient k(n) at each n, as `normalize` prints it (rounded to `digits`
/// decimals when given), as data for fit::search: variable n, target coef. InvalidField "params"
/// when n is among the parameters, else as lobe_model_at (field "model").
fit::Data normalization_data(const ModelSpec& spec, std::span<const double> n, std::optional<int> digits,
                             Spelling spelling);

// ---- glsl and models ---------------------------------------------------------------------------

/// The dialect named `text` (glsl::parse_dialect); InvalidField "dialect" otherwise.
glsl::Dialect dialect_named(std::string_view text);

/// The model as a self-contained GLSL function in `dialect` with a comment saying how to call it
/// (`specula glsl`).
std::string glsl_function(const Model& model, glsl::Dialect dialect);

/// Every model as a JSON array: id, name, kind, summary, source, parameters with their ranges,
/// and form, normalization and coef formula for lobe models.
std::string models_json();

}  // namespace specula::queries
