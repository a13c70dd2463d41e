// Base64 against RFC 4648 §10's test vectors, and a byte of every value.
#include "specula/io/base64.h"

#include <gtest/gtest.h>

namespace specula::io {
namespace {

TEST(Base64, Rfc4648TestVectors) {
  EXPECT_EQ(base64(""), "");
  EXPECT_EQ(base64("f"), "Zg==");
  EXPECT_EQ(base64("fo"), "Zm8=");
  EXPECT_EQ(base64("foo"), "Zm9v");
  EXPECT_EQ(base64("foob"), "Zm9vYg==");
  EXPECT_EQ(base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
}

TEST(Base64, HighBytesAreUnsigned) {
  EXPECT_EQ(base64(std::string("\xff\xfe\x00", 3)), "//4A");
  EXPECT_NE(base64(std::string("\xff\xfe\x01", 3)), "//4A");
}

}  // namespace
}  // namespace specula::io
