#pragma once
// The normalizing coefficient of a lobe in a form, by closed form or by quadrature.
// The paper's condition (albedo 1 at normal incidence) is what these compute; the strict
// condition (max over θ_i of the albedo = 1) needs the albedo at every θ_i and lives with it
// in the analysis module, built on normal_incidence_albedo's conventions.
#include "specula/normalize/closed_form.h"
#include "specula/normalize/quadrature.h"

namespace specula::normalize {

enum class Method {
  automatic,  ///< the closed form where one is known, else quadrature
  exact,      ///< the closed form; InvalidArgument where none is known
  quadrature
};

double coefficient(const lobes::Lobe& lobe, Form form, Method method = Method::automatic);

}  // namespace specula::normalize
