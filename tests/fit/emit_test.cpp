// fit::emit_function's comment line: the origin (which quotes the data file or the model, any
// text) stays one line of comment in C++, GLSL and LaTeX, and one escaped docstring in Python.
#include <gtest/gtest.h>

#include "specula/fit/emit.h"
#include "text_support.h"

namespace specula::fit {
namespace {

constexpr const char* kOrigin = "specula fit: coef from lobe: c\n#error injected\nint pwned; \"\"\" \\N{x} \\";

TEST(EmitFunction, KeepsTheOriginInOneCommentLine) {
  const expr::Expression formula = expr::parse("2*x", {"x"});
  EXPECT_EQ(emit_function(formula, "cpp", "y", kOrigin),
            "// specula fit: coef from lobe: c #error injected int pwned; \"\"\" \\N{x} /\n"
            "inline double fitted_y(double x) { return 2.0 * x; }\n");
  const std::string glsl = emit_function(formula, "glsl", "y", kOrigin);
  EXPECT_TRUE(testing::only_in_comments(glsl, "pwned")) << glsl;
  EXPECT_EQ(testing::lines_of(glsl).size(), 2u) << glsl;
  const std::string latex = emit_function(formula, "latex", "y", kOrigin);
  EXPECT_EQ(latex.substr(0, latex.find('\n')), "% specula fit: coef from lobe: c #error injected int pwned; \"\"\" \\N{x} /");
  EXPECT_EQ(testing::lines_of(latex).size(), 2u) << latex;
}

TEST(EmitFunction, EscapesTheOriginInPythonsDocstring) {
  const std::string python = emit_function(expr::parse("2*x", {"x"}), "python", "y", kOrigin);
  const auto lines = testing::lines_of(python);
  ASSERT_EQ(lines.size(), 6u) << python;
  EXPECT_EQ(lines[4], "    \"\"\"specula fit: coef from lobe: c #error injected int pwned; \\\"\\\"\\\" \\\\N{x} /\"\"\"");
}

// Negative control: ordinary text is emitted as it is.
TEST(EmitFunction, KeepsAnOrdinaryOriginAsItIs) {
  const std::string origin = "specula fit: coef from data.csv (x), size 3, train rmse 0.01";
  const std::string python = emit_function(expr::parse("2*x", {"x"}), "python", "y", origin);
  EXPECT_EQ(testing::lines_of(python)[4], "    \"\"\"" + origin + "\"\"\"");
  EXPECT_EQ(emit_function(expr::parse("2*x", {"x"}), "cpp", "y", origin).substr(0, origin.size() + 4), "// " + origin + "\n");
}

}  // namespace
}  // namespace specula::fit
