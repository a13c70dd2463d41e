// Models defined in the request: every endpoint that takes a model id also takes an inline
// definition ("lobe: c^n") and a definition object with a model file's keys, gives the numbers
// of the built-in model it copies, and refuses a bad definition with 400 naming the key at fault.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <thread>

#include "glsl_support.h"
#include "serve_support.h"
#include "text_support.h"

namespace specula::serve {
namespace {

using json = nlohmann::json;
using specula::testing::Answer;
using specula::testing::get;
using specula::testing::post_json;
using ::testing::HasSubstr;
using ::testing::Not;

json exponent_param(double default_value = 20) {
  return {{"default", default_value}, {"min", 0}, {"min_exclusive", true}, {"max", 1e9}};
}

/// phong-normalized as a user types it: c^n with the closed form (n + 2)/(2π) as a formula.
json phong_copy() {
  return {{"kind", "lobe"}, {"form", "rv"}, {"lobe", "c^n"}, {"lobe_u", "exp(-n*u)"},
          {"normalization", "(n + 2)/(2*pi)"}, {"params", {{"n", exponent_param()}}}};
}

/// log-normalized as a user types it: the log lobe with k by quadrature.
json log_copy() {
  return {{"id", "my-log"}, {"name", "log lobe, my copy"}, {"kind", "lobe"}, {"form", "rv"},
          {"lobe", "max(0, 1 - 0.5*log2(1 - n*log2(c)))"},
          {"lobe_u", "max(0, 1 - 0.5*log1p(n*u/log(2))/log(2))"},
          {"normalization", "quadrature"}, {"params", {{"n", exponent_param()}}}};
}

/// ggx as a user types it (examples/models/builtin-copies.toml).
json ggx_copy() {
  return {{"kind", "brdf"},
          {"let", {"a2 = alpha^2", "q = nh^2*(a2 - 1) + 1", "D = a2/(pi*q^2)",
                   "lambda_l = (sqrt(1 + a2*(1 - nl^2)/nl^2) - 1)/2", "lambda_v = (sqrt(1 + a2*(1 - nv^2)/nv^2) - 1)/2",
                   "G = 1/(1 + lambda_l + lambda_v)", "F = f0 + (1 - f0)*(1 - vh)^5"}},
          {"brdf", "D*F*G/(4*nl*nv)"},
          {"params", {{"alpha", {{"default", 0.3}, {"min", 1e-3}, {"max", 1}}},
                      {"f0", {{"default", 1}, {"min", 0}, {"max", 1}}}}}};
}

double relative(double a, double b) { return a == b ? 0 : std::abs(a - b) / std::max(std::abs(a), std::abs(b)); }

/// `request` with `key` set to `model`.
json with(json request, const std::string& key, const json& model) {
  request[key] = model;
  return request;
}

class ServeModels : public specula::testing::ServerSuite {
 protected:
  /// The largest relative difference between the numbers `columns` of two table answers.
  static double table_difference(const json& a, const json& b, const std::vector<std::string>& columns) {
    EXPECT_EQ(a["rows"].size(), b["rows"].size());
    double worst = 0;
    for (std::size_t i = 0; i < std::min(a["rows"].size(), b["rows"].size()); ++i)
      for (const auto& c : columns) worst = std::max(worst, relative(a["rows"][i][c].get<double>(), b["rows"][i][c].get<double>()));
    return worst;
  }

