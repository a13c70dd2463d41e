// Lobes the code has never seen, written as a user writes them (a model file), against mpmath
// (tests/reference/make_user_lobe_reference.py, user_lobes.csv): the coefficient by quadrature in
// both forms (≥ 12 digits) and the exact error maxima against cⁿ (≤ 1e-9), found through the
// numerically located support ends and kinks.
#include <gtest/gtest.h>

#include <cmath>

#include "reference_table.h"
#include "specula/analysis/error.h"
#include "specula/catalogue/model_file.h"
#include "specula/normalize/quadrature.h"

namespace specula {
namespace {

constexpr const char* kLobes = R"toml([[model]]
id = "quartic"
name = "quartic"
kind = "lobe"
form = "rv"
lobe = "max(0, 1 - n*(1-c)/4)^4"
lobe_u = "max(0, 1 + n*expm1(-u)/4)^4"
normalization = "quadrature"
[model.params.n]
default = 10
min = 0
min_exclusive = true
max = 1e9

[[model]]
id = "cauchy"
name = "cauchy"
kind = "lobe"
form = "rv"
lobe_u = "1/(1 + n*u)^2"
normalization = "quadrature"
[model.params.n]
default = 10
min = 0
min_exclusive = true
max = 1e9

[[model]]
id = "clipped"
name = "clipped"
kind = "lobe"
form = "rv"
lobe = "min(1, 2*c^n)"
lobe_u = "min(1, 2*exp(-n*u))"
normalization = "quadrature"
[model.params.n]
default = 10
min = 0
min_exclusive = true
max = 1e9
)toml";

class UserLobeReference : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { register_models(parse_model_file(kLobes, "user_lobes.toml")); }
  static void TearDownTestSuite() { clear_registered_models(); }
};

TEST_F(UserLobeReference, CoefficientsInBothFormsAndErrorMaximaMatchMpmath) {
  const auto rows = testing::read_reference("user_lobes.csv");
  ASSERT_EQ(rows.size(), 13u);
  for (const auto& row : rows) {
    const std::string lobe = row.text("lobe");
    const double n = row.number("n");
    const Model model = make_model(lobe, {{"n", n}});
    EXPECT_NEAR(model.coef() / row.number("coef_rv"), 1, 1e-12) << lobe << " n=" << n;
    EXPECT_NEAR(normalize::quadrature(model.lobe(), Form::nh) / row.number("coef_nh"), 1, 1e-12) << lobe << " n=" << n;
    const auto error = analysis::approximation_error(model.lobe(), lobes::Power<>{n}, 0.5);
    EXPECT_NEAR(error.max_abs, row.number("max_abs_vs_power"), 1e-9) << lobe << " n=" << n;
  }
}

TEST_F(UserLobeReference, TheChecksFailWhereTheyShould) {
  // Negative control: the quartic's coefficient is not the clipped lobe's, nor its error maximum.
  const Model quartic = make_model("quartic", {{"n", 10.0}}), clipped = make_model("clipped", {{"n", 10.0}});
  EXPECT_GT(std::abs(quartic.coef() / clipped.coef() - 1), 1e-3);
  EXPECT_GT(std::abs(analysis::approximation_error(quartic.lobe(), lobes::Power<>{10.0}, 0.5).max_abs -
                     analysis::approximation_error(clipped.lobe(), lobes::Power<>{10.0}, 0.5).max_abs),
            1e-3);
}

}  // namespace
}  // namespace specula
