#include "lut_code.h"

#include <fmt/format.h>

#include "specula/expr/comment.h"
#include "specula/glsl/glsl.h"

namespace specula::cli {
namespace {

/// An evenly spaced axis as the lookup sees it, in u = x^(1/power): first u, step (1 for a single
/// value), count, power.
struct Axis {
  double first, step;
  std::size_t count;
  double power = 1;
};

Axis axis_of(const std::vector<double>& v, double power) {
  const double first = std::pow(v.front(), 1 / power), last = std::pow(v.back(), 1 / power);
  return {first, v.size() > 1 ? (last - first) / static_cast<double>(v.size() - 1) : 1.0, v.size(), power};
}

/// The lookup's coordinate of `x` on `axis`: x, or x^(1/power) (`pow` as the language spells it,
/// `suffix` "f" for a C++ float literal).
std::string coordinate(const std::string& x, const Axis& axis, const char* pow, const char* suffix) {
  if (axis.power == 1) return x;
  return fmt::format("{}({}, {}{})", pow, x, glsl::float_literal(1 / axis.power), suffix);
}

/// How the header states an axis: "mu = 0.25 + 0.25 j, j < 4" or "mu = (0.1 + 0.3 j)^2, j < 4".
std::string axis_text(const std::string& name, const Axis& a, char index) {
  if (a.power == 1) return fmt::format("{} = {:.9g} + {:.9g} {}, {} < {}", name, a.first, a.step, index, index, a.count);
  return fmt::format("{} = ({:.9g} + {:.9g} {})^{:g}, {} < {}", name, a.first, a.step, index, a.power, index, a.count);
}

std::string float_list(const std::vector<double>& values, std::size_t per_line) {
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i)
    text += fmt::format("{}{}", i == 0 ? "" : (i % per_line == 0 ? ",\n    " : ", "), glsl::float_literal(values[i]));
  return text;
}

std::string header_comment(std::span<const LutChannel> channels, const LutDescription& d) {
  const analysis::AlbedoLut& lut = *channels.front().lut;
  const Axis mu = axis_of(lut.mu, d.mu_power), p = axis_of(lut.p, d.p_power);
  std::string text = fmt::format(
      "// {}\n// Directional albedo E(mu, {}) of {} (mu = cos theta_i) by specula's deterministic cubature\n"
      "// (>= 8 digits); E_avg = 2 int_0^1 E(mu) mu dmu by adaptive quadrature in s = mu^(1/3).\n"
      "// Grid: {}",
      expr::comment_text(d.command), (d.param.empty() ? "-" : d.param) + (d.q_param.empty() ? "" : ", " + d.q_param),
      expr::comment_text(d.model),
      axis_text("mu", mu, 'j'));
  if (!d.param.empty()) text += "; " + axis_text(d.param, p, 'i');
  if (!d.q_param.empty()) text += "; " + axis_text(d.q_param, axis_of(d.q, d.q_power), 'k') + " (one table per value)";
  if (channels.size() > 1 && d.q_param.empty())
    text += ".\n// Two tables, E at F0 = 0 (_f0_0) and at F0 = 1 (_f0_1): with Schlick's Fresnel E is linear in F0,\n"
            "// E(F0) = E_f0_0 + F0 (E_f0_1 - E_f0_0) exactly";
  for (const LutChannel& c : d.q_param.empty() ? channels : channels.first(1)) {
    text += fmt::format(".\n// {}{} interpolation error, max |lookup - cubature| at the cells' centres: {:.3g}",
                        c.suffix.empty() ? "" : "E" + c.suffix + ": ", d.q_param.empty() ? "Bilinear" : "Trilinear", c.error.e);
    if (!c.lut->e_avg.empty())
      text += fmt::format("; E_avg ({} in {}{}): {:.3g}", d.q_param.empty() ? "linear" : "bilinear",
                          d.param.empty() ? "-" : d.param, d.q_param.empty() ? "" : " and " + d.q_param, c.error.e_avg);
  }
  return text + ". Outside the grid the lookup clamps.\n";
}

/// The C++ lookups' cell finder.
constexpr const char* kCppLocate =
    "\n/// Cell index and weight of x on an axis, clamped to it.\n"
    "inline void locate(float x, float first, float step, int count, int& i, int& i1, float& w) {\n"
    "  const float t = std::clamp((x - first) / step, 0.0f, float(count - 1));\n"
    "  i = std::min(int(t), std::max(count - 2, 0));\n  i1 = std::min(i + 1, count - 1);\n  w = t - float(i);\n}\n";

/// Every table's E (or E_avg) one after the other: a second --sweep's tables, q-major.
std::vector<double> concatenated(std::span<const LutChannel> channels, bool average) {
  std::vector<double> all;
  for (const LutChannel& c : channels) {
    const std::vector<double>& v = average ? c.lut->e_avg : c.lut->e;
    all.insert(all.end(), v.begin(), v.end());
  }
  return all;
}

/// A second --sweep's tables in C++: E(mu, p, q) trilinear, E_avg(p, q) bilinear.
std::string sliced_cpp(std::span<const LutChannel> channels, const LutDescription& d) {
  const analysis::AlbedoLut& first = *channels.front().lut;
  const Axis mu = axis_of(first.mu, d.mu_power), p = axis_of(first.p, d.p_power), q = axis_of(d.q, d.q_power);
  const std::string mu_at = coordinate("mu", mu, "std::pow", "f"), p_at = coordinate("p", p, "std::pow", "f"),
                    q_at = coordinate("q", q, "std::pow", "f");
  std::string text = header_comment(channels, d);
  text += fmt::format(
      "#include <algorithm>\n#include <cmath>\n\nnamespace specula_lut {{\n\n"
      "inline constexpr int kMuCount = {}, kPCount = {}, kQCount = {};\n"
      "inline constexpr float kMuFirst = {}f, kMuStep = {}f, kPFirst = {}f, kPStep = {}f, kQFirst = {}f, kQStep = {}f;\n"
      "/// E at (mu_j, p_i, q_k): kE[(k * kPCount + i) * kMuCount + j].\n"
      "inline constexpr float kE[kQCount * kPCount * kMuCount] = {{\n    {}}};\n",
      mu.count, p.count, q.count, glsl::float_literal(mu.first), glsl::float_literal(mu.step), glsl::float_literal(p.first),
      glsl::float_literal(p.step), glsl::float_literal(q.first), glsl::float_literal(q.step),
      float_list(concatenated(channels, false), 8));
  if (!first.e_avg.empty())
    text += fmt::format("/// E_avg at (p_i, q_k): kEAvg[k * kPCount + i].\n"
                        "inline constexpr float kEAvg[kQCount * kPCount] = {{\n    {}}};\n",
                        float_list(concatenated(channels, true), 8));
  text += fmt::format(
      "{3}\n/// E in the table of q_k at (mu, p), bilinear.\n"
      "inline float energy_in_table(int k, int i, int i1, float wp, int j, int j1, float wm) {{\n"
      "  const float* e = kE + k * kPCount * kMuCount;\n"
      "  const float e0 = e[i * kMuCount + j] + wm * (e[i * kMuCount + j1] - e[i * kMuCount + j]);\n"
      "  const float e1 = e[i1 * kMuCount + j] + wm * (e[i1 * kMuCount + j1] - e[i1 * kMuCount + j]);\n"
      "  return e0 + wp * (e1 - e0);\n}}\n\n"
      "/// E(mu, p, q), trilinear.\ninline float energy(float mu, float p, float q) {{\n"
      "  int i, i1, j, j1, k, k1;\n  float wp, wm, wq;\n"
      "  locate({0}, kQFirst, kQStep, kQCount, k, k1, wq);\n  locate({1}, kPFirst, kPStep, kPCount, i, i1, wp);\n"
      "  locate({2}, kMuFirst, kMuStep, kMuCount, j, j1, wm);\n"
      "  const float e0 = energy_in_table(k, i, i1, wp, j, j1, wm), e1 = energy_in_table(k1, i, i1, wp, j, j1, wm);\n"
      "  return e0 + wq * (e1 - e0);\n}}\n",
      q_at, p_at, mu_at, kCppLocate);
  if (!first.e_avg.empty())
    text += fmt::format(
        "\n/// E_avg(p, q), bilinear.\ninline float energy_average(float p, float q) {{\n  int i, i1, k, k1;\n  float wp, wq;\n"
        "  locate({0}, kQFirst, kQStep, kQCount, k, k1, wq);\n  locate({1}, kPFirst, kPStep, kPCount, i, i1, wp);\n"
        "  const float a0 = kEAvg[k * kPCount + i] + wp * (kEAvg[k * kPCount + i1] - kEAvg[k * kPCount + i]);\n"
        "  const float a1 = kEAvg[k1 * kPCount + i] + wp * (kEAvg[k1 * kPCount + i1] - kEAvg[k1 * kPCount + i]);\n"
        "  return a0 + wq * (a1 - a0);\n}}\n",
        q_at, p_at);
  return text + "\n}  // namespace specula_lut\n";
}

}  // namespace