  /// table_difference of `path`'s answers for the built-in `builtin` and for `copy` as `key`.
  static double difference(const std::string& path, const json& request, const std::string& key, const json& builtin,
                           const json& copy, const std::vector<std::string>& columns) {
    return table_difference(ok(path, with(request, key, builtin)), ok(path, with(request, key, copy)), columns);
  }

};

const json kCosines = json::array({1, 0.999, 0.99, 0.95, 0.9, 0.5, 0.1, 0, -0.5});

TEST_F(ServeModels, EvalOfACopyIsTheBuiltIns) {
  const json at_cosines{{"params", {{"n", 50}}}, {"cos", kCosines}};
  EXPECT_LE(difference("/api/eval", at_cosines, "model", "phong-normalized", phong_copy(), {"value"}), 1e-12);
  EXPECT_LE(difference("/api/eval", at_cosines, "model", "phong", "lobe: c^n", {"value"}), 1e-12);
  const json at_directions{{"params", {{"alpha", 0.2}}}, {"theta_i", 30}, {"theta_o", "0:85:5"}, {"phi_o", 170}};
  EXPECT_LE(difference("/api/eval", at_directions, "model", "ggx", ggx_copy(), {"value"}), 1e-12);
  const json lambert{{"params", {{"rho", 0.8}}}, {"theta_i", 10}, {"theta_o", "0:80:20"}};
  EXPECT_LE(difference("/api/eval", lambert, "model", "lambert", "brdf: rho/pi", {"value"}), 1e-12);
}

TEST_F(ServeModels, ADifferentFormulaIsDetected) {  // the negative control of the comparisons
  json other = phong_copy();
  other["lobe"] = "c^(n + 1)";
  other.erase("lobe_u");
  const json at_cosines{{"params", {{"n", 50}}}, {"cos", kCosines}};
  EXPECT_GT(difference("/api/eval", at_cosines, "model", "phong-normalized", other, {"value"}), 1e-3);
  EXPECT_GT(difference("/api/eval", at_cosines, "model", "phong", "lobe: c^(n+1)", {"value"}), 1e-3);
}

TEST_F(ServeModels, NormalizeOfACopyIsTheClosedForm) {
  const json request{{"n", json::array({0.5, 1, 10, 100, 1000, 1e5})}};
  EXPECT_LE(difference("/api/normalize", request, "model", "log-normalized", log_copy(), {"coef"}), 1e-12);
  EXPECT_LE(difference("/api/normalize", request, "model", "phong-normalized", phong_copy(), {"coef"}), 1e-12);
  EXPECT_LE(difference("/api/normalize", request, "model", "phong-normalized", "lobe: c^n", {"coef"}), 1e-12);
  const json compared = with(request, "model", "log");
  EXPECT_LE(difference("/api/normalize", compared, "compare", "log-normalized", log_copy(), {"coef_compare"}), 1e-12);
  EXPECT_EQ(ok("/api/normalize", with(compared, "compare", log_copy()))["compare"], "my-log");
}

TEST_F(ServeModels, AlbedoAndCheckOfACopyAreTheBuiltIns) {
  const json angles{{"params", {{"n", 200}}}, {"theta", json::array({0, 30, 60, 85})}};
  EXPECT_LE(difference("/api/albedo", angles, "model", "log-normalized", log_copy(), {"albedo"}), 1e-9);
  const json coarse{{"params", {{"alpha", 0.4}}}, {"pairs", 1000}, {"step", 5}};  // quick under the sanitizers
  const json builtin = ok("/api/check", with(coarse, "model", "ggx"));
  const json copy = ok("/api/check", with(coarse, "model", ggx_copy()));
  ASSERT_EQ(copy.size(), 1u);
  for (const char* key : {"albedo_normal", "max_albedo"})
    EXPECT_LE(relative(builtin[0][key].get<double>(), copy[0][key].get<double>()), 1e-9) << key;
  for (const char* key : {"conserves_energy", "reciprocal", "non_negative"}) EXPECT_EQ(builtin[0][key], copy[0][key]) << key;
  EXPECT_EQ(ok("/api/check", {{"model", log_copy()}, {"n", json::array({10, 100})}}).size(), 2u);
}

TEST_F(ServeModels, ErrorOfACopyIsTheBuiltIns) {
  const json request{{"n", json::array({2, 20, 200})}};
  const std::vector<std::string> columns{"max_abs", "max_rel_epicenter"};
  EXPECT_LE(difference("/api/error", request, "model", "log", log_copy(), columns), 1e-9);
  EXPECT_LE(difference("/api/error", with(request, "model", "log"), "reference", "phong", phong_copy(), columns), 1e-9);
  EXPECT_LE(difference("/api/error", with(request, "model", "log"), "reference", "phong", "lobe: c^n", columns), 1e-9);
}

TEST_F(ServeModels, GlslOfADefinitionIsAShaderOfIt) {
  const json glsl = ok("/api/glsl", {{"model", phong_copy()}, {"params", {{"n", 50}}}, {"shader", true}});
  EXPECT_EQ(glsl["model"], "user");
  EXPECT_EQ(glsl["entry_params"][0], 50);  // n, the first of the shader's parameters
  EXPECT_LE(relative(std::stod(glsl["coef"].get<std::string>()), 52 / (2 * M_PI)), 1e-12);
  EXPECT_THAT(glsl["fragment_shader"].get<std::string>(), HasSubstr("specula_brdf"));
  EXPECT_EQ(ok("/api/glsl", {{"model", "lobe: c^n"}})["model"], "lobe: c^n");
}

// A definition's text (here its name, summary and source) may hold anything: the GLSL answered
// keeps it in comments and compiles, the function and the whole fragment shader alike.
TEST_F(ServeModels, GlslOfAHostileDefinitionKeepsItsTextInComments) {
  json hostile = phong_copy();
  hostile["name"] = "innocent\n#error injected\nstatic int pwned = 1; //";
  hostile["summary"] = "*/ float pwned_block; /* \r#error pwned_cr \u2028 pwned_ls ?\?/";
  hostile["source"] = "a trailing backslash splices the next line: pwned \\";
  const json glsl = ok("/api/glsl", {{"model", hostile}, {"dialect", "glsl330"}, {"shader", true}});
  const std::string function = glsl["version_header"].get<std::string>() + glsl["function"].get<std::string>() +
                               "out vec4 color;\nvoid main() { color = vec4(specula_brdf(vec3(0.0), vec3(0.0), "
                               "vec3(0.0), vec4(1.0))); }\n";
  const std::string fragment = glsl["fragment_shader"];
  for (const std::string& shader : {function, fragment}) {
    EXPECT_TRUE(specula::testing::only_in_comments(shader, "pwned")) << shader;
    const auto check = specula::testing::validate_glsl(shader, "frag");
    EXPECT_TRUE(check.ok) << check.log << shader;
  }
  EXPECT_THAT(fragment, HasSubstr("// innocent #error injected static int pwned = 1; //: f = k F(c)"));
  // Negative control: a line of code added to the shader is caught by both checks.
  const std::string injected = fragment + "\n#error injected\nfloat pwned = 1.0;\n";
  EXPECT_FALSE(specula::testing::only_in_comments(injected, "pwned"));
  EXPECT_FALSE(specula::testing::validate_glsl(injected, "frag").ok);
}

// The search itself is not reproducible run to run, so this compares what the job fits: its rows.
// The smallest search (one island of 20, enumeration to size 5): the default's enumeration of
// 20 000 forms took 11 s a fit under the sanitizers and checked nothing more here.
TEST_F(ServeModels, AFitOfADefinitionFitsItsNormalization) {
  const json fit{{"n", "1:100@10:log"}, {"generations", 1}, {"islands", 1}, {"population", 20}, {"enumerate_size", 5}};
  std::vector<json> finished;
  for (const json& model : {json("phong-normalized"), phong_copy()}) {
    const Answer started = post_json(port(), "/api/fit", with(fit, "model", model));
    ASSERT_EQ(started.status, 202) << started.body;
    const std::string url = started.json()["url"];
    json status = get(port(), url).json();
    for (int i = 0; i < 600 && status["state"] == "running"; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      status = get(port(), url).json();
    }
    ASSERT_EQ(status["state"], "done") << status.dump(2);
    finished.push_back(status);
  }
  EXPECT_EQ(finished[0]["rows"], 10);
  EXPECT_EQ(finished[1]["rows"], finished[0]["rows"]);
  EXPECT_EQ(finished[1]["variables"], finished[0]["variables"]);
}

TEST_F(ServeModels, ADefinitionIsTheRequestsOwnAndNeverRegistered) {
  const std::size_t listed = get(port(), "/api/models").json().size();
  json clash = phong_copy();
  clash["id"] = "phong";
  clash["lobe"] = "c^(n + 1)";
  clash.erase("lobe_u");
  const json request{{"params", {{"n", 1}}}, {"cos", json::array({0.5})}};
  EXPECT_DOUBLE_EQ(ok("/api/eval", with(request, "model", clash))["rows"][0]["value"].get<double>(), 0.25 * 3 / (2 * M_PI));
  EXPECT_DOUBLE_EQ(ok("/api/eval", with(request, "model", "phong"))["rows"][0]["value"].get<double>(), 0.5);
  EXPECT_EQ(get(port(), "/api/models").json().size(), listed);
}

struct BadDefinition {
  std::string what;
  std::string path;
  json body;
  std::string field;
  std::string message;  ///< a part of the error message
};

std::ostream& operator<<(std::ostream& os, const BadDefinition& b) { return os << b.what; }

json phong_with(const std::string& key, const json& value) {
  json d = phong_copy();
  if (value.is_null()) d.erase(key);
  else d[key] = value;
  return d;
}

json phong_with_n(const std::string& key, const json& value) {
  json d = phong_copy();
  if (value.is_null()) d["params"]["n"].erase(key);
  else d["params"]["n"][key] = value;
  return d;
}

/// c+(c+(…)) nested `depth` deep.
std::string nested(int depth) {
  std::string formula = "c";
  for (int i = 0; i < depth; ++i) formula = "c+(" + formula + ")";
  return formula;
}

class ServeBadDefinition : public ServeModels, public ::testing::WithParamInterface<BadDefinition> {};

TEST_P(ServeBadDefinition, IsRefusedNamingTheKey) {
  const BadDefinition& b = GetParam();
  const Answer a = post_json(port(), b.path, b.body);
  EXPECT_EQ(a.status, 400) << a.body;
  const json j = json::parse(a.body, nullptr, false);
  ASSERT_TRUE(j.is_object()) << a.body;
  EXPECT_EQ(j["field"], b.field) << a.body;
  EXPECT_THAT(j["error"].get<std::string>(), HasSubstr(b.message));
  EXPECT_THAT(j["error"].get<std::string>(), Not(HasSubstr("definition:")));  // no file name of the conversion
  EXPECT_EQ(get(port(), "/api/models").status, 200);  // and the server answers on
}

const json kAtCos{{"cos", json::array({0.5})}};

INSTANTIATE_TEST_SUITE_P(
    Every, ServeBadDefinition,
    ::testing::Values(
        BadDefinition{"a syntax error", "/api/eval", with(kAtCos, "model", phong_with("lobe", "c^*n")), "model.lobe", "column 3: "},
        BadDefinition{"an unknown identifier", "/api/eval", with(kAtCos, "model", phong_with("lobe", "c^n + 2*x")), "model.lobe",
                      "column 9: unknown variable 'x'"},
        BadDefinition{"an unknown identifier in a let", "/api/glsl", {{"model", phong_with("let", {"a = n", "b = a*q"})}},
                      "model.let[1]", "column 7: unknown variable 'q'"},
        BadDefinition{"a bad normalization", "/api/normalize", {{"model", phong_with("normalization", "(n+2)/(2*pie)")}},
                      "model.normalization", "column 10: unknown variable 'pie'"},
        BadDefinition{"a formula too deep", "/api/eval", with(kAtCos, "model", phong_with("lobe", nested(80))), "model.lobe", "too deep"},
        BadDefinition{"a missing key", "/api/albedo", {{"model", phong_with("form", nullptr)}}, "model.form", "missing key 'form'"},
        BadDefinition{"a missing range", "/api/check", {{"model", phong_with_n("max", nullptr)}}, "model.params.n.max", "lacks key 'max'"},
        BadDefinition{"an unknown key", "/api/eval", with(kAtCos, "model", phong_with("from", "Phong")), "model.from", "unknown key 'from'"},
        BadDefinition{"an unknown parameter key", "/api/eval", with(kAtCos, "model", phong_with_n("step", 1)), "model.params.n.step", "unknown key 'step'"},
        BadDefinition{"a default outside its range", "/api/eval", with(kAtCos, "model", phong_with_n("max", 10)),
                      "model.params.n.default", "default 20 is outside its range (0, 10]"},
        BadDefinition{"a wrong type", "/api/eval", with(kAtCos, "model", phong_with("form", 3)), "model.form", "must be a string"},
        BadDefinition{"an unknown kind", "/api/eval", with(kAtCos, "model", phong_with("kind", "blob")), "model.kind", "neither"},
        BadDefinition{"a bad id", "/api/eval", with(kAtCos, "model", phong_with("id", "my model")), "model.id", "must be 1"},
        BadDefinition{"params not an object", "/api/eval", with(kAtCos, "model", phong_with("params", 20)), "model.params", "must be an object"},
        BadDefinition{"a parameter not an object", "/api/eval", with(kAtCos, "model", phong_with("params", {{"n", 20}})), "model.params.n",
                      "must be an object"},
        BadDefinition{"a bad BRDF", "/api/eval", {{"model", {{"kind", "brdf"}, {"brdf", "1/pi + nx"}}}, {"theta_i", 0}, {"theta_o", {0}}},
                      "model.brdf", "column 8: unknown variable 'nx'"},
        BadDefinition{"a model of the wrong type", "/api/eval", with(kAtCos, "model", json::array({"c^n"})), "model", "definition object"},
        BadDefinition{"a bad compare", "/api/normalize", {{"model", "log"}, {"compare", phong_with("lobe", "c^")}}, "compare.lobe", "column 3"},
        BadDefinition{"a bad reference", "/api/error", {{"model", "log"}, {"reference", phong_with("lobe", "x")}, {"n", {2}}},
                      "reference.lobe", "column 1: unknown variable 'x'"},
        BadDefinition{"a bad fit model", "/api/fit", {{"model", phong_with("lobe_u", "exp(-n*c*)")}}, "model.lobe_u", "column 10"},
        BadDefinition{"a bad inline lobe", "/api/eval", with(kAtCos, "model", "lobe: c^*n"), "model", "column 9"}));

}  // namespace
}  // namespace specula::serve
