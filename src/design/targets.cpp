// The designer's targets beyond lobes (docs/designer.md, "Targets beyond lobes"): the terms of a
// microfacet BRDF that engines approximate by hand, exact as specula computes them, with the
// approximations the engines ship as the front's reference rows.
#include <algorithm>
#include <array>
#include <memory>
#include <cctype>
#include <fmt/format.h>

#include "specula/catalogue/catalogue.h"
#include "specula/design/design.h"
#include "specula/expr/simplify.h"
#include "split_sum.h"

namespace specula::design {
namespace {

constexpr std::string_view kExpr = "expr:";

// Schlick's F0 of a dielectric of index η, and of a conductor of index η + iκ (normal incidence).
#define F0_DIELECTRIC "((eta - 1)/(eta + 1))^2"
#define F0_CONDUCTOR "(((eta - 1)^2 + kappa^2)/((eta + 1)^2 + kappa^2))"
// Karis's exp2((−5.55473c − 6.98316)c) as exp: its coefficients times ln 2 (the same function; one
// exp, as a GPU's exp2 is one instruction).
#define KARIS "exp((-3.850245438271745*c - 4.8403576653989875)*c)"

// Height-correlated Smith masking-shadowing of GGX, G₂ = 4·NoV·NoL·V (Heitz 2014), written as
// Filament's V_SmithGGXCorrelated is (no division by a cosine squared).
#define SMITH_GGX "2*NoV*NoL/(NoL*sqrt(NoV^2*(1 - alpha^2) + alpha^2) + NoV*sqrt(NoL^2*(1 - alpha^2) + alpha^2))"

// Height-correlated Smith masking-shadowing of Beckmann, G₂ = 1/(1 + Λ(NoV) + Λ(NoL)) (Heitz 2014,
// eq. 99), Λ(a) = (erf(a) − 1)/2 + e^(−a²)/(2a√π) with a = cos θ/(α sin θ) (Walter et al. 2007,
// eq. 25): erfc(a) by Abramowitz & Stegun 7.1.26 (|error| ≤ 1.5e-7, so the term's is ≤ 1.5e-7).
#define BECKMANN_A(x) "(" #x "/(alpha*sqrt(1 - " #x "^2)))"
#define BECKMANN_T(x) "(1/(1 + 0.3275911*" BECKMANN_A(x) "))"
#define BECKMANN_LAMBDA(x)                                                                                      \
  "exp(-" BECKMANN_A(x) "^2)*(1/(" BECKMANN_A(x) "*1.7724538509055159) - " BECKMANN_T(x) "*(0.254829592 + "   \
  BECKMANN_T(x) "*(-0.284496736 + " BECKMANN_T(x) "*(1.421413741 + " BECKMANN_T(x) "*(-1.453152027 + "          \
  BECKMANN_T(x) "*1.061405429)))))/2"
#define SMITH_BECKMANN "1/(1 + " BECKMANN_LAMBDA(NoV) " + " BECKMANN_LAMBDA(NoL) ")"
// Walter et al. 2007's rational G₁ of Beckmann (eq. 27) as Λ = 1/G₁ − 1, 0 from a = 1.6 on, as
// pbrt-v3's BeckmannDistribution::Lambda: written in b = 1/a = α·tan θ (finite at normal
// incidence, where a is infinite) as (b² − 1.259b + 0.396)/(3.535b + 2.181), the cut at b = 0.625
// as min(max((b − 0.625)·10³⁰, 0), 1) (a step but within 10⁻³⁰ of it).
#define WALTER_B(x) "(alpha*sqrt(1 - " #x "^2)/" #x ")"
#define WALTER_LAMBDA(x)                                                                                    \
  "(" WALTER_B(x) "^2 - 1.259*" WALTER_B(x) " + 0.396)/(3.535*" WALTER_B(x) " + 2.181)*min(max((" WALTER_B(x) \
  " - 0.625)*1e30, 0), 1)"

constexpr std::array<Term, 11> kTerms{{
    {"fresnel-dielectric", "fresnel_dielectric(c, eta)", "eta", 1.2, 2.5,
     "the exact Fresnel reflectance of unpolarized light at a dielectric interface of index η"},
    {"fresnel-conductor", "fresnel_conductor(c, eta, kappa)", "eta", 0.1, 3,
     "the exact Fresnel reflectance of a conductor of complex index η + iκ (κ a parameter, -p kappa=…, default 1)"},
    {"schlick-weight", "(1 - c)^5", "", 1, 1, "Schlick's weight (1 − c)⁵, the power every Schlick Fresnel computes"},
    {"smith-g2-ggx", SMITH_GGX, "alpha", 0.05, 1,
     "the height-correlated Smith G₂(NoV, NoL; α) of GGX", "NoV,NoL"},
    {"smith-g2-beckmann", SMITH_BECKMANN, "alpha", 0.05, 1,
     "the height-correlated Smith G₂(NoV, NoL; α) of Beckmann (erfc by Abramowitz & Stegun 7.1.26: within 1.5e-7)",
     "NoV,NoL"},
    {"env-brdf-a-ggx", "A(NoV, r) of GGX, tabulated", "", 1, 1,
     "the split-sum scale A(NoV, r) of GGX (height-correlated Smith, α = r²): E = F0·A + B", "NoV,r", Tabulation::split_sum_a,
     "ggx-schlick"},
    {"env-brdf-b-ggx", "B(NoV, r) of GGX, tabulated", "", 1, 1,
     "the split-sum bias B(NoV, r) of GGX (height-correlated Smith, α = r²): E = F0·A + B", "NoV,r", Tabulation::split_sum_b,
     "ggx-schlick"},
    {"env-brdf-a-beckmann", "A(NoV, r) of Beckmann, tabulated", "", 1, 1,
     "the split-sum scale A(NoV, r) of Beckmann (α = r²)", "NoV,r", Tabulation::split_sum_a, "beckmann-schlick"},
    {"env-brdf-b-beckmann", "B(NoV, r) of Beckmann, tabulated", "", 1, 1,
     "the split-sum bias B(NoV, r) of Beckmann (α = r²)", "NoV,r", Tabulation::split_sum_b, "beckmann-schlick"},
    {"env-brdf-ggx", "(A, B)(NoV, r) of GGX, tabulated: A at output = 0, B at output = 1", "", 1, 1,
     "the split-sum pair (A, B)(NoV, r) of GGX fitted together (two outputs)", "NoV,r,output", Tabulation::split_sum_ab,
     "ggx-schlick"},
    {"env-brdf-beckmann", "(A, B)(NoV, r) of Beckmann, tabulated: A at output = 0, B at output = 1", "", 1, 1,
     "the split-sum pair (A, B)(NoV, r) of Beckmann fitted together (two outputs)", "NoV,r,output",
     Tabulation::split_sum_ab, "beckmann-schlick"},
}};

// Karis 2014's EnvBRDFApprox (Unreal Engine 4 on mobile, after Lazarov 2013), its exp2(−9.28·NoV)
// as exp: a004 = min(r₁², 2^(−9.28·NoV))·r₁ + r_y with r₁ = 1 − r, r_y = 0.0425 − 0.0275·r;
// A = −1.04·a004 + 1.04 − 0.572·r, B = 1.04·a004 − 0.04 + 0.022·r.
#define ENV_A004 "(min((1 - r)^2, exp(-6.432405835596292*NoV))*(1 - r) + (0.0425 - 0.0275*r))"

constexpr std::array<TermReference, 14> kReferences{{
    {"fresnel-dielectric", "schlick", "fresnel_schlick(c, " F0_DIELECTRIC ")",
     "Schlick 1994, with F0 from η: Unreal, Filament, three.js, MaterialX"},
    {"fresnel-dielectric", "unreal-exp2", F0_DIELECTRIC " + (1 - " F0_DIELECTRIC ")*" KARIS,
     "Karis 2013 (Unreal Engine 4): (1 − c)⁵ as exp2((−5.55473c − 6.98316)c)"},
    {"fresnel-dielectric", "exact", "fresnel_dielectric(c, eta)", "the term itself, computed directly"},
    {"fresnel-conductor", "schlick", "fresnel_schlick(c, " F0_CONDUCTOR ")", "Schlick 1994, with F0 from η + iκ"},
    {"fresnel-conductor", "exact", "fresnel_conductor(c, eta, kappa)", "the term itself, computed directly"},
    {"schlick-weight", "unreal-exp2", KARIS, "Karis 2013 (Unreal Engine 4): exp2((−5.55473c − 6.98316)c)"},
    {"schlick-weight", "exact", "(1 - c)^5", "the power, computed directly"},
    {"smith-g2-ggx", "fast-smith", "2*NoV*NoL/(NoV*(NoL*(1 - alpha) + alpha) + NoL*(NoV*(1 - alpha) + alpha))",
     "Hammon 2017's approximation (Filament's V_SmithGGXCorrelatedFast, Unreal's Vis_SmithJointApprox), as G₂"},
    {"smith-g2-ggx", "exact", SMITH_GGX, "the term itself, computed directly (Filament's V_SmithGGXCorrelated)"},
    {"smith-g2-beckmann", "walter-rational", "1/(1 + " WALTER_LAMBDA(NoV) " + " WALTER_LAMBDA(NoL) ")",
     "Walter et al. 2007's rational G₁ as Λ (pbrt-v3's BeckmannDistribution::Lambda), height-correlated"},
    {"smith-g2-beckmann", "exact", SMITH_BECKMANN, "the term itself, computed directly (erfc by Abramowitz & Stegun 7.1.26)"},
    {"env-brdf-a-ggx", "lazarov", "-1.04*" ENV_A004 " + (1.04 - 0.572*r)",
     "Karis 2014's EnvBRDFApprox (Unreal Engine 4 mobile), after Lazarov 2013"},
    {"env-brdf-b-ggx", "lazarov", "1.04*" ENV_A004 " + (0.022*r - 0.04)",
     "Karis 2014's EnvBRDFApprox (Unreal Engine 4 mobile), after Lazarov 2013"},
    {"env-brdf-ggx", "lazarov", "(1 - output)*(-1.04*" ENV_A004 " + (1.04 - 0.572*r)) + output*(1.04*" ENV_A004
     " + (0.022*r - 0.04))", "Karis 2014's EnvBRDFApprox (Unreal Engine 4 mobile), after Lazarov 2013: A and B sharing a004"},
}};

#undef F0_DIELECTRIC
#undef F0_CONDUCTOR
#undef KARIS
#undef SMITH_GGX
#undef BECKMANN_A
#undef BECKMANN_T
#undef BECKMANN_LAMBDA
#undef SMITH_BECKMANN
#undef ENV_A004
#undef WALTER_B
#undef WALTER_LAMBDA

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  return text;
}

// The parts of "expr: F0; F1; …" (one for an expression without ';').
std::vector<std::string_view> expression_parts(std::string_view target) {
  std::vector<std::string_view> out;
  const std::string_view text = target.substr(kExpr.size());
  for (std::size_t start = 0; start <= text.size();) {
    const std::size_t end = std::min(text.find(';', start), text.size());
    out.push_back(trimmed(text.substr(start, end - start)));
    start = end + 1;
  }
  return out;
}

}  // namespace

