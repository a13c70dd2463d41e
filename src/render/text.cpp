#include "text.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <fmt/format.h>

#include "specula/exceptions.h"

namespace specula::render {
namespace {

constexpr char32_t kReplacement = 0xFFFD;

// Bytes in the sequence that `lead` starts, 0 for a byte that cannot start one.
int sequence_length(unsigned char lead) noexcept {
  if (lead < 0x80) return 1;
  if ((lead >> 5) == 0x6) return 2;
  if ((lead >> 4) == 0xE) return 3;
  if ((lead >> 3) == 0x1E) return 4;
  return 0;
}

// The code point of the `length`-byte sequence at `bytes`, or kReplacement if it is malformed,
// overlong, a surrogate or beyond U+10FFFF.
char32_t decode_sequence(std::string_view bytes, int length) noexcept {
  static constexpr unsigned char kLeadMask[] = {0, 0x7F, 0x1F, 0x0F, 0x07};
  static constexpr char32_t kSmallest[] = {0, 0, 0x80, 0x800, 0x10000};
  char32_t code = static_cast<unsigned char>(bytes[0]) & kLeadMask[length];
  for (int k = 1; k < length; ++k) {
    const auto c = static_cast<unsigned char>(bytes[k]);
    if ((c & 0xC0) != 0x80) return kReplacement;
    code = (code << 6) | (c & 0x3F);
  }
  const bool surrogate = code >= 0xD800 && code <= 0xDFFF;
  return code < kSmallest[length] || code > 0x10FFFF || surrogate ? kReplacement : code;
}

// FreeType's 26.6 fixed point to whole pixels, rounded.
int pixels_of(FT_Pos value) noexcept {
  return static_cast<int>((value + 32) >> 6);
}

// A rendered glyph's coverage, placed relative to the pen's start on the baseline.
struct PlacedGlyph {
  int left = 0, top = 0;  // column of its first pixel; rows above the baseline of its first row
  int width = 0, rows = 0;
  std::vector<std::uint8_t> coverage;
};

PlacedGlyph copy_bitmap(const FT_GlyphSlot slot, int pen) {
  const FT_Bitmap& bitmap = slot->bitmap;
  PlacedGlyph glyph{pen + slot->bitmap_left, slot->bitmap_top, static_cast<int>(bitmap.width),
                    static_cast<int>(bitmap.rows), {}};
  glyph.coverage.resize(static_cast<std::size_t>(glyph.width) * glyph.rows);
  for (int y = 0; y < glyph.rows; ++y) {
    const unsigned char* row = bitmap.buffer + static_cast<std::ptrdiff_t>(y) * bitmap.pitch;
    std::copy(row, row + glyph.width, glyph.coverage.begin() + static_cast<std::ptrdiff_t>(y) * glyph.width);
  }
  return glyph;
}

// The glyphs on one line box: from the leftmost ink or the pen's start to the rightmost ink or
// the pen's end, `line_height` rows with the baseline `ascender` rows down. Ink beyond the line
// box vertically is clipped.
TextMask mask_of(const std::vector<PlacedGlyph>& glyphs, int pen_end, int ascender, int line_height) {
  int left = 0, right = pen_end;
  for (const auto& g : glyphs) {
    left = std::min(left, g.left);
    right = std::max(right, g.left + g.width);
  }
  TextMask mask{right - left, line_height, ascender, -left, {}};
  mask.coverage.resize(static_cast<std::size_t>(mask.width) * mask.height);
  for (const auto& g : glyphs)
    for (int y = 0; y < g.rows; ++y) {
      const int row = mask.baseline - g.top + y;
      if (row < 0 || row >= mask.height) continue;
      for (int x = 0; x < g.width; ++x) {
        std::uint8_t& cell = mask.coverage[static_cast<std::size_t>(row) * mask.width + mask.origin + g.left + x];
        cell = std::max(cell, g.coverage[static_cast<std::size_t>(y) * g.width + x]);
      }
    }
  return mask;
}

}  // namespace

std::vector<char32_t> decode_utf8(std::string_view utf8) {
  std::vector<char32_t> codes;
  for (std::size_t i = 0; i < utf8.size();) {
    const int length = sequence_length(static_cast<unsigned char>(utf8[i]));
    if (length == 0 || i + length > utf8.size()) {
      codes.push_back(kReplacement);
      ++i;
      continue;
    }
    const char32_t code = decode_sequence(utf8.substr(i, length), length);
    codes.push_back(code);
    i += code == kReplacement ? 1 : length;
  }
  return codes;
}

struct Font::Face {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
  ~Face() {
    if (face) FT_Done_Face(face);
    if (library) FT_Done_FreeType(library);
  }
};

Font::Font(const std::filesystem::path& path, int pixel_size) : face_(std::make_unique<Face>()) {
  const auto fail = [&](std::string_view why) {
    throw InvalidArgument(fmt::format("cannot open font '{}': {}", path.string(), why));
  };
  if (pixel_size < 1 || pixel_size > 1000) fail(fmt::format("text size {} px is outside [1, 1000]", pixel_size));
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail("no such file");
  if (FT_Init_FreeType(&face_->library) != 0) fail("FreeType failed to start");
  if (const FT_Error error = FT_New_Face(face_->library, path.c_str(), 0, &face_->face); error != 0)
    fail(fmt::format("not a font FreeType can read (FreeType error 0x{:02X})", error));
  if (FT_Set_Pixel_Sizes(face_->face, 0, static_cast<FT_UInt>(pixel_size)) != 0)
    fail(fmt::format("it has no {} px size", pixel_size));
}

Font::~Font() = default;

int Font::ascender() const noexcept {
  return pixels_of(face_->face->size->metrics.ascender);
}

int Font::line_height() const noexcept {
  return ascender() - pixels_of(face_->face->size->metrics.descender);
}

TextMask Font::render(std::string_view utf8) const {
  FT_Face face = face_->face;
  std::vector<PlacedGlyph> glyphs;
  int pen = 0;
  FT_UInt previous = 0;
  for (const char32_t code : decode_utf8(utf8)) {
    const FT_UInt index = FT_Get_Char_Index(face, code);
    FT_Vector kerning{0, 0};
    if (previous != 0 && FT_HAS_KERNING(face)) FT_Get_Kerning(face, previous, index, FT_KERNING_DEFAULT, &kerning);
    pen += pixels_of(kerning.x);
    if (FT_Load_Glyph(face, index, FT_LOAD_RENDER) != 0) continue;  // drawn as nothing
    glyphs.push_back(copy_bitmap(face->glyph, pen));
    pen += pixels_of(face->glyph->advance.x);
    previous = index;
  }
  return mask_of(glyphs, pen, ascender(), line_height());
}

namespace {

std::uint8_t blend(std::uint8_t background, std::uint8_t ink, std::uint8_t coverage) noexcept {
  return static_cast<std::uint8_t>((background * (255 - coverage) + ink * coverage + 127) / 255);
}

bool inside(const Rect& r, int x, int y) noexcept {
  return x >= r.x && x < r.x + r.width && y >= r.y && y < r.y + r.height;
}

}  // namespace

void draw_mask(Srgb8Image& canvas, const TextMask& mask, int x, int y, bool upward, const Rect& clip, Srgb8 ink) {
  for (int my = 0; my < mask.height; ++my)
    for (int mx = 0; mx < mask.width; ++mx) {
      const std::uint8_t a = mask.at(mx, my);
      const int cx = upward ? x + my : x + mx, cy = upward ? y + mask.width - 1 - mx : y + my;
      if (a == 0 || !inside(clip, cx, cy)) continue;
      const Srgb8 under = canvas.at(cx, cy);
      canvas.set(cx, cy, {blend(under.r, ink.r, a), blend(under.g, ink.g, a), blend(under.b, ink.b, a)});
    }
}

}  // namespace specula::render
