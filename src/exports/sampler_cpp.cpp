// The C++ export's sampler (src/exports/sampler_cpp.h): the text of sampling::Sampler
// (src/sampling/sampler.cpp) and of the radial density its method uses (src/sampling/radial.cpp),
// the same operations in the same order, with the model's parameter, cosine share and table baked in.
#include "sampler_cpp.h"

#include <fmt/format.h>

#include "specula/expr/comment.h"
#include "specula/glsl/glsl.h"
#include "specula/sampling/sampler.h"

namespace specula::exports {
namespace {

using sampling::Method;

std::string lit(double value) { return glsl::double_literal(value); }

// What every sampler uses: sampler.cpp's helpers and Frame (brdf/directions.h).
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
struct PolarAngle {
  double cos = 1, sin = 0;
};
inline PolarAngle from_log_cos(double y) { return {std::exp(-y), std::sqrt(max(0.0, -std::expm1(-2 * y)))}; }
// y = -ln cos of the angle between unit vectors, from the sine near 0 degrees; +inf at 90 and beyond.
inline double log_cos_between(const Vec3& a, const Vec3& b) {
  const double c = dot(a, b);
  if (!(c > 0)) return HUGE_VAL;
  if (c < 0.5) return -std::log(c);
  const Vec3 s = cross(a, b);
  return -0.5 * std::log1p(-dot(s, s));
}
inline Vec3 mirror(const Vec3& wi, const Vec3& h) { return h * (2 * dot(wi, h)) - wi; }
inline Vec3 cosine_direction(double u1, double u2) {
  const double r = std::sqrt(u1), phi = 2 * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(max(0.0, 1 - u1))};
}
struct Frame {
  Vec3 t, b, w;
  explicit Frame(const Vec3& axis) : w(axis) {
    const Vec3 helper = std::abs(w.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    t = normalize(cross(helper, w));
    b = cross(w, t);
  }
  Vec3 to_world(double cos_theta, double sin_theta, double phi) const {
    return t * (sin_theta * std::cos(phi)) + b * (sin_theta * std::sin(phi)) + w * cos_theta;
  }
};
)";

std::string power_radial(double n) {
  return fmt::format(R"(// Power-cosine: (n + 1)/(2 pi) cos^n about the axis, cos = (1 - u)^(1/(n+1)).
constexpr double kN = {};
inline double radial_density(double y) {{ return (kN + 1) / (2 * kPi) * std::exp(-kN * y); }}
inline PolarAngle radial_sample(double u) {{ return from_log_cos(-std::log1p(-u) / (kN + 1)); }}
)",
                     lit(n));
}

std::string beckmann_radial(double alpha) {
  return fmt::format(R"(// Beckmann's D cos(theta_h): tan^2 = -alpha^2 ln(1 - u).
constexpr double kAlpha = {};
inline double radial_density(double y) {{
  const double tan2 = std::expm1(2 * y), a2 = kAlpha * kAlpha;
  return std::exp(3 * y - tan2 / a2) / (kPi * a2);
}}
inline PolarAngle radial_sample(double u) {{
  const double tan2 = -kAlpha * kAlpha * std::log1p(-u);
  const double c = 1 / std::sqrt(1 + tan2);
  return {{c, std::sqrt(tan2) * c}};
}}
)",
                     lit(alpha));
}

