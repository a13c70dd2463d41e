#pragma once
// Publication-quality SVG charts for the report: line and scatter charts with linear or log axes,
// labelled ticks, legends and one colour per model across every figure; polar plots of lobes in
// the plane of incidence. The output is plain SVG 1.1 text, inlined in index.html and written
// beside it, so the report needs no plotting tool and no network.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "specula/render/image.h"

namespace specula::report {

enum class Scale { linear, log };

struct Axis {
  std::string label;  ///< with its unit, e.g. "angle θ (degrees)"
  Scale scale = Scale::linear;
  std::optional<double> min, max;  ///< the data's range (padded to ticks) when absent
};

enum class Stroke { solid, dashed, dotted, none };

struct Series {
  std::string name;    ///< legend text; empty: not in the legend
  std::string colour;  ///< any SVG colour, e.g. model_colour(id)
  std::vector<double> x, y;
  Stroke stroke = Stroke::solid;
  bool markers = false;
  std::vector<std::string> point_labels = {};  ///< drawn beside each point when non-empty
};

enum class Legend { top_right, top_left, bottom_right, bottom_left, none };

struct Chart {
  std::string title;
  Axis x, y;
  std::vector<Series> series;
  Legend legend = Legend::top_right;
  int width = 640;
  int height = 400;
};

/// Whether the chart has a point to draw: finite, and > 0 on a log axis (what to_svg needs).
bool has_points(const Chart& chart);

/// The chart as a standalone SVG document. Points that are not finite, or ≤ 0 on a log axis, are
/// skipped and break the line. Throws InvalidArgument for a series whose x and y differ in size or
/// a chart with no finite point.
std::string to_svg(const Chart& chart);

/// The chart as pixels, laid out as to_svg lays it out (solid strokes; text in DejaVu Sans):
/// what a PNG of the chart shows. Throws what to_svg throws, and InvalidArgument for a series
/// colour that is not #rrggbb.
render::Srgb8Image to_image(const Chart& chart);
/// A lobe's value over the angle from the normal in the plane of incidence, drawn in polar form
/// (0° up along the normal, ±90° the horizon): the view BRDF Explorer shows.
struct PolarSeries {
  std::string name;
  std::string colour;
  std::vector<double> angle_deg;  ///< from the normal, positive toward the mirror direction
  std::vector<double> radius;     ///< ≥ 0
  Stroke stroke = Stroke::solid;
};

struct PolarChart {
  std::string title;
  std::string radius_label;  ///< e.g. "f · cos θ_o (1/sr)"
  std::vector<PolarSeries> series;
  double incident_deg = 0;  ///< drawn as an arrow toward the light, when ≥ 0
  int size = 420;
};

std::string to_svg(const PolarChart& chart);

/// Tick positions: 1-2-5 steps covering [lo, hi] with about `target` ticks (linear), or the
/// decades covering it (log; with 2…9 × 10^k as minor ticks when fewer than 3 decades).
std::vector<double> linear_ticks(double lo, double hi, int target = 6);
std::vector<double> log_ticks(double lo, double hi);
/// A tick label for `value` on a grid of `step`: fixed notation with the step's decimals
/// ("0.25", "1000", "−2"), scientific beyond [1e-3, 1e5) ("1e-06").
std::string tick_text(double value, double step);

/// One colour per model id, the same in every figure (Okabe & Ito's colour-blind-safe palette,
/// then Tableau's); unknown ids get a deterministic colour from the id.
std::string model_colour(std::string_view model_id);

/// Text with &, <, > and quotes escaped for XML.
std::string xml_escape(std::string_view text);

}  // namespace specula::report
