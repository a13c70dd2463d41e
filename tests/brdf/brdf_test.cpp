// Full BRDFs against mpmath (tests/reference/brdfs.csv), lobes in their forms against the
// geometry written out by angles, and reciprocity and non-negativity for every model.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <set>

#include "reference_table.h"
#include "specula/catalogue/catalogue.h"

namespace specula {
namespace {

const Vec3 kNormal{0, 0, 1};

Model model_from_row(const testing::ReferenceRow& row) {
  const std::string id = row.text("model");
  const ModelInfo* info = find_model(id);
  if (!info) throw std::runtime_error("unknown model " + id);
  ParamValues params;  // p1..p4: the model's parameters in order
  for (std::size_t i = 0; i < info->params.size(); ++i)
    params[std::string(info->params[i].name)] = row.number(fmt::format("p{}", i + 1));
  return make_model(id, params);
}

TEST(BrdfReference, FullBrdfsMatchMpmath) {
  const auto rows = testing::read_reference("brdfs.csv");
  ASSERT_GT(rows.size(), 1000u);
  std::set<std::string> ids;
  for (const auto& row : rows) {
    const Model m = model_from_row(row);
    ids.insert(row.text("model"));
    const Vec3 l{row.number("lx"), row.number("ly"), row.number("lz")};
    const Vec3 v{row.number("vx"), row.number("vy"), row.number("vz")};
    const double expected = row.number("value");
    // A few ulp per operation; the exponent exp(−tan²δ/α²) amplifies rounding by tan²δ/α².
    const double nh = dot(kNormal, half_vector(l, v));
    const double exponent = (1 - nh * nh) / (nh * nh) / (m.params()[0] * m.params()[0]);
    const double tolerance = (64 + 4 * exponent) * 2.2e-16 * expected + 1e-300;
    EXPECT_NEAR(m(kNormal, l, v), expected, tolerance)
        << row.text("model") << " p=" << row.text("p1") << "," << row.text("p2") << " L=(" << row.text("lx")
        << "," << row.text("lz") << ") V=(" << row.text("vx") << "," << row.text("vy") << "," << row.text("vz") << ")";
  }
  for (const auto& m : models())
    if (m.kind == ModelKind::brdf) {
      EXPECT_TRUE(ids.contains(std::string(m.id))) << m.id;
    }
}

// Lobe models: f = k·F(c) with c written out by angles, L at (θ_i, 0), V at (θ_o, φ):
// R·V = cos θ_i cos θ_o − sin θ_i sin θ_o cos φ; N·H = (cos θ_i + cos θ_o)/√(2 + 2 L·V).
TEST(LobeBrdf, FormCosinesMatchTheAngles) {
  for (const double ti : {0.0, 0.3, 1.0, 1.4})
    for (const double to : {0.0, 0.2, 0.9, 1.5})
      for (const double phi : {0.0, 1.0, std::numbers::pi}) {
        const Vec3 l = from_spherical(ti, 0.0), v = from_spherical(to, phi);
        const double lv = std::sin(ti) * std::sin(to) * std::cos(phi) + std::cos(ti) * std::cos(to);
        const double rv = std::cos(ti) * std::cos(to) - std::sin(ti) * std::sin(to) * std::cos(phi);
        const double nh = (std::cos(ti) + std::cos(to)) / std::sqrt(2 + 2 * lv);
        const Model log_rv = make_model("log-normalized", {{"n", 5}});
        const Model phong_nh = make_model("blinn-phong-normalized", {{"n", 5}});
        EXPECT_NEAR(log_rv(kNormal, l, v), log_rv.coef() * lobes::Log<>{5}(rv), 1e-13);
        EXPECT_NEAR(phong_nh(kNormal, l, v), phong_nh.coef() * std::pow(std::max(nh, 0.0), 5), 1e-13);
      }
}

TEST(LobeBrdf, CompileTimeLobeMatchesTheRegistryModel) {
  // A renderer's float path: LobeBrdf<lobes::Log<float>> against the run-time double Model.
  const Model m = make_model("log-normalized", {{"n", 20}});
  const LobeBrdf<lobes::Log<float>> brdf{{20.0f}, Form::rv, m.coef()};
  for (const double to : {0.0, 0.2, 0.4}) {
    const Vec3 l = from_spherical(0.3, 0.0), v = from_spherical(to, std::numbers::pi);
    const Vec3T<float> lf{float(l.x), float(l.y), float(l.z)}, vf{float(v.x), float(v.y), float(v.z)};
    EXPECT_NEAR(brdf(Vec3T<float>{0, 0, 1}, lf, vf), m(kNormal, l, v), 1e-5 * (1 + m(kNormal, l, v))) << to;
  }
}

TEST(LobeBrdf, ZeroBelowTheHorizon) {
  const Vec3 up = from_spherical(0.5, 0.0), down = from_spherical(2.0, 1.0);
  for (const auto& info : models()) {
    const Model m = make_model(info.id);
    EXPECT_EQ(m(kNormal, up, down), 0.0) << info.id;
    EXPECT_EQ(m(kNormal, down, up), 0.0) << info.id;
  }
}

rc::Gen<Vec3> upper_hemisphere() {
  return rc::gen::apply(
      [](int t, int p) { return from_spherical(t * 1e-6 * std::numbers::pi / 2, p * 1e-6 * 2 * std::numbers::pi); },
      rc::gen::inRange(0, 1'000'000), rc::gen::inRange(0, 1'000'000));
}

rc::Gen<Model> any_model() {
  return rc::gen::apply(
      [](std::size_t index, double u1, double u2) {
        const ModelInfo& info = models()[index];
        ParamValues params;
        for (std::size_t i = 0; i < info.params.size(); ++i) {
          const ParamInfo& p = info.params[i];
          const double u = i == 0 ? u1 : u2;
          const double lo = p.min_exclusive ? std::max(p.min, 1e-3) : p.min;
          const double hi = std::min(p.max, lo > 0 ? 1e4 : p.max);
          params[std::string(p.name)] = lo > 0 ? lo * std::pow(hi / lo, u) : lo + (hi - lo) * u;
        }
        return make_model(info.id, params);
      },
      rc::gen::inRange<std::size_t>(0, models().size()),
      rc::gen::map(rc::gen::inRange(0, 1001), [](int k) { return k / 1000.0; }),
      rc::gen::map(rc::gen::inRange(0, 1001), [](int k) { return k / 1000.0; }));
}

RC_GTEST_PROP(BrdfProperties, ReciprocalAndNonNegative, ()) {
  const Model m = *any_model();
  const Vec3 l = *upper_hemisphere(), v = *upper_hemisphere();
  const double f_lv = m(kNormal, l, v), f_vl = m(kNormal, v, l);
  RC_ASSERT(f_lv >= 0.0);
  RC_ASSERT(std::isfinite(f_lv) || dot(kNormal, l) * dot(kNormal, v) < 1e-12);
  // Full BRDFs are symmetric in L and V; lobes in rv form are too, since R(L)·V = R(V)·L.
  RC_ASSERT(std::abs(f_lv - f_vl) <= 1e-9 * std::max(f_lv, f_vl) + 1e-300);
}

}  // namespace
}  // namespace specula
