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
#include "specula/exports/exports.h"
#include "specula/glsl/glsl.h"

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
/// Only the model's own where its k is baked in (glsl::coef_is_baked), which holds there alone.
std::vector<std::vector<double>> parameter_sets(const Model& model) {
  std::vector<std::vector<double>> sets{{model.params().begin(), model.params().end()}};
  if (glsl::coef_is_baked(model) || model.params().empty()) return sets;
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

/// The driver: each export in a namespace of its own (two exports of one model, rv and nh, share
/// their header's namespace), printing the entry at every parameter set and f at every direction.
std::string driver(const std::vector<std::string>& headers, const std::vector<Model>& cases) {
  std::string program = "#include <cmath>\n#include <cstdio>\n";
  std::string calls;
  for (std::size_t i = 0; i < headers.size(); ++i) {
    const std::string ns = cpp_namespace(cases[i]);
    program += fmt::format("namespace case{} {{\n#include \"case{}.h\"\n}}\n", i, i);
    const auto sets = parameter_sets(cases[i]);
    for (std::size_t s = 0; s < sets.size(); ++s) {
      std::string args;
      for (std::size_t a = 0; a < sets[s].size(); ++a) args += fmt::format(", {}", glsl::double_literal(sets[s][a]));
      calls += fmt::format("  for (const auto& d : kDirections) print(case{0}::{1}::{2}({3}{4}));\n", i, ns,
                           glsl::entry_name(cases[i]), "NLV(case" + std::to_string(i) + "::" + ns + "::Vec3, d)", args);
    }
    calls += fmt::format("  for (const auto& d : kDirections) print(case{0}::{1}::f(NLV(case{0}::{1}::Vec3, d)));\n", i, ns);
  }
  std::string table;
  for (const auto& d : directions())
    table += "  " + array_literal({d[0].x, d[0].y, d[0].z, d[1].x, d[1].y, d[1].z, d[2].x, d[2].y, d[2].z}) + ",\n";
  return program + "const double kDirections[][9] = {\n" + table + "};\n" +
         "#define NLV(T, d) T(d[0], d[1], d[2]), T(d[3], d[4], d[5]), T(d[6], d[7], d[8])\n"
         "void print(double v) { std::printf(\"%.17g\\n\", v); }\nint main() {\n" +
         calls + "}\n";
}

/// What the library computes, in the driver's order.
std::vector<double> library_values(const std::vector<Model>& cases) {
  std::vector<double> values;
  const auto dirs = directions();
  for (const Model& model : cases) {
    for (const auto& set : parameter_sets(model)) {
      ParamValues params;
      for (std::size_t a = 0; a < set.size(); ++a) params[model.info().params[a].name] = set[a];
      const bool own = set == std::vector<double>(model.params().begin(), model.params().end());
      const auto form = model.is_lobe() ? std::optional(model.form()) : std::nullopt;
      const Model at = own ? model : make_model(model.shared_info(), params, form);
      for (const auto& d : dirs) values.push_back(at(d[0], d[1], d[2]));
    }
    for (const auto& d : dirs) values.push_back(model(d[0], d[1], d[2]));
  }
  return values;
}

struct Comparison {
  bool compiled = false;
  std::string log;
  double worst = 0;  ///< the largest |cpp - library| / (|library| + 1e-12 peak) of any value
  std::string worst_case;
};

/// Compiles `headers` (the exports of `cases`) into the driver, runs it and compares.
Comparison compare(const std::vector<std::string>& headers, const std::vector<Model>& cases) {
  const testing::ScratchDir dir("cpp-export");
  for (std::size_t i = 0; i < headers.size(); ++i) dir.write(fmt::format("case{}.h", i), headers[i]);
  const auto source = dir.write("driver.cpp", driver(headers, cases));
  const auto binary = dir.path() / "driver";
  Comparison result;
  const auto build = testing::run_command(fmt::format("'{}' -std=c++20 -O1 -Wall -Wextra -Wpedantic -Werror -o '{}' '{}'",
                                                      SPECULA_CXX, binary.string(), source.string()));
  result.compiled = build.ok;
  result.log = build.log;
  if (!build.ok) return result;
  const auto run = testing::run_command("'" + binary.string() + "'");
  std::istringstream printed(run.log);
  const std::vector<double> expected = library_values(cases);
  std::size_t at = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::size_t count = (parameter_sets(cases[i]).size() + 1) * kDirections;
    double peak = 0;
    for (std::size_t k = at; k < at + count; ++k) peak = std::max(peak, std::abs(expected[k]));
    for (std::size_t k = at; k < at + count; ++k) {
      double value = NAN;
      printed >> value;
      const double deviation = std::abs(value - expected[k]) / (std::abs(expected[k]) + 1e-12 * peak + 1e-300);
      if (!(deviation <= result.worst)) {
        result.worst = std::isnan(deviation) ? INFINITY : deviation;
        result.worst_case = fmt::format("{}: {} against the library's {}", case_name(cases[i]), value, expected[k]);
      }
    }
    at += count;
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
  const Comparison c = compare(headers_of(cases), cases);
  ASSERT_TRUE(c.compiled) << c.log.substr(0, 4000);
  EXPECT_LE(c.worst, kTolerance) << c.worst_case;
  std::printf("worst relative deviation over %zu models: %.3g (%s)\n", cases.size(), c.worst, c.worst_case.c_str());
}

// Negative controls: a header whose k is off by one in n differs; one with a syntax error does
// not compile.
TEST(CppExport, ATamperedHeaderDiffersAndABrokenOneDoesNotCompile) {
  const std::vector<Model> cases{make_model("phong-normalized", {{"n", 30}})};
  const std::string header = headers_of(cases)[0];
  const std::string tampered = std::regex_replace(header, std::regex(R"(\(n \+ 2\.0\))"), "(n + 3.0)");
  ASSERT_NE(tampered, header);
  const Comparison c = compare({tampered}, cases);
  ASSERT_TRUE(c.compiled) << c.log;
  EXPECT_GT(c.worst, 1e-3);
  EXPECT_FALSE(compare({std::regex_replace(header, std::regex("return"), "retrun")}, cases).compiled);
  EXPECT_LE(compare({header}, cases).worst, kTolerance);
}

TEST(CppExport, AHeaderCompilesAloneAndBesideAnotherModels) {
  const testing::ScratchDir dir("cpp-alone");
  dir.write("log.h", export_model(make_model("log-normalized", {{"n", 50}}), Format::cpp));
  dir.write("ggx.h", export_model(make_model("ggx"), Format::cpp));
  const auto alone = dir.write("alone.cpp", "#include \"log.h\"\nint main() { return specula_export_log_normalized::f({0, 0, 1}, {0, 0, 1}, {0, 0, 1}) > 0 ? 0 : 1; }\n");
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
