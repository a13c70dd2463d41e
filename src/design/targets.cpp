// The designer's targets beyond lobes (docs/designer.md, "Targets beyond lobes"): the terms of a
// microfacet BRDF that engines approximate by hand, exact as specula computes them, with the
// approximations the engines ship as the front's reference rows.
#include <algorithm>
#include <array>
#include <fmt/format.h>

#include "specula/catalogue/catalogue.h"
#include "specula/design/design.h"

namespace specula::design {
namespace {

constexpr std::string_view kExpr = "expr:";

// Schlick's F0 of a dielectric of index η, and of a conductor of index η + iκ (normal incidence).
#define F0_DIELECTRIC "((eta - 1)/(eta + 1))^2"
#define F0_CONDUCTOR "(((eta - 1)^2 + kappa^2)/((eta + 1)^2 + kappa^2))"
// Karis's exp2((−5.55473c − 6.98316)c) as exp: its coefficients times ln 2 (the same function; one
// exp, as a GPU's exp2 is one instruction).
#define KARIS "exp((-3.850245438271745*c - 4.8403576653989875)*c)"

constexpr std::array<Term, 3> kTerms{{
    {"fresnel-dielectric", "fresnel_dielectric(c, eta)", "eta", 1.2, 2.5,
     "the exact Fresnel reflectance of unpolarized light at a dielectric interface of index η"},
    {"fresnel-conductor", "fresnel_conductor(c, eta, kappa)", "eta", 0.1, 3,
     "the exact Fresnel reflectance of a conductor of complex index η + iκ (κ a parameter, -p kappa=…, default 1)"},
    {"schlick-weight", "(1 - c)^5", "", 1, 1, "Schlick's weight (1 − c)⁵, the power every Schlick Fresnel computes"},
}};

constexpr std::array<TermReference, 7> kReferences{{
    {"fresnel-dielectric", "schlick", "fresnel_schlick(c, " F0_DIELECTRIC ")",
     "Schlick 1994, with F0 from η: Unreal, Filament, three.js, MaterialX"},
    {"fresnel-dielectric", "unreal-exp2", F0_DIELECTRIC " + (1 - " F0_DIELECTRIC ")*" KARIS,
     "Karis 2013 (Unreal Engine 4): (1 − c)⁵ as exp2((−5.55473c − 6.98316)c)"},
    {"fresnel-dielectric", "exact", "fresnel_dielectric(c, eta)", "the term itself, computed directly"},
    {"fresnel-conductor", "schlick", "fresnel_schlick(c, " F0_CONDUCTOR ")", "Schlick 1994, with F0 from η + iκ"},
    {"fresnel-conductor", "exact", "fresnel_conductor(c, eta, kappa)", "the term itself, computed directly"},
    {"schlick-weight", "unreal-exp2", KARIS, "Karis 2013 (Unreal Engine 4): exp2((−5.55473c − 6.98316)c)"},
    {"schlick-weight", "exact", "(1 - c)^5", "the power, computed directly"},
}};

#undef F0_DIELECTRIC
#undef F0_CONDUCTOR
#undef KARIS

const Term* term_named(std::string_view id) {
  const auto it = std::ranges::find(kTerms, id, &Term::id);
  return it == kTerms.end() ? nullptr : &*it;
}

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  return text;
}

}  // namespace

std::span<const Term> terms() { return kTerms; }
std::span<const TermReference> term_references() { return kReferences; }

bool is_function_target(std::string_view target) { return target.starts_with(kExpr) || term_named(target); }

std::string function_formula(std::string_view target) {
  if (const Term* t = term_named(target)) return std::string(t->formula);
  return std::string(trimmed(target.substr(kExpr.size())));
}

DefaultRange default_range(std::string_view target) {
  if (const Term* t = term_named(target)) return {std::string(t->param), t->lo, t->hi};
  if (!target.starts_with(kExpr)) return {"n", 1, 1000};
  const auto info = model_definition("lobe: " + function_formula(target));
  if (info->params.empty()) return {"", 1, 1};
  if (info->find_param("n")) return {"n", 1, 1000};
  throw InvalidField("range", fmt::format("give the range of {} with --range {}=LO:HI (the target has no default range)",
                                          info->params.front().name, info->params.front().name));
}

}  // namespace specula::design
