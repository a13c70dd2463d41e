// Fresnel channels written as text (fresnel_spec.h).
#include "specula/catalogue/fresnel_spec.h"

#include <array>
#include <fmt/format.h>
#include <set>

#include "specula/analysis/fresnel.h"
#include "specula/exceptions.h"
#include "specula/io/values.h"

namespace specula {

namespace {

using fresnel::Kind;

struct KindName {
  Kind kind;
  std::string_view name;
  std::string_view parameters;  // the ones it reads, as the error lists them
};

constexpr std::array<KindName, 5> kKinds{{{Kind::one, "one", ""},
                                          {Kind::schlick, "schlick", "f0, f90, p"},
                                          {Kind::f82_tint, "f82", "f0, tint"},
                                          {Kind::dielectric, "dielectric", "eta"},
                                          {Kind::conductor, "conductor", "eta, kappa"}}};

const KindName& kind_named(std::string_view name) {
  for (const auto& k : kKinds)
    if (k.name == name) return k;
  throw InvalidArgument(fmt::format("Fresnel '{}': unknown kind (one of one, schlick, f82, dielectric, conductor)", name));
}

double* parameter(fresnel::Channel& f, const KindName& kind, std::string_view name) {
  switch (kind.kind) {
    case Kind::one: break;
    case Kind::schlick:
      if (name == "f0") return &f.f0;
      if (name == "f90") return &f.f90;
      if (name == "p") return &f.exponent;
      break;
    case Kind::f82_tint:
      if (name == "f0") return &f.f0;
      if (name == "tint") return &f.tint;
      break;
    case Kind::dielectric:
      if (name == "eta") return &f.eta;
      break;
    case Kind::conductor:
      if (name == "eta") return &f.eta;
      if (name == "kappa") return &f.kappa;
      break;
  }
  return nullptr;
}

}  // namespace

fresnel::Channel parse_fresnel(std::string_view spec) {
  const std::size_t colon = spec.find(':');
  const KindName& kind = kind_named(spec.substr(0, colon));
  fresnel::Channel f{kind.kind};
  if (kind.kind == Kind::schlick || kind.kind == Kind::f82_tint) f.f0 = 0.04;
  if (colon != std::string_view::npos) {
    std::set<std::string_view> seen;
    for (std::string_view item : io::split(spec.substr(colon + 1), ',')) {
      const std::size_t eq = item.find('=');
      const std::string_view name = item.substr(0, eq);
      double* value = parameter(f, kind, name);
      if (eq == std::string_view::npos || !value)
        throw InvalidArgument(fmt::format("Fresnel '{}': '{}' is not a parameter of {} (it takes {})", spec, item,
                                          kind.name, kind.parameters.empty() ? "none" : kind.parameters));
      if (!seen.insert(name).second) throw InvalidArgument(fmt::format("Fresnel '{}': {} is given twice", spec, name));
      *value = io::parse_number(item.substr(eq + 1), fmt::format("Fresnel '{}': {}", spec, name));
    }
  }
  if (const std::string error = analysis::fresnel_domain_error(f); !error.empty())
    throw InvalidArgument(fmt::format("Fresnel '{}': {}", spec, error));
  return f;
}

std::string to_spec(const fresnel::Channel& f) {
  switch (f.kind) {
    case Kind::one: return "one";
    case Kind::schlick: return fmt::format("schlick:f0={},f90={},p={}", f.f0, f.f90, f.exponent);
    case Kind::f82_tint: return fmt::format("f82:f0={},tint={}", f.f0, f.tint);
    case Kind::dielectric: return fmt::format("dielectric:eta={}", f.eta);
    case Kind::conductor: return fmt::format("conductor:eta={},kappa={}", f.eta, f.kappa);
  }
  return "one";
}

}  // namespace specula
