// The designer's targets beyond lobes (issue 41): functions of c ("expr: …") and the engine terms,
// with the engines' approximations as reference rows. What the designer measures is checked
// against independent dense evaluations of the same functions through brdf/fresnel.h and libm.
#include <cmath>
#include <numbers>
#include <set>
#include <gtest/gtest.h>

#include "specula/analysis/albedo.h"
#include "specula/brdf/fresnel.h"
#include "specula/catalogue/catalogue.h"
#include "specula/design/design.h"
#include "specula/design/output.h"
#include "specula/expr/expr.h"
#include "design/fitting.h"
#include "design/laws.h"
#include "design/shapes.h"
#include "design/verify.h"
#include "function_settings.h"

namespace specula::design {
namespace {

Settings small(const std::string& target) {
  Settings s = function_settings(target);
  s.operations = parse_operations("fma,mul,max");
  s.max_cost = 5;
  s.threads = 1;
  s.measure_cost = false;
  return s;
}

// The shape of `key` among those of cost ≤ max_cost over `ops`.
Shape shape_named(const char* ops, int max_cost, std::string_view key) {
  for (const Shape& x : enumerate_shapes(parse_operations(ops), max_cost, 1000))
    if (x.key == key) return x;
  throw std::runtime_error("no shape " + std::string(key));
}

const Lobe& reference(const Result& r, std::string_view id) {
  for (const Lobe& l : r.references)
    if (l.id == id) return l;
  throw std::runtime_error("no reference " + std::string(id));
}

// max over a dense (η, c) grid of |f(c, η) − the exact dielectric Fresnel|, c denser toward grazing.
template <class F>
double dense_dielectric_error(F f, double lo, double hi) {
  double worst = 0;
  for (int j = 0; j <= 130; ++j) {
    const double eta = lo + (hi - lo) * j / 130.0;
    for (int i = 1; i <= 4000; ++i) {
      const double c = std::pow(i / 4000.0, 2);
      worst = std::max(worst, std::abs(f(c, eta) - fresnel::dielectric(c, eta)));
    }
  }
  return worst;
}

// Schlick's approximation of the exact dielectric Fresnel over η ∈ [1.2, 2.5]: 0.113 (issue 41's
// figure), as a dense evaluation through brdf/fresnel.h finds it; the exact term itself is the
// third reference, at zero error. (The search is tiny: its members are not the point here.)
TEST(FunctionTargets, TheEnginesFresnelApproximationsAreMeasuredAsTheyAre) {
  Settings s = small("fresnel-dielectric");
  s.max_cost = 1;
  const Result r = design(s);
  const auto schlick = [](double c, double eta) {
    const double f0 = std::pow((eta - 1) / (eta + 1), 2);
    return fresnel::schlick(c, f0);
  };
  const double dense = dense_dielectric_error(schlick, 1.2, 2.5);
  EXPECT_NEAR(dense, 0.113, 0.001);
  EXPECT_GE(reference(r, "schlick").max_abs, dense - 1e-9);  // a maximum is at least the grid's
  EXPECT_LE(reference(r, "schlick").max_abs, dense + 1e-4);
  EXPECT_LT(reference(r, "exact").max_abs, 1e-12);
  EXPECT_GT(reference(r, "unreal-exp2").max_abs, reference(r, "schlick").max_abs);  // exp2's own error on top
  for (const Lobe& m : r.front) EXPECT_EQ(m.check, "-");  // not lobes: nothing to normalize or check
}

// A function of c without parameters: (1 − c)⁵ is found exactly within cost 5, each member's
// claimed error holds on a dense grid, and Karis's exp2 form misses by 0.0038 (issue 41's figure).
TEST(FunctionTargets, AnExpressionWithoutParametersIsFoundAndItsClaimsHold) {
  Settings s = small("expr: (1 - c)^5");
  s.operations = parse_operations("fma,mul");  // (1 − c)⁵ needs no clamp: fewer shapes to finish
  EXPECT_EQ(s.param, "");
  const Result r = design(s);
  ASSERT_FALSE(r.front.empty());
  EXPECT_LT(r.front.back().max_abs, 1e-12) << r.front.back().formula;
  for (const Lobe& m : r.front) {
    const expr::Expression f = expr::parse(m.formula, {"c"});
    double dense = 0;
    for (int i = 1; i <= 20000; ++i)  // even in c, and toward grazing down to c = 1e-12
      for (const double c : {i / 20000.0, std::pow(10.0, -12 + 8 * i / 20000.0)})
        dense = std::max(dense, std::abs(expr::evaluate(f, std::vector<double>{c}) - std::pow(1 - c, 5)));
    EXPECT_GE(m.max_abs, dense - 1e-12) << m.formula;  // never understated
    EXPECT_LE(m.max_abs, dense + 1e-4) << m.formula;   // the grid's step (5e-5) times the slope (≤ 5)
  }
  const Result weight = design([] {
    Settings w = small("schlick-weight");
    w.max_cost = 1;
    return w;
  }());
  EXPECT_NEAR(reference(weight, "unreal-exp2").max_abs, 0.00377, 0.00005);
  // A function's member has no normalization: front.csv's column is empty (a lobe's is not).
  const std::string csv = front_csv(weight);
  const auto row = csv.substr(csv.find("\nschlick-weight-d1,") + 1);
  EXPECT_NE(row.substr(0, row.find('\n')).find(",-,,"), std::string::npos) << row.substr(0, row.find('\n'));
}

// Two per-pixel variables: the height-correlated Smith G₂ of GGX over (NoV, NoL) ∈ (0, 1]² and
// α ∈ [0.05, 1]. The fast form of Filament and Unreal misses it by 0.214 (issue 41's 0.22), as a
// dense evaluation of the two formulas here finds; the exact row is the term itself. (The
// references measured as design() measures them; a search's cost is not needed here.)
TEST(FunctionTargets, SmithG2OverTwoVariablesMeasuresTheFastForm) {
  const Settings s = small("smith-g2-ggx");
  EXPECT_EQ(s.variables, (std::vector<std::string>{"NoV", "NoL"}));
  validate(s);
  // The references as design() measures them (domain_error), without a search.
  const auto measured = [&](std::string_view id) {
    for (const TermReference& r : term_references())
      if (r.term == s.target && r.id == id) {
        Lobe l;
        l.reference = l.evaluable = true;
        l.formula = r.formula;
        return domain_error(l, s, [] { return false; });
      }
    throw std::runtime_error("no reference " + std::string(id));
  };
  const auto exact = [](double v, double l, double a) {
    return 2 * v * l / (l * std::sqrt(v * v * (1 - a * a) + a * a) + v * std::sqrt(l * l * (1 - a * a) + a * a));
  };
  const auto fast = [](double v, double l, double a) { return 2 * v * l / (v * (l * (1 - a) + a) + l * (v * (1 - a) + a)); };
  double dense = 0;
  for (int k = 0; k <= 40; ++k) {
    const double a = 0.05 + 0.95 * k / 40;
    for (int i = 1; i <= 200; ++i)
      for (int j = 1; j <= 200; ++j) {
        const double v = std::pow(i / 200.0, 2), l = std::pow(j / 200.0, 2);
        dense = std::max(dense, std::abs(fast(v, l, a) - exact(v, l, a)));
      }
  }
  EXPECT_NEAR(dense, 0.214, 0.002);
  const DomainError fast_error = measured("fast-smith");
  EXPECT_GE(fast_error.max_abs, dense - 1e-9);
  EXPECT_LE(fast_error.max_abs, dense + 2e-3);
  EXPECT_LT(measured("exact").max_abs, 1e-12);
}

// a·(k·c + m)⁴ + b against the exact dielectric Fresnel: a and the affine map's scale trade off
// (a·(k·c + m)⁴ = (a^¼·k·c + a^¼·m)⁴), so the per-η fits wander along equally good constants that
// no small law follows. The constant the others make up for is held at one value, the rest get
// laws, and the laws are fitted together at the end: the finished lobe keeps the per-η fits'
// error (0.0325 against Schlick's 0.113), and is finite between the grid's η. The control: the
// same constants each held at its median, none refitted, miss by far more. (About 12 s under the
// sanitizers.)
TEST(FunctionTargets, LawsOfAShapeWithARedundantScaleKeepItsFitsError) {
  Settings s = small("fresnel-dielectric");
  const Shape shape = shape_named("fma,mul", 4, "((c * 7 + 7) ^ 2) ^ 2 * 7 + 7");
  std::vector<Samples> grid;
  for (double eta : param_grid(s.lo, s.hi, 17)) grid.push_back(samples_at(s, eta));  // the search's fine grid
  const GridFit fitted = fit_over_grid(shape, grid, s);
  EXPECT_LT(fitted.worst, 0.04);
  const auto lawful = constant_laws(shape, grid, fitted, s, [] { return false; });
  ASSERT_TRUE(lawful);
  EXPECT_LE(lawful->grid_error, fitted.worst * 1.05);
  double dense = 0;  // over η every 0.001, c denser toward grazing
  for (int j = 0; j <= 1300; ++j) {
    const double eta = s.lo + 0.001 * j;
    for (int i = 1; i <= 100; ++i) {
      const double c = std::pow(i / 100.0, 2), x[] = {c, eta};
      const double e = std::abs(expr::evaluate(lawful->lobe, x) - fresnel::dielectric(c, eta));
      ASSERT_TRUE(std::isfinite(e)) << "at eta = " << eta << ": " << expr::to_infix(lawful->lobe);
      dense = std::max(dense, e);
    }
  }
  EXPECT_LT(dense, fitted.worst * 1.1) << expr::to_infix(lawful->lobe);
  std::vector<std::vector<double>> medians = fitted.constants;
  for (std::size_t k = 0; k < medians[0].size(); ++k)
    for (auto& row : medians) row[k] = fitted.constants[8][k];
  double held = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) held = std::max(held, shape_error(shape, medians[i], grid[i], s));
  EXPECT_GT(held, 3 * fitted.worst);
}

// A function is not a lobe: a member may dip below 0, which counts as its error there. The
// minimax line of (1 − c)² is −1/8 at c = 1 (error ±1/8); a lobe target refuses the same line.
TEST(FunctionTargets, AMemberMayBeNegativeWhereALobeMayNot) {
  Settings s = small("expr: (1 - c)^2");
  const Shape line = shape_named("fma", 1, "c * 7 + 7");
  const std::vector<Samples> rows{samples_at(s, 1)};
  EXPECT_NEAR(fit_over_grid(line, rows, s).worst, 0.125, 1e-3);
  const double at_minimax[] = {-1, 0.875};
  EXPECT_NEAR(shape_error(line, at_minimax, rows[0], s), 0.125, 1e-3);
  Settings lobe = small("phong");
  lobe.lo = lobe.hi = 2;
  EXPECT_EQ(shape_error(line, at_minimax, samples_at(lobe, 2), lobe), INFINITY);  // the control: a lobe's
}

// Two ways of writing every quadratic in c compute the same best fit: the same signature, and
// the search screens only the cheaper further. The control: c²·a + b, a quadratic without its
// linear term, computes something else.
TEST(FunctionTargets, ShapesThatComputeTheSameFunctionHaveOneSignature) {
  Settings s = small("fresnel-dielectric");
  const Samples rows = samples_at(s, 1.85);
  const auto signature = [&](std::string_view key) {
    const Shape shape = shape_named("fma,mul", 3, key);
    const GridFit fit = fit_over_grid(shape, std::span<const Samples>(&rows, 1), s);
    return value_signature(shape, fit.constants[0], rows, s);
  };
  EXPECT_EQ(signature("(c * 7 + 7) ^ 2 * 7 + 7"), signature("c * (c * 7 + 7) * 7 + 7"));
  EXPECT_NE(signature("(c * 7 + 7) ^ 2 * 7 + 7"), signature("c ^ 2 * 7 + 7"));
  Settings weight = small("schlick-weight");  // no parameter: no laws to find, a quick search
  weight.max_cost = 3;
  weight.operations = parse_operations("fma,mul");
  const Result r = design(weight);
  EXPECT_GT(r.forms_same, 0);
  EXPECT_LT(r.forms_same, r.forms_screened);
}

// Beckmann's height-correlated G₂ as the designer computes it (erfc by Abramowitz & Stegun 7.1.26)
// within 2e-7 of the same G₂ with libm's erfc over a dense (NoV, NoL, α) grid; Walter et al.'s
// rational Λ (the reference row) misses by far more, the control that the comparison sees a
// difference.
TEST(FunctionTargets, BeckmannsSmithG2IsTheTermWithinItsStatedError) {
  const Settings s = small("smith-g2-beckmann");
  validate(s);  // finite, ≥ 0 and ≤ the bound over the whole box
  const auto lambda = [](double cos, double alpha) {
    if (cos >= 1) return 0.0;
    const double a = cos / (alpha * std::sqrt(1 - cos * cos));
    return (std::exp(-a * a) / (a * std::sqrt(std::numbers::pi)) - std::erfc(a)) / 2;
  };
  const auto deviation = [&](std::string_view formula) {
    const expr::Expression e = function_expression(s, formula);
    double worst = 0;
    for (int k = 0; k <= 20; ++k) {
      const double alpha = 0.05 + 0.95 * k / 20;
      for (int i = 1; i <= 100; ++i)
        for (int j = 1; j <= 100; ++j) {
          const double v = std::pow(i / 100.0, 2), l = std::pow(j / 100.0, 2), x[] = {v, l, alpha};
          worst = std::max(worst, std::abs(expr::evaluate(e, x) - 1 / (1 + lambda(v, alpha) + lambda(l, alpha))));
        }
    }
    return worst;
  };
  std::string walter;
  for (const TermReference& r : term_references())
    if (r.term == s.target && r.id == "walter-rational") walter = r.formula;
  EXPECT_LT(deviation(function_formula(s.target)), 2e-7);
  EXPECT_GT(deviation(walter), 1e-3);
}

// A member whose clamp kinks along NoV·NoL = 0.0678: its error climbs along the kink to the box's
// side NoV = 1 (or NoL = 1), at α = 1. Refining from the grid's interior maxima one variable at a
// time stopped on the ridge (0.4692 claimed, found by bench/design/check_front.py); the box's
// edges, searched as problems of one variable, reach the side. The claim is at least a dense
// evaluation's, which is above the old claim (the control that the dense grid sees the ridge).
TEST(FunctionTargets, TheErrorOfTwoVariablesIsFoundWhereARidgeMeetsTheBoxsSide) {
  const Settings s = small("smith-g2-ggx");
  Lobe member;
  member.formula = "(max(NoL * NoV * -3.5519856194238404 + 0.24098280510857412, 0) * -1.7129616473582567 + "
                   "(0.0879152747122454 / (alpha + 0.171762810449951) + 0.7013427231696733)) ^ 2";
  const expr::Expression f = function_expression(s, member.formula), t = function_expression(s);
  double dense = 0;
  for (int i = 1; i <= 400; ++i)
    for (int j = 1; j <= 400; ++j) {
      const double x[] = {i / 400.0, j / 400.0, 1.0};
      dense = std::max(dense, std::abs(expr::evaluate(f, x) - expr::evaluate(t, x)));
    }
  EXPECT_GT(dense, 0.4692 + 3e-3);
  const DomainError e = domain_error(member, s, [] { return false; });
  EXPECT_GE(e.max_abs, dense - 1e-9);
  EXPECT_NEAR(e.max_abs, 0.47568, 1e-4);
}

// The split-sum terms of GGX as the designer interpolates them, against the cubature itself at
// points off the grid: within 2e-3 (the mirror seen at grazing, μ < 0.002 and r < 0.04, where
// they turn fastest) and 2e-4 elsewhere; and A + B is the albedo of GGX with F = 1 (a second
// model's cubature). The control: A's values in place of B's miss by far more. Lazarov's
// approximation is measured on the front as the other references are, and its form refitted; the
// pair (A, B) as one target of two outputs. (Two tables of 49 × 49
// albedos: about 15 s under the sanitizers.)
TEST(FunctionTargets, TheSplitSumTermsAreTheCubaturesWithinTheirStatedError) {
  const auto direct = [](std::string_view model, ParamValues params, double mu, double r) {
    params["alpha"] = std::max(r * r, 0.001);
    return analysis::albedo(make_model(model, params), std::acos(mu)).value;
  };
  Settings a = small("env-brdf-a-ggx"), b = small("env-brdf-b-ggx");
  const auto table_a = target_function(a), table_b = target_function(b);
  double corner = 0, elsewhere = 0, swapped = 0, sum = 0;
  std::vector<std::pair<double, double>> points{{3e-4, 0.02}, {1.3e-3, 0.033}, {6e-4, 0.011}};  // the corner's
  for (int i = 0; i < 24; ++i) points.emplace_back(std::pow((i % 6 + 0.37) / 6, 2), std::pow((i / 6 + 0.61) / 4, 1.5));
  for (const auto& [mu, r] : points) {  // off the grid's nodes
    const double x[] = {mu, r};
    const double exact_a = direct("ggx-schlick", {{"f0", 1}, {"f90", 0}}, mu, r);
    const double exact_b = direct("ggx-schlick", {{"f0", 0}, {"f90", 1}}, mu, r);
    const double e = std::max(std::abs(table_a(x) - exact_a), std::abs(table_b(x) - exact_b));
    (mu < 0.002 && r < 0.04 ? corner : elsewhere) = std::max(mu < 0.002 && r < 0.04 ? corner : elsewhere, e);
    swapped = std::max(swapped, std::abs(table_a(x) - exact_b));
    if (!(mu < 0.002 && r < 0.04)) sum = std::max(sum, std::abs(table_a(x) + table_b(x) - direct("ggx", {{"f0", 1}}, mu, r)));
  }
  EXPECT_GT(corner, 0);  // the corner was visited
  EXPECT_LT(corner, 2e-3);
  EXPECT_LT(elsewhere, 2e-4);
  EXPECT_LT(sum, 4e-4);
  EXPECT_GT(swapped, 0.1);
  // Karis's EnvBRDFApprox B against the cubature on a grid (0.1631 at μ = 10⁻³, r = 0): the
  // design's measure of it, against the table, is that within the table's 2e-3.
  const auto lazarov_b = [](double mu, double r) {
    const double a004 = std::min((1 - r) * (1 - r), std::exp2(-9.28 * mu)) * (1 - r) + 0.0425 - 0.0275 * r;
    return 1.04 * a004 - 0.04 + 0.022 * r;
  };
  double dense = 0;
  for (double mu : {1e-4, 1e-3, 0.01, 0.1, 0.5, 1.0})
    for (int j = 0; j <= 10; ++j)
      dense = std::max(dense, std::abs(lazarov_b(mu, j / 10.0) - direct("ggx-schlick", {{"f0", 0}, {"f90", 1}}, mu, j / 10.0)));
  EXPECT_NEAR(dense, 0.163, 1e-3);
  b.max_cost = 1;
  const Result r = design(b);
  EXPECT_NEAR(reference(r, "lazarov").max_abs, dense, 2e-3);
  // The pair (A, B), a target of two outputs: one function of an output index that takes only 0
  // and 1. Lazarov's pair measured on it is the larger of its errors on A and on B alone.
  const auto lazarov = [](const Settings& s) {
    for (const TermReference& ref : term_references())
      if (ref.term == s.target && ref.id == "lazarov") {
        Lobe l;
        l.reference = l.evaluable = true;
        l.formula = ref.formula;
        return domain_error(l, s, [] { return false; }).max_abs;
      }
    throw std::runtime_error("no lazarov for " + s.target);
  };
  const Settings pair = small("env-brdf-ggx");
  EXPECT_EQ(pair.variables, (std::vector<std::string>{"NoV", "r", "output"}));
  validate(pair);
  const double error_a = lazarov(a), error_b = lazarov(b);
  EXPECT_NEAR(error_a, 0.5, 0.01);
  EXPECT_NEAR(lazarov(pair), std::max(error_a, error_b), 1e-12);
  const Samples rows = function_rows(pair, 1);  // both outputs, and only 0 and 1
  EXPECT_EQ(std::set<double>(rows.x[2].begin(), rows.x[2].end()), (std::set<double>{0, 1}));
  EXPECT_EQ(rows.value.size(), 2 * 24u * 24u);
}

// "expr: c^2; c^3": a member is one formula in c and output, checked here at output = 0 against c²
// and at output = 1 against c³ on a dense grid: within the error it claims. Its shader computes
// both outputs in one expression (their sum, what they share once). (About 3 s.)
TEST(FunctionTargets, AnExpressionOfTwoOutputsIsFittedTogether) {
  Settings s = small("expr: c^2; c^3");
  EXPECT_EQ(s.variables, (std::vector<std::string>{"c", "output"}));
  EXPECT_EQ(output_count(s.target), 2);
  EXPECT_EQ(function_formula(s.target), "(1 - output)*(c^2) + output*(c^3)");
  s.max_cost = 3;
  const Result r = design(s);
  ASSERT_FALSE(r.front.empty());
  EXPECT_LT(r.front.back().max_abs, 0.1) << r.front.back().formula;
  for (const Lobe& m : r.front) {
    const expr::Expression f = expr::parse(m.formula, {"c", "output"});
    double worst = 0;
    for (int i = 1; i <= 4000; ++i) {
      const double c = i / 4000.0, at0[] = {c, 0}, at1[] = {c, 1};
      worst = std::max({worst, std::abs(expr::evaluate(f, at0) - c * c), std::abs(expr::evaluate(f, at1) - c * c * c)});
    }
    EXPECT_LE(worst, m.max_abs * (1 + 1e-9) + 1e-12) << m.formula;
    const expr::Expression shader = shader_expression(s, m.formula);
    ASSERT_EQ(shader.variables(), (std::vector<std::string>{"c"}));
    const double half[] = {0.5}, at0[] = {0.5, 0}, at1[] = {0.5, 1};
    EXPECT_NEAR(expr::evaluate(shader, half), expr::evaluate(f, at0) + expr::evaluate(f, at1), 1e-12) << m.formula;
  }
}

TEST(FunctionTargets, BadTargetsAreRefusedInOneLine) {
  const auto refused = [](Settings s, const char* field, const char* what) {
    try {
      validate(s);
      ADD_FAILURE() << s.target << " was accepted";
    } catch (const InvalidField& e) {
      EXPECT_EQ(e.field(), field) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  };
  Settings not_finite = small("expr: (1 - c)^5");
  not_finite.target = "expr: 1/(1 - c)";
  refused(not_finite, "target", "not finite");
  Settings negative = not_finite;
  negative.target = "expr: c - 0.5";
  refused(negative, "target", "negative");
  Settings ranged = small("schlick-weight");
  ranged.param = "n";
  ranged.lo = 1;
  ranged.hi = 10;
  refused(ranged, "range", "no parameter 'n'");
  Settings unranged = small("fresnel-dielectric");
  unranged.param = "";
  unranged.lo = unranged.hi = 1;
  refused(unranged, "target", "unknown variable 'eta'");  // a parameter with no range and no value
  Settings twice = small("smith-g2-ggx");
  twice.variables = {"NoV", "NoV"};
  refused(twice, "vars", "named twice");
  Settings unused = small("smith-g2-ggx");
  unused.variables = {"NoV", "NoL", "NoH"};
  refused(unused, "vars", "does not use the variable NoH");
  Settings both = small("smith-g2-ggx");
  both.variables = {"NoV", "alpha"};
  refused(both, "vars", "alpha is a parameter and a per-pixel variable");
  Settings lobe = small("phong");
  lobe.variables = {"c", "d"};
  refused(lobe, "vars", "--vars is for functions");
  Settings empty_output = small("expr: c^2; c^3");
  empty_output.target = "expr: c^2; ";
  refused(empty_output, "target", "empty");
  Settings five = small("expr: c^2; c^3");
  five.target = "expr: c; c^2; c^3; c^4; c^5";
  refused(five, "target", "at most 4 outputs");
  Settings no_output = small("expr: c^2; c^3");
  no_output.variables = {"c"};
  refused(no_output, "vars", "then 'output'");
  Settings pair = small("env-brdf-ggx");
  pair.variables = {"NoV", "output"};
  refused(pair, "vars", "two per-pixel variables (NoV, r), got 1");
  EXPECT_THROW(default_range("expr: c^eta"), InvalidField);  // a parameter without a range of its own
  EXPECT_EQ(default_range("fresnel-dielectric").param, "eta");
  EXPECT_EQ(default_range("phong").param, "n");
}

}  // namespace
}  // namespace specula::design
