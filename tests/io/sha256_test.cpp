// SHA-256 against the test vectors of FIPS 180-4's examples (NIST's "SHA256.pdf" and the one
// million 'a' of the Secure Hash Standard validation), and Python's hashlib for the doubles.
#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "specula/io/sha256.h"

namespace specula::io {
namespace {

std::string of(std::string_view text) { return sha256_hex(std::as_bytes(std::span(text.data(), text.size()))); }

TEST(Sha256, MatchesTheStandardsVectors) {
  EXPECT_EQ(of(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(of("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(of("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),  // 56 bytes: padding spills
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(of(std::string(1'000'000, 'a')), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  EXPECT_NE(of("abd"), of("abc"));  // the control
}

TEST(Sha256, DoublesAreHashedAsLittleEndianBinary64) {
  // hashlib.sha256(struct.pack('<2d', 0.5, 1.0)).hexdigest()
  const std::vector<double> values{0.5, 1.0};
  EXPECT_EQ(sha256_of_doubles(values), "79eefa853821e579e1cb3a257a43dedb028c59cfcb82bf0cbbd8c398ad268f12");
}

}  // namespace
}  // namespace specula::io
