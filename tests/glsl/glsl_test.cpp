// The emitted GLSL: accepted by the reference compiler for every model and dialect, ASCII only,
// every function cited on its first line, parameters and overrides wired as documented. (What it
// computes is compared with the C++ models on a GL context in gl_test.)
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <regex>
#include <span>

#include "glsl_support.h"
#include "specula/catalogue/catalogue.h"
#include "specula/exceptions.h"
#include "specula/glsl/glsl.h"
#include "specula/normalize/log_coef_chebyshev.h"
#include "text_support.h"

namespace specula::glsl {
namespace {

constexpr Dialect kDialects[] = {Dialect::glsl330, Dialect::gles300, Dialect::webgl2};

/// A fragment shader that calls the entry point of `model_text` (a model's GLSL) with its
/// parameters as a uniform.
std::string test_shader(const std::string& model_text, Dialect dialect) {
  return version_header(dialect) + model_text +
         "uniform vec4 u_params;\nout vec4 colour;\n"
         "void main() {\n  vec3 N = vec3(0.0, 0.0, 1.0), L = normalize(vec3(1.0, 0.0, 1.0));\n"
         "  colour = vec4(specula_brdf(N, L, normalize(vec3(-1.0, 0.2, 1.0)), u_params));\n}\n";
}

std::string test_shader(const Model& model, Dialect dialect) { return test_shader(model_glsl(model), dialect); }

TEST(Glsl, EveryModelCompilesInEveryDialect) {
  for (const auto& info : models())
    for (const Dialect dialect : kDialects)
      for (const Form form : {Form::rv, Form::nh}) {
        if (info.kind == ModelKind::brdf && form == Form::nh) continue;
        const Model model = make_model(info.id, {}, info.kind == ModelKind::lobe ? std::optional(form) : std::nullopt);
        const auto check = testing::validate_glsl(test_shader(model, dialect), "frag");
        EXPECT_TRUE(check.ok) << info.id << " " << to_string(dialect) << "\n" << check.log;
      }
}

// Compensated models (M+ms and the other suffixes) are not listed by models(): a BRDF's and a
// lobe's, added and scaled, with each kind of Fresnel a scale reads, in every dialect.
TEST(Glsl, CompensatedModelsCompileInEveryDialect) {
  for (const Model& model :
       {make_model("ggx+ms", {{"alpha", 0.4}}), make_model("log-normalized+ms", {{"n", 5}}),
        make_model("ggx+kulla-conty", {{"f0", 0.5}}), make_model("ggx+cycles", {{"f0", 0.5}}),
        make_model("ggx+turquin-f", {{"f0", 0.5}}), make_model("cook-torrance-1982+turquin-f"),
        make_model("log-normalized+turquin-f", {{"n", 5}})})
    for (const Dialect dialect : kDialects) {
      const auto check = testing::validate_glsl(test_shader(model, dialect), "frag");
      EXPECT_TRUE(check.ok) << model.id() << " " << to_string(dialect) << "\n" << check.log;
    }
}

// The negative control of EveryModelCompilesInEveryDialect: the same check fails for a model
// whose GLSL is missing, is another model's, or calls a function nothing defines.
TEST(Glsl, TheEveryModelCheckFailsForAModelWithoutItsGlsl) {
  const std::string bogus =
      "// no source\nfloat specula_brdf(vec3 N, vec3 L, vec3 V, vec4 params) {\n  return specula_nothing(N, params.x);\n}\n";
  const std::string ggx = model_glsl(make_model("ggx"));
  const std::string without_its_lobe = std::regex_replace(
      model_glsl(make_model("log")), std::regex("float specula_log_lobe[^}]*\\}"), "");
  for (const std::string& text : {std::string(), bogus, without_its_lobe})
    EXPECT_FALSE(testing::validate_glsl(test_shader(text, Dialect::glsl330), "frag").ok) << text;
  EXPECT_TRUE(testing::validate_glsl(test_shader(ggx, Dialect::glsl330), "frag").ok);
}

TEST(Glsl, EveryNormalizedModelComputesItsOwnCoefficient) {
  for (const auto& info : models()) {
    if (info.kind != ModelKind::lobe || !info.is_builtin()) continue;  // user lobes: below
    const std::string glsl = model_glsl(make_model(info.id));
    const bool calls_k = std::regex_search(glsl, std::regex(R"(return specula_\w+_coef\(n\) \* specula_\w+_lobe\()"));
    EXPECT_EQ(calls_k, info.normalization != Normalization::none) << info.id;
  }
}

TEST(Glsl, TheValidatorRejectsABrokenShader) {
  EXPECT_FALSE(testing::validate_glsl(version_header(Dialect::glsl330) + "void main() { float x = ; }\n", "frag").ok);
  // A model function without its entry point's caller still needs every helper it calls.
  const std::string glsl = model_glsl(make_model("log-normalized"));
  const std::string missing = std::regex_replace(glsl, std::regex("float specula_log_coef_j[^}]*\\}"), "");
  EXPECT_FALSE(testing::validate_glsl(version_header(Dialect::glsl330) + missing +
                                          "out vec4 c;\nvoid main() { c = vec4(specula_log_rv_coef(2.0)); }\n",
                                      "frag").ok);
}

TEST(Glsl, AsciiOnlyAndEveryFunctionCitedOnItsFirstLine) {
  const std::regex definition(R"(^(float|vec2|vec3|vec4) (\w+)\(.*\) \{$)");
  for (const auto& info : models()) {
    const std::string glsl = model_glsl(make_model(info.id));
    for (const char ch : glsl) ASSERT_LT(static_cast<unsigned char>(ch), 0x80) << info.id;
    const auto lines = testing::lines_of(glsl);
    int functions = 0;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      std::smatch match;
      if (!std::regex_match(lines[i], match, definition)) continue;
      ++functions;
      ASSERT_GT(i, 0u);
      EXPECT_EQ(lines[i - 1].rfind("// ", 0), 0u) << info.id << ": " << match[2] << " has no citation";
    }
    EXPECT_GE(functions, 2) << info.id;
  }
}

TEST(Glsl, EntryPointTakesTheModelsParametersInOrder) {
  const std::string schlick = model_glsl(make_model("schlick-modified"));
  EXPECT_NE(schlick.find("float specula_schlick_modified(vec3 N, vec3 L, vec3 V, float n, float s)"), std::string::npos);
  EXPECT_NE(schlick.find("return specula_schlick_modified(N, L, V, params.x, params.y);"), std::string::npos);
  const auto packed = model_params(make_model("schlick-modified", {{"n", 7}, {"s", 2.5}}));
  EXPECT_EQ(packed, (std::array<float, 4>{7, 2.5, 0, 0}));
  const auto ward = model_params(make_model("ward", {{"alpha", 0.125}}));
  EXPECT_EQ(ward, (std::array<float, 4>{0.125f, 1, 0, 0}));
  EXPECT_EQ(entry_name(make_model("cook-torrance-1982")), "specula_cook_torrance_1982");
}

TEST(Glsl, FormAndCoefficientOverridesAreBakedIn) {
  const std::string rv = model_glsl(make_model("log-normalized"));
  EXPECT_NE(rv.find("specula_log_rv_coef(n) * specula_log_lobe(specula_cos_rv(N, L, V), n)"), std::string::npos);
  const std::string nh = model_glsl(make_model("log-normalized", {}, Form::nh));
  EXPECT_NE(nh.find("specula_log_rv_coef(n) * specula_log_lobe(specula_cos_nh(N, L, V), n)"), std::string::npos);
  EXPECT_EQ(nh.find("specula_cos_rv"), std::string::npos);
  const std::string overridden = model_glsl(make_model("log-normalized").with_coef(3.5));
  EXPECT_NE(overridden.find("return 3.5 * specula_log_lobe("), std::string::npos);
  EXPECT_EQ(overridden.find("specula_log_rv_coef"), std::string::npos);
  const std::string bare = model_glsl(make_model("log"));
  EXPECT_NE(bare.find("return specula_log_lobe(specula_cos_rv(N, L, V), n);"), std::string::npos);
}

// Whether k was overridden is the Model's own knowledge (Model::coef_overridden): its own k given
// back is no override, another k is, and the emitter makes no model to find out.
TEST(Glsl, AnOverrideIsWhatTheModelSaysItIs) {
  const Model own = make_model("log-normalized", {{"n", 50}});
  EXPECT_FALSE(own.coef_overridden());
  EXPECT_FALSE(own.with_coef(own.coef()).coef_overridden());
  EXPECT_EQ(model_glsl(own.with_coef(own.coef())), model_glsl(own));
  const Model given = own.with_coef(3.5);
  EXPECT_TRUE(given.coef_overridden());
  EXPECT_FALSE(given.with_coef(own.coef()).coef_overridden());  // its own k again
  EXPECT_TRUE(coef_is_baked(given));
  EXPECT_FALSE(coef_is_baked(own));
  EXPECT_FALSE(make_model("ggx").coef_overridden());
}

TEST(Glsl, TheEmitterMakesNoModel) {
  auto made = std::make_shared<int>(0);
  auto info = std::make_shared<ModelInfo>(*find_model("log-normalized"));
  info->make = [made, make = info->make](std::span<const double> values) {
    ++*made;
    return make(values);
  };
  const Model own = make_model(info, {{"n", 50}});
  EXPECT_EQ(*made, 1);  // the control: the counter counts
  const Model given = own.with_coef(3.5);
  EXPECT_NE(model_glsl(own), model_glsl(given));
  EXPECT_NE(coef_is_baked(own), coef_is_baked(given));
  EXPECT_EQ(*made, 1);
}

TEST(Glsl, UserModelsCarryTheirFormulasCoefficientsAndParameters) {
  // A formula k is an expression in the p_ parameters; a quadrature k is baked in as a literal.
  const std::string phong = model_glsl(make_model("my-phong", {{"n", 10}}));
  EXPECT_NE(phong.find("return ((p_n + 2.0) / (2.0 * 3.1415927)) * specula_my_phong_lobe(specula_cos_rv(N, L, V), p_n);"),
            std::string::npos) << phong;
  const Model log = make_model("my-log", {{"n", 20}});
  EXPECT_NE(model_glsl(log).find("return " + float_literal(log.coef()) + " * specula_my_log_lobe("), std::string::npos);
  // Lets become locals; the BRDF's inputs are computed once, those its formula reads.
  const std::string ggx = model_glsl(make_model("my-ggx"));
  EXPECT_NE(ggx.find("  float l_D = "), std::string::npos) << ggx;
  EXPECT_NE(ggx.find("  vec3 H = normalize(L + V);\n  float nh = dot(N, H);\n  float vh = dot(V, H);\n"), std::string::npos);
  EXPECT_EQ(ggx.find("float lv"), std::string::npos);
  const std::string lambert = model_glsl(make_model("brdf: rho/pi"));
  EXPECT_EQ(lambert.find("vec3 H"), std::string::npos) << lambert;
  // Parameters beyond the vec4's four are baked into specula_brdf.
  const std::string six = model_glsl(make_model("six-parameters", {{"e2", 0.75}}));
  EXPECT_NE(six.find("return specula_six_parameters(N, L, V, params.x, params.y, params.z, params.w, 1.0, 0.75);"),
            std::string::npos) << six;
  // An inline model's id becomes an identifier: runs of other characters are one '_'.
  EXPECT_EQ(entry_name(make_model("lobe: c^n")), "specula_lobe_c_n");
  // A long formula's name keeps a prefix and a hash of the whole id (glslang refuses names of over
  // 1024 characters; this one was 4100): distinct formulas, distinct names; the shader compiles.
  std::string product = "c";
  for (int i = 0; i < 2047; ++i) product += "*c";
  const std::string long_name = entry_name(make_model("lobe: " + product));
  EXPECT_LE(long_name.size(), 64u) << long_name;
  EXPECT_NE(long_name, entry_name(make_model("lobe: " + product.substr(2))));
  for (const Dialect dialect : kDialects) {
    const auto check = testing::validate_glsl(test_shader(make_model("lobe: " + product), dialect), "frag");
    EXPECT_TRUE(check.ok) << check.log.substr(0, 2000);
  }
  for (const Dialect dialect : kDialects) {
    const auto check = testing::validate_glsl(test_shader(make_model("lobe: max(0, 1 - n*(1-c)/4)^4", {{"n", 8}}), dialect), "frag");
    EXPECT_TRUE(check.ok) << check.log;
  }
}

TEST(Glsl, LogCoefficientCarriesTheFittedSeries) {
  const std::string glsl = model_glsl(make_model("log-normalized"));
  for (const double c : normalize::log_coef_chebyshev::kJ) EXPECT_NE(glsl.find(float_literal(c)), std::string::npos) << c;
  for (const double c : normalize::log_coef_chebyshev::kK) EXPECT_NE(glsl.find(float_literal(c)), std::string::npos) << c;
}

TEST(Glsl, FloatLiteralsReadBackExactly) {
  for (const double value : {0.0, 1.0, 2.0, -3.0, 0.1, 1e-9, 2.0229990733663571e-9, 0.19725399633894418, 1e30, -7.5e-30}) {
    const std::string text = float_literal(value);
    EXPECT_NE(text.find_first_of(".e"), std::string::npos) << text;  // never an int literal
    EXPECT_EQ(std::strtof(text.c_str(), nullptr), static_cast<float>(value)) << text;
  }
  EXPECT_EQ(float_literal(2), "2.0");
  EXPECT_THROW(float_literal(std::nan("")), InvalidArgument);
  EXPECT_THROW(float_literal(1e308), InvalidArgument);  // finite in double, inf in float
  EXPECT_THROW(float_literal(-3.5e38), InvalidArgument);
  EXPECT_EQ(float_literal(3.4e38), "3.39999995e+38");
}

TEST(Glsl, Dialects) {
  EXPECT_EQ(parse_dialect("webgl2"), Dialect::webgl2);
  EXPECT_EQ(version_header(Dialect::glsl330), "#version 330 core\n");
  EXPECT_EQ(version_header(Dialect::gles300).rfind("#version 300 es\nprecision highp float;", 0), 0u);
  for (const Dialect d : kDialects) EXPECT_EQ(parse_dialect(to_string(d)), d);
  try {
    parse_dialect("glsl450");
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("'glsl450'"), std::string::npos);
  }
}

