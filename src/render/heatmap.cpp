#include "specula/render/heatmap.h"

#include <algorithm>
#include <fmt/format.h>

#include "specula/render/panel.h"
#include "text.h"

namespace specula::render {
namespace {

/// "θi = 45°: χ² p = 0.431, passes" ("θi = 0°: f < 0, FAILS" for a negative model, "f not finite" for inf or NaN), the verdict as
/// `specula check --sampling` prints it.
std::string angle_label(const sampling::AngleCheck& angle) {
  if (angle.non_finite_samples) return fmt::format("θi = {:g}°: f not finite, FAILS", angle.theta_deg);
  if (angle.negative_samples) return fmt::format("θi = {:g}°: f < 0, FAILS", angle.theta_deg);
  return fmt::format("θi = {:g}°: χ² p = {:.3g}, {}", angle.theta_deg, angle.p_value,
                     angle.passes() ? "passes" : "FAILS");
}

}  // namespace

Srgb8Image sampling_heatmap(const sampling::SamplingCheck& check, int scale) {
  const int rows = check.cos_bins, cols = 2 * check.cos_bins, gap = 2 * scale;
  const int map_w = cols * scale, map_h = rows * scale;
  const PanelLayout colours;  // the comparison panels' ink and background
  const Font font(default_font(), std::max(11, 2 * scale + 2));
  const TextMask titles[] = {font.render("samples"), font.render("expected (pdf)")};
  std::vector<TextMask> labels;
  int widest_label = 0;
  for (const sampling::AngleCheck& angle : check.angles) {
    labels.push_back(font.render(angle_label(angle)));
    widest_label = std::max(widest_label, labels.back().width);
  }
  // Each map in a column at least as wide as the titles, the image at least as wide as the labels.
  const int column = std::max({map_w, titles[0].width, titles[1].width});
  const int line = font.line_height(), row_h = line + scale / 2 + map_h + gap;
  const int width = std::max(2 * column + 3 * gap, widest_label + 2 * gap);
  const int count = std::max<int>(1, int(check.angles.size()));
  Srgb8Image image(width, gap + line + gap / 2 + count * row_h, colours.background);
  const Rect all{0, 0, image.width(), image.height()};
  for (int m = 0; m < 2; ++m)
    draw_mask(image, titles[m], gap + m * (column + gap) + (column - titles[m].width) / 2, gap, false, all, colours.ink);
  for (int a = 0; a < int(check.angles.size()); ++a) {
    const sampling::AngleCheck& angle = check.angles[std::size_t(a)];
    const double top = std::max({1.0, *std::max_element(angle.observed.begin(), angle.observed.end()),
                                 *std::max_element(angle.expected.begin(), angle.expected.end())});
    const int label_y = gap + line + gap / 2 + a * row_h, y0 = label_y + line + scale / 2;
    draw_mask(image, labels[std::size_t(a)], gap, label_y, false, all, colours.ink);
    for (int m = 0; m < 2; ++m) {
      const std::vector<double>& counts = m == 0 ? angle.observed : angle.expected;
      const int x0 = gap + m * (column + gap) + (column - map_w) / 2;
      for (int y = 0; y < map_h; ++y)
        for (int x = 0; x < map_w; ++x) {
          const int row = rows - 1 - y / scale, col = x / scale;  // cos θ_o = 1 at the top
          image.set(x0 + x, y0 + y, viridis_srgb8(counts[std::size_t(row * cols + col)] / top));
        }
    }
  }
  return image;
}

}  // namespace specula::render
