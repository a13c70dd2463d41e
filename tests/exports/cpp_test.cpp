// The C++ export: every model's header compiled with g++ into one program whose values are
// compared with Model::operator() at many directions and parameter values; a header compiles on
// its own with every warning as an error, and two models' headers live side by side; a tampered
// header differs and a broken one fails to compile (the negative controls).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <regex>
#include <sstream>

#include "export_cases.h"
#include "glsl_support.h"
#include "specula/catalogue/catalogue.h"
#include "specula/exports/exports.h"
#include "specula/glsl/glsl.h"
#include "specula/sampling/sampler.h"

namespace specula::exports {
namespace {

using testing::case_name;

constexpr std::size_t kDirections = 240;
constexpr std::size_t kParameterSets = 6;

/// Direction triples (N, L, V) from a fixed seed: a third anywhere, a third about the mirror
/// direction and a third about the half vector of narrow lobes, some below the horizon.
std::vector<std::array<Vec3, 3>> directions() {
  std::mt19937_64 rng(16);
  std::normal_distribution<double> gauss;
  const auto unit = [&] { return normalized(Vec3{gauss(rng), gauss(rng), gauss(rng)}); };
  std::vector<std::array<Vec3, 3>> out;
  for (std::size_t i = 0; i < kDirections; ++i) {
    const Vec3 n = unit();
    Vec3 l = unit();
    if (dot(n, l) < 0 && i % 7 != 0) l = l - n * (2 * dot(n, l));
    const Vec3 mirror = n * (2 * dot(n, l)) - l;
    const double spread = std::pow(10.0, -3.0 * double(i % 5) / 4);
    const Vec3 v = i % 3 == 0 ? unit() : normalized(mirror + unit() * spread);
    out.push_back({n, l, v});
  }
  return out;
}

/// Parameter sets: the model's own, then values across each parameter's slider (log-spaced where
/// it spans two decades), and below it where the range allows (n < 1: the log lobe's other series).
/// Only the model's own where its k is baked in (glsl::coef_is_baked) or its energy table (M+ms),
/// which hold there alone.
std::vector<std::vector<double>> parameter_sets(const Model& model) {
  std::vector<std::vector<double>> sets{{model.params().begin(), model.params().end()}};
  const bool table_baked = model.compensated() != nullptr;
  if (glsl::coef_is_baked(model) || table_baked || model.params().empty()) return sets;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit;
  for (std::size_t k = 1; k < kParameterSets; ++k) {
    std::vector<double> set;
    for (const auto& p : model.info().params) {
      const Slider s = slider_range(p, p.default_value);
      const bool wide = s.min > 0 && s.max >= 100 * s.min;
      const double t = unit(rng);
      double value = wide ? s.min * std::pow(s.max / s.min, t) : s.min + (s.max - s.min) * t;
      if (k == 1 && p.accepts(s.min / 20)) value = s.min / 20;
      set.push_back(value);
    }
    sets.push_back(set);
  }
  return sets;
}

std::string array_literal(const std::vector<double>& values) {
  std::string text;
  for (const double v : values) text += glsl::double_literal(v) + ", ";
  return "{" + text + "}";
}

struct Comparison {
  bool compiled = false;
  std::string log;
  double worst = 0;  ///< the largest |cpp - library| / (|library| + 1e-12 column peak) of any value
  std::string worst_case;
};

/// What a driver prints for each model, and what the library says it should: `columns` numbers a
/// line, compared column by column.
struct Probe {
  std::size_t columns;
  /// The driver's statements for model `i` (its header in namespace case<i>::<ns>), printing lines.
  std::string (*calls)(std::size_t i, const std::string& ns, const Model& model);
  /// The library's numbers for the same lines, in order.
  std::vector<double> (*expected)(const Model& model);
};

std::string direction_table(const char* name) {
  std::string table;
  for (const auto& d : directions())
    table += "  " + array_literal({d[0].x, d[0].y, d[0].z, d[1].x, d[1].y, d[1].z, d[2].x, d[2].y, d[2].z}) + ",\n";
  return fmt::format("const double {}[][9] = {{\n{}}};\n", name, table);
}

/// The driver: each export in a namespace of its own (two exports of one model, rv and nh, share
/// their header's namespace), then the probe's statements for each.
std::string driver(std::size_t count, const std::vector<Model>& cases, const Probe& probe) {
  std::string program = "#include <cmath>\n#include <cstdio>\n";
  std::string calls;
  for (std::size_t i = 0; i < count; ++i) {
    program += fmt::format("namespace case{} {{\n#include \"case{}.h\"\n}}\n", i, i);
    calls += probe.calls(i, cpp_namespace(cases[i]), cases[i]);
  }
  return program + direction_table("kDirections") +
         "#define NLV(T, d) T(d[0], d[1], d[2]), T(d[3], d[4], d[5]), T(d[6], d[7], d[8])\n"
         "void print(double v) { std::printf(\"%.17g\\n\", v); }\nint main() {\n" +
         calls + "}\n";
}

// ---- the model's value: the entry at every parameter set, f at the exported ones ----

std::string value_calls(std::size_t i, const std::string& ns, const Model& model) {
  const std::string scope = fmt::format("case{}::{}", i, ns);
  std::string calls;
  for (const auto& set : parameter_sets(model)) {
    std::string args;
    for (const double value : set) args += ", " + glsl::double_literal(value);
    calls += fmt::format("  for (const auto& d : kDirections) print({0}::{1}(NLV({0}::Vec3, d){2}));\n", scope,
                         glsl::entry_name(model), args);
  }
  return calls + fmt::format("  for (const auto& d : kDirections) print({0}::f(NLV({0}::Vec3, d)));\n", scope);
}

std::vector<double> library_values(const Model& model) {
  std::vector<double> values;
  const auto dirs = directions();
  for (const auto& set : parameter_sets(model)) {
    ParamValues params;
    for (std::size_t a = 0; a < set.size(); ++a) params[model.info().params[a].name] = set[a];
    const bool own = set == std::vector<double>(model.params().begin(), model.params().end());
    const auto form = model.is_lobe() ? std::optional(model.form()) : std::nullopt;
    const Model at = own ? model : make_model(model.shared_info(), params, form);
    for (const auto& d : dirs) values.push_back(at(d[0], d[1], d[2]));
  }
  for (const auto& d : dirs) values.push_back(model(d[0], d[1], d[2]));
  return values;
}

constexpr Probe kValues{1, value_calls, library_values};

// ---- the sampler: sample(wi, u1, u2) and pdf(wi, wo) in the frame N = +z ----

/// wi from a direction triple's L (made to face +z), (u1, u2) from its V, wo its V as it is.
Vec3 sampler_wi(const std::array<Vec3, 3>& d) { return {d[1].x, d[1].y, std::abs(d[1].z) + 1e-3}; }
double sampler_u(double x) { return (x + 1) / 2 * (1 - 0x1p-53); }

std::string sampler_calls(std::size_t i, const std::string& ns, const Model&) {
  return fmt::format(
      "  for (const auto& d : kDirections) {{\n"
      "    const {0}::Vec3 wi = {0}::normalize({0}::Vec3(d[3], d[4], std::abs(d[5]) + 1e-3));\n"
      "    const auto s = {0}::sample(wi, (d[6] + 1) / 2 * (1 - 0x1p-53), (d[7] + 1) / 2 * (1 - 0x1p-53));\n"
      "    print(s.wo.x); print(s.wo.y); print(s.wo.z); print(s.pdf); print(s.weight);\n"
      "    print({0}::pdf(wi, {0}::Vec3(d[6], d[7], d[8])));\n  }}\n",
      fmt::format("case{}::{}", i, ns));
}

std::vector<double> library_sampler_values(const Model& model) {
  const sampling::Sampler sampler(model);
  std::vector<double> values;
  for (const auto& d : directions()) {
    const Vec3 wi = normalized(sampler_wi(d));
    const sampling::Sample s = sampler.sample(wi, sampler_u(d[2].x), sampler_u(d[2].y));
    for (const double v : {s.wo.x, s.wo.y, s.wo.z, s.pdf, s.weight, sampler.pdf(wi, d[2])}) values.push_back(v);
  }
  return values;
}

constexpr Probe kSampler{6, sampler_calls, library_sampler_values};

/// Compiles `headers` (the exports of `cases`) into the probe's driver, runs it and compares.
Comparison compare(const std::vector<std::string>& headers, const std::vector<Model>& cases, const Probe& probe) {
  const testing::ScratchDir dir("cpp-export");
  for (std::size_t i = 0; i < headers.size(); ++i) dir.write(fmt::format("case{}.h", i), headers[i]);
  const auto source = dir.write("driver.cpp", driver(headers.size(), cases, probe));
  const auto binary = dir.path() / "driver";
  Comparison result;
  const auto build = testing::run_command(fmt::format("'{}' -std=c++20 -O1 -Wall -Wextra -Wpedantic -Werror -o '{}' '{}'",
                                                      SPECULA_CXX, binary.string(), source.string()));
  result.compiled = build.ok;
  result.log = build.log;
  if (!build.ok) return result;
  std::istringstream printed(testing::run_command(fmt::format("'{}'", binary.string())).log);
  for (const Model& model : cases) {
    const std::vector<double> expected = probe.expected(model);
    std::vector<double> peak(probe.columns, 0.0);
    for (std::size_t k = 0; k < expected.size(); ++k)
      peak[k % probe.columns] = std::max(peak[k % probe.columns], std::abs(expected[k]));
    for (std::size_t k = 0; k < expected.size(); ++k) {
      double value = NAN;
      printed >> value;
      const double deviation =
          std::abs(value - expected[k]) / (std::abs(expected[k]) + 1e-12 * peak[k % probe.columns] + 1e-300);
      if (!(deviation <= result.worst)) {
        result.worst = std::isnan(deviation) ? INFINITY : deviation;
        result.worst_case = fmt::format("{} [{} column {}]: {} against the library's {}", case_name(model),
                                        k / probe.columns, k % probe.columns, value, expected[k]);
      }
    }
  }
  return result;
}

std::vector<std::string> headers_of(const std::vector<Model>& cases) {
  std::vector<std::string> headers;
  for (const Model& model : cases) headers.push_back(export_model(model, Format::cpp));
  return headers;
}

// The log lobe's coef(n) comes from its Chebyshev series (truncation 9.2e-10 relative); every other
// value agrees to a few ulp with the library, which evaluates the same formulas.
constexpr double kTolerance = 2e-9;

TEST(CppExport, EveryModelsHeaderComputesWhatTheLibraryComputes) {
  const std::vector<Model> cases = testing::export_cases();
  const Comparison c = compare(headers_of(cases), cases, kValues);
  ASSERT_TRUE(c.compiled) << c.log.substr(0, 4000);
  EXPECT_LE(c.worst, kTolerance) << c.worst_case;
  std::printf("worst relative deviation over %zu models: %.3g (%s)\n", cases.size(), c.worst, c.worst_case.c_str());
}

// sample() and pdf() run sampling::Sampler's algorithms with its tables: the same directions,
// densities and weights (the weight carries f, hence the log lobe's k within the series' 1e-9).
TEST(CppExport, EveryModelsSamplerDrawsWhatTheLibrarysDraws) {
  const std::vector<Model> cases = testing::export_cases();
  for (const Model& model : cases) {  // the comparison sees real samples, not only "no sample"
    const std::vector<double> values = library_sampler_values(model);
    std::size_t valid = 0;
    for (std::size_t k = 3; k < values.size(); k += kSampler.columns) valid += values[k] > 0;
    EXPECT_GT(valid, kDirections / 2) << case_name(model);
  }
  const Comparison c = compare(headers_of(cases), cases, kSampler);
  ASSERT_TRUE(c.compiled) << c.log.substr(0, 4000);
  EXPECT_LE(c.worst, kTolerance) << c.worst_case;
  std::printf("worst relative deviation over %zu samplers: %.3g (%s)\n", cases.size(), c.worst, c.worst_case.c_str());
}

/// The sampler's negative control: the model's header with each (pattern, replacement) applied
/// compiles and draws or weighs differently; the header itself agrees.
void expect_tampering_shows(const Model& model, const std::vector<std::pair<std::string, std::string>>& edits) {
  const std::vector<Model> cases{model};
  const std::string header = headers_of(cases)[0];
  for (const auto& [pattern, replacement] : edits) {
    const std::string tampered = std::regex_replace(header, std::regex(pattern), replacement);
    ASSERT_NE(tampered, header) << pattern;
    const Comparison c = compare({tampered}, cases, kSampler);
    ASSERT_TRUE(c.compiled) << c.log;
    EXPECT_GT(c.worst, 1e-3) << pattern;
  }
  EXPECT_LE(compare({header}, cases, kSampler).worst, kTolerance);
}

// Another cosine share, or a table whose cells are 1 % wider.
TEST(CppExport, ATamperedSamplerDiffers) {
  expect_tampering_shows(make_model("gauss", {{"n", 40}}),
                         {{R"(constexpr double kShare = 0\.1;)", "constexpr double kShare = 0.2;"},
                          {"TableView kTable\\{kCumulative, kCells, ", "TableView kTable{kCumulative, kCells, 1.01 * "}});
}

// M+ms: M's share 0.9 E(mu_i) in place of E(mu_i), or M's density alone.
TEST(CppExport, ATamperedCompensatedSamplerDiffers) {
  expect_tampering_shows(make_model("ggx+ms", {{"alpha", 0.6}}),
                         {{R"(clamp\(specula_ggx_ms_energy\(wi\.z\))", "clamp(0.9 * specula_ggx_ms_energy(wi.z)"},
                          {R"(\+ \(1 - p\) \* wo\.z / kPi;)", ";"}});
}

// Negative controls: a header whose k is off by one in n differs; one with a syntax error does
// not compile.
TEST(CppExport, ATamperedHeaderDiffersAndABrokenOneDoesNotCompile) {
  const std::vector<Model> cases{make_model("phong-normalized", {{"n", 30}})};
  const std::string header = headers_of(cases)[0];
  const std::string tampered = std::regex_replace(header, std::regex(R"(\(n \+ 2\.0\))"), "(n + 3.0)");
  ASSERT_NE(tampered, header);
  const Comparison c = compare({tampered}, cases, kValues);
  ASSERT_TRUE(c.compiled) << c.log;
  EXPECT_GT(c.worst, 1e-3);
  EXPECT_FALSE(compare({std::regex_replace(header, std::regex("return"), "retrun")}, cases, kValues).compiled);
  EXPECT_LE(compare({header}, cases, kValues).worst, kTolerance);
}

TEST(CppExport, AHeaderCompilesAloneAndBesideAnotherModels) {
  const testing::ScratchDir dir("cpp-alone");
  dir.write("log.h", export_model(make_model("log-normalized", {{"n", 50}}), Format::cpp));
  dir.write("ggx.h", export_model(make_model("ggx"), Format::cpp));
  const auto alone = dir.write("alone.cpp", "#include \"log.h\"\nint main() { return specula_export_log_normalized::sample({0, 0, 1}, 0.5, 0.5).pdf > 0 ? 0 : 1; }\n");
  const auto both = dir.write("both.cpp", "#include \"log.h\"\n#include \"ggx.h\"\n#include \"log.h\"\n"
                                          "int main() { specula_export_ggx::Vec3 n(0, 0, 1);\n"
                                          "  return specula_export_ggx::f(n, n, n) > 0 && specula_export_log_normalized::f({0, 0, 1}, {0, 0, 1}, {0, 0, 1}) > 0 ? 0 : 1; }\n");
  for (const auto& file : {alone, both}) {
    const auto binary = file.string() + ".out";
    const auto build = testing::run_command(fmt::format("'{}' -std=c++17 -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Werror -o '{}' '{}'",
                                                        SPECULA_CXX, binary, file.string()));
    ASSERT_TRUE(build.ok) << build.log;
    EXPECT_TRUE(testing::run_command("'" + binary + "'").ok) << file;
  }
}

}  // namespace
}  // namespace specula::exports