std::string log_radial(double n) {
  return fmt::format(R"(// The log lobe's own density in t = y/b, b = ln 2/n: Newton on its closed-form CDF.
constexpr double kLn2 = 0.6931471805599453;
constexpr double kB = kLn2 / {};
// e^x E1(x) for x >= 1 by its continued fraction (modified Lentz).
inline double scaled_e1(double x) {{
  constexpr double tiny = 1e-300;
  double b = x + 1, c = 1 / tiny, d = 1 / b, h = d;
  for (int i = 1; i < 200; ++i) {{
    const double an = -double(i) * i;
    b += 2;
    d = 1 / (an * d + b);
    c = b + an / c;
    const double delta = c * d;
    h *= delta;
    if (std::abs(delta - 1) < 1e-16) break;
  }}
  return h;
}}
inline double log_lobe_t(double t) {{ return t >= 3 ? 0 : 1 - 0.5 * std::log1p(t) / kLn2; }}
// The integral of F_t(s) e^(-bs) over [0, t].
inline double cdf_integral(double t) {{
  if (!(t > 0)) return 0;
  const double b = kB, log_t = std::log1p(t);
  double p_over_b = 0;
  if (b <= 1) {{
    double integral = log_t, t_pow = 1, b_pow = 1, factorial = 1;
    for (int k = 1; k < 60; ++k) {{
      t_pow *= t;
      factorial *= k;
      integral = t_pow / k - integral;
      const double term = (k % 2 ? -1 : 1) * b_pow * (integral - t_pow * log_t) / factorial;
      p_over_b += term;
      if (k > 3 && std::abs(term) < 1e-17 * std::abs(p_over_b)) break;
      b_pow *= b;
    }}
  }} else {{
    const double decay = std::exp(-b * t);
    p_over_b = (scaled_e1(b) - decay * scaled_e1(b * (1 + t)) - log_t * decay) / b;
  }}
  return -std::expm1(-b * t) / b - p_over_b / (2 * kLn2);
}}
// The total, and Newton's first guesses: t at u = j/64 by bisection.
struct LogStarts {{
  double total = cdf_integral(3);
  double start[65] = {{}};
  LogStarts() {{
    for (int j = 0; j < 65; ++j) {{
      const double target = total * j / 64;
      double lo = 0, hi = 3;
      for (int k = 0; k < 60; ++k) {{
        const double mid = (lo + hi) / 2;
        (cdf_integral(mid) < target ? lo : hi) = mid;
      }}
      start[j] = j == 0 ? 0 : (j == 64 ? 3 : (lo + hi) / 2);
    }}
  }}
}};
inline const LogStarts& log_starts() {{
  static const LogStarts starts;
  return starts;
}}
inline double radial_density(double y) {{
  const double t = y / kB;
  return t >= 3 ? 0 : log_lobe_t(t) / (2 * kPi * kB * log_starts().total);
}}
inline PolarAngle radial_sample(double u) {{
  const LogStarts& s = log_starts();
  const double target = u * s.total;
  const double position = u * 64;
  const int j = position >= 63 ? 63 : static_cast<int>(position);
  double lo = s.start[j], hi = s.start[j + 1];
  double t = lo + (position - double(j)) * (hi - lo);
  for (int k = 0; k < 60; ++k) {{
    const double excess = cdf_integral(t) - target;
    (excess < 0 ? lo : hi) = t;
    const double slope = log_lobe_t(t) * std::exp(-kB * t);
    double next = slope > 0 ? t - excess / slope : (lo + hi) / 2;
    if (!(next > lo && next < hi)) next = (lo + hi) / 2;
    const double step = std::abs(next - t);
    t = next;
    if (step <= 4e-16 * t || hi - lo <= 4e-16 * hi) break;
  }}
  return from_log_cos(kB * t);
}}
)",
                     lit(n));
}

std::string table_radial(const sampling::Sampler::Table& table) {
  std::string values;
  for (std::size_t j = 0; j < table.cumulative.size(); ++j)
    values += lit(table.cumulative[j]) + (j % 4 == 3 ? ",\n" : ", ");
  const std::size_t cells = table.cumulative.size() - 1;
  return fmt::format(R"(// A tabulated inverse CDF in y = -ln cos: cells with edges y_j = width (e^(j ds) - 1), kCumulative[j] = P(y < y_j).
constexpr int kCells = {};
constexpr double kWidth = {}, kYEnd = {}, kDs = {};
constexpr double kCumulative[kCells + 1] = {{
{}}};
inline double y_at(int cell) {{ return cell >= kCells ? kYEnd : kWidth * std::expm1(kDs * cell); }}
inline int cell_of(double y) {{
  const int cell = static_cast<int>(std::log1p(y / kWidth) / kDs);
  return cell < 0 ? 0 : (cell > kCells - 1 ? kCells - 1 : cell);
}}
inline double radial_density(double y) {{
  if (!(y >= 0 && y < kYEnd)) return 0;
  const int j = cell_of(y);
  const double per_y = (kCumulative[j + 1] - kCumulative[j]) / (y_at(j + 1) - y_at(j));
  return per_y * std::exp(y) / (2 * kPi);
}}
inline PolarAngle radial_sample(double u) {{
  int above = 0;  // the first cell edge whose probability exceeds u (std::upper_bound)
  for (int step = kCells + 1; step > 0;) {{
    const int half = step / 2;
    if (!(u < kCumulative[above + half])) above += half + 1, step -= half + 1;
    else step = half;
  }}
  const int j = above - 1 < 0 ? 0 : (above - 1 > kCells - 1 ? kCells - 1 : above - 1);
  const double mass = kCumulative[j + 1] - kCumulative[j];
  const double fraction = mass > 0 ? clamp((u - kCumulative[j]) / mass, 0.0, 1.0) : 0.5;
  return from_log_cos(y_at(j) + fraction * (y_at(j + 1) - y_at(j)));
}}
)",
                     cells, lit(table.width), lit(table.y_end), lit(table.ds), values);
}

