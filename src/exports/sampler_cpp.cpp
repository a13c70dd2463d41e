// The C++ export's sampler (src/exports/sampler_cpp.h): the math is the library's own source, the
// <cmath>-only files of include/specula/lobes/portable/ embedded as text; what is written here is
// sampling::Sampler's wiring of it for one model (src/sampling/sampler.cpp: its strategy, cosine
// share and M+ms mixture), with the model's parameter, cosine share and table baked in.
#include "sampler_cpp.h"

#include <algorithm>
#include <fmt/format.h>
#include <string>
#include <string_view>

#include "portable_files.h"
#include "specula/expr/comment.h"
#include "specula/glsl/glsl.h"
#include "specula/sampling/sampler.h"

namespace specula::exports {
namespace {

using sampling::Method;

std::string lit(double value) { return glsl::double_literal(value); }

// What every sampler uses.
constexpr const char* kCommon = R"(// Importance sampling as specula's sampling::Sampler does it (docs/sampling.md): frame N = +z, wi
// toward the light, wo toward the viewer; densities per unit solid angle of wo.
struct Sample {
  Vec3 wo;
  double pdf = 0;     // 0: no sample
  double weight = 0;  // f(N, wi, wo) cos(theta_o) / pdf
};
namespace sampling_detail {
constexpr double kPi = 3.141592653589793;
constexpr double kBelowOne = 1 - 0x1p-53;
// Directions: specula::radial's (specula/lobes/portable/directions.h, above).
using Frame = radial::Frame<Vec3>;
using radial::log_cos_between;
using radial::mirror;
inline Vec3 cosine_direction(double u1, double u2) { return radial::cosine_direction<Vec3>(u1, u2); }
)";

// The radial densities are specula::radial's (include/specula/lobes/portable/radial.h, embedded
// above the model's namespace as CppSampler::prelude).
constexpr const char* kUsingRadial = "using radial::PolarAngle;\n";

std::string power_radial(double n) {
  return fmt::format(R"(// Power-cosine: (n + 1)/(2 pi) cos^n about the axis, cos = (1 - u)^(1/(n+1)).
{}constexpr double kN = {};
inline double radial_density(double y) {{ return radial::power_density(kN, y); }}
inline PolarAngle radial_sample(double u) {{ return radial::power_sample(kN, u); }}
)",
                     kUsingRadial, lit(n));
}

std::string beckmann_radial(double alpha) {
  return fmt::format(R"(// Beckmann's D cos(theta_h): tan^2 = -alpha^2 ln(1 - u).
{}constexpr double kAlpha = {};
inline double radial_density(double y) {{ return radial::beckmann_density(kAlpha, y); }}
inline PolarAngle radial_sample(double u) {{ return radial::beckmann_sample(kAlpha, u); }}
)",
                     kUsingRadial, lit(alpha));
}

std::string log_radial(double n) {
  return fmt::format(R"(// The log lobe's own density in t = y/b, b = ln 2/n: Newton on its closed-form CDF.
{}constexpr double kN = {};
inline const radial::LogRadialData& log_data() {{
  static const radial::LogRadialData data(kN);
  return data;
}}
inline double radial_density(double y) {{ return radial::log_density(log_data(), y); }}
inline PolarAngle radial_sample(double u) {{ return radial::log_sample(log_data(), u); }}
)",
                     kUsingRadial, lit(n));
}

std::string table_radial(const sampling::Sampler::Table& table) {
  std::string values;
  for (std::size_t j = 0; j < table.cumulative.size(); ++j)
    values += lit(table.cumulative[j]) + (j % 4 == 3 ? ",\n" : ", ");
  const std::size_t cells = table.cumulative.size() - 1;
  return fmt::format(R"(// A tabulated inverse CDF in y = -ln cos: cells with edges y_j = width (e^(j ds) - 1), kCumulative[j] = P(y < y_j).
{}constexpr int kCells = {};
constexpr double kCumulative[kCells + 1] = {{
{}}};
constexpr radial::TableView kTable{{kCumulative, kCells, {}, {}, {}}};
inline double radial_density(double y) {{ return radial::table_density(kTable, y); }}
inline PolarAngle radial_sample(double u) {{ return radial::table_sample(kTable, u); }}
)",
                     kUsingRadial, cells, values, lit(table.width), lit(table.y_end), lit(table.ds));
}

std::string ggx_normals(double alpha) {
  return fmt::format(R"(// GGX's visible normals seen from wi (Heitz 2018, "Sampling the GGX Distribution of Visible Normals").
constexpr double kAlpha = {};
inline Vec3 ggx_sample(const Vec3& wi, double u1, double u2) {{
  return radial::ggx_visible_normal(kAlpha, wi, u1, u2);
}}
inline double ggx_pdf(const Vec3& wi, const Vec3& h) {{ return radial::ggx_visible_pdf(kAlpha, wi, h); }}
)",
                     lit(alpha));
}