std::string lut_cpp(std::span<const LutChannel> channels, const LutDescription& d) {
  if (!d.q_param.empty()) return sliced_cpp(channels, d);
  const analysis::AlbedoLut& first = *channels.front().lut;
  const Axis mu = axis_of(first.mu, d.mu_power), p = axis_of(first.p, d.p_power);
  const std::string mu_at = coordinate("mu", mu, "std::pow", "f"), p_at = coordinate("p", p, "std::pow", "f");
  std::string text = header_comment(channels, d);
  text += fmt::format(
      "#include <algorithm>\n#include <cmath>\n\nnamespace specula_lut {{\n\n"
      "inline constexpr int kMuCount = {}, kPCount = {};\n"
      "inline constexpr float kMuFirst = {}f, kMuStep = {}f, kPFirst = {}f, kPStep = {}f;\n",
      mu.count, p.count, glsl::float_literal(mu.first), glsl::float_literal(mu.step), glsl::float_literal(p.first),
      glsl::float_literal(p.step));
  for (const LutChannel& c : channels) {
    text += fmt::format("/// E at (mu_j, p_i): kE{0}[i * kMuCount + j].\n"
                        "inline constexpr float kE{0}[kPCount * kMuCount] = {{\n    {1}}};\n",
                        c.suffix, float_list(c.lut->e, 8));
    if (!c.lut->e_avg.empty())
      text += fmt::format("inline constexpr float kEAvg{}[kPCount] = {{\n    {}}};\n", c.suffix, float_list(c.lut->e_avg, 8));
  }
  text += kCppLocate;
  for (const LutChannel& c : channels) {
    text += fmt::format(
        "\n/// E{0}(mu, p), bilinear.\ninline float energy{0}(float mu, float p) {{\n  int i, i1, j, j1;\n  float wp, wm;\n"
        "  locate({1}, kPFirst, kPStep, kPCount, i, i1, wp);\n  locate({2}, kMuFirst, kMuStep, kMuCount, j, j1, wm);\n"
        "  const float e0 = kE{0}[i * kMuCount + j] + wm * (kE{0}[i * kMuCount + j1] - kE{0}[i * kMuCount + j]);\n"
        "  const float e1 = kE{0}[i1 * kMuCount + j] + wm * (kE{0}[i1 * kMuCount + j1] - kE{0}[i1 * kMuCount + j]);\n"
        "  return e0 + wp * (e1 - e0);\n}}\n",
        c.suffix, p_at, mu_at);
    if (!c.lut->e_avg.empty())
      text += fmt::format("\n/// E_avg{0}(p), linear.\ninline float energy_average{0}(float p) {{\n  int i, i1;\n  float w;\n"
                          "  locate({1}, kPFirst, kPStep, kPCount, i, i1, w);\n  return kEAvg{0}[i] + w * (kEAvg{0}[i1] - kEAvg{0}[i]);\n}}\n",
                          c.suffix, p_at);
  }
  if (channels.size() > 1) {
    text += "\n/// E(mu, p) at Schlick's F0: linear in F0.\ninline float energy(float mu, float p, float f0) {\n"
            "  const float e0 = energy_f0_0(mu, p);\n  return e0 + f0 * (energy_f0_1(mu, p) - e0);\n}\n";
    if (!first.e_avg.empty())
      text += "\n/// E_avg(p) at Schlick's F0: linear in F0.\ninline float energy_average(float p, float f0) {\n"
              "  const float e0 = energy_average_f0_0(p);\n  return e0 + f0 * (energy_average_f0_1(p) - e0);\n}\n";
  }
  return text + "\n}  // namespace specula_lut\n";
}

