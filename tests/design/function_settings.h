#pragma once
// Settings for a function target as the CLI makes them with no options: the target's variables
// (its output index appended), its own range. Shared by the designer's tests.
#include <string>

#include "specula/design/design.h"

namespace specula::design {

inline Settings function_settings(const std::string& target) {
  Settings s;
  s.target = target;
  s.variables = target_variables(target, {});
  const DefaultRange r = default_range(target, s.variables);
  s.param = r.param;
  s.lo = r.lo;
  s.hi = r.hi;
  return s;
}

}  // namespace specula::design
