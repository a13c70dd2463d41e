#include "specula/render/heatmap.h"

#include <algorithm>

#include "specula/render/panel.h"

namespace specula::render {

Srgb8Image sampling_heatmap(const sampling::SamplingCheck& check, int scale) {
  const int rows = check.cos_bins, cols = 2 * check.cos_bins, gap = 2 * scale;
  const int map_w = cols * scale, map_h = rows * scale;
  const int count = std::max<int>(1, int(check.angles.size()));
  Srgb8Image image(2 * map_w + 3 * gap, count * (map_h + gap) + gap, Srgb8{255, 255, 255});
  for (int a = 0; a < int(check.angles.size()); ++a) {
    const sampling::AngleCheck& angle = check.angles[std::size_t(a)];
    const double top = std::max({1.0, *std::max_element(angle.observed.begin(), angle.observed.end()),
                                 *std::max_element(angle.expected.begin(), angle.expected.end())});
    const int y0 = gap + a * (map_h + gap);
    for (int m = 0; m < 2; ++m) {
      const std::vector<double>& counts = m == 0 ? angle.observed : angle.expected;
      const int x0 = gap + m * (map_w + gap);
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
