// The JSON API of `specula serve` over real HTTP on a loopback port: every endpoint's answer
// against the library called directly, and every kind of bad request with its status and field.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "serve_support.h"
#include "specula/analysis/albedo.h"
#include "specula/analysis/check.h"
#include "specula/analysis/error.h"
#include "specula/brdf/directions.h"
#include "specula/glsl/glsl.h"
#include "specula/io/table.h"
#include "specula/io/values.h"
#include "specula/catalogue/catalogue.h"
#include "specula/normalize/normalize.h"
#include "specula/render/scene.h"
#include "specula/render/scene_shader.h"
#include "specula/sampling/check.h"
#include "specula/sampling/estimators.h"
#include "specula/sampling/sampler.h"

namespace specula::serve {
namespace {

using json = nlohmann::json;
using specula::testing::Answer;
using specula::testing::get;
using specula::testing::post;
using specula::testing::post_json;
using ::testing::HasSubstr;

class ServeApi : public specula::testing::ServerSuite {
 protected:
  /// The column `name` of a table answer.
  static std::vector<double> column(const json& table, const std::string& name) {
    std::vector<double> values;
    for (const auto& row : table["rows"]) values.push_back(row[name].is_null() ? NAN : row[name].get<double>());
    return values;
  }
};

TEST_F(ServeApi, ModelsListsEveryModelWithItsParameters) {
  const Answer a = get(port(), "/api/models");
  ASSERT_EQ(a.status, 200);
  EXPECT_EQ(a.content_type, "application/json");
  const json list = a.json();
  ASSERT_EQ(list.size(), models().size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    EXPECT_EQ(list[i]["id"], std::string(models()[i].id));
    EXPECT_EQ(list[i]["params"].size(), models()[i].params.size());
  }
}

TEST_F(ServeApi, NormalizeGivesTheLibrarysCoefficients) {
  const json t = ok("/api/normalize", {{"model", "log"}, {"n", {1, 2, 5, 1000}}});
  EXPECT_EQ(t["form"], "rv");
  const auto coef = column(t, "coef");
  ASSERT_EQ(coef.size(), 4u);
  EXPECT_NEAR(coef[0], 0.48274947790781993, 1e-15);
  EXPECT_NEAR(coef[3], 197.49861008019521, 197.5 * 1e-14);  // docs/math.md §4
  const std::vector<double> n{1, 2, 5, 1000};
  for (std::size_t i = 0; i < n.size(); ++i) {
    const Model m = make_model("log", {{"n", n[i]}});
    EXPECT_EQ(coef[i], normalize::coefficient(m.lobe(), m.form())) << "n = " << n[i];
  }
}

TEST_F(ServeApi, NormalizeTakesTheClisRangesAndMethods) {
  const json t = ok("/api/normalize", {{"model", "log"}, {"n", "1:1000@50:log"}, {"method", "both"}, {"compare", "log-paper"}});
  EXPECT_EQ(column(t, "n"), io::parse_values("1:1000@50:log"));
  EXPECT_THAT(t["columns"], ::testing::ElementsAre("n", "coef", "coef_quadrature", "rel_diff", "coef_compare", "delta"));
  for (const double rel : column(t, "rel_diff")) EXPECT_LT(std::abs(rel), 1e-12);
  const Model m = make_model("gauss", {{"n", 10}}, Form::nh);
  const json gauss = ok("/api/normalize", {{"model", "gauss"}, {"form", "nh"}, {"n", {10}}});
  EXPECT_EQ(column(gauss, "coef")[0], normalize::coefficient(m.lobe(), Form::nh));
}

TEST_F(ServeApi, EvalAtCosinesIsTheModelsValue) {
  const std::vector<double> cosines{0, 0.5, 0.9, 0.95, 0.99, 1};
  const json t = ok("/api/eval", {{"model", "log-normalized"}, {"params", {{"n", 20}}}, {"cos", cosines}});
  const json bare = ok("/api/eval", {{"model", "log-normalized"}, {"params", {{"n", 20}}}, {"cos", cosines}, {"lobe", true}});
  const Model m = make_model("log-normalized", {{"n", 20}});
  for (std::size_t i = 0; i < cosines.size(); ++i) {
    EXPECT_EQ(column(t, "value")[i], m.at_cos(cosines[i]));
    EXPECT_EQ(column(bare, "value")[i], lobes::eval(m.lobe(), cosines[i]));
  }
  EXPECT_EQ(t["coef"], io::format_number(m.coef()));
}

TEST_F(ServeApi, EvalAtDirectionsIsTheBrdfsValue) {
  const json t = ok("/api/eval", {{"model", "ggx"}, {"params", {{"alpha", 0.2}}}, {"theta_i", 30}, {"theta_o", "0:60:20"}, {"phi_o", 180}});
  const Model m = make_model("ggx", {{"alpha", 0.2}});
  const Vec3 l = from_spherical(radians(30.0), 0.0);
  const auto values = column(t, "value");
  ASSERT_EQ(values.size(), 4u);
  for (int i = 0; i < 4; ++i)
    EXPECT_EQ(values[static_cast<std::size_t>(i)], m({0, 0, 1}, l, from_spherical(radians(20.0 * i), radians(180.0))));
  EXPECT_NEAR(values[1], 1.7407662153196157, 1e-15);  // README's example
}

// Rusinkiewicz's angles: H at θ_h from N, L at θ_d from H; the values are the model's at those
// directions, and the directions are what the angles say (H the half vector, ∠(L, H) = θ_d).
TEST_F(ServeApi, SliceIsTheBrdfsValueAtTheHalfDifferenceAngles) {
  const json t = ok("/api/slice", {{"model", "ggx"}, {"params", {{"alpha", 0.3}}}, {"theta_h", {0, 20, 40}},
                                   {"theta_d", "0:60:30"}, {"phi_d", 45}});
  const Model m = make_model("ggx", {{"alpha", 0.3}});
  const auto values = column(t, "value");
  ASSERT_EQ(values.size(), 9u);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double theta_h = radians(20.0 * i), theta_d = radians(30.0 * j);
      const auto [l, v] = from_half_difference(theta_h, theta_d, radians(45.0));
      EXPECT_EQ(values[static_cast<std::size_t>(3 * i + j)], m({0, 0, 1}, l, v)) << i << " " << j;
      const Vec3 h = half_vector(l, v);
      EXPECT_NEAR(std::acos(h.z), theta_h, 1e-7);
      EXPECT_NEAR(std::acos(dot(l, h)), theta_d, 1e-7);
    }
  // θ_h = θ_d = 0 is L = V = N: the peak, as eval gives it at normal incidence.
  const json peak = ok("/api/eval", {{"model", "ggx"}, {"params", {{"alpha", 0.3}}}, {"theta_i", 0}, {"theta_o", {0}}});
  EXPECT_DOUBLE_EQ(values[0], column(peak, "value")[0]);
}

// The 3-D lobe's data: f over the outgoing hemisphere, one row per θ_o, as the model gives it at
// (θ_o, φ_o) with L at θ_i and azimuth 0.
TEST_F(ServeApi, HemisphereIsTheModelOverTheOutgoingDirections) {
  const json t = ok("/api/hemisphere", {{"model", "ggx"}, {"params", {{"alpha", 0.3}}}, {"theta_i", 40},
                                        {"theta_o", {0, 30, 60}}, {"phi_o", "0:270:90"}});
  const Model m = make_model("ggx", {{"alpha", 0.3}});
  ASSERT_EQ(t["values"].size(), 3u);
  const Vec3 l = from_spherical(radians(40.0), 0.0);
  for (std::size_t i = 0; i < 3; ++i) {
    ASSERT_EQ(t["values"][i].size(), 4u);
    for (std::size_t j = 0; j < 4; ++j) {
      const Vec3 v = from_spherical(radians(30.0 * i), radians(90.0 * j));
      EXPECT_NEAR(t["values"][i][j].get<double>(), m({0, 0, 1}, l, v), 1e-12 * m({0, 0, 1}, l, v)) << i << " " << j;
    }
  }
  // Its default grid: 2° in θ_o, 5° in φ_o.
  const json grid = ok("/api/hemisphere", {{"model", "lambert"}});
  EXPECT_EQ(grid["theta_o_deg"].size(), 46u);
  EXPECT_EQ(grid["phi_o_deg"].size(), 72u);
  EXPECT_EQ(grid["theta_i_deg"], 30);
}

// The energy view's compensations: each one's albedo beside the random walk's truth on the model's
// own microsurface and Fresnel. What specula ships follows the walk; no compensation at all misses
// the multiply scattered light of a rough surface (the control).
TEST_F(ServeApi, CompensationIsEachSchemesAlbedoAgainstTheWalk) {
  const json t = ok("/api/compensation", {{"model", "ggx-f82"}, {"params", {{"alpha", 0.9}, {"f0", 0.9}, {"tint", 0.8}}},
                                          {"mu", {0.2, 0.6, 1}}});
  ASSERT_EQ(t["rows"].size(), 3u);
  EXPECT_EQ(t["model"], "ggx-f82");
  for (const auto& r : t["rows"]) {
    EXPECT_DOUBLE_EQ(r["alpha"].get<double>(), 0.9);
    const double truth = r["E_F"].get<double>() + r["E_ms"].get<double>();
    EXPECT_DOUBLE_EQ(r["albedo_none"].get<double>(), r["E_F"].get<double>());
    EXPECT_LT(std::abs(r["albedo_ggx+ms"].get<double>() - truth), 0.02) << r.dump();
    EXPECT_GT(truth - r["albedo_none"].get<double>(), 0.05) << r.dump();
  }
  // ggx-f82+ms names the same microsurface and Fresnel.
  EXPECT_EQ(ok("/api/compensation", {{"model", "ggx-f82+ms"}, {"params", {{"alpha", 0.9}, {"f0", 0.9}, {"tint", 0.8}}},
                                     {"mu", {0.2, 0.6, 1}}})["rows"], t["rows"]);
}

// The sampling view's data: check --sampling at one angle (its histograms and verdict, as the
// library gives them) and directions the sampler draws, each in the upper hemisphere.
TEST_F(ServeApi, SamplingIsTheChecksVerdictWithItsHistograms) {
  const json c = ok("/api/sampling", {{"model", "ggx"}, {"params", {{"alpha", 0.3}}}, {"theta", 30}, {"samples", 20000},
                                      {"bins", 8}, {"points", 100}});
  sampling::SamplingCheckOptions o;
  o.theta_deg = {30};
  o.samples = 20000;
  o.cos_bins = 8;
  const sampling::AngleCheck a = sampling::check_sampling(sampling::Sampler(make_model("ggx", {{"alpha", 0.3}})), o).angles[0];
  EXPECT_EQ(c["chi2"].get<double>(), a.chi2);
  EXPECT_EQ(c["observed"].get<std::vector<double>>(), a.observed);
  EXPECT_EQ(c["expected"].get<std::vector<double>>(), a.expected);
  EXPECT_EQ(c["observed"].size(), 8u * 16u);
  EXPECT_TRUE(c["passes"].get<bool>());
  ASSERT_LE(c["points"].size(), 100u);  // draws that fall below the horizon are left out
  ASSERT_GE(c["points"].size(), 80u);
  for (const auto& p : c["points"]) EXPECT_GT(p[2].get<double>(), 0);
}

TEST_F(ServeApi, AlbedoIsTheCubaturesValue) {
  const json t = ok("/api/albedo", {{"model", "log-normalized"}, {"params", {{"n", 20}}}, {"theta", {0, 60, 89}}});
  const Model m = make_model("log-normalized", {{"n", 20}});
  const auto albedo = column(t, "albedo");
  ASSERT_EQ(albedo.size(), 3u);
  EXPECT_EQ(albedo[0], analysis::albedo(m, 0).value);
  EXPECT_EQ(albedo[1], analysis::albedo(m, radians(60.0)).value);
  EXPECT_EQ(albedo[2], analysis::albedo(m, radians(89.0)).value);
  EXPECT_NEAR(albedo[0], 1, 1e-9);
  const json mc = ok("/api/albedo", {{"model", "lambert"}, {"theta", {30}}, {"method", "monte-carlo"}, {"samples", 10000}});
  EXPECT_THAT(mc["columns"], ::testing::Contains("standard_error"));
  // BRDF Explorer's estimators: the library's estimate, the same for the same seed.
  const json mis = ok("/api/albedo", {{"model", "log-normalized"}, {"params", {{"n", 20}}}, {"theta", {60}},
                                      {"method", "mis"}, {"samples", 5000}, {"seed", 4}});
  const sampling::AlbedoEstimate e = sampling::albedo_estimate(m, radians(60.0), sampling::Estimator::mis, 5000, 4);
  EXPECT_EQ(column(mis, "albedo")[0], e.mean);
  EXPECT_EQ(column(mis, "standard_error")[0], e.standard_error);
}

TEST_F(ServeApi, CheckGivesTheVerdictsOfTheLibrary) {
  // k made for the rv form breaks in nh (README): reflects 254 % more than it receives.
  const json fails = ok("/api/check", {{"model", "log-normalized"}, {"params", {{"n", 20}}}, {"form", "nh"}, {"pairs", 1000}});
  ASSERT_EQ(fails.size(), 1u);
  EXPECT_FALSE(fails[0]["conserves_energy"].get<bool>());
  EXPECT_NEAR(fails[0]["max_albedo"].get<double>(), 3.543598137, 1e-9);
  analysis::CheckOptions options;
  options.reciprocity_pairs = 1000;
  const auto direct = analysis::check(make_model("log-normalized", {{"n", 20}}, Form::nh), options);
  EXPECT_EQ(fails[0]["max_albedo"].get<double>(), direct.max_albedo.value);
  const json holds = ok("/api/check", {{"model", "log-normalized"}, {"n", {1, 20}}, {"pairs", 1000}});
  ASSERT_EQ(holds.size(), 2u);
  for (const auto& c : holds) EXPECT_TRUE(c["conserves_energy"].get<bool>() && c["reciprocal"].get<bool>()) << c.dump();
  const json swept = ok("/api/check", {{"model", "phong-normalized"}, {"sweep", "n"}, {"values", {2, 30}}, {"pairs", 100}});
  ASSERT_EQ(swept.size(), 2u);
  EXPECT_EQ(swept[1]["n"], "30");
}

TEST_F(ServeApi, ErrorGivesTheExactMaxima) {
  const json t = ok("/api/error", {{"model", "log"}, {"reference", "phong"}, {"n", {1, 20, 1000}}});
  const auto direct = analysis::approximation_error(make_model("log", {{"n", 20}}).lobe(), make_model("phong", {{"n", 20}}).lobe());
  EXPECT_EQ(column(t, "max_abs")[1], direct.max_abs);
  for (const double e : column(t, "max_abs")) EXPECT_NEAR(e, 0.125, 1e-12);  // docs/math.md §3
}

TEST_F(ServeApi, GlslGivesTheModelsFunctionAndHowToCallIt) {
  const json t = ok("/api/glsl", {{"model", "log-normalized"}, {"params", {{"n", 50}}}});
  const Model m = make_model("log-normalized", {{"n", 50}});
  EXPECT_EQ(t["dialect"], "webgl2");
  EXPECT_EQ(t["entry"], "specula_brdf");
  EXPECT_THAT(t["function"].get<std::string>(), HasSubstr(glsl::model_glsl(m)));
  EXPECT_EQ(t["entry_params"].get<std::vector<float>>()[0], glsl::model_params(m)[0]);
  EXPECT_EQ(t["version_header"], glsl::version_header(glsl::Dialect::webgl2));
  EXPECT_THAT(ok("/api/glsl", {{"model", "ggx"}, {"dialect", "glsl330"}})["function"].get<std::string>(), HasSubstr("GLSL 3.30"));
  EXPECT_FALSE(t.contains("fragment_shader"));
}

TEST_F(ServeApi, GlslWithShaderGivesTheSceneShaderAndItsUniforms) {
  const json t = ok("/api/glsl", {{"model", "schlick"}, {"shader", true}, {"light", {0, 0, 1}}, {"size", {64, 48}}});
  const Model m = make_model("schlick");
  EXPECT_EQ(t["fragment_shader"],
            render::scene_fragment_shader(m, glsl::Dialect::webgl2, render::SceneGeometry::spheres));
  EXPECT_EQ(t["vertex_shader"], render::scene_vertex_shader(glsl::Dialect::webgl2));
  render::Scene scene = render::default_scene(m);
  scene.lights[0].direction = {0, 0, 1};
  const render::SceneUniforms u = render::scene_uniforms(scene, {64, 48}, render::Display{});
  const json& uniforms = t["uniforms"];
  EXPECT_EQ(uniforms["u_resolution"].get<std::vector<float>>(), std::vector<float>({64, 48}));
  EXPECT_EQ(uniforms["u_lights"][0].get<std::vector<float>>(), std::vector<float>(u.lights[0].begin(), u.lights[0].end()));
  EXPECT_EQ(uniforms["u_eye"].get<std::vector<float>>(), std::vector<float>(u.eye.begin(), u.eye.end()));
  EXPECT_EQ(uniforms["u_display"], 1);
}

// ---- bad requests ------------------------------------------------------------------------------

struct BadRequest {
  const char* what;
  const char* path;
  std::string body;
  int status;
  const char* field;
};

std::ostream& operator<<(std::ostream& os, const BadRequest& b) { return os << b.what; }

class ServeBadRequest : public ServeApi, public ::testing::WithParamInterface<BadRequest> {};

TEST_P(ServeBadRequest, IsRefusedNamingTheField) {
  const BadRequest& b = GetParam();
  const Answer a = post(port(), b.path, b.body);
  EXPECT_EQ(a.status, b.status) << a.body;
  EXPECT_EQ(a.content_type, "application/json");
  const json j = json::parse(a.body, nullptr, false);
  ASSERT_TRUE(j.is_object()) << a.body;
  EXPECT_EQ(j["field"], b.field) << a.body;
  EXPECT_FALSE(j["error"].get<std::string>().empty());
}

std::string repeated(const std::string& item, int count) {
  std::string list;
  for (int i = 0; i < count; ++i) list += (i ? "," : "") + item;
  return list;
}

INSTANTIATE_TEST_SUITE_P(
    Every, ServeBadRequest,
    ::testing::Values(
        // malformed or mistyped bodies
        BadRequest{"malformed JSON", "/api/normalize", R"({"model": "log", "n": [1, 2)", 400, "body"},
        BadRequest{"empty body", "/api/normalize", "", 400, "body"},
        BadRequest{"a NUL byte after the object", "/api/normalize", std::string(R"({"model": "log"})") + '\0' + "junk", 400, "body"},
        BadRequest{"a NUL byte alone after the object", "/api/albedo", std::string(R"({"model": "log"})") + '\0', 400, "body"},
        BadRequest{"an array body", "/api/normalize", "[1, 2]", 400, "body"},
        // a body that is valid once a byte order mark is skipped ({} is a whole design job)
        BadRequest{"a byte order mark", "/api/design", "\xEF\xBB\xBF{}", 400, "body"},
        BadRequest{"NaN literal", "/api/eval", R"({"model": "log", "cos": [NaN]})", 400, "body"},
        BadRequest{"model not a string", "/api/normalize", R"({"model": 3})", 400, "model"},
        BadRequest{"n of strings", "/api/normalize", R"({"model": "log", "n": [1, "2"]})", 400, "n"},
        BadRequest{"n an object", "/api/normalize", R"({"model": "log", "n": {"a": 1}})", 400, "n"},
        BadRequest{"params not an object", "/api/eval", R"({"model": "log", "params": [20], "cos": [1]})", 400, "params"},
        BadRequest{"param not a number", "/api/eval", R"({"model": "log", "params": {"n": "20"}, "cos": [1]})", 400, "params"},
        BadRequest{"lobe not a boolean", "/api/eval", R"({"model": "log", "cos": [1], "lobe": 1})", 400, "lobe"},
        BadRequest{"samples not whole", "/api/albedo", R"({"model": "lambert", "method": "monte-carlo", "samples": 1.5})", 400, "samples"},
        BadRequest{"unknown field", "/api/normalize", R"({"model": "log", "ns": [1]})", 400, "ns"},
        // missing fields
        BadRequest{"no model", "/api/normalize", R"({"n": [1]})", 400, "model"},
        BadRequest{"no points", "/api/eval", R"({"model": "log"})", 400, "cos"},
        BadRequest{"theta_o without theta_i", "/api/eval", R"({"model": "ggx", "theta_o": [1]})", 400, "theta_i"},
        BadRequest{"fit with nothing to fit", "/api/fit", R"({"generations": 1})", 400, "data"},
        // not a number, out of range
        BadRequest{"nan in a range", "/api/normalize", R"({"model": "log", "n": "1,nan"})", 400, "n"},
        BadRequest{"inf in a range", "/api/error", R"({"model": "log", "n": "inf"})", 400, "n"},
        BadRequest{"huge literal", "/api/eval", R"({"model": "log", "cos": [1e999]})", 400, "body"},
        BadRequest{"malformed range", "/api/normalize", R"({"model": "log", "n": "1:"})", 400, "n"},
        BadRequest{"empty list", "/api/normalize", R"({"model": "log", "n": []})", 400, "n"},
        BadRequest{"n = 0", "/api/normalize", R"({"model": "log", "n": [0]})", 400, "n"},
        BadRequest{"n given as a param", "/api/normalize", R"({"model": "log", "params": {"n": 2}})", 400, "params"},
        BadRequest{"param out of range", "/api/eval", R"({"model": "ggx", "params": {"alpha": 5}, "theta_i": 0, "theta_o": [0]})", 400, "params"},
        BadRequest{"unknown param", "/api/eval", R"({"model": "log", "params": {"q": 1}, "cos": [1]})", 400, "params"},
        BadRequest{"cos > 1", "/api/eval", R"({"model": "log", "cos": [0.5, 2]})", 400, "cos"},
        BadRequest{"cos on a full BRDF", "/api/eval", R"({"model": "ggx", "cos": [1]})", 400, "cos"},
        BadRequest{"theta_i > 90", "/api/eval", R"({"model": "ggx", "theta_i": 91, "theta_o": [0]})", 400, "theta_i"},
        BadRequest{"theta_o < 0", "/api/eval", R"({"model": "ggx", "theta_i": 10, "theta_o": [-1]})", 400, "theta_o"},
        BadRequest{"phi_o > 360", "/api/eval", R"({"model": "ggx", "theta_i": 10, "theta_o": [0], "phi_o": 400})", 400, "phi_o"},
        BadRequest{"theta_h > 90", "/api/slice", R"({"model": "ggx", "theta_h": [95], "theta_d": [0]})", 400, "theta_h"},
        BadRequest{"theta_d < 0", "/api/slice", R"({"model": "ggx", "theta_h": [5], "theta_d": [-1]})", 400, "theta_d"},
        BadRequest{"phi_d > 360", "/api/slice", R"({"model": "ggx", "theta_h": [5], "theta_d": [0], "phi_d": 361})", 400, "phi_d"},
        BadRequest{"no theta_d", "/api/slice", R"({"model": "ggx", "theta_h": [5]})", 400, "theta_d"},
        BadRequest{"a slice over its points", "/api/slice", R"({"model": "ggx", "theta_h": "0:90@101", "theta_d": "0:90@101"})", 400, "theta_d"},
        BadRequest{"a hemisphere over its points", "/api/hemisphere", R"({"model": "ggx", "theta_o": "0:90@101", "phi_o": "0:360@101"})", 400, "phi_o"},
        BadRequest{"a hemisphere below the horizon", "/api/hemisphere", R"({"model": "ggx", "theta_i": 95})", 400, "theta_i"},
        BadRequest{"compensation of a lobe", "/api/compensation", R"({"model": "phong"})", 400, "model"},
        BadRequest{"compensation with too few paths", "/api/compensation", R"({"model": "ggx", "paths": 100})", 400, "paths"},
        BadRequest{"compensation at mu 0", "/api/compensation", R"({"model": "ggx", "mu": [0]})", 400, "mu"},
        BadRequest{"sampling at 90 degrees", "/api/sampling", R"({"model": "ggx", "theta": 90})", 400, "theta"},
        BadRequest{"sampling with too few samples", "/api/sampling", R"({"model": "ggx", "samples": 10})", 400, "samples"},
        BadRequest{"theta = 90", "/api/albedo", R"({"model": "lambert", "theta": [90]})", 400, "theta"},
        BadRequest{"coef 0", "/api/albedo", R"({"model": "log-normalized", "coef": 0, "theta": [0]})", 400, "coef"},
        BadRequest{"coef on a full BRDF", "/api/albedo", R"({"model": "ggx", "coef": 2, "theta": [0]})", 400, "coef"},
        BadRequest{"form on a full BRDF", "/api/glsl", R"({"model": "ggx", "form": "nh"})", 400, "form"},
        BadRequest{"unknown form", "/api/glsl", R"({"model": "log", "form": "xy"})", 400, "form"},
        BadRequest{"a zero light direction", "/api/glsl", R"({"model": "log", "shader": true, "light": [0, 0, 0]})", 400, "light"},
        BadRequest{"an image side of 0", "/api/glsl", R"({"model": "log", "shader": true, "size": [0, 10]})", 400, "size"},
        BadRequest{"a light without the shader", "/api/glsl", R"({"model": "log", "light": [0, 0, 1]})", 400, "light"},
        BadRequest{"unknown dialect", "/api/glsl", R"({"model": "log", "dialect": "hlsl"})", 400, "dialect"},
        BadRequest{"unknown method", "/api/normalize", R"({"model": "log", "method": "guess"})", 400, "method"},
        BadRequest{"strict and exact", "/api/normalize", R"({"model": "log", "condition": "strict", "method": "exact"})", 400, "method"},
        BadRequest{"step 0", "/api/check", R"({"model": "lambert", "step": 0})", 400, "step"},
        BadRequest{"zone 1", "/api/error", R"({"model": "log", "n": [2], "zone": 1})", 400, "zone"},
        BadRequest{"sweep of an unknown parameter", "/api/check", R"({"model": "ward", "sweep": "q", "values": [1]})", 400, "sweep"},
        BadRequest{"fit time beyond 60 s", "/api/fit", R"({"model": "log", "time": 61})", 400, "time"},
        BadRequest{"fit rows of unequal length", "/api/fit", R"({"data": {"columns": {"x": [1, 2], "y": [1]}, "target": "y"}})", 400, "data.columns"},
        BadRequest{"fit variable named like a function", "/api/fit", R"({"data": {"columns": {"exp": [1, 2], "y": [1, 2]}, "target": "y"}})", 400, "data.vars"},
        BadRequest{"fit unknown operator", "/api/fit", R"({"model": "log", "ops": "+,%"})", 400, "ops"},
        // unknown names
        BadRequest{"unknown model", "/api/normalize", R"({"model": "nope"})", 400, "model"},
        BadRequest{"full BRDF to normalize", "/api/normalize", R"({"model": "ggx"})", 400, "model"},
        BadRequest{"unknown reference", "/api/error", R"({"model": "log", "reference": "nope", "n": [2]})", 400, "reference"},
        BadRequest{"full BRDF to compare", "/api/normalize", R"({"model": "log", "compare": "ggx", "n": [2]})", 400, "compare"},
        // too much work
        BadRequest{"2001 n values", "/api/normalize", R"({"model": "log", "n": "1:2001"})", 400, "n"},
        BadRequest{"a range of a billion", "/api/error", R"({"model": "log", "n": "1:1000000000"})", 400, "n"},
        BadRequest{"51 strict n values", "/api/normalize", R"({"model": "log", "condition": "strict", "n": "1:51"})", 400, "n"},
        BadRequest{"10001 cosines", "/api/eval", R"({"model": "log", "cos": "0:1@10001"})", 400, "cos"},
        BadRequest{"201 albedo angles", "/api/albedo", "{\"model\": \"lambert\", \"theta\": [" + repeated("1", 201) + "]}", 400, "theta"},
        BadRequest{"monte-carlo beyond its budget", "/api/albedo", R"({"model": "lambert", "method": "monte-carlo", "samples": 100000000})", 400, "samples"},
        BadRequest{"too many reciprocity pairs", "/api/check", R"({"model": "lambert", "pairs": 100001})", 400, "pairs"},
        BadRequest{"fit generations beyond the cap", "/api/fit", R"({"model": "log", "generations": 100001})", 400, "generations"},
        BadRequest{"fit formula size beyond the cap", "/api/fit", R"({"model": "log", "max_size": 41})", 400, "max_size"},
        BadRequest{"a body beyond 64 KiB", "/api/normalize", "{\"model\": \"log\", \"n\": [" + repeated("1", 40000) + "]}", 413, "body"}));

// Errors name the request's keys, never a CLI option: a bad inline formula quotes its field, a
// lobe without a closed form says how to ask for quadrature, a bad choice lists its names.
TEST_F(ServeApi, ErrorsNameTheJsonKeyNotACliOption) {
  struct Case {
    std::string path;
    json body;
    std::string field;
    std::string says;
  };
  const std::vector<Case> cases{
      {"/api/eval", {{"model", "lobe: c^*n"}, {"cos", {0.5}}}, "model", "model: column 9: "},
      {"/api/normalize", {{"model", "log"}, {"compare", "lobe: c^"}, {"n", {2}}}, "compare", "compare: column "},
      {"/api/normalize", {{"model", "gauss"}, {"n", {20}}, {"method", "exact"}}, "method", "; use method quadrature"},
      {"/api/normalize", {{"model", "log"}, {"method", "guess"}}, "method",
       "method must be one of auto, exact, quadrature, both, got 'guess'"},
      {"/api/normalize", {{"model", "log"}, {"condition", "lax"}}, "condition", "condition must be one of normal, strict"},
      {"/api/albedo", {{"model", "ggx"}, {"method", "mc"}}, "method", "method must be one of cubature, monte-carlo"},
      {"/api/normalize", {{"model", "log"}, {"params", {{"n", 2}}}}, "params", "give n with n, not params"}};
  for (const Case& c : cases) {
    const Answer a = post_json(port(), c.path, c.body);
    EXPECT_EQ(a.status, 400) << a.body;
    const json j = json::parse(a.body, nullptr, false);
    ASSERT_TRUE(j.is_object()) << a.body;
    EXPECT_EQ(j["field"], c.field) << a.body;
    const std::string error = j["error"].get<std::string>();
    EXPECT_THAT(error, HasSubstr(c.says));
    EXPECT_THAT(error, ::testing::Not(HasSubstr("--")));
  }
}

// ---- routes, methods, files --------------------------------------------------------------------

TEST_F(ServeApi, UnknownRoutesAndJobsAre404) {
  for (const char* path : {"/api/nope", "/api", "/api/fit/999999", "/api/fit/abc", "/api/fit/-1", "/nope.html"}) {
    const Answer a = get(port(), path);
    EXPECT_EQ(a.status, 404) << path;
    EXPECT_EQ(a.content_type, "application/json") << path;
    EXPECT_THAT(a.body, HasSubstr("\"error\"")) << path;
  }
  EXPECT_EQ(specula::testing::del(port(), "/api/fit/999999").status, 404);
  EXPECT_EQ(post(port(), "/api/nope", "{}").status, 404);
}

TEST_F(ServeApi, WrongMethodsAre405WithTheAllowedOnes) {
  const Answer get_eval = get(port(), "/api/eval");
  EXPECT_EQ(get_eval.status, 405);
  EXPECT_EQ(get_eval.allow, "POST");
  const Answer post_models = post(port(), "/api/models", "{}");
  EXPECT_EQ(post_models.status, 405);
  EXPECT_EQ(post_models.allow, "GET");
  EXPECT_EQ(get(port(), "/api/fit").allow, "POST");
  EXPECT_EQ(specula::testing::del(port(), "/api/normalize").status, 405);
  EXPECT_EQ(post(port(), "/index.html", "{}").status, 405);
  EXPECT_EQ(specula::testing::raw_request(port(), "PUT /api/glsl HTTP/1.1").first, 405);
}

TEST_F(ServeApi, ServesThePageFromTheBinary) {
  const Answer root = get(port(), "/");
  ASSERT_EQ(root.status, 200);
  EXPECT_EQ(root.content_type, "text/html; charset=utf-8");
  EXPECT_THAT(root.body, HasSubstr("<!doctype html>"));
  EXPECT_EQ(get(port(), "/index.html").body, root.body);
}

TEST_F(ServeApi, ServesNothingOutsideItsAssets) {
  for (const char* line : {"GET /../CMakeLists.txt HTTP/1.1", "GET /%2e%2e/CMakeLists.txt HTTP/1.1",
                           "GET /..%2fCMakeLists.txt HTTP/1.1", "GET /%2e%2e%2f%2e%2e%2fetc%2fpasswd HTTP/1.1",
                           "GET /../../../../etc/passwd HTTP/1.1", "GET /web/index.html HTTP/1.1",
                           "GET /./index.html/.. HTTP/1.1", "GET //etc/passwd HTTP/1.1",
                           "GET /src/serve/api.cpp HTTP/1.1"}) {
    const auto [status, text] = specula::testing::raw_request(port(), line);
    EXPECT_TRUE(status == 404 || status == 400) << line << "\n" << text;
    EXPECT_THAT(text, ::testing::Not(HasSubstr("cmake_minimum_required"))) << line;
    EXPECT_THAT(text, ::testing::Not(HasSubstr("root:"))) << line;
  }
}

}  // namespace
}  // namespace specula::serve
