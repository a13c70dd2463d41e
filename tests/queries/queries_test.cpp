// What the CLI and the server both ask (queries/queries.h): every query makes each model once
// (make_model names the field at fault, so that no query makes a model again to find out which
// field was bad), its choices are enums parsed from one list of names, and its errors name the
// field by key, spelled as the interface that asked spells it: never a CLI option for the server.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "specula/catalogue/catalogue.h"
#include "specula/exceptions.h"
#include "specula/queries/queries.h"

namespace specula::queries {
namespace {

using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

/// Phong's lobe model (c^n, k = (n+2)/(2π)) under a definition of its own that counts how often a
/// model of it is made.
class Counted {
 public:
  Counted() {
    auto info = std::make_shared<ModelInfo>(*find_model("phong-normalized"));
    info->id = "counted";
    info->origin = {OriginKind::request, ""};
    info->make = [made = made_, make = info->make](std::span<const double> values) {
      ++*made;
      return make(values);
    };
    info_ = info;
  }
  ModelRef ref() const { return ModelRef(info_); }
  const std::shared_ptr<const ModelInfo>& info() const { return info_; }
  int made() const { return made_->load(); }

 private:
  std::shared_ptr<std::atomic<int>> made_ = std::make_shared<std::atomic<int>>(0);
  std::shared_ptr<const ModelInfo> info_;
};

NormalizeQuery normalize_query(ModelRef model, std::vector<double> n,
                               NormalizeMethod method = NormalizeMethod::automatic) {
  NormalizeQuery q;
  q.model = std::move(model);
  q.n = std::move(n);
  q.method = method;
  return q;
}

/// The InvalidField that `f` throws: its field and message ("no error" when f returns).
struct Failure {
  std::string field;
  std::string message;
};
Failure failure_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidField& e) {
    return {e.field(), e.what()};
  } catch (const InvalidArgument& e) {
    return {"(no field)", e.what()};
  }
  return {"", "no error"};
}

// ---- each model made once ------------------------------------------------------------------------

TEST(MadeOnce, TheCounterCountsEveryModelMade) {  // the control of the tests below
  const Counted counted;
  make_model(counted.info());
  make_model(counted.info(), {{"n", 3}});
  EXPECT_EQ(counted.made(), 2);
}

TEST(MadeOnce, MakeBuildsOneModelWithParametersFormAndCoefficient) {
  const Counted counted;
  const Model m = make({counted.ref(), {{"n", 30}}, Form::nh, 2.5}, Spelling::key);
  EXPECT_EQ(counted.made(), 1);
  EXPECT_EQ(m.param("n"), 30);
  EXPECT_EQ(m.form(), Form::nh);
  EXPECT_EQ(m.coef(), 2.5);
}

TEST(MadeOnce, ALobeModelAtNIsMadeOnce) {
  const Counted counted;
  const Model m = lobe_model_at("model", "normalize", counted.ref(), {}, 50, Form::nh, Spelling::key);
  EXPECT_EQ(counted.made(), 1);
  EXPECT_EQ(m.param("n"), 50);
}

TEST(MadeOnce, NormalizeMakesOneModelPerN) {
  const Counted counted;
  normalize_table(normalize_query(counted.ref(), {1, 2, 3}), Spelling::key);
  EXPECT_EQ(counted.made(), 3);
  const Counted at_default;
  normalize_table(normalize_query(at_default.ref(), {}), Spelling::key);  // n: the model's default
  EXPECT_EQ(at_default.made(), 1);
}

TEST(MadeOnce, ErrorAndCheckMakeOneModelPerValue) {
  const Counted error_model;
  error_table({error_model.ref(), {}, ModelRef("phong"), {1, 10, 100}, 0.5}, Spelling::key);
  EXPECT_EQ(error_model.made(), 3);
  const Counted checked;
  CheckQuery q;
  q.model.model = checked.ref();
  q.sweep = "n";
  q.values = {5, 50};
  q.options.reciprocity_pairs = 10;
  check_cases(q, Spelling::key);
  EXPECT_EQ(checked.made(), 2);
}