const Term* term_named(std::string_view id) {
  const auto it = std::ranges::find(kTerms, id, &Term::id);
  return it == kTerms.end() ? nullptr : &*it;
}

bool is_tabulated(std::string_view target) {
  const Term* t = term_named(target);
  return t && t->tabulation != Tabulation::none;
}

std::function<double(std::span<const double>)> target_function(const Settings& s) {
  if (const Term* t = term_named(s.target); t && t->tabulation != Tabulation::none) {
    if (t->tabulation == Tabulation::split_sum_ab)
      return [model = t->model](std::span<const double> x) {
        return split_sum(model, x[2] < 0.5 ? SplitSumPart::a : SplitSumPart::b, x[0], x[1]);
      };
    const SplitSumPart part = t->tabulation == Tabulation::split_sum_a ? SplitSumPart::a : SplitSumPart::b;
    return [model = t->model, part](std::span<const double> x) { return split_sum(model, part, x[0], x[1]); };
  }
  auto e = std::make_shared<const expr::Expression>(function_expression(s));
  return [e](std::span<const double> x) { return expr::evaluate(*e, x); };
}

std::vector<double> target_values(const Settings& s, const std::vector<std::vector<double>>& columns) {
  const std::size_t rows = columns.empty() ? 0 : columns.front().size();
  std::vector<double> out(rows);
  if (!is_tabulated(s.target)) {
    std::vector<std::span<const double>> spans(columns.begin(), columns.end());
    expr::evaluate_batch(function_expression(s), spans, out);
    return out;
  }
  const auto target = target_function(s);
  std::vector<double> point(columns.size());
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t v = 0; v < columns.size(); ++v) point[v] = columns[v][r];
    out[r] = target(point);
  }
  return out;
}