// The strategies, by where the density is centred (sampler.cpp's Axis).
constexpr const char* kAboutReflection = R"(// The lobe's density about R, the mirror direction of wi.
inline Vec3 strategy_sample(const Vec3& wi, double u1, double u2) {
  const PolarAngle a = radial_sample(u1);
  return Frame(Vec3(-wi.x, -wi.y, wi.z)).to_world(a.cos, a.sin, 2 * kPi * u2);
}
inline double strategy_pdf(const Vec3& wi, const Vec3& wo) {
  return radial_density(log_cos_between(Vec3(-wi.x, -wi.y, wi.z), wo));
}
)";

constexpr const char* kHalfVector = R"(// The density of the half vector H about N; wo = 2(wi.H)H - wi, pdf(wo) = pdf(H)/(4 wo.H).
inline Vec3 strategy_sample(const Vec3& wi, double u1, double u2) {
  const PolarAngle a = radial_sample(u1);
  const double phi = 2 * kPi * u2;
  const Vec3 h(a.sin * std::cos(phi), a.sin * std::sin(phi), a.cos);
  return dot(wi, h) > 0 ? mirror(wi, h) : Vec3(0, 0, -1);
}
inline double strategy_pdf(const Vec3& wi, const Vec3& wo) {
  const Vec3 sum = wi + wo;
  if (!(dot(sum, sum) > 0)) return 0;
  const Vec3 h = normalize(sum);
  const double wo_h = dot(wo, h);
  if (!(wo_h > 0)) return 0;
  return radial_density(log_cos_between(Vec3(0, 0, 1), h)) / (4 * wo_h);
}
)";

constexpr const char* kVisibleNormals = R"(// GGX: the visible normal H, wo = 2(wi.H)H - wi.
inline Vec3 strategy_sample(const Vec3& wi, double u1, double u2) { return mirror(wi, ggx_sample(wi, u1, u2)); }
inline double strategy_pdf(const Vec3& wi, const Vec3& wo) {
  const Vec3 sum = wi + wo;
  if (!(dot(sum, sum) > 0)) return 0;
  const Vec3 h = normalize(sum);
  if (!(dot(wo, h) > 0)) return 0;
  return ggx_pdf(wi, h);
}
)";

/// True if `sampler` draws from a radial density (specula::radial's).
bool draws_radially(const sampling::Sampler& sampler) {
  if (sampler.cosine_share() >= 1) return false;
  switch (sampler.method()) {
    case Method::ggx_visible_normals:
    case Method::cosine: return false;
    case Method::power_cosine:
    case Method::log_t_space:
    case Method::beckmann:
    case Method::tabulated: return true;
  }
  unreachable();
}

/// The radial density and the strategy of the model's method; "" for cosine-weighted alone.
std::string strategy(const Model& model, const sampling::Sampler& sampler) {
  if (sampler.cosine_share() >= 1) return "";
  const double first = model.params().empty() ? 0 : model.params()[0];
  switch (sampler.method()) {
    case Method::ggx_visible_normals: return ggx_normals(first) + kVisibleNormals;
    case Method::power_cosine: return power_radial(first) + (model.form() == Form::rv ? kAboutReflection : kHalfVector);
    case Method::log_t_space: return log_radial(first) + (model.form() == Form::rv ? kAboutReflection : kHalfVector);
    case Method::beckmann: return beckmann_radial(first) + kHalfVector;
    case Method::cosine: return "";
    case Method::tabulated: {
      const bool about_r = model.is_lobe() && model.form() == Form::rv;
      return table_radial(sampler.table()) + (about_r ? kAboutReflection : kHalfVector);
    }
  }
  unreachable();
}

// The model's own density and draw: its strategy with the cosine share (a one-sample mixture).
constexpr const char* kStrategyDensity = R"(inline double model_pdf(const Vec3& wi, const Vec3& wo) {
  const double lobe = (1 - kShare) * strategy_pdf(wi, wo);
  return lobe + kShare * wo.z / kPi;
}
inline Vec3 model_draw(const Vec3& wi, double u1, double u2) {
  if (u1 < kShare) return cosine_direction(min(u1 / kShare, kBelowOne), u2);
  const double u = kShare > 0 ? min((u1 - kShare) / (1 - kShare), kBelowOne) : u1;
  return strategy_sample(wi, u, u2);
}
)";

// Cosine-weighted alone (kShare = 1).
constexpr const char* kCosineDensity = R"(inline double model_pdf(const Vec3&, const Vec3& wo) { return wo.z / kPi; }
inline Vec3 model_draw(const Vec3&, double u1, double u2) { return cosine_direction(min(u1, kBelowOne), u2); }
)";

