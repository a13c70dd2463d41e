// The model catalogue: every model of docs/math.md §2 is there, builds with its defaults, validates
// its parameters, and its k is what its normalization says.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <functional>
#include <set>

#include "error_message.h"
#include "specula/exceptions.h"
#include "specula/catalogue/catalogue.h"
#include "specula/lobes/closed_form.h"

namespace specula {
namespace {

using ::testing::HasSubstr;

using testing::error_of;

TEST(Registry, HasEveryModelOfMathMdOnce) {
  std::set<std::string> ids;
  for (const auto& m : models()) EXPECT_TRUE(ids.insert(std::string(m.id)).second) << m.id;
  for (const char* id : {"phong", "phong-normalized", "phong-lafortune", "blinn-phong-normalized",
                         "schlick", "schlick-modified", "gauss", "log", "log-normalized", "log-paper",
                         "ward", "ward-duer", "ward-gmd", "cook-torrance-1982", "cook-torrance", "ggx",
                         "lambert"})
    EXPECT_TRUE(ids.contains(id)) << id;
}

TEST(Registry, EveryModelBuildsWithItsDefaultsInsideItsRanges) {
  for (const auto& info : models()) {
    EXPECT_FALSE(info.name.empty());
    EXPECT_FALSE(info.source.empty());
    for (const auto& p : info.params) EXPECT_TRUE(p.accepts(p.default_value)) << info.id << " " << p.name;
    const Model m = make_model(info.id);
    EXPECT_EQ(m.is_lobe(), info.kind == ModelKind::lobe);
    if (m.is_lobe()) {
      EXPECT_EQ(m.form(), info.form) << info.id;
      EXPECT_GT(m.coef(), 0) << info.id;
      EXPECT_EQ(m.param("n"), 20);
    }
  }
}

TEST(Registry, CoefficientsFollowTheNormalization) {
  const double n = 37;
  auto k = [&](const char* id) { return make_model(id, {{"n", n}}).coef(); };
  constexpr double pi = std::numbers::pi;
  EXPECT_EQ(k("phong"), 1);
  EXPECT_EQ(k("log"), 1);
  EXPECT_DOUBLE_EQ(k("phong-normalized"), (n + 2) / (2 * pi));
  EXPECT_DOUBLE_EQ(k("phong-lafortune"), (n + 1) / (2 * pi));
  EXPECT_DOUBLE_EQ(k("blinn-phong-normalized"), (n + 2) * (n + 4) / (8 * pi * (std::exp2(-n / 2) + n)));
  EXPECT_DOUBLE_EQ(k("blinn-phong-approx"), (n + 8) / (8 * pi));
  EXPECT_DOUBLE_EQ(k("log-normalized"), lobes::log_rv(n));
  EXPECT_DOUBLE_EQ(k("log-paper"), 0.197 * (n + 1.24) + 0.068 / (0.64 + n));
  EXPECT_DOUBLE_EQ(k("schlick-normalized"), lobes::schlick_rv(n));
}

TEST(Registry, FormOverrideKeepsTheModelsCoefficient) {
  const Model rv = make_model("log-normalized", {{"n", 50}});
  const Model nh = make_model("log-normalized", {{"n", 50}}, Form::nh);
  EXPECT_EQ(nh.form(), Form::nh);
  EXPECT_EQ(nh.coef(), rv.coef());
}

TEST(Registry, BadInputIsNamed) {
  EXPECT_THAT(error_of([] { make_model("blinn"); }), HasSubstr("unknown model 'blinn'"));
  EXPECT_THAT(error_of([] { make_model("log", {{"m", 2}}); }), HasSubstr("no parameter 'm'"));
  EXPECT_THAT(error_of([] { make_model("log", {{"n", 0}}); }), HasSubstr("n = 0 is out of range"));
  EXPECT_THAT(error_of([] { make_model("log", {{"n", -1}}); }), HasSubstr("out of range"));
  EXPECT_THAT(error_of([] { make_model("log", {{"n", 2e9}}); }), HasSubstr("out of range"));
  EXPECT_THAT(error_of([] { make_model("log", {{"n", std::nan("")}}); }), HasSubstr("out of range"));
  EXPECT_THAT(error_of([] { make_model("ggx", {{"alpha", 0}}); }), HasSubstr("alpha"));
  EXPECT_THAT(error_of([] { make_model("ggx", {{"f0", 1.5}}); }), HasSubstr("f0"));
  EXPECT_THAT(error_of([] { make_model("ward", {}, Form::nh); }), HasSubstr("full BRDF"));
  EXPECT_THAT(error_of([] { parse_form("hn"); }), HasSubstr("unknown form 'hn'"));
  EXPECT_THAT(error_of([] { make_model("log").param("alpha"); }), HasSubstr("no parameter 'alpha'"));
}

/// The field (and for a parameter, the parameter) that make_model names: "no error" when it makes
/// the model.
std::string field_of(const std::function<void()>& make) {
  try {
    make();
  } catch (const InvalidParameter& e) {
    return e.field() + " " + e.param();
  } catch (const InvalidField& e) {
    return e.field();
  }
  return "no error";
}

// make_model names the field at fault, so that an interface asks it once and answers with the
// field (queries::make).
TEST(Registry, MakeModelNamesTheFieldAtFault) {
  EXPECT_EQ(field_of([] { make_model("ggx", {{"alpha", 0.5}}); }), "no error");  // control
  EXPECT_EQ(field_of([] { make_model("blinn"); }), "model");
  EXPECT_EQ(field_of([] { make_model("lobe: c^*n"); }), "model");
  EXPECT_EQ(field_of([] { make_model("log", {{"m", 2}}); }), "params m");
  EXPECT_EQ(field_of([] { make_model("log", {{"n", 0}}); }), "params n");
  EXPECT_EQ(field_of([] { make_model("ward", {}, Form::nh); }), "form");
  EXPECT_EQ(field_of([] { make_model("ward", {{"alpha", -1}}, Form::nh); }), "params alpha");  // params first
}

TEST(Registry, KindsNormalizationsAndOriginsHaveNames) {
  EXPECT_STREQ(to_string(ModelKind::lobe), "lobe");
  EXPECT_STREQ(to_string(ModelKind::brdf), "brdf");
  EXPECT_STREQ(to_string(Normalization::quadrature), "quadrature");
  EXPECT_EQ(find_model("log")->origin.kind, OriginKind::builtin);
  EXPECT_TRUE(find_model("log")->is_builtin());
  EXPECT_EQ(to_string(find_model("log")->origin), "built-in");
  const Model inline_lobe = make_model("lobe: c^n");
  EXPECT_EQ(inline_lobe.info().origin.kind, OriginKind::inline_formula);
  EXPECT_FALSE(inline_lobe.info().is_builtin());
  EXPECT_EQ(to_string(inline_lobe.info().origin), "inline");
  EXPECT_EQ(to_string(ModelOrigin{OriginKind::file, "my.toml:3"}), "my.toml:3");
  EXPECT_EQ(error_of([] { parse_form("hn"); }), "unknown form 'hn' (expected rv or nh)");
}

TEST(Registry, ParamRangeText) {
  EXPECT_EQ(find_model("log")->params[0].range_text(), "(0, 1e+09]");
  EXPECT_EQ(find_model("ggx")->find_param("f0")->range_text(), "[0, 1]");
}

}  // namespace
}  // namespace specula