std::span<const Term> terms() { return kTerms; }
std::span<const TermReference> term_references() { return kReferences; }

bool is_function_target(std::string_view target) { return target.starts_with(kExpr) || term_named(target); }

int output_count(std::string_view target) {
  if (const Term* t = term_named(target)) return t->tabulation == Tabulation::split_sum_ab ? 2 : 1;
  return target.starts_with(kExpr) ? static_cast<int>(expression_parts(target).size()) : 1;
}

bool is_output_variable(const Settings& s, std::size_t v) {
  return output_count(s.target) > 1 && v + 1 == s.variables.size() && s.variables[v] == kOutputVariable;
}

std::vector<std::string> target_variables(std::string_view target, std::vector<std::string> given) {
  if (given.empty()) given = default_variables(target);
  if (output_count(target) > 1 && given.back() != kOutputVariable) given.emplace_back(kOutputVariable);
  return given;
}

std::vector<std::string> output_targets(std::string_view target) {
  if (output_count(target) == 1) return {std::string(target)};
  if (const Term* t = term_named(target)) {
    const std::string rest(t->id.substr(std::string_view("env-brdf-").size()));
    return {"env-brdf-a-" + rest, "env-brdf-b-" + rest};
  }
  std::vector<std::string> out;
  for (const std::string_view part : expression_parts(target)) out.push_back(fmt::format("{} {}", kExpr, part));
  return out;
}

