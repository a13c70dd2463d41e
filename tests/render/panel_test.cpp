// Comparison panels (include/specula/render/panel.h): the layout formula, panels exactly as the
// display transform codes them, labels inside their cells, heat maps and their shared scale, the
// viridis approximation and the colour bar; FreeType text (src/render/text.h); the sampling
// check's labelled heat map (render/heatmap.h).
#include "specula/render/panel.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../src/render/text.h"
#include "render_support.h"
#include "specula/exceptions.h"
#include "specula/render/heatmap.h"

namespace specula::render {
namespace {

using ::testing::DoubleNear;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Pointwise;
using specula::testing::TempDir;

constexpr Srgb8 kWhite{255, 255, 255};

// A small layout with round numbers: margin 5, label height 22, bar 8, tick labels 40.
PanelLayout small_layout() {
  PanelLayout layout;
  layout.margin = 5;
  layout.label_height = 22;
  layout.text_size = 12;
  layout.colour_bar_width = 8;
  layout.tick_label_width = 40;
  return layout;
}

// HDR content in [0, 3) per channel, different for each seed.
Image noise_image(int width, int height, unsigned seed) {
  Image image(width, height);
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(0, 3);
  for (float& s : image.samples()) s = static_cast<float>(value(random));
  return image;
}

Image constant_image(int width, int height, const Rgb& colour) {
  Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.set(x, y, colour);
  return image;
}

bool is_dark(Srgb8 c) {
  return c.r < 128 && c.g < 128 && c.b < 128;
}

int dark_pixels(const Srgb8Image& image, const Rect& r) {
  int count = 0;
  for (int y = r.y; y < r.y + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x) count += is_dark(image.at(x, y));
  return count;
}

// Every pixel of `r` in `image` that is not `colour`, as "(x,y)" strings (first few).
std::vector<std::string> pixels_not(const Srgb8Image& image, const Rect& r, Srgb8 colour) {
  std::vector<std::string> wrong;
  for (int y = r.y; y < r.y + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x)
      if (!(image.at(x, y) == colour) && wrong.size() < 5) wrong.push_back(fmt::format("({},{})", x, y));
  return wrong;
}

bool within(const Rect& r, int x, int y) {
  return x >= r.x && x < r.x + r.width && y >= r.y && y < r.y + r.height;
}

// ---- layout ---------------------------------------------------------------------------------

TEST(PanelGeometry, SizeIsTheDocumentedFormula) {
  const PanelLayout layout = small_layout();
  // width = m + N(W + m); height = m + (H + h + m): 5 + 3·45 = 140, 5 + 30 + 22 + 5 = 62.
  const PanelGeometry one_row(3, 40, 30, false, layout);
  EXPECT_EQ(one_row.width(), 140);
  EXPECT_EQ(one_row.height(), 62);
  // + the colour bar column (8 + 40 + 22) and a margin; two rows: 5 + 2·57.
  const PanelGeometry two_rows(3, 40, 30, true, layout);
  EXPECT_EQ(two_rows.width(), 140 + 70 + 5);
  EXPECT_EQ(two_rows.height(), 119);
  EXPECT_EQ(two_rows.panel(0, 2), (Rect{95, 5, 40, 30}));
  EXPECT_EQ(two_rows.label(0, 2), (Rect{95, 35, 40, 22}));
  EXPECT_EQ(two_rows.panel(1, 1), (Rect{50, 62, 40, 30}));
  EXPECT_EQ(two_rows.colour_bar(), (Rect{140, 62, 8, 30}));
  EXPECT_EQ(two_rows.tick_labels(), (Rect{148, 62, 40, 30}));
  EXPECT_EQ(two_rows.colour_bar_title(), (Rect{188, 62, 22, 30}));
}

TEST(PanelGeometry, LabelsAboveShiftThePanelsDown) {
  PanelLayout layout = small_layout();
  layout.labels = LabelPlacement::above;
  const PanelGeometry g(2, 40, 30, true, layout);
  EXPECT_EQ(g.height(), 119);
  EXPECT_EQ(g.label(0, 1), (Rect{50, 5, 40, 22}));
  EXPECT_EQ(g.panel(0, 1), (Rect{50, 27, 40, 30}));
  EXPECT_EQ(g.panel(1, 0), (Rect{5, 84, 40, 30}));
}

TEST(PanelGeometry, RefusesNoPanelBadLengthsAndOversizedFigures) {
  const PanelLayout layout = small_layout();
  EXPECT_THROW(PanelGeometry(0, 40, 30, false, layout), InvalidArgument);
  EXPECT_THROW(PanelGeometry(1, 0, 30, false, layout), InvalidArgument);
  PanelLayout negative = layout;
  negative.margin = -1;
  EXPECT_THROW(PanelGeometry(1, 40, 30, false, negative), InvalidArgument);
  // 16384 = 5 + N·45 at most: N = 364 fits (16385 does not: 5 + 364·45 = 16385).
  EXPECT_NO_THROW(PanelGeometry(363, 40, 30, false, layout));
  try {
    PanelGeometry(364, 40, 30, false, layout);
    ADD_FAILURE() << "no error";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("16385x62"));
  }
}

// ---- composition ----------------------------------------------------------------------------

TEST(Comparison, PanelsAreExactlyTheDisplayCodesAtTheDocumentedOffsets) {
  const PanelLayout layout = small_layout();
  const Display display{-0.5, ToneMap::aces};
  std::vector<LabelledImage> panels;
  for (unsigned i = 0; i < 3; ++i) panels.push_back({noise_image(40, 30, i), fmt::format("model {}  n = {}", i, 10 * i)});
  const ComparisonPanel figure = compose_comparison(panels, display, layout);
  ASSERT_EQ(figure.image.width(), 140);
  ASSERT_EQ(figure.image.height(), 62);
  EXPECT_TRUE(figure.differences.empty());
  EXPECT_EQ(figure.scale_max, 0);
  for (int i = 0; i < 3; ++i)
    for (int y = 0; y < 30; ++y)
      for (int x = 0; x < 40; ++x) {
        const Rgb v = panels[static_cast<std::size_t>(i)].image.at(x, y);
        const Srgb8 expected{to_srgb8(v.r, display), to_srgb8(v.g, display), to_srgb8(v.b, display)};
        ASSERT_EQ(figure.image.at(5 + 45 * i + x, 5 + y), expected) << i << ' ' << x << ' ' << y;
      }
}

TEST(Comparison, LabelsHaveInkInTheirCellsAndNothingElseLeavesTheBackground) {
  const PanelLayout layout = small_layout();
  // The middle label is far wider than its 40-pixel cell: it must be clipped, not spill.
  const std::vector<LabelledImage> panels{{constant_image(40, 30, {0.2, 0.2, 0.2}), "log  n = 5"},
                                          {constant_image(40, 30, {0.2, 0.2, 0.2}), "a label much wider than its cell"},
                                          {constant_image(40, 30, {0.2, 0.2, 0.2}), "Δ"}};
  const ComparisonPanel figure = compose_comparison(panels, {}, layout);
  const PanelGeometry g(3, 40, 30, false, layout);
  for (int i = 0; i < 3; ++i) {
    EXPECT_GT(dark_pixels(figure.image, g.label(0, i)), 5) << i;
    EXPECT_THAT(pixels_not(figure.image, g.panel(0, i), {124, 124, 124}), ::testing::IsEmpty()) << i;  // 0.2 → 124
  }
  for (int y = 0; y < figure.image.height(); ++y)
    for (int x = 0; x < figure.image.width(); ++x) {
      bool in_a_cell = false;
      for (int i = 0; i < 3; ++i) in_a_cell = in_a_cell || within(g.panel(0, i), x, y) || within(g.label(0, i), x, y);
      if (!in_a_cell) {
        ASSERT_EQ(figure.image.at(x, y), kWhite) << x << ',' << y;
      }
    }
}

// Columns of `r` holding ink, as [first, last]; {-1, -1} if none.
std::pair<int, int> ink_columns(const Srgb8Image& image, const Rect& r) {
  std::pair<int, int> columns{-1, -1};
  for (int x = r.x; x < r.x + r.width; ++x)
    if (dark_pixels(image, {x, r.y, 1, r.height}) > 0) {
      if (columns.first < 0) columns.first = x;
      columns.second = x;
    }
  return columns;
}

TEST(Comparison, ALabelTooWideIsSetSmallerAndClippedOnlyBeyondThat) {
  PanelLayout layout = small_layout();
  layout.text_size = 20;
  // "mmmmmm" is about 117 px wide at 20 px: too wide for 100, narrow enough at 16 px (60 % is 12).
  const std::vector<LabelledImage> panels{{constant_image(100, 10, {}), "mmmmmm"},
                                          {constant_image(100, 10, {}), "mmmmmmmmmmmmmmmmmmmm"}};
  const ComparisonPanel figure = compose_comparison(panels, {}, layout);
  const PanelGeometry g(2, 100, 10, false, layout);
  const Rect fits = g.label(0, 0), clipped = g.label(0, 1);
  const auto [first, last] = ink_columns(figure.image, fits);
  EXPECT_GT(first, fits.x + 1);
  EXPECT_LT(last, fits.x + fits.width - 2);
  EXPECT_NEAR((first - fits.x) - (fits.x + fits.width - 1 - last), 0, 2);  // centred
  EXPECT_EQ(ink_columns(figure.image, clipped).second, clipped.x + clipped.width - 1);
}

TEST(Comparison, LabelsAboveAreDrawnAboveThePanels) {
  PanelLayout layout = small_layout();
  layout.labels = LabelPlacement::above;
  const ComparisonPanel figure = compose_comparison({{constant_image(40, 30, {}), "phong  n = 20"}}, {}, layout);
  EXPECT_GT(dark_pixels(figure.image, {5, 5, 40, 22}), 5);
  EXPECT_THAT(pixels_not(figure.image, {5, 27, 40, 30}, {0, 0, 0}), ::testing::IsEmpty());
  EXPECT_THAT(pixels_not(figure.image, {5, 57, 40, 5}, kWhite), ::testing::IsEmpty());
}

TEST(Comparison, AModelComparedWithItselfIsTheColourMapsZeroEverywhere) {
  const PanelLayout layout = small_layout();
  const Image a = noise_image(40, 30, 1), b = noise_image(40, 30, 2);
  const ComparisonPanel figure =
      compose_comparison({{a, "a"}, {b, "b"}}, {}, layout, HeatMaps{a, std::nullopt, "|ΔL|"});
  const PanelGeometry g(2, 40, 30, true, layout);
  ASSERT_EQ(figure.image.width(), g.width());
  EXPECT_EQ(figure.differences[0].max, 0);
  EXPECT_THAT(pixels_not(figure.image, g.panel(1, 0), viridis_srgb8(0)), ::testing::IsEmpty());
  // matplotlib's viridis starts at (0.267004, 0.004874, 0.329415) = codes (68, 1, 84).
  const Srgb8 zero = viridis_srgb8(0);
  EXPECT_NEAR(zero.r, 68, 3);
  EXPECT_NEAR(zero.g, 1, 3);
  EXPECT_NEAR(zero.b, 84, 3);
  EXPECT_GT(figure.differences[1].max, 0);
}

TEST(Comparison, HeatMapsShowTheLuminanceDifferenceOnOneSharedScale) {
  const PanelLayout layout = small_layout();
  Image reference = constant_image(4, 3, {});
  Image red = constant_image(4, 3, {}), grey = constant_image(4, 3, {});
  red.set(1, 1, {1, 0, 0});        // |ΔY| = 0.2126
  grey.set(2, 0, {0.5, 0.5, 0.5});  // |ΔY| = 0.5
  grey.set(3, 2, {0.25, 0.25, 0.25});
  const auto figure = compose_comparison({{red, "red"}, {grey, "grey"}}, {}, layout, HeatMaps{reference, {}, "t"});
  EXPECT_DOUBLE_EQ(figure.scale_max, 0.5);  // the largest over both panels
  EXPECT_DOUBLE_EQ(figure.differences[0].max, 0.2126);
  EXPECT_DOUBLE_EQ(figure.differences[0].mean, 0.2126 / 12);
  const PanelGeometry g(2, 4, 3, true, layout);
  const auto at = [&](int column, int x, int y) {
    const Rect p = g.panel(1, column);
    return figure.image.at(p.x + x, p.y + y);
  };
  EXPECT_EQ(at(0, 1, 1), viridis_srgb8(0.2126 / 0.5));
  EXPECT_EQ(at(0, 0, 0), viridis_srgb8(0));
  EXPECT_EQ(at(1, 2, 0), viridis_srgb8(1));
  EXPECT_EQ(at(1, 3, 2), viridis_srgb8(0.5));

  // A given scale is used as it is; larger differences saturate at its top.
  const auto scaled = compose_comparison({{red, "red"}, {grey, "grey"}}, {}, layout, HeatMaps{reference, 0.25, "t"});
  EXPECT_EQ(scaled.scale_max, 0.25);
  const Rect p = g.panel(1, 1);
  EXPECT_EQ(scaled.image.at(p.x + 2, p.y), viridis_srgb8(1));
  EXPECT_EQ(scaled.image.at(p.x + 3, p.y + 2), viridis_srgb8(1));
  EXPECT_THROW(compose_comparison({{red, "red"}}, {}, layout, HeatMaps{reference, 0.0, "t"}), InvalidArgument);
}

TEST(Comparison, TheColourBarRunsFromZeroAtTheBottomToTheScaleAtTheTopWithTicks) {
  PanelLayout layout = small_layout();
  const int height = 101;  // the bar's rows are 0.01 apart on a scale of 1
  const Image reference = constant_image(30, height, {});
  const auto figure = compose_comparison({{constant_image(30, height, {0.5, 0.5, 0.5}), "x"}}, {}, layout,
                                         HeatMaps{reference, 1.0, "|ΔL|"});
  const PanelGeometry g(1, 30, height, true, layout);
  const Rect bar = g.colour_bar();
  for (int x = bar.x; x < bar.x + bar.width; ++x) {
    EXPECT_EQ(figure.image.at(x, bar.y), viridis_srgb8(1));
    EXPECT_EQ(figure.image.at(x, bar.y + 50), viridis_srgb8(0.5));
    EXPECT_EQ(figure.image.at(x, bar.y + height - 1), viridis_srgb8(0));
  }
  // Ticks 0, 0.2, …, 1 at rows 100, 80, …, 0 of the bar: a 6-pixel mark right of it, and a
  // number beside the mark.
  const Rect ticks = g.tick_labels();
  for (const int row : {0, 20, 40, 60, 80, 100}) {
    for (int x = ticks.x; x < ticks.x + 6; ++x) EXPECT_TRUE(is_dark(figure.image.at(x, bar.y + row))) << row;
    EXPECT_GT(dark_pixels(figure.image, {ticks.x + 8, bar.y + row - 6, ticks.width - 8, 12}), 3) << row;
  }
  for (const int row : {10, 30, 50, 70, 90}) EXPECT_EQ(figure.image.at(ticks.x + 2, bar.y + row), kWhite) << row;
  EXPECT_GT(dark_pixels(figure.image, g.colour_bar_title()), 10);
}

TEST(Comparison, RefusesNoImageMixedSizesAndAMissingFont) {
  const Image a = constant_image(4, 4, {}), b = constant_image(5, 4, {});
  EXPECT_THROW(compose_comparison({}, {}), InvalidArgument);
  EXPECT_THROW(compose_comparison({{a, "a"}, {b, "b"}}, {}), InvalidArgument);
  EXPECT_THROW(compose_comparison({{a, "a"}}, {}, {}, HeatMaps{b, {}, "t"}), InvalidArgument);
  TempDir dir;
  PanelLayout layout;
  layout.font = dir / "missing.ttf";
  try {
    compose_comparison({{a, "a"}}, {}, layout);
    ADD_FAILURE() << "no error";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot open font '" + layout.font.string() + "': no such file"));
  }
  layout.font = dir.write("text.ttf", "not a font");
  EXPECT_THROW(compose_comparison({{a, "a"}}, {}, layout), InvalidArgument);
}

TEST(LuminanceDifference, IsTheAbsoluteDifferenceOfRec709Luminance) {
  EXPECT_DOUBLE_EQ(luminance({1, 1, 1}), 1);
  EXPECT_DOUBLE_EQ(luminance({0, 1, 0}), 0.7152);
  Image a = constant_image(2, 1, {}), b = constant_image(2, 1, {});
  a.set(0, 0, {0, 0, 1});
  b.set(1, 0, {0, 2, 0});
  const LuminanceDifference d = luminance_difference(a, b);
  EXPECT_THAT(d.values, Pointwise(DoubleNear(1e-15), std::vector<double>{0.0722, 1.4304}));
  EXPECT_DOUBLE_EQ(d.max, 1.4304);
  EXPECT_DOUBLE_EQ(d.mean, (0.0722 + 1.4304) / 2);
  EXPECT_THROW(luminance_difference(a, constant_image(1, 2, {})), InvalidArgument);
}

// ---- colour map -----------------------------------------------------------------------------

void expect_near(const Rgb& value, const Rgb& expected, double tolerance) {
  EXPECT_NEAR(value.r, expected.r, tolerance);
  EXPECT_NEAR(value.g, expected.g, tolerance);
  EXPECT_NEAR(value.b, expected.b, tolerance);
}

TEST(Viridis, FollowsMatplotlibsTableAtItsEndsAndMiddle) {
  // matplotlib's _viridis_data entries 0, 128 and 255.
  expect_near(viridis(0), {0.267004, 0.004874, 0.329415}, 0.013);
  expect_near(viridis(128 / 255.0), {0.127568, 0.566949, 0.550556}, 0.013);
  expect_near(viridis(1), {0.993248, 0.906157, 0.143936}, 0.013);
  EXPECT_EQ(viridis(-3), viridis(0));
  EXPECT_EQ(viridis(7), viridis(1));
  EXPECT_EQ(viridis(std::nan("")), viridis(0));
}

TEST(Viridis, LuminanceRisesMonotonically) {
  const auto relative_luminance = [](const Rgb& encoded) {
    return luminance({srgb_decode(encoded.r), srgb_decode(encoded.g), srgb_decode(encoded.b)});
  };
  double previous = -1;
  for (int i = 0; i <= 1000; ++i) {
    const double y = relative_luminance(viridis(i / 1000.0));
    ASSERT_GT(y, previous) << i;
    previous = y;
  }
  EXPECT_LT(relative_luminance(viridis(0)), 0.06);
  EXPECT_GT(relative_luminance(viridis(1)), 0.75);
}

TEST(ColourBarTicks, AreMultiplesOfTheSmallest125StepAtLeastAFifthOfTheScale) {
  EXPECT_THAT(colour_bar_ticks(1), Pointwise(DoubleNear(1e-12), std::vector<double>{0, 0.2, 0.4, 0.6, 0.8, 1}));
  EXPECT_THAT(colour_bar_ticks(0.0347), Pointwise(DoubleNear(1e-12), std::vector<double>{0, 0.01, 0.02, 0.03}));
  EXPECT_THAT(colour_bar_ticks(7), Pointwise(DoubleNear(1e-12), std::vector<double>{0, 2, 4, 6}));
  EXPECT_THAT(colour_bar_ticks(0.5), Pointwise(DoubleNear(1e-12), std::vector<double>{0, 0.1, 0.2, 0.3, 0.4, 0.5}));
  EXPECT_THAT(colour_bar_ticks(3e-4), Pointwise(DoubleNear(1e-15), std::vector<double>{0, 1e-4, 2e-4, 3e-4}));
  EXPECT_THAT(colour_bar_ticks(260), Pointwise(DoubleNear(1e-9), std::vector<double>{0, 100, 200}));
  for (const double bad : {0.0, -1.0, std::nan(""), HUGE_VAL}) EXPECT_THROW(colour_bar_ticks(bad), InvalidArgument);
}

// ---- text -----------------------------------------------------------------------------------

TEST(Text, DecodesUtf8AndReplacesMalformedBytes) {
  EXPECT_THAT(decode_utf8("n = 5"), ElementsAre(U'n', U' ', U'=', U' ', U'5'));
  EXPECT_THAT(decode_utf8("|ΔL|"), ElementsAre(U'|', U'\u0394', U'L', U'|'));
  EXPECT_THAT(decode_utf8("\xF0\x9F\x98\x80"), ElementsAre(U'\U0001F600'));
  EXPECT_THAT(decode_utf8("a\xFF"), ElementsAre(U'a', U'\uFFFD'));
  EXPECT_THAT(decode_utf8("\xCE"), ElementsAre(U'\uFFFD'));              // truncated
  EXPECT_THAT(decode_utf8("\xC0\x80"), ElementsAre(U'\uFFFD', U'\uFFFD'));  // overlong
  EXPECT_THAT(decode_utf8("\xED\xA0\x80").front(), U'\uFFFD');            // a surrogate
}

TEST(Text, SetsALineOfInkAsWideAsItsAdvances) {
  const Font font(default_font(), 20);
  EXPECT_GE(font.line_height(), 20);
  EXPECT_LT(font.ascender(), font.line_height());
  const TextMask short_text = font.render("Hi"), long_text = font.render("Hi there");
  EXPECT_EQ(short_text.height, font.line_height());
  EXPECT_GT(long_text.width, short_text.width + 30);
  EXPECT_EQ(*std::max_element(short_text.coverage.begin(), short_text.coverage.end()), 255);
  // "H" stands on the baseline: its ink ends on the row above it.
  int lowest_ink = -1;
  for (int y = 0; y < short_text.height; ++y)
    for (int x = 0; x < short_text.width; ++x)
      if (short_text.at(x, y) > 128) lowest_ink = y;
  EXPECT_EQ(lowest_ink, short_text.baseline - 1);
  EXPECT_EQ(font.render("").width, 0);
}

// ---- the sampling check's heat map ----------------------------------------------------------

/// Two angles on a 4 × 8 grid, every cell 10 except one 40 in the samples' top right; the second
/// angle's χ² p-value as given (α = 0.005).
sampling::SamplingCheck two_angle_check(double second_p) {
  sampling::SamplingCheck check;
  check.cos_bins = 4;
  for (const double theta : {0.0, 45.0}) {
    sampling::AngleCheck a;
    a.theta_deg = theta;
    a.alpha = 0.005;
    a.p_value = theta == 0 ? 0.5 : second_p;
    a.mean_weight = a.albedo = a.pdf_integral = 1;
    a.standard_error = 0.01;
    a.z = 3;
    a.observed.assign(32, 10);
    a.expected.assign(32, 10);
    a.observed[31] = 40;  // cos θ_o row 3 (the top), φ column 7
    check.angles.push_back(a);
  }
  return check;
}

bool is_ink(Srgb8 p) noexcept { return p.r == p.g && p.g == p.b && p.r < 128; }

TEST(SamplingHeatmap, TitlesLabelsAndMapsWhereTheyBelong) {
  const sampling::SamplingCheck check = two_angle_check(0.3);
  const Srgb8Image image = sampling_heatmap(check);
  const Font font(default_font(), 14);  // 2·scale + 2 at the default scale 6
  EXPECT_GE(image.width(), font.render("θi = 45°: χ² p = 0.3, passes").width);
  // The largest count (40) is viridis(1) over one 6 × 6 cell per angle, in the samples' map (left).
  int brightest = 0, first_map_row = image.height(), ink_above_maps = 0, ink = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const Srgb8 p = image.at(x, y);
      if (p == viridis_srgb8(1)) {
        ++brightest;
        EXPECT_LT(x, image.width() / 2);
      }
      if (p == viridis_srgb8(0.25)) first_map_row = std::min(first_map_row, y);
      ink += is_ink(p);
    }
  for (int y = 0; y < first_map_row; ++y)
    for (int x = 0; x < image.width(); ++x) ink_above_maps += is_ink(image.at(x, y));
  EXPECT_EQ(brightest, 2 * 36);
  EXPECT_GT(ink_above_maps, 100);  // the column titles and the first angle's label
  EXPECT_GT(ink, ink_above_maps + 100);  // and the second angle's label
}

// Negative control: a failing second angle changes its label alone — every pixel that differs
// is text on white in both images, none is a map's.
TEST(SamplingHeatmap, AFailingAngleChangesItsLabelOnly) {
  const Srgb8Image passing = sampling_heatmap(two_angle_check(0.3)), failing = sampling_heatmap(two_angle_check(1e-9));
  ASSERT_EQ(passing.width(), failing.width());
  ASSERT_EQ(passing.height(), failing.height());
  const auto text_or_white = [](Srgb8 p) { return p.r == p.g && p.g == p.b; };
  int differing = 0;
  for (int y = 0; y < passing.height(); ++y)
    for (int x = 0; x < passing.width(); ++x) {
      if (passing.at(x, y) == failing.at(x, y)) continue;
      ++differing;
      EXPECT_TRUE(text_or_white(passing.at(x, y)) && text_or_white(failing.at(x, y))) << x << ", " << y;
    }
  EXPECT_GT(differing, 50);
}

}  // namespace
}  // namespace specula::render
