#include "specula/render/canvas.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "specula/exceptions.h"
#include "specula/render/panel.h"
#include "text.h"

namespace specula::render {

namespace {

std::uint8_t mix(std::uint8_t under, std::uint8_t ink, double a) {
  return static_cast<std::uint8_t>(std::lround(under + (ink - under) * a));
}

// Distance from p to the segment a–b.
double distance_to_segment(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay, length2 = dx * dx + dy * dy;
  const double t = length2 > 0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / length2, 0.0, 1.0) : 0.0;
  return std::hypot(px - (ax + t * dx), py - (ay + t * dy));
}

}  // namespace

Srgb8 parse_hex_colour(std::string_view text) {
  unsigned value = 0;
  if (text.size() != 7 || text[0] != '#' || std::sscanf(std::string(text.substr(1)).c_str(), "%6x", &value) != 1)
    throw InvalidArgument(fmt::format("'{}' is not a colour #rrggbb", text));
  return {static_cast<std::uint8_t>(value >> 16), static_cast<std::uint8_t>(value >> 8 & 0xff),
          static_cast<std::uint8_t>(value & 0xff)};
}

Canvas::Canvas(int width, int height, Srgb8 background, std::filesystem::path font)
    : image_(width, height, background), font_path_(font.empty() ? default_font() : std::move(font)) {}

Canvas::~Canvas() = default;

const Font& Canvas::font(int pixel_size) {
  auto& f = fonts_[pixel_size];
  if (!f) f = std::make_unique<Font>(font_path_, pixel_size);
  return *f;
}

void Canvas::cover(int x, int y, double coverage, Srgb8 ink) {
  if (x < 0 || y < 0 || x >= image_.width() || y >= image_.height() || coverage <= 0) return;
  const Srgb8 under = image_.at(x, y);
  const double a = std::min(coverage, 1.0);
  image_.set(x, y, {mix(under.r, ink.r, a), mix(under.g, ink.g, a), mix(under.b, ink.b, a)});
}

void Canvas::line(double x0, double y0, double x1, double y1, Srgb8 ink, double width) {
  const double reach = width / 2 + 1;
  const int left = static_cast<int>(std::floor(std::min(x0, x1) - reach)), right = static_cast<int>(std::ceil(std::max(x0, x1) + reach));
  const int top = static_cast<int>(std::floor(std::min(y0, y1) - reach)), bottom = static_cast<int>(std::ceil(std::max(y0, y1) + reach));
  for (int y = std::max(top, 0); y <= std::min(bottom, image_.height() - 1); ++y)
    for (int x = std::max(left, 0); x <= std::min(right, image_.width() - 1); ++x)
      cover(x, y, width / 2 + 0.5 - distance_to_segment(x + 0.5, y + 0.5, x0, y0, x1, y1), ink);
}

void Canvas::dot(double x, double y, double radius, Srgb8 ink) { line(x, y, x, y, ink, 2 * radius); }

int Canvas::text_width(std::string_view utf8, int pixel_size) { return font(pixel_size).render(utf8).width; }

void Canvas::text(std::string_view utf8, double x, double y, int pixel_size, Anchor anchor, Srgb8 ink, bool upward) {
  const TextMask mask = font(pixel_size).render(utf8);
  const double shift = anchor == Anchor::start ? 0 : anchor == Anchor::middle ? mask.width / 2.0 : mask.width;
  const Rect all{0, 0, image_.width(), image_.height()};
  if (upward) {  // the baseline runs up through (x, y): the mask's top left at (x − baseline, y − width + shift)
    draw_mask(image_, mask, static_cast<int>(std::lround(x - mask.baseline)),
              static_cast<int>(std::lround(y - mask.width + shift)), true, all, ink);
  } else {
    draw_mask(image_, mask, static_cast<int>(std::lround(x - shift - mask.origin)),
              static_cast<int>(std::lround(y - mask.baseline)), false, all, ink);
  }
}

}  // namespace specula::render