namespace {

/// What GLSL and HLSL spell differently in the table and its lookup.
struct ShaderWords {
  const char* language;   ///< for the header line
  const char* vec3;       ///< vec3 | float3
  const char* mix;        ///< mix | lerp
  std::string (*array)(const std::string& name, std::size_t size, const std::string& values);
};

std::string glsl_array(const std::string& name, std::size_t size, const std::string& values) {
  return fmt::format("const float {}[{}] = float[{}](\n    {});\n", name, size, size, values);
}

std::string hlsl_array(const std::string& name, std::size_t size, const std::string& values) {
  return fmt::format("static const float {}[{}] = {{\n    {}}};\n", name, size, values);
}

constexpr ShaderWords kGlsl{"GLSL 3.30, ES 3.00, WebGL 2", "vec3", "mix", glsl_array};
constexpr ShaderWords kHlsl{"HLSL (Shader Model 4 and later)", "float3", "lerp", hlsl_array};

/// The shaders' cell finder.
std::string shader_locate(const ShaderWords& w) {
  return fmt::format(
      "\n// Cell index (x), next index (y) and weight (z) of x on an axis, clamped to it.\n"
      "{0} specula_lut_locate(float x, float first, float step, int count) {{\n"
      "  float t = clamp((x - first) / step, 0.0, float(count - 1));\n"
      "  int i = min(int(t), max(count - 2, 0));\n  return {0}(float(i), float(min(i + 1, count - 1)), t - float(i));\n}}\n",
      w.vec3);
}

/// A second --sweep's tables in GLSL or HLSL: E(mu, p, q) trilinear, E_avg(p, q) bilinear.
std::string sliced_shader(std::span<const LutChannel> channels, const LutDescription& d, const ShaderWords& w) {
  const analysis::AlbedoLut& first = *channels.front().lut;
  const Axis mu = axis_of(first.mu, d.mu_power), p = axis_of(first.p, d.p_power), q = axis_of(d.q, d.q_power);
  const std::string mu_at = coordinate("mu", mu, "pow", ""), p_at = coordinate("p", p, "pow", ""),
                    q_at = coordinate("q", q, "pow", "");
  const std::vector<double> e = concatenated(channels, false);
  std::string text = header_comment(channels, d);
  text += fmt::format("// E at (mu_j, p_i, q_k): specula_lut_E[(k * {} + i) * {} + j]. {}.\n", p.count, mu.count, w.language);
  text += w.array("specula_lut_E", e.size(), float_list(e, 8));
  if (!first.e_avg.empty()) {
    const std::vector<double> e_avg = concatenated(channels, true);
    text += w.array("specula_lut_E_avg", e_avg.size(), float_list(e_avg, 8));
  }
  text += shader_locate(w) + fmt::format(
      "\n// E in the table of q_k at (mu, p), bilinear: a locates p, b locates mu.\n"
      "float specula_lut_energy_in_table(int k, {0} a, {0} b) {{\n"
      "  int i = int(a.x), i1 = int(a.y), j = int(b.x), j1 = int(b.y), t = k * {2} * {3};\n"
      "  float e0 = {1}(specula_lut_E[t + i * {3} + j], specula_lut_E[t + i * {3} + j1], b.z);\n"
      "  float e1 = {1}(specula_lut_E[t + i1 * {3} + j], specula_lut_E[t + i1 * {3} + j1], b.z);\n"
      "  return {1}(e0, e1, a.z);\n}}\n\n"
      "// E(mu, p, q), trilinear.\nfloat specula_lut_energy(float mu, float p, float q) {{\n"
      "  {0} c = specula_lut_locate({4}, {5}, {6}, {7});\n"
      "  {0} a = specula_lut_locate({8}, {9}, {10}, {2});\n  {0} b = specula_lut_locate({11}, {12}, {13}, {3});\n"
      "  return {1}(specula_lut_energy_in_table(int(c.x), a, b), specula_lut_energy_in_table(int(c.y), a, b), c.z);\n}}\n",
      w.vec3, w.mix, p.count, mu.count, q_at, glsl::float_literal(q.first), glsl::float_literal(q.step), q.count, p_at,
      glsl::float_literal(p.first), glsl::float_literal(p.step), mu_at, glsl::float_literal(mu.first),
      glsl::float_literal(mu.step));
  if (!first.e_avg.empty())
    text += fmt::format(
        "\n// E_avg(p, q), bilinear.\nfloat specula_lut_energy_average(float p, float q) {{\n"
        "  {0} c = specula_lut_locate({2}, {3}, {4}, {5});\n  {0} a = specula_lut_locate({6}, {7}, {8}, {9});\n"
        "  int i = int(a.x), i1 = int(a.y), k = int(c.x), k1 = int(c.y);\n"
        "  float a0 = {1}(specula_lut_E_avg[k * {9} + i], specula_lut_E_avg[k * {9} + i1], a.z);\n"
        "  float a1 = {1}(specula_lut_E_avg[k1 * {9} + i], specula_lut_E_avg[k1 * {9} + i1], a.z);\n"
        "  return {1}(a0, a1, c.z);\n}}\n",
        w.vec3, w.mix, q_at, glsl::float_literal(q.first), glsl::float_literal(q.step), q.count, p_at,
        glsl::float_literal(p.first), glsl::float_literal(p.step), p.count);
  return text;
}

std::string lut_shader(std::span<const LutChannel> channels, const LutDescription& d, const ShaderWords& w) {
  if (!d.q_param.empty()) return sliced_shader(channels, d, w);
  const analysis::AlbedoLut& first = *channels.front().lut;
  const Axis mu = axis_of(first.mu, d.mu_power), p = axis_of(first.p, d.p_power);
  const std::string mu_at = coordinate("mu", mu, "pow", ""), p_at = coordinate("p", p, "pow", "");
  std::string text = header_comment(channels, d);
  text += fmt::format("// E at (mu_j, p_i): specula_lut_E{}[i * {} + j]. {}.\n", channels.front().suffix, mu.count, w.language);
  for (const LutChannel& c : channels) {
    text += w.array("specula_lut_E" + c.suffix, c.lut->e.size(), float_list(c.lut->e, 8));
    if (!c.lut->e_avg.empty()) text += w.array("specula_lut_E_avg" + c.suffix, p.count, float_list(c.lut->e_avg, 8));
  }
  text += shader_locate(w);
  for (const LutChannel& c : channels) {
    text += fmt::format(
        "\n// E{8}(mu, p), bilinear.\nfloat specula_lut_energy{8}(float mu, float p) {{\n"
        "  {0} a = specula_lut_locate({9}, {2}, {3}, {4});\n  {0} b = specula_lut_locate({10}, {5}, {6}, {7});\n"
        "  int i = int(a.x), i1 = int(a.y), j = int(b.x), j1 = int(b.y);\n"
        "  float e0 = {1}(specula_lut_E{8}[i * {7} + j], specula_lut_E{8}[i * {7} + j1], b.z);\n"
        "  float e1 = {1}(specula_lut_E{8}[i1 * {7} + j], specula_lut_E{8}[i1 * {7} + j1], b.z);\n"
        "  return {1}(e0, e1, a.z);\n}}\n",
        w.vec3, w.mix, glsl::float_literal(p.first), glsl::float_literal(p.step), p.count, glsl::float_literal(mu.first),
        glsl::float_literal(mu.step), mu.count, c.suffix, p_at, mu_at);
    if (!c.lut->e_avg.empty())
      text += fmt::format(
          "\n// E_avg{5}(p), linear.\nfloat specula_lut_energy_average{5}(float p) {{\n"
          "  {0} a = specula_lut_locate({6}, {2}, {3}, {4});\n"
          "  return {1}(specula_lut_E_avg{5}[int(a.x)], specula_lut_E_avg{5}[int(a.y)], a.z);\n}}\n",
          w.vec3, w.mix, glsl::float_literal(p.first), glsl::float_literal(p.step), p.count, c.suffix, p_at);
  }
  if (channels.size() > 1) {
    text += fmt::format("\n// E(mu, p) at Schlick's F0: linear in F0.\nfloat specula_lut_energy(float mu, float p, float f0) {{\n"
                        "  return {}(specula_lut_energy_f0_0(mu, p), specula_lut_energy_f0_1(mu, p), f0);\n}}\n",
                        w.mix);
    if (!first.e_avg.empty())
      text += fmt::format("\n// E_avg(p) at Schlick's F0: linear in F0.\nfloat specula_lut_energy_average(float p, float f0) {{\n"
                          "  return {}(specula_lut_energy_average_f0_0(p), specula_lut_energy_average_f0_1(p), f0);\n}}\n",
                          w.mix);
  }
  return text;
}

}  // namespace

std::string lut_glsl(std::span<const LutChannel> channels, const LutDescription& d) { return lut_shader(channels, d, kGlsl); }

std::string lut_hlsl(std::span<const LutChannel> channels, const LutDescription& d) { return lut_shader(channels, d, kHlsl); }

}  // namespace specula::cli
