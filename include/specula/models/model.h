#pragma once
// The model types (docs/math.md §2): a model's definition (ModelInfo: id, parameters, default form
// and normalization, how it is made) and `Model`, a model with its parameter values bound, ready
// to evaluate: a lobe model k·F(c), a full BRDF, or a compensated model M+ms. The catalogue of
// models by id (built-in, registered, M+ms) is catalogue/catalogue.h.
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "specula/brdf/full_brdf.h"
#include "specula/brdf/lobe_brdf.h"
#include "specula/exceptions.h"
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
inline constexpr std::size_t kModelKindCount = static_cast<std::size_t>(ModelKind::brdf) + 1;  // brdf: the last

/// How a lobe model's k is defined.
enum class Normalization {
  none,     ///< k = 1: the bare lobe
  exact,    ///< k from the exact closed form (lobes/closed_form.h)
  formula,     ///< k from a published formula, exact or not (e.g. the paper's fit)
  quadrature   ///< k = 1 / (albedo at normal incidence), by quadrature (user-defined lobes)
};
inline constexpr std::size_t kNormalizationCount = static_cast<std::size_t>(Normalization::quadrature) + 1;

const char* to_string(ModelKind kind) noexcept;
const char* to_string(Normalization normalization) noexcept;

/// A lobe model: f = k·F(c), c from the form (the run-time twin of LobeBrdf<L>).
struct LobeModel {
  lobes::Lobe lobe;
  Form form = Form::rv;
  double k = 1;
};

using ModelImpl = std::variant<LobeModel, FullBrdf, Compensated>;

/// Where a model is defined.
enum class OriginKind {
  builtin,         ///< a built-in family (families/)
  file,            ///< a model file (catalogue/model_file.h)
  inline_formula,  ///< an inline definition, "lobe: FORMULA" or "brdf: FORMULA"
  request          ///< a definition object in a server request
};
inline constexpr std::size_t kOriginKindCount = static_cast<std::size_t>(OriginKind::request) + 1;  // request: the last

/// "built-in", "file", "inline" or "request" ("" outside the enum).
constexpr const char* to_string(OriginKind kind) noexcept {
  switch (kind) {
    case OriginKind::builtin: return "built-in";
    case OriginKind::file: return "file";
    case OriginKind::inline_formula: return "inline";
    case OriginKind::request: return "request";
  }
  return "";
}
static_assert(names_complete<OriginKind, kOriginKindCount>([](OriginKind k) { return to_string(k); }));

struct ModelOrigin {
  OriginKind kind = OriginKind::builtin;
  std::string file_line;  ///< a model file's "FILE:LINE" (kind file only)
};

/// What messages, comments and `models --json` show: the model file's "FILE:LINE", else the kind.
std::string to_string(const ModelOrigin& origin);

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
  ModelOrigin origin;  ///< where the model is defined

  const ParamInfo* find_param(std::string_view name) const noexcept;
  bool is_builtin() const noexcept { return origin.kind == OriginKind::builtin; }
};

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
  /// M+ms (or another compensation suffix): its base model M, M's energy table and the scheme;
  /// nullptr for any other model. The one accessor of compensation: every consumer composes f
  /// from f_M with these (Compensated::apply).
  const Compensated* compensated() const noexcept { return std::get_if<Compensated>(&impl_); }
  /// Preconditions for the next three: is_lobe().
  const lobes::Lobe& lobe() const noexcept { return std::get<LobeModel>(impl_).lobe; }
  Form form() const noexcept { return std::get<LobeModel>(impl_).form; }
  /// The normalizing coefficient k of a lobe model.
  double coef() const noexcept { return std::get<LobeModel>(impl_).k; }
  /// Precondition: !is_lobe() && !compensated().
  const FullBrdf& brdf() const noexcept { return std::get<FullBrdf>(impl_); }
  /// The same lobe model with coefficient k (e.g. k = 1 for the bare lobe, or a strict k).
  /// Throws InvalidArgument for a full BRDF or a k that is not finite and > 0.
  Model with_coef(double k) const;
  /// Whether a lobe model's k is not its own: with_coef gave another (false for a full BRDF).
  bool coef_overridden() const noexcept { return is_lobe() && coef() != own_coef_; }
  /// k·F(c): the BRDF's value as a function of its form's cosine.
  double at_cos(double c) const noexcept { return coef() * lobes::eval(lobe(), c); }

  /// f(L, V) about the normal N (unit vectors, L toward the light, V toward the viewer).
  double operator()(const Vec3& n, const Vec3& l, const Vec3& v) const noexcept {
    return std::visit([&](const auto& m) { return eval(m, n, l, v); }, impl_);
  }
  /// Whether the direction an albedo holds fixed is V (the viewer's albedo, integrated over L):
  /// true for a scaled compensation, which is not reciprocal (models/compensated.h); for any
  /// other model it is L, and by reciprocity the two albedos are one.
  bool fixes_viewer() const noexcept {
    const Compensated* c = compensated();
    return c && scales(c->scheme);
  }
  /// f with ω_fixed the direction an albedo or a sampler holds fixed and ω the one it integrates
  /// over: f(N, ω_fixed, ω), or f(N, ω, ω_fixed) where fixes_viewer().
  double from_fixed(const Vec3& n, const Vec3& fixed, const Vec3& other) const noexcept {
    return fixes_viewer() ? (*this)(n, other, fixed) : (*this)(n, fixed, other);
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
  /// f_M + F_ms f_ms, or f_M times Turquin's scale (models/compensated.h).
  static double eval(const Compensated& c, const Vec3& n, const Vec3& l, const Vec3& v) noexcept {
    const double nl = dot(n, l), nv = dot(n, v);
    if (nl <= 0 || nv <= 0) return 0;
    return c.apply((*c.base)(n, l, v), nl, nv);
  }

  std::shared_ptr<const ModelInfo> info_;
  std::vector<double> values_;
  ModelImpl impl_;
  double own_coef_ = 1;  ///< a lobe model's k as its definition made it
};

/// make_model's error about one parameter (unknown, out of range, NaN): InvalidField "params"
/// that names the parameter, so that an interface that takes a parameter under a key of its own
/// (normalize's n) can name that key.
class InvalidParameter : public InvalidField {
 public:
  InvalidParameter(std::string param, const std::string& message)
      : InvalidField("params", message), param_(std::move(param)) {}
  const std::string& param() const noexcept { return param_; }

 private:
  std::string param_;
};

/// The model `info` defines, with the given parameters (others at their defaults), in `form` if
/// given (lobe models only; k stays the model's own). Throws InvalidField naming the field at
/// fault: InvalidParameter ("params") for an unknown parameter or a value out of range or NaN,
/// "form" for a form on a full BRDF, and for a definition that cannot be made at these values
/// (a user lobe's k not finite and > 0) "params" when parameters are given, else "model". By id:
/// catalogue/catalogue.h.
Model make_model(std::shared_ptr<const ModelInfo> info, const ParamValues& params = {},
                 std::optional<Form> form = std::nullopt);

/// "rv" or "nh"; throws InvalidArgument otherwise.
Form parse_form(std::string_view text);

}  // namespace specula
