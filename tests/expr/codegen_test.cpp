// Emitted code compiles and computes what the evaluator computes: C++ through the project's own
// compiler (bit-identical results), GLSL through glslangValidator.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "specula/expr/expr.h"
#include "text_support.h"

namespace specula::expr {
namespace {

namespace fs = std::filesystem;

constexpr const char* kExpressions[] = {
    "0.5*x^2",
    "-(-x) + log2(y) / 1e-5",
    "max(abs(x), sqrt(y)) - acos(cos(sin(exp(3))))",
    "(-x)^-2",
    "0.197*(x + 1.24) + 0.068/(0.64 + x)",
    "min(log(x), max(-y, acos(1)))",
    "pow(x, y) - exp(-x*y)",
    "x/y/2 - (x - y - 1)",
    "2^3^2 + -2^2 * x",
    "1/(1 + x*x)",
    "sqrt(abs(x - y)) * cos(y)",
    "log(1 + x) / log(2) - 1.5e-300 * y",
};
constexpr std::array<std::array<double, 2>, 3> kInputs{{{0.7, 1.3}, {2.5, 0.25}, {1e-3, 7.0}}};

struct TempDir {
  fs::path path = fs::temp_directory_path() / fmt::format("specula-codegen-{}", ::getpid());
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

std::string run(const std::string& command) {
  std::string output;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return output;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
  const int status = ::pclose(pipe);
  return status == 0 ? output : "exit status " + std::to_string(status) + ": " + output;
}

TEST(Codegen, CppCompilesAndMatchesTheEvaluatorBitForBit) {
  TempDir dir;
  std::string program = "#include <cmath>\n#include <cstdio>\nint main() {\n";
  for (const char* text : kExpressions)
    for (const auto& [x, y] : kInputs)
      program += fmt::format("  {{ const double x = {}, y = {}; std::printf(\"%a\\n\", {}); }}\n", x, y,
                             to_cpp(parse(text, {"x", "y"})));
  program += "}\n";
  std::ofstream(dir.path / "generated.cpp") << program;
  const std::string compile = fmt::format("'{}' -std=c++20 -O0 -ffp-contract=off -o '{}' '{}' 2>&1", SPECULA_CXX,
                                          (dir.path / "generated").string(), (dir.path / "generated.cpp").string());
  ASSERT_EQ(run(compile), "") << program;
  const auto lines = specula::testing::lines_of(run(fmt::format("'{}'", (dir.path / "generated").string())));
  ASSERT_EQ(lines.size(), std::size(kExpressions) * kInputs.size());
  std::size_t line = 0;
  for (const char* text : kExpressions) {
    const Expression e = parse(text, {"x", "y"});
    for (const auto& [x, y] : kInputs) {
      const double expected = evaluate(e, std::array{x, y});
      const double got = std::strtod(lines[line++].c_str(), nullptr);
      EXPECT_TRUE(got == expected || (std::isnan(got) && std::isnan(expected)))
          << text << " at x=" << x << ", y=" << y << ": C++ " << got << ", evaluator " << expected;
    }
  }
}

TEST(Codegen, GlslPassesGlslangValidator) {
  TempDir dir;
  for (const char* version : {"#version 300 es\nprecision highp float;", "#version 330 core"}) {
    std::string shader = std::string(version) + "\nuniform float x;\nuniform float y;\nout vec4 color;\n";
    std::string sum = "0.0";
    for (std::size_t i = 0; i < std::size(kExpressions); ++i) {
      shader += fmt::format("float f{}(float x, float y) {{ return {}; }}\n", i, to_glsl(parse(kExpressions[i], {"x", "y"})));
      sum += fmt::format(" + f{}(x, y)", i);
    }
    shader += "void main() { color = vec4(" + sum + "); }\n";
    const fs::path file = dir.path / "generated.frag";
    std::ofstream(file) << shader;
    const std::string output = run(fmt::format("'{}' '{}' 2>&1", SPECULA_GLSLANG, file.string()));
    EXPECT_EQ(output.find("ERROR"), std::string::npos) << output << shader;
    EXPECT_EQ(output.find("exit status"), std::string::npos) << output << shader;
  }
}

}  // namespace
}  // namespace specula::expr
