#pragma once
// The name a test parameterized by SIMD target gets: the target's name with every character
// that GoogleTest does not allow in a name replaced by '_' (tests/simd).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <string>

#include "specula/simd/targets.h"

namespace specula::simd {

inline std::string target_label(const ::testing::TestParamInfo<std::int64_t>& info) {
  std::string name = target_name(info.param);
  std::replace_if(name.begin(), name.end(), [](char ch) { return !std::isalnum(static_cast<unsigned char>(ch)); }, '_');
  return name;
}

}  // namespace specula::simd
