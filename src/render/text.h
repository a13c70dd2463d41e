#pragma once
// Text for figures (internal to specula_render): one line of UTF-8 set in a TrueType font with
// FreeType — grey-scale anti-aliasing, hinting and kerning as FreeType does them — as a coverage
// mask, and its blending into an image.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

#include "specula/render/panel.h"

namespace specula::render {

/// One line of text: coverage 0 (none) to 255 (full) per pixel, row-major; the baseline is
/// `baseline` rows below the top, and the pen starts at column `origin`.
struct TextMask {
  int width = 0;
  int height = 0;
  int baseline = 0;
  int origin = 0;
  std::vector<std::uint8_t> coverage;

  std::uint8_t at(int x, int y) const noexcept { return coverage[static_cast<std::size_t>(y) * width + x]; }
};

/// A font face at one size. Not thread-safe: one per thread.
class Font {
 public:
  /// Throws InvalidArgument ("cannot open font '…': …") when the file is missing or is not a
  /// font FreeType reads, or `pixel_size` is not in [1, 1000].
  Font(const std::filesystem::path& path, int pixel_size);
  ~Font();
  Font(const Font&) = delete;
  Font& operator=(const Font&) = delete;

  /// Pixels from the baseline up to the top of the tallest glyphs (the font's ascender).
  int ascender() const noexcept;
  /// Ascender + descender: the height of every mask.
  int line_height() const noexcept;
  /// `utf8` on one line (malformed bytes show as U+FFFD, characters the font lacks as its
  /// missing-glyph box). The mask is as wide as the ink and the advances reach.
  TextMask render(std::string_view utf8) const;

 private:
  struct Face;
  std::unique_ptr<Face> face_;
};

/// Blends `ink` through the mask's coverage, the mask's top left at (x, y), rotated a quarter turn
/// counter-clockwise (reading upward) if `upward`; nothing outside `clip`.
void draw_mask(Srgb8Image& canvas, const TextMask& mask, int x, int y, bool upward, const Rect& clip, Srgb8 ink);

/// The code points of `utf8`; each malformed or truncated sequence gives U+FFFD.
std::vector<char32_t> decode_utf8(std::string_view utf8);

}  // namespace specula::render
