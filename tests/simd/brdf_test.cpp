// The batch models (simd/brdf.h) against the scalar Model::operator() at the same directions,
// within the bound error_bound(model, tier) states, for every model of the catalogue (both forms
// of the lobe models, narrow and wide parameters) on every instruction set this CPU runs.
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <random>
#include <vector>

#include "specula/brdf/directions.h"
#include "specula/catalogue/catalogue.h"
#include "specula/exceptions.h"
#include "specula/simd/brdf.h"
#include "specula/simd/targets.h"

namespace specula::simd {
namespace {

struct Directions {
  std::vector<double> c[9];

  DirectionBatch batch() const {
    return {c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8]};
  }
  Vec3 at(int k, std::size_t i) const { return {c[3 * k][i], c[3 * k + 1][i], c[3 * k + 2][i]}; }
  void push(const Vec3& n, const Vec3& l, const Vec3& v) {
    for (int k = 0; k < 3; ++k) {
      const Vec3& d = k == 0 ? n : (k == 1 ? l : v);
      c[3 * k].push_back(d.x);
      c[3 * k + 1].push_back(d.y);
      c[3 * k + 2].push_back(d.z);
    }
  }
};

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  return normalized(Vec3{normal(rng), normal(rng), normal(rng)});
}

/// Random normals; L over the sphere; V near the mirror direction or the normal (where narrow
/// lobes and NDFs have their values) or anywhere.
Directions random_directions(std::size_t count) {
  std::mt19937_64 rng(20231105u);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Directions dirs;
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 n = random_unit(rng), l = random_unit(rng);
    const Vec3 target = i % 3 == 0 ? reflect(l, n) : (i % 3 == 1 ? n : random_unit(rng));
    const double spread = std::pow(10.0, -4 * uniform(rng));
    dirs.push(n, l, normalized(target + random_unit(rng) * spread));
  }
  return dirs;
}

std::vector<Model> models_to_check() {
  std::vector<Model> out;
  for (const auto& info : models()) {
    if (info.kind == ModelKind::brdf) {
      out.push_back(make_model(info.id));
      for (const char* p : {"alpha", "m"})
        if (info.find_param(p)) out.push_back(make_model(info.id, {{p, 0.05}}));
      continue;
    }
    for (const double n : {5.0, 200.0})
      for (const Form form : {Form::rv, Form::nh}) out.push_back(make_model(info.id, {{"n", n}}, form));
  }
  return out;
}

void expect_models_within_bounds() {
  const Directions dirs = random_directions(3000);
  for (const Model& model : models_to_check())
    for (const Tier tier : {Tier::exact, Tier::fast}) {
      std::vector<double> got(dirs.c[0].size());
      eval_batch(model, tier, dirs.batch(), got);
      const ErrorBound bound = error_bound(model, tier);
      const double k = model.is_lobe() ? model.coef() : 1;
      std::size_t failures = 0;
      std::string worst;
      double worst_ratio = 0;
      for (std::size_t i = 0; i < got.size(); ++i) {
        const double f = model(dirs.at(0, i), dirs.at(1, i), dirs.at(2, i));
        const double error = std::abs(got[i] - f);
        const double allowed = bound.allowed(f, f > 0 ? std::log(f / k) : 0);
        failures += error > allowed;
        if (allowed > 0 && error / allowed > worst_ratio) {
          worst_ratio = error / allowed;
          worst = fmt::format("i = {}: got {:.17g}, scalar {:.17g}", i, got[i], f);
        }
      }
      EXPECT_EQ(failures, 0u) << current_target().name << " " << model.id() << " "
                              << (model.is_lobe() ? to_string(model.form()) : "") << " " << to_string(tier)
                              << ": worst " << worst << " (" << worst_ratio << " × allowed)";
    }
}

class EveryTargetBrdf : public ::testing::TestWithParam<std::int64_t> {
 protected:
  void SetUp() override { scope_.emplace(GetParam()); }
  void TearDown() override { scope_.reset(); }

 private:
  std::optional<ScopedTarget> scope_;
};

TEST_P(EveryTargetBrdf, EveryModelWithinItsBound) { expect_models_within_bounds(); }

