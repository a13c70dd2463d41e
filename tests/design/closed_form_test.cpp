// Closed-form k of designed lobes against two independent references: the antiderivative by hand
// for F = c, and normalize::quadrature (adaptive Gauss–Kronrod in u) for every other lobe. The
// controls: lobes that are no polynomial on each side of one clamp get no closed form.
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

#include "design/closed_form.h"
#include "specula/catalogue/catalogue.h"
#include "specula/expr/expr.h"
#include "specula/normalize/quadrature.h"

namespace specula::design {
namespace {

Settings over(double lo, double hi, Form form = Form::rv) {
  Settings s;  // the target phong, its range parameter n
  s.lo = lo;
  s.hi = hi;
  s.form = form;
  return s;
}

double k_at(const std::string& k, double n) { return expr::evaluate(expr::parse(k, {"n"}), std::vector<double>{n}); }

double quadrature_k(const std::string& formula, double n, Form form) {
  const auto info = model_definition("lobe: " + formula, {{"n", n}});
  ParamValues params;
  if (info->find_param("n")) params["n"] = n;  // F = c^4 … does not read n
  return normalize::quadrature(make_model(info, params, form).lobe(), form);
}

TEST(ClosedForm, MatchesTheAntiderivativeOfTheLinearLobe) {
  const auto rv = closed_form_k("c", over(1, 10));
  ASSERT_TRUE(rv);
  EXPECT_NEAR(k_at(*rv, 3), 3 / (2 * std::numbers::pi), 1e-14);  // 1/(2π ∫₀¹ c·c dc)
  const auto nh = closed_form_k("c", over(1, 10, Form::nh));
  ASSERT_TRUE(nh);
  // 2π ∫ from 1/√2 to 1 of x (2x² − 1) 4x dx = 2π [8x⁵/5 − 4x³/3]
  const auto antiderivative = [](double x) { return 8 * std::pow(x, 5) / 5 - 4 * std::pow(x, 3) / 3; };
  const double albedo = 2 * std::numbers::pi * (antiderivative(1) - antiderivative(std::sqrt(0.5)));
  EXPECT_NEAR(k_at(*nh, 3) * albedo, 1, 1e-13);
}

TEST(ClosedForm, AgreesWithQuadratureOnPolynomialsAndClampedLobes) {
  const char* lobes[] = {
      "c^4 * (0.5 + 0.5 * c)",                            // a polynomial
      "max(n * c - (n - 1), 0)^2",                        // a clamp, its kink moving with n
      "max(0, (n + 2) / 3 * c + 1 - (n + 2) / 3)^3 * c",  // the clamp second, times c
      "max(1 - 2 * c, 0) + 0.1",                          // α < 0 and F ≠ 0 off the clamp
      "max(2 * c - 1, 0) + c^2 / n",                      // the clamp not outermost
      "(sqrt(n) * c + 1 - sqrt(n))^2 / (1 + log(n))",     // the parameter through functions
  };
  for (const Form form : {Form::rv, Form::nh})
    for (const char* lobe : lobes) {
      SCOPED_TRACE(lobe);
      SCOPED_TRACE(form == Form::rv ? "rv" : "nh");
      const auto k = closed_form_k(lobe, over(1, 100, form));
      ASSERT_TRUE(k);
      for (double n : {1.0, 2.5, 20.0, 100.0}) {
        const double reference = quadrature_k(lobe, n, form);
        EXPECT_NEAR(k_at(*k, n), reference, 1e-11 * reference) << "n = " << n << ", k = " << *k;
      }
    }
}

TEST(ClosedForm, OtherLobesHaveNone) {  // the controls
  for (const char* lobe : {"c^n",                                   // no polynomial in c
                           "exp(n * (c - 1))",                      // a transcendental of c
                           "max(c^2 - 0.5, 0)",                     // a clamp of a quadratic
                           "max(c - 0.5, 0) * max(c - 0.2, 0)",     // two kinks
                           "1 / (1 + n * (1 - c))",                 // rational in c
                           "max((n - 10) * c + 1, 0)",              // α changes sign over [1, 100]
                           "c^20"})                                 // beyond the nodes' degree
    EXPECT_FALSE(closed_form_k(lobe, over(1, 100))) << lobe;
}

}  // namespace
}  // namespace specula::design
