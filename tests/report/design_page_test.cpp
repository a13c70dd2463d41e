// The designer's page and front chart, from a result made by hand (no search).
#include <gtest/gtest.h>

#include "specula/report/design_page.h"

namespace specula::report {
namespace {

design::Result a_result() {
  design::Result r;
  r.settings.lo = 1;
  r.settings.hi = 100;
  design::Lobe member;
  member.id = "phong-d1";
  member.formula = "max(c * (0.3236 * n + 0.27) + (0.697 - 0.3236 * n), 0) ^ 2";
  member.max_abs = 0.074;
  member.ns_per_eval = 0.1;
  member.model_cost = 3;
  member.k = 3.6;
  member.check = "pass";
  r.front.push_back(member);
  design::Lobe log;
  log.id = "log";
  log.reference = true;
  log.formula = "F = max(0, 1 − ½ log₂(1 − n log₂ c))";
  log.max_abs = 0.125;
  log.ns_per_eval = 1.0;
  r.references.push_back(log);
  return r;
}

TEST(DesignPage, ShowsTheFrontEveryMemberAndItsGlsl) {
  const std::string page = design_page(a_result());
  EXPECT_NE(page.find("<svg"), std::string::npos);
  EXPECT_NE(page.find("id=\"phong-d1\""), std::string::npos);
  EXPECT_NE(page.find("float specula_brdf("), std::string::npos);  // the member's GLSL
  EXPECT_NE(page.find("|F − phong| against c"), std::string::npos);  // its error curves
  EXPECT_EQ(page.find("<script"), std::string::npos);  // self-contained, static
}

TEST(DesignPage, TheChartPlacesMembersAndReferencesOnMeasuredCost) {
  const Chart chart = design_front_chart(a_result());
  ASSERT_EQ(chart.series.size(), 2u);
  EXPECT_EQ(chart.series[0].x, std::vector<double>{0.1});
  EXPECT_EQ(chart.series[1].name, "log");
  EXPECT_EQ(chart.x.scale, Scale::log);
}

TEST(DesignPage, AnUntimedFrontIsPlacedOnTheCostModel) {  // the control: no ns, the model's units
  design::Result r = a_result();
  r.front[0].ns_per_eval = NAN;
  const Chart chart = design_front_chart(r);
  EXPECT_EQ(chart.series[0].x, std::vector<double>{3});
  EXPECT_EQ(chart.series.size(), 1u);  // references are not on the cost model's axis
}

}  // namespace
}  // namespace specula::report

namespace specula::report {
namespace {

int pixels_of(const render::Srgb8Image& image, render::Srgb8 colour) {
  int count = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) count += image.at(x, y) == colour;
  return count;
}

TEST(ChartImage, DrawsTheSeriesInItsColourWithTheAxesText) {
  Chart chart{"a line", {"x", Scale::linear, {}, {}}, {"y", Scale::log, {}, {}}, {}, Legend::none, 320, 200};
  chart.series.push_back({"", "#0072B2", {0, 1, 2}, {1, 10, 100}, Stroke::solid, true, {}});
  const render::Srgb8Image image = to_image(chart);
  EXPECT_EQ(image.width(), 320);
  EXPECT_EQ(image.height(), 200);
  EXPECT_GT(pixels_of(image, {0x00, 0x72, 0xB2}), 100);  // the line and its markers, fully covered
  EXPECT_GT(pixels_of(image, {0x22, 0x22, 0x22}), 20);   // the frame and the labels' ink
  chart.series[0].colour = "#D55E00";                    // the control: another colour, no blue
  EXPECT_EQ(pixels_of(to_image(chart), {0x00, 0x72, 0xB2}), 0);
}

TEST(ChartImage, RefusesWhatItCannotDraw) {
  Chart chart{"bad", {"x", Scale::linear, {}, {}}, {"y", Scale::linear, {}, {}}, {}, Legend::none, 320, 200};
  chart.series.push_back({"", "blue", {0, 1}, {0, 1}, Stroke::solid, false, {}});
  EXPECT_THROW(to_image(chart), InvalidArgument);  // not #rrggbb
  chart.series[0] = {"", "#000000", {NAN}, {NAN}, Stroke::solid, false, {}};
  EXPECT_THROW(to_image(chart), InvalidArgument);  // nothing to draw
}

}  // namespace
}  // namespace specula::report
