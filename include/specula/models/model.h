#pragma once
// The model catalogue (docs/math.md §2): every model with its id, parameters, default form and
// normalization, and `Model`, a model with its parameter values bound, ready to evaluate.
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "specula/brdf/cook_torrance.h"
#include "specula/brdf/formula_brdf.h"
#include "specula/brdf/ggx.h"
#include "specula/brdf/lambert.h"
#include "specula/brdf/lobe_brdf.h"
#include "specula/brdf/ward.h"
#include "specula/lobes/lobes.h"
#include "specula/models/compensated.h"

namespace specula {

struct ParamInfo {
  std::string name;
  double default_value;
  double min;  ///< valid range [min, max], or (min, max] when min_exclusive
  double max;
  bool min_exclusive;
  std::string meaning;

  bool accepts(double value) const noexcept {
    return (min_exclusive ? value > min : value >= min) && value <= max;
  }
  std::string range_text() const;  ///< e.g. "(0, 1e9]"
};

enum class ModelKind { lobe, brdf };

/// How a lobe model's k is defined.
enum class Normalization {
  none,     ///< k = 1: the bare lobe
  exact,    ///< k from the exact closed form (normalize/closed_form.h)
  formula,     ///< k from a published formula, exact or not (e.g. the paper's fit)
  quadrature   ///< k = 1 / (albedo at normal incidence), by quadrature (user-defined lobes)
};

const char* to_string(ModelKind kind) noexcept;
const char* to_string(Normalization normalization) noexcept;

/// Compensated (models/compensated.h): any model with Kulla-Conty's multiple-scattering lobe.
using FullBrdf = std::variant<Ward, CookTorrance1982, CookTorrance, Ggx, Lambert, FormulaBrdf, Compensated>;

/// A lobe model: f = k·F(c), c from the form (the run-time twin of LobeBrdf<L>).
struct LobeModel {
  lobes::Lobe lobe;
  Form form = Form::rv;
  double k = 1;
};

using ModelImpl = std::variant<LobeModel, FullBrdf>;

struct ModelInfo {
  std::string id;
  std::string name;
  std::string summary;
  std::string source;  ///< where the formula comes from
  ModelKind kind;
  Form form;           ///< default form (lobe models)
  Normalization normalization;
  std::string coef_formula;  ///< k as text, "1" for bare lobes
  std::vector<ParamInfo> params;
  /// Builds the model's implementation from parameter values in `params` order.
  std::function<ModelImpl(std::span<const double> values)> make;
  /// A user lobe's k as a formula in the parameters (normalization = formula), for code generators.
  std::shared_ptr<const expr::Program> coef_program;
  /// Where the model is defined: "built-in", or the model file ("my.toml:3") or "inline".
  std::string origin = "built-in";

  const ParamInfo* find_param(std::string_view name) const noexcept;
  bool is_builtin() const noexcept { return origin == "built-in"; }
};

/// Every model, in the order the CLI lists them: the built-in ones, then those registered.
/// References stay valid while models are registered.
const std::deque<ModelInfo>& models();
/// nullptr if unknown. "M+ms" for a known M (not itself compensated) is M's compensated model
/// (models/compensated.h): not in models(), made on first lookup and kept.
const ModelInfo* find_model(std::string_view id) noexcept;
/// Adds user-defined models (models/model_file.h) to models(). Throws InvalidArgument, adding
/// none, if an id is already taken (by a built-in model or an earlier registration) or repeated.
/// Not thread-safe against concurrent lookups: register before the work starts.
void register_models(std::vector<ModelInfo> infos);
/// Removes every registered model (tests).
void clear_registered_models();

using ParamValues = std::map<std::string, double, std::less<>>;

class Model {
 public:
  const ModelInfo& info() const noexcept { return *info_; }
  /// The definition, shared: it outlives the registry entry (inline models have none).
  const std::shared_ptr<const ModelInfo>& shared_info() const noexcept { return info_; }
  std::string_view id() const noexcept { return info_->id; }
  /// Parameter values in info().params order.
  std::span<const double> params() const noexcept { return values_; }
  double param(std::string_view name) const;

  bool is_lobe() const noexcept { return std::holds_alternative<LobeModel>(impl_); }
  /// Preconditions for the next three: is_lobe().
  const lobes::Lobe& lobe() const noexcept { return std::get<LobeModel>(impl_).lobe; }
  Form form() const noexcept { return std::get<LobeModel>(impl_).form; }
  /// The normalizing coefficient k of a lobe model.
  double coef() const noexcept { return std::get<LobeModel>(impl_).k; }
  /// Precondition: !is_lobe().
  const FullBrdf& brdf() const noexcept { return std::get<FullBrdf>(impl_); }
  /// The same lobe model with coefficient k (e.g. k = 1 for the bare lobe, or a strict k).
  /// Throws InvalidArgument for a full BRDF or a k that is not finite and > 0.
  Model with_coef(double k) const;
  /// k·F(c): the BRDF's value as a function of its form's cosine.
  double at_cos(double c) const noexcept { return coef() * lobes::eval(lobe(), c); }

  /// f(L, V) about the normal N (unit vectors, L toward the light, V toward the viewer).
  double operator()(const Vec3& n, const Vec3& l, const Vec3& v) const noexcept {
    return std::visit([&](const auto& m) { return eval(m, n, l, v); }, impl_);
  }

  friend Model make_model(std::shared_ptr<const ModelInfo> info, const ParamValues& params,
                          std::optional<Form> form);

 private:
  static double eval(const LobeModel& m, const Vec3& n, const Vec3& l, const Vec3& v) noexcept {
    return m.k * lobes::eval(m.lobe, form_cosine(m.form, n, l, v));
  }
  static double eval(const FullBrdf& b, const Vec3& n, const Vec3& l, const Vec3& v) noexcept {
    return std::visit([&](const auto& brdf) { return brdf(n, l, v); }, b);
  }

  std::shared_ptr<const ModelInfo> info_;
  std::vector<double> values_;
  ModelImpl impl_;
};

/// The model `id` with the given parameters (others at their defaults), in `form` if given
/// (lobe models only; k stays the model's own). `id` is a model's id (built-in or registered) or
/// an inline definition, "lobe: FORMULA" or "brdf: FORMULA" (models/model_file.h), whose
/// parameters are the formula's other identifiers, each given in `params`. Throws
/// InvalidArgument naming the problem for an unknown model or parameter, a value out of range
/// or NaN, a form on a full BRDF, or a bad inline formula.
Model make_model(std::string_view id, const ParamValues& params = {},
                 std::optional<Form> form = std::nullopt);
/// The same for a definition held outside the registry.
Model make_model(std::shared_ptr<const ModelInfo> info, const ParamValues& params = {},
                 std::optional<Form> form = std::nullopt);

/// "rv" or "nh"; throws InvalidArgument otherwise.
Form parse_form(std::string_view text);

inline double Compensated::operator()(const Vec3& n, const Vec3& l, const Vec3& v) const noexcept {
  const double nl = dot(n, l), nv = dot(n, v);
  if (nl <= 0 || nv <= 0) return 0;
  return (*base)(n, l, v) + table->multiple_scattering(nl, nv);
}

}  // namespace specula
