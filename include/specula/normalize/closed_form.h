#pragma once
// A lobe's exact normalizing coefficient k, when its family states one in closed form
// (lobes/closed_form.h, named by families/<family>.h).
#include <optional>

#include "specula/lobes/closed_form.h"
#include "specula/lobes/lobes.h"

namespace specula::normalize {

/// The closed form for this lobe and form, if its family states one (families/<family>.h).
std::optional<double> closed_form(const lobes::Lobe& lobe, Form form) noexcept;

}  // namespace specula::normalize
