// Model text in the exports: a model's name, summary, source, origin, a parameter's meaning and an
// inline formula may hold anything (newlines, "*/", a trailing backslash, "??/", U+2028, control
// characters); every export in every format keeps it inside comments and compiles. Then the same
// for every model that the model-file fuzz corpus (fuzz/corpus/model_file/) defines.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fmt/ranges.h>
#include <map>

#include "export_compilers.h"
#include "specula/exceptions.h"
#include "specula/exports/exports.h"
#include "specula/glsl/glsl.h"
#include "specula/catalogue/model_file.h"
#include "specula/queries/queries.h"

namespace specula::exports {
namespace {

using testing::case_name, testing::only_in_comments;

// Each attack ends in "pwned", a word that must only ever appear in a comment.
constexpr const char* kHostile[] = {
    "innocent\n#error injected\nstatic int pwned = 1; //",
    "*/ int pwned_block; /*",
    "a trailing backslash splices the next line pwned \\",
    "a trailing backslash and spaces pwned \\   ",
    "carriage\r#error pwned_cr",
    "a trigraph splices the next line pwned ?\?/",
    "line separator\u2028#error pwned_ls\u2029paragraph\u0085next line",
    "controls \x01\x1b[31m\x7f\x0b\x0c\t#error pwned_controls",
};

/// `text` as a TOML basic string: quotes, backslashes and control characters escaped.
std::string toml_string(std::string_view text) {
  std::string out = "\"";
  for (const char ch : text) {
    const auto byte = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\') out += fmt::format("\\{}", ch);
    else if (byte < 0x20 || byte == 0x7f) out += fmt::format("\\u{:04x}", byte);
    else out += ch;
  }
  return out + "\"";
}

/// A lobe and a BRDF for each hostile text, carrying it in every text key a model file has.
std::string hostile_model_file() {
  std::string file;
  for (std::size_t i = 0; i < std::size(kHostile); ++i) {
    const std::string text = toml_string(kHostile[i]);
    file += fmt::format(
        "[[model]]\nid = \"lobe{0}\"\nname = {1}\nsummary = {1}\nsource = {1}\nkind = \"lobe\"\nform = \"rv\"\n"
        "lobe = \"c^n\"\nnormalization = \"(n + 2)/(2*pi)\"\n"
        "[model.params.n]\ndefault = 20\nmin = 0\nmin_exclusive = true\nmax = 1e4\nmeaning = {1}\n"
        "[[model]]\nid = \"brdf{0}\"\nname = {1}\nsummary = {1}\nsource = {1}\nkind = \"brdf\"\nbrdf = \"rho/pi\"\n"
        "[model.params.rho]\ndefault = 0.5\nmin = 0\nmax = 1\nmeaning = {1}\n",
        i, text);
  }
  return file;
}

/// The hostile models, from a file whose name (each model's origin) is hostile too, and inline
/// models whose formula (their id) holds a newline and other whitespace.
std::vector<Model> hostile_models() {
  std::vector<Model> models;
  for (const auto& info : parse_model_file(hostile_model_file(), "models\n#error pwned_origin\n.toml"))
    models.push_back(make_model(std::make_shared<const ModelInfo>(info)));
  models.push_back(make_model("lobe: c\n^n", {{"n", 8}}));
  models.push_back(make_model("lobe: c^n\r\n\t\v\f* (1 - 0*c)", {{"n", 8}}));
  models.push_back(make_model("brdf: rho/pi\n*1", {{"rho", 0.5}}));
  return models;
}

/// What failed for a set of models: each line names a model and a format.
struct Failures {
  std::vector<std::string> lines;
  std::string text() const { return fmt::format("{}", fmt::join(lines, "\n")); }
};

/// Every export of every model: the word "pwned" only in comments, and each format compiled as its
/// consumer compiles it, in batches: the C++ headers in one g++ run, the Metal exports in another,
/// the GLSL functions and the .brdf shaders (in BRDF Explorer's sphere template) in one glslang run
/// each; HLSL, which glslang links, one run per model.
Failures check_exports(const std::vector<Model>& models) {
  Failures failures;
  auto expect = [&](bool ok, std::string_view what, const std::string& log = "") {
    if (!ok) failures.lines.push_back(fmt::format("{} {}", what, log.substr(0, 4000)));
  };
  std::vector<std::string> headers, metal, functions, spheres;
  for (const Model& model : models) {
    const std::string name = case_name(model);
    std::map<Format, std::string> text;
    for (const Format format : {Format::hlsl, Format::msl, Format::brdf, Format::cpp}) {
      text[format] = export_model(model, format);
      expect(only_in_comments(text[format], "pwned", format == Format::brdf),
             fmt::format("{}: 'pwned' outside a comment in --format {}", name, to_string(format)));
    }
    const std::string function = queries::glsl_function(model, glsl::Dialect::glsl330);
    expect(only_in_comments(function, "pwned"), name + ": 'pwned' outside a comment in its GLSL");
    const auto hlsl = testing::validate_hlsl(text[Format::hlsl]);
    expect(hlsl.ok, name + ": HLSL", hlsl.log);
    const testing::BrdfFile brdf = testing::read_brdf(text[Format::brdf]);
    expect(brdf.ok && brdf.sliders.size() == model.params().size(), name + ": a .brdf file BRDF Explorer cannot load");
    functions.push_back(testing::glsl_function_shader(function));
    spheres.push_back(testing::sphere_fragment(brdf));
    headers.push_back(text[Format::cpp]);
    metal.push_back(text[Format::msl]);
  }
  const auto glsl = testing::validate_each_glsl(functions, "frag");
  expect(glsl.ok, "the GLSL functions (case<i> is models[i]):", glsl.log);
  const auto sphere = testing::validate_each_glsl(spheres, "frag");
  expect(sphere.ok, "the .brdf shaders in BRDF Explorer's sphere template (case<i> is models[i]):", sphere.log);
  const auto cpp = testing::compile_cpp_headers(headers);
  expect(cpp.ok, "the C++ headers (namespace case<i> is models[i]):", cpp.log);
  const auto msl = testing::compile_metal(metal);
  expect(msl.ok, "the Metal exports (namespace case<i> is models[i]):", msl.log);
  return failures;
}

TEST(ModelText, StaysInCommentsAndEveryExportCompiles) {
  const std::vector<Model> models = hostile_models();
  ASSERT_EQ(models.size(), 2 * std::size(kHostile) + 3);
  const Failures failures = check_exports(models);
  EXPECT_TRUE(failures.lines.empty()) << failures.text();
}

// The text is still there, on one line: a reader sees what the model file says.
TEST(ModelText, IsKeptOnTheCommentLine) {
  const Model model = hostile_models()[0];
  const std::string header = export_model(model, Format::cpp);
  EXPECT_NE(header.find("// innocent #error injected static int pwned = 1; //: the model in double"), std::string::npos)
      << header;
  const std::string glsl = glsl::model_glsl(hostile_models().back());
  EXPECT_NE(glsl.find("// The entry point renderers call: brdf: rho/pi *1 with params = (p_rho)."), std::string::npos)
      << glsl;
}

// Negative controls: each check catches the text outside a comment — the word on a line of code,
// and a line of code added to an export fails every compiler.
TEST(ModelText, TheChecksCatchTextOutsideAComment) {
  EXPECT_FALSE(only_in_comments("// innocent\n#error pwned\n", "pwned"));
  EXPECT_FALSE(only_in_comments("# a .brdf comment\n#error pwned\n", "pwned", true));
  EXPECT_TRUE(only_in_comments("// innocent #error pwned\n# pwned\n", "pwned", true));
  const Model model = make_model("lobe: c^n", {{"n", 8}});
  const std::string injected = "\nstatic int pwned = 1;\n#error injected\n";
  EXPECT_FALSE(testing::validate_glsl(testing::glsl_function_shader(glsl::model_glsl(model) + injected), "frag").ok);
  EXPECT_FALSE(testing::validate_each_glsl({testing::glsl_function_shader(glsl::model_glsl(model)),
                                            testing::glsl_function_shader(glsl::model_glsl(model) + injected)},
                                           "frag")
                   .ok);
  EXPECT_FALSE(testing::validate_hlsl(export_model(model, Format::hlsl) + injected).ok);
  EXPECT_FALSE(testing::compile_metal({export_model(model, Format::msl) + injected}).ok);
  EXPECT_FALSE(testing::compile_cpp_headers({export_model(model, Format::cpp) + injected}).ok);
  const std::string brdf = export_model(model, Format::brdf);
  const std::string tampered = brdf.substr(0, brdf.find("vec3 BRDF(")) + injected + brdf.substr(brdf.find("vec3 BRDF("));
  EXPECT_FALSE(testing::validate_glsl(testing::sphere_fragment(testing::read_brdf(tampered)), "frag").ok);
  EXPECT_TRUE(check_exports({model}).lines.empty());
}

/// The models of every corpus file that parse_model_file accepts, each that can be made at its
/// defaults (a file or model it refuses is bad input, not an export).
std::vector<Model> corpus_models(std::size_t& accepted_files) {
  std::vector<Model> models;
  const std::filesystem::path corpus = SPECULA_SOURCE_DIR "/fuzz/corpus/model_file";
  std::vector<std::filesystem::path> files{std::filesystem::directory_iterator(corpus), {}};
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    std::vector<ModelInfo> infos;
    try {
      infos = parse_model_file(testing::read_file(file), file.filename().string());
      ++accepted_files;
    } catch (const InvalidArgument&) {  // a file the tool refuses: no models
    }
    for (const auto& info : infos) {
      try {
        models.push_back(make_model(std::make_shared<const ModelInfo>(info)));
      } catch (const InvalidArgument&) {  // refused at its defaults (a k that is not finite and > 0)
      }
    }
  }
  return models;
}

TEST(ModelText, EveryModelOfTheFuzzCorpusExportsInEveryFormatAndCompiles) {
  const auto start = std::chrono::steady_clock::now();
  std::size_t accepted_files = 0;
  const std::vector<Model> models = corpus_models(accepted_files);
  ASSERT_GE(accepted_files, 5u);
  ASSERT_GE(models.size(), 10u);
  const Failures failures = check_exports(models);
  EXPECT_TRUE(failures.lines.empty()) << failures.text();
  std::printf("%zu models from %zu accepted corpus files, exported and compiled in %.1f s\n", models.size(),
              accepted_files, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace
}  // namespace specula::exports
