// The export formats' names (exports.h): one list, read by parse_format and to_string alike.
#include <gtest/gtest.h>

#include <string>

#include "specula/exceptions.h"
#include "specula/exports/exports.h"

namespace specula::exports {
namespace {

// Every format up to kFormatCount round-trips name → format → name. The compile-time control is
// the static_assert(names_complete…) beside the switch in src/exports/exports.cpp: a format added
// after cpp fails the build there until kFormatCount moves.
TEST(FormatNames, EveryFormatRoundTrips) {
  for (const Format format : enumerators<Format, kFormatCount>()) {
    EXPECT_EQ(parse_format(to_string(format)), format);
    EXPECT_STREQ(to_string(parse_format(to_string(format))), to_string(format));
  }
}

TEST(FormatNames, TheMessageListsEveryFormat) {
  try {
    parse_format("spirv");
    FAIL() << "no error";
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "unknown export format 'spirv' (expected hlsl, msl, brdf or cpp)");
  }
}

}  // namespace
}  // namespace specula::exports