// ---- the field at fault ----------------------------------------------------------------------------

TEST(FieldAtFault, MakeNamesTheModelItsParametersItsFormAndItsCoefficient) {
  const auto field_of = [](ModelSpec spec) { return failure_of([&] { make(spec, Spelling::key); }).field; };
  EXPECT_EQ(field_of({ModelRef("log"), {{"n", 20}}, Form::nh, 2.0}), "");  // control: all good
  EXPECT_EQ(field_of({ModelRef("nope"), {}, {}, {}}), "model");
  EXPECT_EQ(field_of({ModelRef("log"), {{"q", 1}}, {}, {}}), "params");
  EXPECT_EQ(field_of({ModelRef("log"), {{"n", 0}}, {}, {}}), "params");
  EXPECT_EQ(field_of({ModelRef("ggx"), {}, Form::nh, {}}), "form");
  EXPECT_EQ(field_of({ModelRef("ggx"), {{"alpha", 5}}, Form::nh, {}}), "params");  // params before form
  EXPECT_EQ(field_of({ModelRef("log-normalized"), {}, {}, 0.0}), "coef");
  EXPECT_EQ(field_of({ModelRef("ggx"), {}, {}, 2.0}), "coef");
}

TEST(FieldAtFault, AnInlineFormulasColumnFollowsItsFieldAsTheInterfaceSpellsIt) {
  const ModelSpec spec{ModelRef("lobe: c^*n"), {}, {}, {}};
  const Failure cli = failure_of([&] { make(spec, Spelling::option); });
  EXPECT_EQ(cli.field, "model");
  EXPECT_THAT(cli.message, StartsWith("--model: column 9: "));
  const Failure server = failure_of([&] { make(spec, Spelling::key); });
  EXPECT_EQ(server.field, "model");
  EXPECT_THAT(server.message, StartsWith("model: column 9: "));
  // A compared model's error is that field's.
  const Failure compare = failure_of(
      [] { lobe_model_at("compare", "--compare", ModelRef("lobe: c^"), {}, 2, {}, Spelling::option); });
  EXPECT_EQ(compare.field, "compare");
  EXPECT_THAT(compare.message, StartsWith("--compare: column "));
}

TEST(FieldAtFault, ALobeModelAtNNamesItsFieldNAndParams) {
  const auto at = [](std::string_view field, const std::string& id, ParamValues params, double n) {
    return failure_of([&] { lobe_model_at(field, "error", ModelRef(id), params, n, {}, Spelling::key); });
  };
  EXPECT_EQ(at("reference", "phong", {}, 2).field, "");  // control
  EXPECT_EQ(at("reference", "nope", {}, 2).field, "reference");
  const Failure brdf = at("reference", "ggx", {}, 2);
  EXPECT_EQ(brdf.field, "reference");
  EXPECT_EQ(brdf.message, "error works on lobe models; 'ggx' is a full BRDF");
  EXPECT_EQ(at("model", "log", {}, 0).field, "n");
  EXPECT_EQ(at("model", "lobe: c^2", {}, 2).field, "n");  // a lobe without n
  EXPECT_EQ(at("model", "schlick-modified", {{"s", -1}}, 2).field, "params");
}

// ---- choices: enums parsed from one list -----------------------------------------------------------

TEST(Choices, EveryNameParsesToItsEnumerator) {
  for (const NormalizeMethod m : enumerators<NormalizeMethod, kNormalizeMethodCount>())
    EXPECT_EQ(normalize_method_named(to_string(m), Spelling::key), m);
  for (const Condition c : enumerators<Condition, kConditionCount>())
    EXPECT_EQ(condition_named(to_string(c), Spelling::key), c);
  for (const AlbedoMethod m : enumerators<AlbedoMethod, kAlbedoMethodCount>())
    EXPECT_EQ(albedo_method_named(to_string(m), Spelling::key), m);
  for (const glsl::Dialect d : enumerators<glsl::Dialect, glsl::kDialectCount>())
    EXPECT_EQ(dialect_named(glsl::to_string(d)), d);
  EXPECT_EQ((names_of<NormalizeMethod, kNormalizeMethodCount>()),
            (std::vector<std::string>{"auto", "exact", "quadrature", "both"}));
}

