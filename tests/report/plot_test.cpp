// The SVG charts: tick choice, labels, log axes, skipped points, legends, well-formed output.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "specula/exceptions.h"
#include "specula/report/plot.h"

namespace specula::report {
namespace {

/// True when every element opened is closed in order (self-closing ones count as both).
/// (A scan rather than std::regex, whose GCC 12 headers warn under the sanitizers.)
bool balanced_tags(const std::string& svg) {
  std::vector<std::string> open;
  for (std::size_t at = svg.find('<'); at != std::string::npos; at = svg.find('<', at + 1)) {
    const std::size_t end = svg.find('>', at);
    if (end == std::string::npos) return false;
    const bool closing = svg[at + 1] == '/', self_closing = svg[end - 1] == '/';
    const std::size_t name_at = at + (closing ? 2 : 1);
    const std::string name = svg.substr(name_at, svg.find_first_of(" />", name_at) - name_at);
    if (self_closing) continue;
    if (closing) {
      if (open.empty() || open.back() != name) return false;
      open.pop_back();
    } else {
      open.push_back(name);
    }
  }
  return open.empty();
}

/// The id of the chart's clip path.
std::string clip_id(const std::string& svg) {
  const std::string key = "clipPath id=\"";
  const std::size_t at = svg.find(key);
  if (at == std::string::npos) return "";
  return svg.substr(at + key.size(), svg.find('"', at + key.size()) - at - key.size());
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

Chart line_chart() {
  Chart c;
  c.title = "Fig. 2 <lobes> & more";
  c.x.label = "angle (degrees)";
  c.y.label = "F";
  c.series.push_back({"phong", model_colour("phong"), {0, 45, 90}, {1, 0.5, 0}});
  c.series.push_back({"log", model_colour("log"), {0, 45, 90}, {1, 0.25, 0}, Stroke::dashed});
  return c;
}

TEST(Ticks, LinearStepsAreOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_EQ(linear_ticks(0, 1, 5), (std::vector<double>{0, 0.2, 0.4, 0.6000000000000001, 0.8, 1}));
  EXPECT_EQ(linear_ticks(0, 90, 6), (std::vector<double>{0, 20, 40, 60, 80, 100}));
  const auto t = linear_ticks(-0.013, 0.042, 5);
  EXPECT_DOUBLE_EQ(t[1] - t[0], 0.02);  // raw step 0.011 rounds up to 2·10⁻²
  EXPECT_LE(t.front(), -0.013);
  EXPECT_GE(t.back(), 0.042);
}

TEST(Ticks, LogTicksAreDecadesWithMinorTicksOnShortRanges) {
  EXPECT_EQ(log_ticks(1, 100), (std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100}));
  EXPECT_EQ(log_ticks(1, 1000), (std::vector<double>{1, 10, 100, 1000}));
  const auto wide = log_ticks(2e-9, 3e-1);
  EXPECT_EQ(wide.size(), 10u);  // 1e-9 … 1, decades only
  EXPECT_DOUBLE_EQ(wide.front(), 1e-9);
  EXPECT_DOUBLE_EQ(wide.back(), 1);
}

TEST(Ticks, TextShowsTheStepsDecimalsAndATrueMinusSign) {
  EXPECT_EQ(tick_text(0.6000000000000001, 0.2), "0.6");
  EXPECT_EQ(tick_text(25, 5), "25");
  EXPECT_EQ(tick_text(-0.25, 0.05), "\u22120.25");
  EXPECT_EQ(tick_text(1e-12, 0.2), "0");
  EXPECT_EQ(tick_text(1e-6, 1e-6), "1e-06");
  EXPECT_EQ(tick_text(2e6, 1e6), "2e+06");
}

TEST(Chart, WellFormedWithTitleAxesLegendAndEscapedText) {
  const std::string svg = to_svg(line_chart());
  EXPECT_TRUE(balanced_tags(svg)) << svg;
  EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  EXPECT_NE(svg.find("Fig. 2 &lt;lobes&gt; &amp; more"), std::string::npos);
  EXPECT_EQ(svg.find("<lobes>"), std::string::npos);
  EXPECT_NE(svg.find(">angle (degrees)</text>"), std::string::npos);
  EXPECT_NE(svg.find("class=\"legend\""), std::string::npos);
  EXPECT_NE(svg.find(">phong</text>"), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray=\"7 4\""), std::string::npos);  // the dashed series and its legend entry
  EXPECT_EQ(count(svg, "<polyline"), 2);
}

TEST(Chart, PointsMapLinearlyOntoThePlotArea) {
  Chart c = line_chart();
  c.x.min = 0;
  c.x.max = 90;
  c.y.min = 0;
  c.y.max = 1;
  const std::string svg = to_svg(c);
  // Plot area: x from 74 to 640 − 18, y from 400 − 54 (value 0) up to 36 (value 1).
  EXPECT_NE(svg.find("points=\" 74.00,36.00 348.00,191.00 622.00,346.00\""), std::string::npos) << svg;
}

TEST(Chart, LogAxisSkipsNonPositiveAndNonFinitePointsAndBreaksTheLine) {
  Chart c;
  c.title = "errors";
  c.y.scale = Scale::log;
  c.series.push_back({"e", "#000", {1, 2, 3, 4, 5}, {1e-3, 0, 1e-2, std::nan(""), 1e-1}});
  const std::string svg = to_svg(c);
  EXPECT_EQ(count(svg, "<polyline"), 0);  // every run between gaps is a single point
  c.series[0].markers = true;
  EXPECT_EQ(count(to_svg(c), "<circle"), 3 + 1);  // three usable points + the legend's marker
  EXPECT_NE(svg.find("0.001"), std::string::npos);
}

TEST(Chart, APointLabelThatWouldRunIntoThePreviousOneGoesBelowItsPoint) {
  Chart c;
  c.title = "labels";
  c.x = {"x", Scale::linear, 0, 90};
  c.y = {"y", Scale::linear, 0, 1};
  c.series.push_back({"s", "#000", {80, 0, 1, 40}, {0.5, 0.5, 0.5, 0.5}, Stroke::solid, true,
                      {"scalar", "exact", "fast", "middle"}});
  const std::string svg = to_svg(c);
  // The points sit at y = 191: labels above at 186, below at 205.
  EXPECT_NE(svg.find("y=\"186.00\" font-size=\"10\" fill=\"#222\">exact<"), std::string::npos) << svg;
  EXPECT_NE(svg.find("y=\"205.00\" font-size=\"10\" fill=\"#222\">fast<"), std::string::npos) << svg;
  EXPECT_NE(svg.find("y=\"186.00\" font-size=\"10\" fill=\"#222\">scalar<"), std::string::npos) << svg;
  EXPECT_NE(svg.find("y=\"186.00\" font-size=\"10\" fill=\"#222\">middle<"), std::string::npos) << svg;
}

TEST(Chart, BadSeriesAreRejected) {
  Chart c = line_chart();
  c.series[0].y.pop_back();
  EXPECT_THROW(to_svg(c), InvalidArgument);
  Chart empty;
  empty.series.push_back({"nan", "#000", {std::nan("")}, {1}});
  EXPECT_THROW(to_svg(empty), InvalidArgument);
}

TEST(Chart, ClipIdsDifferBetweenChartsSoOnePageCanHoldMany) {
  Chart other = line_chart();
  other.title = "another";
  const std::string a = clip_id(to_svg(line_chart())), b = clip_id(to_svg(other));
  EXPECT_FALSE(a.empty());
  EXPECT_NE(a, b);
}

TEST(Polar, LobeDrawnAroundTheNormalWithLegendAndLight) {
  PolarChart p;
  p.title = "lobe";
  p.radius_label = "f cos";
  p.incident_deg = 30;
  p.series.push_back({"up", "#000", {-90, 0, 90}, {0, 2, 0}});
  const std::string svg = to_svg(p);
  EXPECT_TRUE(balanced_tags(svg));
  EXPECT_NE(svg.find(">light</text>"), std::string::npos);
  EXPECT_NE(svg.find(">up</text>"), std::string::npos);
  // The peak (radius 2 = the outer ring) straight above the centre: x = size/2.
  EXPECT_NE(svg.find(" 210.00,"), std::string::npos);
  p.series[0].radius.pop_back();
  EXPECT_THROW(to_svg(p), InvalidArgument);
}

TEST(Colours, OnePerModelStableAndDistinct) {
  EXPECT_EQ(model_colour("log"), model_colour("log"));
  EXPECT_NE(model_colour("log"), model_colour("log-normalized"));
  EXPECT_EQ(model_colour("no-such-model").size(), 7u);
}

}  // namespace
}  // namespace specula::report
