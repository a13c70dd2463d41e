#include "specula/normalize/closed_form.h"

#include "specula/families/families.h"

namespace specula::normalize {

std::optional<double> closed_form(const lobes::Lobe& lobe, Form form) noexcept {
  if (lobe.index() >= families::kLobeFamilyCount) return std::nullopt;  // a user's formula
  const families::Coefficient k = families::kFamilies[lobe.index()]->closed_form.in(form);
  if (!k) return std::nullopt;
  return k(std::visit([](const auto& l) {
    if constexpr (requires { l.n; }) return l.n;
    else return 0.0;  // lobes::Formula: excluded above
  }, lobe));
}

}  // namespace specula::normalize
