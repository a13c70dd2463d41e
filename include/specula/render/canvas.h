#pragma once
// A raster canvas for figures: anti-aliased lines and dots and text set in a TrueType font
// (FreeType, render/text), on 8-bit sRGB pixels — what the PNG charts are drawn on. Blending is
// in sRGB values, as SVG renderers blend.
#include <filesystem>
#include <map>
#include <memory>
#include <string_view>

#include "specula/render/image.h"

namespace specula::render {

class Font;

/// "#rrggbb" as a colour; InvalidArgument otherwise.
Srgb8 parse_hex_colour(std::string_view text);

class Canvas {
 public:
  enum class Anchor { start, middle, end };

  /// `font` empty: default_font() (render/panel.h).
  Canvas(int width, int height, Srgb8 background = {255, 255, 255}, std::filesystem::path font = {});
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  /// A segment `width` pixels wide with round ends, coverage by distance (1 px of smoothing).
  void line(double x0, double y0, double x1, double y1, Srgb8 ink, double width = 1);
  /// A disc.
  void dot(double x, double y, double radius, Srgb8 ink);
  /// One line of text at `pixel_size`, its baseline at y, placed at x by `anchor`; `upward` turns
  /// it a quarter turn counter-clockwise, (x, y) then being the middle of its left edge's baseline.
  void text(std::string_view utf8, double x, double y, int pixel_size, Anchor anchor, Srgb8 ink, bool upward = false);
  /// The width in pixels `utf8` takes at `pixel_size`.
  int text_width(std::string_view utf8, int pixel_size);

  const Srgb8Image& image() const noexcept { return image_; }

 private:
  const Font& font(int pixel_size);
  void cover(int x, int y, double coverage, Srgb8 ink);

  Srgb8Image image_;
  std::filesystem::path font_path_;
  std::map<int, std::unique_ptr<Font>> fonts_;
};

}  // namespace specula::render