// M+ms (sampler.cpp's compensated_sample and pdf); M's own model_pdf / model_draw in namespace base.
constexpr const char* kCompensatedDensity = R"(// M+ms: M's sampler with probability E(mu_i) (the energy f_M reflects), cosine-weighted otherwise.
inline double base_probability(const Vec3& wi) { return clamp(%ENERGY%(wi.z), 0.0, 1.0); }
inline double model_pdf(const Vec3& wi, const Vec3& wo) {
  const double p = base_probability(wi);
  return p * base::model_pdf(wi, wo) + (1 - p) * wo.z / kPi;
}
inline Vec3 model_draw(const Vec3& wi, double u1, double u2) {
  const double p = base_probability(wi);
  if (u1 < p) return base::model_draw(wi, min(u1 / p, kBelowOne), u2);
  return cosine_direction(min((u1 - p) / (1 - p), kBelowOne), u2);
}
)";

constexpr const char* kSampleAndPdf = R"(}  // namespace sampling_detail

// The density sample() draws wo with (0 below the horizon).
inline double pdf(const Vec3& wi, const Vec3& wo) {
  if (!(wo.z > 0) || !(wi.z > 0)) return 0;
  return sampling_detail::model_pdf(wi, wo);
}

// wo for wi (wi.z > 0) from two uniform numbers in [0, 1); pdf = 0 when wo leaves the hemisphere.
inline Sample sample(const Vec3& wi, double u1, double u2) {
  if (!(wi.z > 0)) return {};
  const Vec3 wo = sampling_detail::model_draw(wi, u1, u2);
  if (!(wo.z > 0)) return {wo, 0, 0};
  const double f_value = f(Vec3(0, 0, 1), wi, wo), density = pdf(wi, wo);
  if (!(density > 0)) return {wo, 0, 0};
  return {wo, density, f_value * wo.z / density};
}
)";

std::string replaced(std::string text, std::string_view key, std::string_view value) {
  return text.replace(text.find(key), key.size(), value);
}

/// The cosine share, the strategy and model_pdf / model_draw of a model sampled by its method;
/// `radial` is set if the strategy draws from a radial density.
std::string model_density(const Model& model, bool& radial) {
  const sampling::Sampler sampler(model);
  const double share = sampler.cosine_share();
  radial = draws_radially(sampler);
  return fmt::format("// {}; the cosine-weighted share mixed in:\nconstexpr double kShare = {};\n{}{}",
                     sampler.description(), lit(share), strategy(model, sampler),
                     share < 1 ? kStrategyDensity : kCosineDensity);
}

/// M+ms: M's model_pdf / model_draw in namespace base, and the mixture with cosine sampling. A
/// scaled compensation: M's own (its scale is constant over wo).
std::string compensated_density(const Model& model, const Compensated& compensated, bool& radial) {
  if (scales(compensated.scheme)) return model_density(*compensated.base, radial);
  return fmt::format("namespace base {{  // {}\n{}}}  // namespace base\n{}",
                     expr::comment_text(compensated.base->id()), model_density(*compensated.base, radial),
                     replaced(kCompensatedDensity, "%ENERGY%", glsl::entry_name(model) + "_energy"));
}

/// A portable file's text for inside the header's namespace: its include guard and <cmath> line
/// dropped (the header has them), its namespace specula::radial made `radial`, so that every
/// header has its own copy (two headers included together, or each inside a namespace of the
/// includer's, never meet).
std::string nested_portable(std::string_view path) {
  std::string out;
  const std::string_view text = portable_file(path);
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    std::string line(text.substr(start, end - start));
    start = end + 1;
    if (line.starts_with("#ifndef SPECULA_") || line.starts_with("#define SPECULA_") ||
        line.starts_with("#endif  // SPECULA_") || line == "#include <cmath>")
      continue;
    if (line == "namespace specula::radial {") line = "namespace radial {";
    if (line == "}  // namespace specula::radial") line = "}  // namespace radial";
    out += line;
    out += '\n';
  }
  return out;
}

}  // namespace

CppSampler cpp_sampler(const Model& model) {
  const Compensated* compensated = model.compensated();
  bool radial = false;
  const std::string density = compensated ? compensated_density(model, *compensated, radial) : model_density(model, radial);
  std::string prelude = nested_portable("directions.h");
  if (radial) {
    prelude += '\n';
    prelude += nested_portable("radial.h");
  }
  prelude += '\n';
  std::string body = kCommon;
  body += density;
  // A scaled compensation is not reciprocal: wi is its viewer (sampling/sampler.h).
  body += model.fixes_viewer() ? replaced(kSampleAndPdf, "f(Vec3(0, 0, 1), wi, wo)", "f(Vec3(0, 0, 1), wo, wi)")
                               : std::string(kSampleAndPdf);
  return {std::move(prelude), std::move(body)};
}

}  // namespace specula::exports
