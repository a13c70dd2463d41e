// The GLSL dialects' names (glsl.h): one list, read by parse_dialect and to_string alike; and a
// version header for every dialect.
#include <gtest/gtest.h>

#include <string>

#include "specula/exceptions.h"
#include "specula/glsl/glsl.h"

namespace specula::glsl {
namespace {

// Every dialect up to kDialectCount round-trips name → dialect → name. The compile-time control is
// the static_assert(names_complete…) beside the switch in src/glsl/glsl.cpp: a dialect added after
// webgl2 fails the build there until kDialectCount moves.
TEST(DialectNames, EveryDialectRoundTrips) {
  for (const Dialect dialect : enumerators<Dialect, kDialectCount>()) {
    EXPECT_EQ(parse_dialect(to_string(dialect)), dialect);
    EXPECT_STREQ(to_string(parse_dialect(to_string(dialect))), to_string(dialect));
    EXPECT_TRUE(version_header(dialect).starts_with("#version ")) << to_string(dialect);
  }
  EXPECT_EQ(version_header(Dialect::glsl330), "#version 330 core\n");
  EXPECT_EQ(version_header(Dialect::webgl2), version_header(Dialect::gles300));
}

TEST(DialectNames, TheMessageListsEveryDialect) {
  try {
    parse_dialect("glsl450");
    FAIL() << "no error";
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "unknown GLSL dialect 'glsl450' (expected glsl330, gles300 or webgl2)");
  }
}

}  // namespace
}  // namespace specula::glsl