INSTANTIATE_TEST_SUITE_P(Simd, EveryTargetBrdf, ::testing::ValuesIn(runnable_targets()),
                         [](const auto& info) { return target_name(info.param); });

TEST(SimdBrdf, BelowTheHorizonIsZeroAndLengthsMustAgree) {
  Directions dirs;
  dirs.push({0, 0, 1}, {0, 0.6, -0.8}, {0, 0, 1});  // L below
  dirs.push({0, 0, 1}, {0, 0, 1}, {0.6, 0, -0.8});  // V below
  std::vector<double> got(2, -1);
  for (const char* id : {"ggx", "log-normalized", "ward"}) {
    eval_batch(make_model(id), Tier::exact, dirs.batch(), got);
    EXPECT_EQ(got[0], 0) << id;
    EXPECT_EQ(got[1], 0) << id;
  }
  DirectionBatch ragged = dirs.batch();
  ragged.vz = ragged.vz.first(1);
  EXPECT_THROW(eval_batch(make_model("ggx"), Tier::exact, ragged, got), InvalidArgument);
}

TEST(SimdBrdf, LobeModelsSeeTheScalarCosineExactly) {
  // Phong's c^n at n = 1e4 moves by 1e4 ulp for one ulp of c: agreement to the power lobe's own
  // bound shows that the batch forms R·V and N·H bit-identically to the scalar model.
  const Directions dirs = random_directions(500);
  const Model model = make_model("phong", {{"n", 1e4}});
  std::vector<double> got(500);
  eval_batch(model, Tier::exact, dirs.batch(), got);
  for (std::size_t i = 0; i < got.size(); ++i) {
    const double f = model(dirs.at(0, i), dirs.at(1, i), dirs.at(2, i));
    EXPECT_LE(std::abs(got[i] - f), 3e-16 * f + 1e-300) << i;
  }
}

/// The directions of `dirs` as rows (x, y, z): N, L and V.
std::vector<std::vector<double>> as_rows(const Directions& dirs) {
  std::vector<std::vector<double>> rows(3);
  for (int k = 0; k < 3; ++k)
    for (std::size_t i = 0; i < dirs.c[0].size(); ++i) {
      const Vec3 d = dirs.at(k, i);
      rows[k].insert(rows[k].end(), {d.x, d.y, d.z});
    }
  return rows;
}

TEST(SimdBrdf, RowsGiveTheColumnsValuesBitForBit) {
  // 2500 rows: chunks of 1024 and a tail that is not a whole vector.
  const Directions dirs = random_directions(2500);
  const auto rows = as_rows(dirs);
  Directions local = dirs;  // N = +z for the rows without n
  for (std::size_t i = 0; i < local.c[0].size(); ++i) local.c[0][i] = local.c[1][i] = 0, local.c[2][i] = 1;
  for (const char* id : {"ggx", "ward", "log-normalized", "lambert", "ggx+ms"}) {
    const Model model = make_model(id);
    for (const Tier tier : {Tier::exact, Tier::fast}) {
      std::vector<double> columns(2500), from_rows(2500), local_columns(2500), local_rows(2500);
      eval_batch(model, tier, dirs.batch(), columns);
      eval_batch(model, tier, DirectionRows{rows[0], rows[1], rows[2]}, from_rows);
      EXPECT_EQ(from_rows, columns) << id;
      eval_batch(model, tier, local.batch(), local_columns);
      eval_batch(model, tier, DirectionRows{{}, rows[1], rows[2]}, local_rows);
      EXPECT_EQ(local_rows, local_columns) << id;
      EXPECT_NE(local_rows, columns) << id << ": the control, other normals, differs";
    }
  }
  EXPECT_THROW(eval_batch(make_model("ggx"), Tier::exact, DirectionRows{{}, rows[1], std::span(rows[2]).first(9)},
                          std::span<double>()),
               InvalidArgument);
  EXPECT_THROW(eval_batch(make_model("ggx"), Tier::exact, DirectionRows{{}, std::span(rows[1]).first(7),
                                                                       std::span(rows[2]).first(7)},
                          std::span<double>()),
               InvalidArgument);
}

}  // namespace
}  // namespace specula::simd
