#pragma once
// Comparison panels (the paper's Fig. 11, docs/math.md §5): already-rendered linear images side by
// side, each with a one-line label, and optionally a second row of difference heat maps against a
// reference image, on one shared scale shown by a colour bar. Renderer-agnostic: it takes images
// and labels and composes an 8-bit sRGB picture; it does not render.
//
// Layout, in pixels, for N panels of W×H, margin m, label height h and R rows (1, or 2 with heat
// maps), C = colour_bar_width + tick_label_width + h (the colour bar's column):
//
//   width  = m + N·(W + m) + (heat maps ? C + m : 0)
//   height = m + R·(H + h + m)
//   panel (row r, column i):  x = m + i·(W + m),  y = m + r·(H + h + m) + (labels above ? h : 0)
//   its label: the W×h cell right below the panel (right above it with LabelPlacement::above)
//   colour bar: colour_bar_width × H at x = m + N·(W + m), level with the heat maps; its tick
//   marks and numbers in the next tick_label_width columns (on a bar too short for all numbers,
//   those that would overlap the one below are left out), its title (reading upward; on two lines,
//   split at a ", ", if one line does not fit) in the last h columns.
//
// Row 0 holds the images through the Display transform (exactly to_srgb8 of each sample); row 1
// the heat maps. Text is DejaVu Sans set with FreeType at text_size, centred in its cell; a label
// or title too long for its cell is set smaller, down to 60 % of text_size, and if it still does
// not fit it starts at the cell's start and is clipped: nothing is ever drawn into a panel.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "specula/render/image.h"

namespace specula::render {

/// One rendered image and the line that names it (UTF-8), e.g. "log-normalized  n = 50".
struct LabelledImage {
  Image image;  ///< linear radiance, as a renderer returns it
  std::string label;
};

enum class LabelPlacement { below, above };

struct PanelLayout {
  int margin = 16;
  int label_height = 34;
  int text_size = 18;  ///< pixels per em
  LabelPlacement labels = LabelPlacement::below;
  int colour_bar_width = 24;
  int tick_label_width = 84;  ///< tick marks (6 px) and the numbers beside them
  std::filesystem::path font;  ///< a TrueType font; empty: default_font()
  Srgb8 background{255, 255, 255};
  Srgb8 ink{24, 24, 24};  ///< text, tick marks
};

/// DejaVu Sans (Debian's fonts-dejavu-core), found when specula was configured.
std::filesystem::path default_font();

struct Rect {
  int x = 0, y = 0, width = 0, height = 0;
  friend constexpr bool operator==(const Rect&, const Rect&) = default;
};

/// Where everything goes: the formula at the top of this file.
class PanelGeometry {
 public:
  /// Throws InvalidArgument for no panel, a panel size outside [1, kMaxImageSide], a negative
  /// layout length, or a total size beyond kMaxImageSide.
  PanelGeometry(int panel_count, int panel_width, int panel_height, bool heat_maps, const PanelLayout& layout);

  int width() const noexcept { return width_; }
  int height() const noexcept { return height_; }
  /// Row 0: the images; row 1: the heat maps.
  Rect panel(int row, int column) const noexcept;
  Rect label(int row, int column) const noexcept;
  /// The last three: meaningful with heat maps only.
  Rect colour_bar() const noexcept;
  Rect tick_labels() const noexcept;
  Rect colour_bar_title() const noexcept;

 private:
  int count_, panel_width_, panel_height_;
  PanelLayout layout_;
  int width_, height_;
};

/// Relative luminance of linear sRGB (ITU-R BT.709 primaries): Y = 0.2126 R + 0.7152 G + 0.0722 B.
double luminance(const Rgb& linear) noexcept;

/// What a heat map shows: per pixel |Y(a) − Y(b)| of the linear images, row-major.
struct LuminanceDifference {
  int width = 0, height = 0;
  std::vector<double> values;
  double max = 0;   ///< over all pixels
  double mean = 0;  ///< over all pixels, background included
};

/// Throws InvalidArgument unless `a` and `b` have the same size.
LuminanceDifference luminance_difference(const Image& a, const Image& b);

/// Viridis (S. van der Walt and N. Smith, matplotlib's default colour map, 2015) by Matt Zucker's
/// degree-6 polynomial fit ("Colormap polynomial", Shadertoy WlfXRN, 2019, CC0): the sRGB-encoded
/// colour at t, each component within 0.013 of matplotlib's table. t is clamped to [0, 1]; NaN
/// counts as 0. Luminance rises monotonically from dark blue-violet (t = 0) to yellow (t = 1).
Rgb viridis(double t) noexcept;
/// viridis(t) as 8-bit codes (each component × 255, rounded).
Srgb8 viridis_srgb8(double t) noexcept;

/// The colour bar's ticks on [0, scale_max]: the multiples of the smallest step of the form 1, 2
/// or 5 × 10^k that is at least scale_max/5, from 0 up to scale_max: 3 to 6 ticks. Labels show
/// just the decimals the step needs. Throws InvalidArgument unless scale_max is finite and > 0.
std::vector<double> colour_bar_ticks(double scale_max);

/// The heat map row: each panel's luminance_difference against `reference`, coloured by
/// viridis(|ΔY| / scale), clamped at the top of the scale.
struct HeatMaps {
  Image reference;
  /// The top of the shared scale; default: the largest |ΔY| over all panels (1 if all are 0).
  std::optional<double> scale_max;
  std::string title = "|ΔL|, linear luminance";  ///< the colour bar's title
};

struct ComparisonPanel {
  Srgb8Image image;
  std::vector<LuminanceDifference> differences;  ///< one per panel with heat maps, else empty
  double scale_max = 0;                          ///< the heat maps' scale; 0 without
};

/// The panel figure (layout above). Heat-map labels read "max …, mean …" (of |ΔY|). Throws
/// InvalidArgument for no panel, images of different sizes, a scale_max that is not finite and
/// > 0, a layout PanelGeometry refuses, or a font that cannot be opened.
ComparisonPanel compose_comparison(const std::vector<LabelledImage>& panels, const Display& display,
                                   const PanelLayout& layout = {},
                                   const std::optional<HeatMaps>& heat_maps = std::nullopt);

}  // namespace specula::render