std::string ggx_normals(double alpha) {
  return fmt::format(R"(// GGX's visible normals seen from wi (Heitz 2018, "Sampling the GGX Distribution of Visible Normals").
constexpr double kAlpha = {};
inline Vec3 ggx_sample(const Vec3& wi, double u1, double u2) {{
  const Vec3 vh = normalize(Vec3(kAlpha * wi.x, kAlpha * wi.y, wi.z));
  const double len2 = vh.x * vh.x + vh.y * vh.y;
  const Vec3 t1 = len2 > 0 ? Vec3(-vh.y, vh.x, 0) * (1 / std::sqrt(len2)) : Vec3(1, 0, 0);
  const Vec3 t2 = cross(vh, t1);
  const double r = std::sqrt(u1), phi = 2 * kPi * u2;
  const double p1 = r * std::cos(phi), s = 0.5 * (1 + vh.z);
  const double p2 = (1 - s) * std::sqrt(max(0.0, 1 - p1 * p1)) + s * r * std::sin(phi);
  const Vec3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(max(0.0, 1 - p1 * p1 - p2 * p2));
  return normalize(Vec3(kAlpha * nh.x, kAlpha * nh.y, max(0.0, nh.z)));
}}
// D_wi(H)/(4 wi.H) = G1(wi) D(H)/(4 cos theta_i).
inline double ggx_pdf(const Vec3& wi, const Vec3& h) {{
  if (!(h.z > 0) || !(dot(wi, h) > 0)) return 0;
  const double a2 = kAlpha * kAlpha, sin2 = h.x * h.x + h.y * h.y, q = h.z * h.z * a2 + sin2;
  const double d = a2 / (kPi * q * q);
  const double c2 = wi.z * wi.z;
  const double g1 = 1 / (1 + (std::sqrt(1 + a2 * ((1 - c2) / c2)) - 1) / 2);
  return g1 * d / (4 * wi.z);
}}
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

/// The cosine share, the strategy and model_pdf / model_draw of a model sampled by its method.
std::string model_density(const Model& model) {
  const sampling::Sampler sampler(model);
  const double share = sampler.cosine_share();
  return fmt::format("// {}; the cosine-weighted share mixed in:\nconstexpr double kShare = {};\n{}{}",
                     sampler.description(), lit(share), strategy(model, sampler),
                     share < 1 ? kStrategyDensity : kCosineDensity);
}

/// M+ms: M's model_pdf / model_draw in namespace base, and the mixture with cosine sampling.
std::string compensated_density(const Model& model, const Compensated& compensated) {
  return fmt::format("namespace base {{  // {}\n{}}}  // namespace base\n{}",
                     expr::comment_text(compensated.base->id()), model_density(*compensated.base),
                     replaced(kCompensatedDensity, "%ENERGY%", glsl::entry_name(model) + "_energy"));
}

}  // namespace

std::string cpp_sampler(const Model& model) {
  const Compensated* compensated = model.compensated();
  return kCommon + (compensated ? compensated_density(model, *compensated) : model_density(model)) + kSampleAndPdf;
}

}  // namespace specula::exports
