#include "specula/normalize/normalize.h"

#include <string>

#include "specula/exceptions.h"
#include "specula/families/families.h"
#include "specula/interrupt/interrupt.h"

namespace specula::normalize {

double coefficient(const lobes::Lobe& lobe, Form form, Method method) {
  check_interrupt();
  if (method == Method::quadrature) return quadrature(lobe, form);
  if (const auto exact = closed_form(lobe, form)) return *exact;
  if (method == Method::exact)
    throw InvalidArgument(std::string("no closed-form normalization is known for the ") +
                          std::string(families::family_name(lobe)) + " lobe in " + to_string(form) +
                          " form");
  return quadrature(lobe, form);
}

}  // namespace specula::normalize
