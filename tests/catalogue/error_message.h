#pragma once
// The models tests' shared helper: the message of the InvalidArgument f() throws.
#include <functional>
#include <string>

#include "specula/exceptions.h"

namespace specula::testing {

/// The InvalidArgument's message, or "no error" when f() returns.
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace specula::testing