// Part i times the Lagrange basis of the points 0, 1, … that is 1 at output = i and 0 at the others.
std::string stacked_formula(const std::vector<std::string>& parts) {
  if (parts.size() == 1) return parts[0];
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    std::string basis;
    for (std::size_t j = 0; j < parts.size(); ++j) {
      if (j == i) continue;
      const long denominator = static_cast<long>(i) - static_cast<long>(j);
      basis += fmt::format("{}(output - {})/({})", basis.empty() ? "" : "*", j, denominator);
    }
    if (parts.size() == 2) basis = i == 0 ? "(1 - output)" : "output";
    out += fmt::format("{}{}*({})", i ? " + " : "", basis, parts[i]);
  }
  return out;
}

std::string function_formula(std::string_view target) {
  if (const Term* t = term_named(target)) return std::string(t->formula);
  std::vector<std::string> parts;
  for (const std::string_view part : expression_parts(target)) parts.emplace_back(part);
  return stacked_formula(parts);
}

std::vector<std::string> default_variables(std::string_view target) {
  const Term* t = term_named(target);
  if (!t) return {"c"};
  std::vector<std::string> out;
  for (std::size_t start = 0; start <= t->variables.size();) {
    const std::size_t end = std::min(t->variables.find(',', start), t->variables.size());
    out.emplace_back(t->variables.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

std::string with_values(std::string_view formula, const ParamValues& params) {
  const auto word = [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; };
  std::string out(formula);
  for (const auto& [name, value] : params) {
    const std::string text = fmt::format("({})", value);
    for (std::size_t at = out.find(name); at != std::string::npos; at = out.find(name, at)) {
      const std::size_t end = at + name.size();
      if ((at == 0 || !word(out[at - 1])) && (end == out.size() || !word(out[end]))) {
        out.replace(at, name.size(), text);
        at += text.size();
      } else {
        at = end;
      }
    }
  }
  return out;
}

expr::Expression function_expression(const Settings& s, std::string_view formula) {
  const std::string text = formula.empty() ? function_formula(s.target) : std::string(formula);
  return expr::parse(with_values(text, s.params), formula_variables(s));
}

std::size_t shader_variables(const Settings& s) { return s.variables.size() - (output_count(s.target) > 1 ? 1 : 0); }

expr::Expression shader_expression(const Settings& s, std::string_view formula) {
  const expr::Expression e = function_expression(s, formula);
  const int outputs = output_count(s.target);
  if (outputs == 1) return e;
  const auto output = static_cast<std::uint32_t>(s.variables.size() - 1);
  std::vector<std::string> names = e.variables();
  names.erase(names.begin() + output);
  std::vector<expr::Node> sum;
  for (int i = 0; i < outputs; ++i) {
    std::vector<expr::Node> nodes(e.nodes().begin(), e.nodes().end());
    for (expr::Node& n : nodes)
      if (n.op == expr::Op::variable && n.var == output) n = expr::exact_constant(i, 1, expr::Symbol::one);
      else if (n.op == expr::Op::variable && n.var > output) --n.var;
    const expr::Expression part = expr::simplify(expr::Expression(std::move(nodes), names));
    sum.insert(sum.end(), part.nodes().begin(), part.nodes().end());
    if (i > 0) sum.push_back({expr::Op::add, 0, 0});
  }
  return expr::Expression(std::move(sum), names);
}

DefaultRange default_range(std::string_view target, const std::vector<std::string>& variables) {
  if (const Term* t = term_named(target)) return {std::string(t->param), t->lo, t->hi};
  if (!target.starts_with(kExpr)) return {"n", 1, 1000};
  const auto info = model_definition("lobe: " + function_formula(target));
  std::vector<const ParamInfo*> params;  // a lobe formula's free names: the variables other than c are not parameters
  for (const ParamInfo& p : info->params)
    if (std::ranges::find(variables, p.name) == variables.end()) params.push_back(&p);
  if (params.empty()) return {"", 1, 1};
  if (info->find_param("n")) return {"n", 1, 1000};
  throw InvalidField("range", fmt::format("give the range of {} with --range {}=LO:HI (the target has no default range)",
                                          params.front()->name, params.front()->name));
}

}  // namespace specula::design
