// specula::render images (include/specula/render/image.h): storage, the sRGB curve, exposure and
// the ACES tone map, 8-bit encoding.
#include "specula/render/image.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "specula/exceptions.h"

namespace specula::render {
namespace {

using ::testing::HasSubstr;

TEST(Image, StoresSamplesAsFloatRowMajorFromTheTop) {
  Image image(3, 2);
  EXPECT_EQ(image.samples().size(), 18u);
  image.set(2, 1, {0.1, 0.2, 0.3});
  EXPECT_EQ(image.at(2, 1), (Rgb{0.1f, 0.2f, 0.3f}));
  EXPECT_EQ(image.samples()[15], 0.1f);  // 3·(1·3 + 2)
  EXPECT_EQ(image.at(0, 0), (Rgb{}));
}

TEST(Image, RejectsSizesOutsideOneToTheMaximum) {
  for (const auto& [w, h] : {std::pair{0, 10}, {10, 0}, {-1, 5}, {kMaxImageSide + 1, 1}}) {
    try {
      Image image(w, h);
      ADD_FAILURE() << w << "x" << h << " accepted";
    } catch (const InvalidArgument& e) {
      EXPECT_THAT(e.what(), HasSubstr(fmt::format("image size {}x{} is invalid", w, h)));
    }
  }
  EXPECT_NO_THROW(Image(1, 1));
}

TEST(Srgb8Image, IsFilledAndStoresBytesRowMajorFromTheTop) {
  Srgb8Image image(3, 2, {1, 2, 3});
  EXPECT_EQ(image.bytes().size(), 18u);
  EXPECT_EQ(image.at(1, 1), (Srgb8{1, 2, 3}));
  image.set(2, 1, {40, 50, 60});
  EXPECT_EQ(image.at(2, 1), (Srgb8{40, 50, 60}));
  EXPECT_EQ(image.bytes()[15], 40);  // 3·(1·3 + 2)
  EXPECT_EQ(image.bytes()[14], 3);
  EXPECT_THROW(Srgb8Image(0, 1), InvalidArgument);
  EXPECT_THROW(Srgb8Image(1, kMaxImageSide + 1), InvalidArgument);
}

TEST(Srgb, MatchesTheStandardCurveAtKnownPoints) {
  EXPECT_EQ(srgb_encode(0), 0);
  EXPECT_NEAR(srgb_encode(1), 1, 1e-15);
  EXPECT_NEAR(srgb_encode(0.0031308), 0.04045, 1e-6);  // the two pieces meet
  EXPECT_NEAR(srgb_encode(0.18), 0.4613561295, 1e-9);  // mid grey
  EXPECT_NEAR(srgb_decode(0.5), 0.2140411405, 1e-9);
}

RC_GTEST_PROP(SrgbProperty, DecodeInvertsEncodeAndBothAreMonotone, ()) {
  const double a = *rc::gen::map(rc::gen::inRange(0, 1'000'001), [](int i) { return i / 1e6; });
  const double b = *rc::gen::map(rc::gen::inRange(0, 1'000'001), [](int i) { return i / 1e6; });
  RC_ASSERT(std::abs(srgb_decode(srgb_encode(a)) - a) <= 1e-12);
  if (a < b) RC_ASSERT(srgb_encode(a) < srgb_encode(b));
}

TEST(Aces, IsNarkowiczsFitClampedToOne) {
  EXPECT_EQ(aces_narkowicz(0), 0);
  EXPECT_NEAR(aces_narkowicz(1), 2.54 / 3.16, 1e-15);  // pre-exposed: 1 maps to ≈ 0.8
  // Rising until it meets 1 where 0.08x² − 0.56x − 0.14 = 0, x = 7.2418…, then clamped.
  double previous = 0;
  for (double x = 0.01; x < 7.24; x *= 1.1) {
    EXPECT_GT(aces_narkowicz(x), previous) << x;
    previous = aces_narkowicz(x);
  }
  EXPECT_LT(aces_narkowicz(7.24), 1);
  EXPECT_EQ(aces_narkowicz(7.25), 1);
  EXPECT_EQ(aces_narkowicz(1e6), 1);
}

TEST(ToSrgb8, RoundsTheEncodedValueAndClamps) {
  EXPECT_EQ(to_srgb8(0, {}), 0);
  EXPECT_EQ(to_srgb8(1, {}), 255);
  EXPECT_EQ(to_srgb8(7.5, {}), 255);
  EXPECT_EQ(to_srgb8(-2, {}), 0);
  EXPECT_EQ(to_srgb8(std::numeric_limits<double>::quiet_NaN(), {}), 0);
  EXPECT_EQ(to_srgb8(0.5, {}), 188);  // 255 · 0.735357 = 187.52
}

TEST(ToSrgb8, AppliesExposureInStopsThenTheToneMap) {
  EXPECT_EQ(to_srgb8(0.125, {2, ToneMap::none}), to_srgb8(0.5, {}));
  EXPECT_EQ(to_srgb8(1, {0, ToneMap::aces}), std::lround(255 * srgb_encode(2.54 / 3.16)));
  EXPECT_EQ(to_srgb8(4, {-2, ToneMap::aces}), to_srgb8(1, {0, ToneMap::aces}));
  EXPECT_EQ(to_srgb8(50, {0, ToneMap::aces}), 255);
}

TEST(ToSrgb8, EncodesAWholeImageInOrder) {
  Image image(2, 2);
  image.set(1, 0, {1, 0.5, 0});
  image.set(0, 1, {0.25, 0, 2});
  const Display display{1, ToneMap::none};
  const auto bytes = to_srgb8(image, display);
  ASSERT_EQ(bytes.size(), 12u);
  EXPECT_EQ(bytes[3], 255);
  EXPECT_EQ(bytes[4], 255);
  EXPECT_EQ(bytes[6], to_srgb8(0.25, display));
  EXPECT_EQ(bytes[8], 255);
}

// Reading "none" or "aces" is the CLI's (tests/cli/scene_options_test.cpp).
TEST(ToneMapName, NamesNoneAndAces) {
  EXPECT_STREQ(to_string(ToneMap::aces), "aces");
  EXPECT_STREQ(to_string(ToneMap::none), "none");
}

}  // namespace
}  // namespace specula::render