TEST(Choices, AnUnknownNameListsTheNamesUnderItsSpelledKey) {
  const Failure cli = failure_of([] { normalize_method_named("guess", Spelling::option); });
  EXPECT_EQ(cli.field, "method");
  EXPECT_EQ(cli.message, "--method must be one of auto, exact, quadrature, both, got 'guess'");
  const Failure server = failure_of([] { condition_named("lax", Spelling::key); });
  EXPECT_EQ(server.field, "condition");
  EXPECT_EQ(server.message, "condition must be one of normal, strict, got 'lax'");
  EXPECT_EQ(failure_of([] { albedo_method_named("mc", Spelling::key); }).field, "method");
  EXPECT_EQ(failure_of([] { dialect_named("hlsl"); }).field, "dialect");
}

TEST(Choices, TheTableNamesTheMethodAndCondition) {
  const NormalizeQuery q = normalize_query(ModelRef("log"), {20}, NormalizeMethod::both);
  const io::Table t = normalize_table(q, Spelling::key);
  EXPECT_THAT(t.meta, ::testing::Contains(std::pair<std::string, std::string>{"method", "both"}));
  EXPECT_THAT(t.meta, ::testing::Contains(std::pair<std::string, std::string>{"condition", "normal"}));
  EXPECT_THAT(t.columns, ::testing::ElementsAre("n", "coef", "coef_quadrature", "rel_diff"));
}

// ---- keys, not options ----------------------------------------------------------------------------

TEST(KeysNotOptions, ExactWithoutAClosedFormSaysHowToAskForQuadrature) {
  const NormalizeQuery q = normalize_query(ModelRef("gauss"), {20}, NormalizeMethod::exact);
  const Failure cli = failure_of([&] { normalize_table(q, Spelling::option); });
  EXPECT_EQ(cli.field, "method");
  EXPECT_THAT(cli.message, EndsWith("; use --method quadrature"));
  const Failure server = failure_of([&] { normalize_table(q, Spelling::key); });
  EXPECT_EQ(server.field, "method");
  EXPECT_THAT(server.message, EndsWith("; use method quadrature"));
}

// Every message of these bad queries names keys when the server asks; the same queries from the
// CLI name its options (the control: the check for "--" can fail).
TEST(KeysNotOptions, NoMessageToTheServerNamesAnOption) {
  const std::vector<std::function<void(Spelling)>> bad{
      [](Spelling s) { make({ModelRef("lobe: c^*n"), {}, {}, {}}, s); },
      [](Spelling s) {
        NormalizeQuery q = normalize_query(ModelRef("log"), {});
        q.params = {{"n", 2}};
        normalize_table(q, s);
      },
      [](Spelling s) { normalize_table(normalize_query(ModelRef("gauss"), {20}, NormalizeMethod::exact), s); },
      [](Spelling s) { normalize_method_named("guess", s); },
      [](Spelling s) { error_table({ModelRef("log"), {}, ModelRef("lobe: c^"), {2}, 0.5}, s); },
      [](Spelling s) { eval_at_directions(make_model("ggx"), 91, std::vector<double>{0}, 0, s); },
  };
  for (std::size_t i = 0; i < bad.size(); ++i) {
    const Failure server = failure_of([&] { bad[i](Spelling::key); });
    EXPECT_NE(server.message, "no error") << i;
    EXPECT_THAT(server.message, Not(HasSubstr("--"))) << i;
    EXPECT_THAT(failure_of([&] { bad[i](Spelling::option); }).message, HasSubstr("--")) << i;
  }
}

}  // namespace
}  // namespace specula::queries
