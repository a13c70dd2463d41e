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
