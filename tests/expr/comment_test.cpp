// expr::comment_text: any text as the body of a one-line comment. Its rules on examples, its
// properties on arbitrary bytes, and random hostile texts in comments of C++14 (trigraphs on) and
// GLSL that g++ and glslang compile with every line of code after them intact.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <random>
#include <unistd.h>

#include "glsl_support.h"
#include "specula/expr/comment.h"

namespace specula::expr {
namespace {

TEST(CommentText, FlattensNeutralizesAndSpells) {
  const std::pair<std::string, std::string> cases[] = {
      {"innocent\n#error injected\nstatic int pwned = 1; //", "innocent #error injected static int pwned = 1; //"},
      {"*/ int x; /*", "* / int x; / *"},
      {"/*/", "/ * /"},
      {"ends in a backslash \\", "ends in a backslash /"},
      {"backslash and spaces \\  \t\n", "backslash and spaces /"},
      {"a \\ inside stays", "a \\ inside stays"},
      {"*\\", "* /"},
      {"trigraph ?\?/ ?\?=", "trigraph ? ?/ ? ?="},
      {"???", "? ? ?"},
      {"cr\rlf\nnul", "cr lf nul"},
      {std::string("nul\0byte", 8), "nul byte"},
      {"escape \x1b[31m del \x7f", "escape  [31m del"},
      {"line\u2028separator\u0085next \u4e2d\u6587", "line?separator?next ? ?"},
      {"k = (n+2)/(2π), θ ≤ 90°", "k = (n+2)/(2pi), theta <= 90?"},
      {"   ", ""},
      {"", ""},
  };
  for (const auto& [text, expected] : cases) EXPECT_EQ(comment_text(text), expected) << text;
}

// Negative control of the properties below: ordinary text comes out as it went in.
TEST(CommentText, LeavesOrdinaryTextAsItIs) {
  for (const char* text : {"Phong 1975, \"Illumination for Computer Generated Pictures\"", "f = rho/pi * (1 + a*nh^4)",
                           "my.toml:12", "c^n, k = 1/albedo(0) by quadrature", "a? b? /x *y"})
    EXPECT_EQ(comment_text(text), text);
}

RC_GTEST_PROP(CommentText, IsPrintableAsciiWithoutCommentDelimitersTrigraphsOrASplice, (const std::string& text)) {
  const std::string out = comment_text(text);
  for (const char ch : out) RC_ASSERT(ch >= 0x20 && ch < 0x7f);
  for (const char* token : {"/*", "*/", "??"}) RC_ASSERT(out.find(token) == std::string::npos);
  RC_ASSERT(!out.ends_with('\\') && !out.ends_with(' '));
  RC_ASSERT(comment_text(out) == out);
}

/// Random texts, mostly of the characters that could end a comment early or splice a line.
std::vector<std::string> hostile_texts(std::size_t count) {
  static constexpr std::string_view kDangerous[] = {"\n", "\r", "\\", "?", "*", "/", "\u2028", "\t", " ", "#error x",
                                                    "int pwned;", "\x01", "\x7f", "\xff", "\"", "'"};
  std::mt19937 random(11);
  std::vector<std::string> texts;
  for (std::size_t i = 0; i < count; ++i) {
    std::string text;
    for (std::size_t length = random() % 24; length > 0; --length) text += kDangerous[random() % std::size(kDangerous)];
    texts.push_back(text);
  }
  return texts;
}

/// One translation unit: each text in a comment, then a line of code that must survive it.
std::string cpp_unit(const std::vector<std::string>& texts) {
  std::string unit, sum = "0";
  for (std::size_t i = 0; i < texts.size(); ++i) {
    unit += fmt::format("// {}\nint v{} = {};\n", texts[i], i, i);
    sum += fmt::format(" + v{}", i);
  }
  return unit + "int total() { return " + sum + "; }\n";
}

std::string glsl_shader(const std::vector<std::string>& texts) {
  std::string shader = "#version 330 core\nout vec4 color;\n", sum = "0.0";
  for (std::size_t i = 0; i < texts.size(); ++i) {
    shader += fmt::format("// {}\nconst float v{} = {}.0;\n", texts[i], i, i);
    sum += fmt::format(" + v{}", i);
  }
  return shader + "void main() { color = vec4(" + sum + "); }\n";
}

/// g++ in C++14, where "??/" is a backslash, with every warning an error (-Wcomment, -Wtrigraphs).
specula::testing::GlslCheck compile_cpp14(const std::string& unit) {
  static int counter = 0;
  const auto file = std::filesystem::temp_directory_path() / fmt::format("specula-comment-{}-{}.cpp", ::getpid(), counter++);
  std::ofstream(file) << unit;
  const auto check = specula::testing::run_command(
      fmt::format("'{}' -std=c++14 -fsyntax-only -Wall -Wextra -Werror '{}'", SPECULA_CXX, file.string()));
  std::filesystem::remove(file);
  return check;
}

std::vector<std::string> commented(const std::vector<std::string>& texts) {
  std::vector<std::string> out;
  for (const auto& text : texts) out.push_back(comment_text(text));
  return out;
}

TEST(CommentText, HostileTextsInCommentsCompileInCppAndGlsl) {
  const std::vector<std::string> texts = hostile_texts(200);
  const auto cpp = compile_cpp14(cpp_unit(commented(texts)));
  EXPECT_TRUE(cpp.ok) << cpp.log.substr(0, 4000);
  const auto glsl = specula::testing::validate_glsl(glsl_shader(commented(texts)), "frag");
  EXPECT_TRUE(glsl.ok) << glsl.log.substr(0, 4000);
}

// Negative control: the same texts as they are break both compilers, and so does each attack alone.
TEST(CommentText, TheCompilersRejectTheTextsAsTheyAre) {
  const std::vector<std::string> texts = hostile_texts(200);
  EXPECT_FALSE(compile_cpp14(cpp_unit(texts)).ok);
  EXPECT_FALSE(specula::testing::validate_glsl(glsl_shader(texts), "frag").ok);
  for (const std::string attack : {"a\n#error x", "a \\", "a ?\?/"}) {
    EXPECT_FALSE(compile_cpp14(cpp_unit({attack})).ok) << attack;
    EXPECT_TRUE(compile_cpp14(cpp_unit({comment_text(attack)})).ok) << attack;
  }
}

}  // namespace
}  // namespace specula::expr
