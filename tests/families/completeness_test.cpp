// One definition per family (include/specula/families/): for every registered built-in model,
// every part its family's definition names is there and works, through one predicate,
// missing_parts; the negative controls show that predicate naming the part a family lacks.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "glsl_support.h"
#include "reference_table.h"
#include "specula/brdf/directions.h"
#include "specula/catalogue/catalogue.h"
#include "specula/families/families.h"
#include "specula/glsl/glsl.h"
#include "specula/normalize/normalize.h"
#include "specula/simd/brdf.h"
#include "src/glsl/shader_files.h"

namespace specula::families {
namespace {

using Parts = std::vector<std::string>;
using ::testing::HasSubstr;

/// The registry knows the model as a built-in of this family's kind.
void check_registered(const Family& family, const ModelDefinition& model, Parts& missing) {
  const ModelInfo* info = find_model(model.id);
  if (!info || !info->is_builtin() || info->kind != family.kind)
    missing.push_back(fmt::format("registry: no built-in {} model '{}'", to_string(family.kind), model.id));
}

/// A fragment shader that calls the model's entry point; valid when glslangValidator accepts it.
bool emitted_shader_compiles(const Model& model) {
  const std::string shader = glsl::version_header(glsl::Dialect::glsl330) + glsl::model_glsl(model) +
                             "uniform vec4 u_params;\nout vec4 colour;\nvoid main() {\n"
                             "  vec3 N = vec3(0.0, 0.0, 1.0), L = normalize(vec3(1.0, 0.0, 1.0));\n"
                             "  colour = vec4(specula_brdf(N, L, normalize(vec3(-1.0, 0.2, 1.0)), u_params));\n}\n";
  return testing::validate_glsl(shader, "frag").ok;
}

/// The family's F(c) file defines its function; the model's own file (k(n) where k ≠ 1, a BRDF's
/// entry) is embedded; the emitted shader compiles in each form.
void check_glsl(const Family& family, const ModelDefinition& model, Parts& missing) {
  const std::size_t before = missing.size();
  if (family.kind == ModelKind::lobe) {
    const glsl::ShaderFile* lobe = glsl::find_shader_file(family.glsl.file);
    if (!lobe) missing.push_back(fmt::format("GLSL: the lobe file '{}' is not embedded", family.glsl.file));
    else if (family.glsl.function.empty() || lobe->text.find(fmt::format("float {}(", family.glsl.function)) == std::string_view::npos)
      missing.push_back(fmt::format("GLSL: '{}' defines no '{}'", family.glsl.file, family.glsl.function));
  }
  const bool needs_file = family.kind == ModelKind::brdf || model.normalization != Normalization::none;
  if (needs_file && model.glsl_file.empty()) missing.push_back(fmt::format("GLSL: '{}' names no file of its own", model.id));
  if (!model.glsl_file.empty() && !glsl::find_shader_file(model.glsl_file))
    missing.push_back(fmt::format("GLSL: '{}' is not embedded", model.glsl_file));
  if (missing.size() > before) return;  // nothing to emit
  for (const Form form : {Form::rv, Form::nh}) {
    if (family.kind == ModelKind::brdf && form == Form::nh) continue;
    const Model m = make_model(model.id, {}, family.kind == ModelKind::lobe ? std::optional(form) : std::nullopt);
    if (!emitted_shader_compiles(m)) missing.push_back(fmt::format("GLSL: the shader of '{}' does not compile", model.id));
  }
}

bool states_a_bound(const simd::ErrorBound& b) { return b.rel > 0 || b.abs > 0; }

/// |batch − scalar| within `bound` at every value (`scalar` the reference, F or f).
bool within(const simd::ErrorBound& bound, const std::vector<double>& batch, const std::vector<double>& scalar) {
  for (std::size_t i = 0; i < batch.size(); ++i) {
    const double f = scalar[i];
    if (!(std::abs(batch[i] - f) <= bound.allowed(f, f > 0 ? std::log(f) : 0))) return false;
  }
  return true;
}

/// A lobe family: its kernels are dispatched (no fallback), the model's lobe maps to them, each tier
/// and lane type states a bound, and the exact and fast batches meet it in double.
void check_simd_lobe(const Family& family, const Model& m, Parts& missing) {
  if (simd::spec_of(m.lobe()).family != family.simd)
    missing.push_back(fmt::format("SIMD: '{}' does not map to its family's kernels", m.id()));
  for (const simd::Tier tier : {simd::Tier::exact, simd::Tier::fast}) {
    if (!simd::has_kernel(family.simd, tier)) {
      missing.push_back(fmt::format("SIMD: no {} kernel for the {} family", to_string(tier), family.name));
      continue;
    }
    if (!states_a_bound(family.bounds.of(tier, true)) || !states_a_bound(family.bounds.of(tier, false)))
      missing.push_back(fmt::format("SIMD: the {} family states no {} bound", family.name, to_string(tier)));
    std::vector<double> c, scalar;
    for (int i = 0; i <= 64; ++i) c.push_back(1 - std::pow(i / 64.0, 3));
    for (const double x : c) scalar.push_back(lobes::eval(m.lobe(), x));
    std::vector<double> batch(c.size());
    simd::eval_batch(simd::spec_of(m.lobe()), tier, std::span<const double>(c), std::span<double>(batch));
    if (!within(simd::error_bound<double>(family.simd, tier), batch, scalar))
      missing.push_back(fmt::format("SIMD: the {} batch of '{}' exceeds its bound", to_string(tier), m.id()));
  }
}

/// A full BRDF: a stated bound per tier, met by the batch at directions around the mirror one.
void check_simd_brdf(const Family& family, const Model& m, Parts& missing) {
  std::vector<double> nx, ny, nz, lx, ly, lz, vx, vy, vz, scalar;
  for (int i = 0; i < 16; ++i) {
    const Vec3 n{0, 0, 1}, l = from_spherical(0.1 * i, 0.3 * i), v = from_spherical(0.05 * i + 0.02, 3.14159 + 0.2 * i);
    nx.push_back(n.x), ny.push_back(n.y), nz.push_back(n.z), lx.push_back(l.x), ly.push_back(l.y), lz.push_back(l.z);
    vx.push_back(v.x), vy.push_back(v.y), vz.push_back(v.z), scalar.push_back(m(n, l, v));
  }
  const simd::DirectionBatch dirs{nx, ny, nz, lx, ly, lz, vx, vy, vz};
  for (const simd::Tier tier : {simd::Tier::exact, simd::Tier::fast}) {
    if (!states_a_bound(family.bounds.of(tier, false)))
      missing.push_back(fmt::format("SIMD: the {} family states no {} bound", family.name, to_string(tier)));
    std::vector<double> batch(scalar.size());
    simd::eval_batch(m, tier, dirs, batch);
    if (!within(simd::error_bound(m, tier), batch, scalar))
      missing.push_back(fmt::format("SIMD: the {} batch of '{}' exceeds its bound", to_string(tier), m.id()));
  }
}

/// Rows of tests/reference/ where the definition says its values are.
void check_reference(const ReferenceRows& where, std::string_view what, Parts& missing) {
  if (where.table.empty()) return missing.push_back(fmt::format("reference: no table for {}", what));
  const auto rows = testing::read_reference(std::string(where.table));
  const bool found = std::any_of(rows.begin(), rows.end(), [&](const testing::ReferenceRow& row) {
    return row.fields.contains(std::string(where.column)) && row.text(std::string(where.column)) == where.key;
  });
  if (!found) missing.push_back(fmt::format("reference: no rows {} = {} in {} for {}", where.column, where.key, where.table, what));
}

/// k as the normalization says: 1, the published formula, or the closed form, which must equal
/// quadrature's to 1e-12 (normalize::Method::quadrature).
void check_normalization(const Family& family, const ModelDefinition& model, Parts& missing) {
  if (model.normalization == Normalization::formula && !model.coef)
    missing.push_back(fmt::format("normalization: '{}' has no k formula", model.id));
  if (model.normalization != Normalization::exact) return;
  const Coefficient exact = family.closed_form.in(model.form);
  if (!exact) return missing.push_back(fmt::format("normalization: the {} family has no closed form in {} form", family.name, to_string(model.form)));
  for (const double n : {1.0, 20.0, 1000.0}) {
    const double quadrature = normalize::coefficient(make_model(model.id, {{"n", n}}).lobe(), model.form, normalize::Method::quadrature);
    if (!(std::abs(exact(n) - quadrature) <= 1e-12 * quadrature))
      missing.push_back(fmt::format("normalization: '{}' k({}) = {} but quadrature gives {}", model.id, n, exact(n), quadrature));
  }
}

/// Every part of `model` of `family` that is missing or does not work, in words; empty when complete.
Parts missing_parts(const Family& family, const ModelDefinition& model) {
  Parts missing;
  check_registered(family, model, missing);
  if (!missing.empty()) return missing;
  const Model m = make_model(model.id);
  check_glsl(family, model, missing);
  if (family.kind == ModelKind::lobe) {
    if (!family.make_lobe || m.lobe().index() != static_cast<std::size_t>(family.simd))
      missing.push_back(fmt::format("scalar: '{}' is not its family's lobes::Lobe alternative", model.id));
    check_simd_lobe(family, m, missing);
    check_reference(family.reference, family.name, missing);
    check_reference(family.coefficients, family.name, missing);
    check_normalization(family, model, missing);
  } else {
    if (!model.make_brdf) missing.push_back(fmt::format("scalar: '{}' has no BRDF", model.id));
    check_simd_brdf(family, m, missing);
    check_reference(model.reference, model.id, missing);
  }
  return missing;
}

TEST(Families, EveryRegisteredBuiltinModelHasADefinition) {
  std::size_t builtin = 0;
  for (const ModelInfo& info : models()) {
    if (!info.is_builtin()) continue;
    ++builtin;
    EXPECT_NE(find_builtin(info.id).model, nullptr) << info.id;
  }
  std::size_t defined = 0;
  for (const Family* family : kFamilies) defined += family->models.size();
  EXPECT_EQ(builtin, defined);
}

TEST(Families, EveryRegisteredBuiltinModelHasEveryPart) {
  for (const ModelInfo& info : models()) {
    if (!info.is_builtin()) continue;
    const BuiltinModel builtin = find_builtin(info.id);
    ASSERT_NE(builtin.model, nullptr) << info.id;
    EXPECT_EQ(missing_parts(*builtin.family, *builtin.model), Parts{}) << info.id;
  }
}

TEST(Families, EachFamilyIsFoundByItsName) {
  for (const Family* family : kFamilies) {
    EXPECT_FALSE(family->models.empty()) << family->name;
    EXPECT_THAT(std::string(family->scalar), HasSubstr("include/specula/")) << family->name;
  }
  EXPECT_EQ(family_name(lobes::Lobe{lobes::SchlickModified<>{}}), "schlick-modified");
  EXPECT_EQ(lobe_family(simd::Family::log).name, "log");
}

// The negative controls: the same predicate names the part a family or model lacks.
TEST(Families, AFamilyWithoutAPartIsIncomplete) {
  Family without_glsl = kPower;
  without_glsl.glsl.file = "lobes/no-such-family.glsl";
  EXPECT_THAT(missing_parts(without_glsl, kPowerModels[0]), ::testing::ElementsAre(HasSubstr("GLSL: the lobe file")));

  ModelDefinition without_coefficient_file = kPowerModels[1];  // phong-normalized
  without_coefficient_file.glsl_file = "";
  EXPECT_THAT(missing_parts(kPower, without_coefficient_file), ::testing::ElementsAre(HasSubstr("names no file")));

  Family without_kernel = kGauss;
  without_kernel.simd = simd::Family::formula;
  EXPECT_THAT(missing_parts(without_kernel, kGaussModels[0]), ::testing::Contains(HasSubstr("SIMD: no exact kernel")));

  Family without_reference = kLog;
  without_reference.reference.key = "no-such-lobe";
  EXPECT_THAT(missing_parts(without_reference, kLogModels[0]), ::testing::ElementsAre(HasSubstr("reference: no rows")));

  Family wrong_closed_form = kSchlick;
  wrong_closed_form.closed_form.rv = lobes::phong_rv;
  EXPECT_THAT(missing_parts(wrong_closed_form, kSchlickModels[1]), ::testing::Contains(HasSubstr("quadrature gives")));

  ModelDefinition unregistered = kGgxModels[0];
  unregistered.id = "ggx-unregistered";
  EXPECT_THAT(missing_parts(kGgx, unregistered), ::testing::ElementsAre(HasSubstr("registry:")));
}

}  // namespace
}  // namespace specula::families
