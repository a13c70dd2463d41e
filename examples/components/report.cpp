// specula::report: a lobe plotted as one of the report's SVG charts.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <specula/catalogue/catalogue.h>
#include <specula/report/plot.h>

int main() {
  const specula::Model model = specula::make_model("phong", {{"n", 20}});
  specula::report::Series series;
  series.name = "phong";
  series.colour = specula::report::model_colour("phong");
  for (int degrees = 0; degrees <= 90; degrees += 5) {
    series.x.push_back(degrees);
    series.y.push_back(model.at_cos(std::cos(degrees * std::numbers::pi / 180)));
  }
  specula::report::Chart chart;
  chart.title = "phong, n = 20";
  chart.x.label = "angle from R (degrees)";
  chart.y.label = "k F(c)";
  chart.series.push_back(series);
  const std::string svg = specula::report::to_svg(chart);
  std::printf("report: an SVG chart of %zu bytes\n", svg.size());
  return svg.starts_with("<svg") ? 0 : 1;
}