int run_cli(const std::string& arguments) {
  const int status = std::system(fmt::format("'{}' glsl {} 2>/dev/null", SPECULA_CLI, arguments).c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(GlslCli, WritesAFunctionThatCompilesAfterAVersionLine) {
  const auto file = std::filesystem::temp_directory_path() / fmt::format("specula-glsl-cli-{}.glsl", ::getpid());
  ASSERT_EQ(run_cli(fmt::format("--model schlick-modified -p n=40 -p s=1.5 --dialect webgl2 -o '{}'", file.string())), 0);
  const std::string text = testing::read_file(file);
  std::filesystem::remove(file);
  EXPECT_NE(text.find("specula_brdf(N, L, V, vec4(40.0, 1.5, 0.0, 0.0))"), std::string::npos) << text;
  const std::string shader = version_header(Dialect::webgl2) + text +
                             "out vec4 c;\nvoid main() { c = vec4(specula_brdf(vec3(0.0, 0.0, 1.0), "
                             "vec3(0.0, 0.0, 1.0), vec3(0.0, 0.0, 1.0), vec4(40.0, 1.5, 0.0, 0.0))); }\n";
  const auto check = testing::validate_glsl(shader, "frag");
  EXPECT_TRUE(check.ok) << check.log;
}

TEST(GlslCli, ShaderAndVertexPrintTheComparisonSphereThatCompiles) {
  const auto dir = std::filesystem::temp_directory_path();
  const auto frag = dir / fmt::format("specula-glsl-cli-{}.frag", ::getpid());
  const auto vert = dir / fmt::format("specula-glsl-cli-{}.vert", ::getpid());
  ASSERT_EQ(run_cli(fmt::format("--model log-normalized --shader --dialect webgl2 -o '{}'", frag.string())), 0);
  ASSERT_EQ(run_cli(fmt::format("--model log-normalized --vertex --dialect webgl2 -o '{}'", vert.string())), 0);
  const std::string fragment = testing::read_file(frag), vertex = testing::read_file(vert);
  std::filesystem::remove(frag);
  std::filesystem::remove(vert);
  EXPECT_EQ(fragment.rfind("#version 300 es", 0), 0u);
  EXPECT_NE(fragment.find("float specula_brdf(vec3 N, vec3 L, vec3 V, vec4 params)"), std::string::npos);
  EXPECT_NE(fragment.find("void main()"), std::string::npos);
  const auto f = testing::validate_glsl(fragment, "frag"), v = testing::validate_glsl(vertex, "vert");
  EXPECT_TRUE(f.ok) << f.log;
  EXPECT_TRUE(v.ok) << v.log;
}

TEST(GlslCli, BadInputExitsWith2AndWritesNothing) {
  const auto file = std::filesystem::temp_directory_path() / fmt::format("specula-glsl-bad-{}.glsl", ::getpid());
  EXPECT_EQ(run_cli(fmt::format("--model log --dialect glsl450 -o '{}'", file.string())), 2);
  EXPECT_EQ(run_cli(fmt::format("--model no-such-model -o '{}'", file.string())), 2);
  EXPECT_EQ(run_cli(fmt::format("--model ward --form nh -o '{}'", file.string())), 2);
  EXPECT_EQ(run_cli(fmt::format("--model log -p n=-1 -o '{}'", file.string())), 2);
  EXPECT_FALSE(std::filesystem::exists(file));
}

}  // namespace
}  // namespace specula::glsl
