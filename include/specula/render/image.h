#pragma once
// A linear HDR RGB image, and the display transform that turns it into 8-bit sRGB: exposure,
// tone mapping, then the sRGB transfer curve.
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "specula/exceptions.h"

namespace specula::render {

/// Linear RGB: a radiance, an irradiance or a reflectance per channel.
struct Rgb {
  double r = 0, g = 0, b = 0;

  constexpr Rgb operator+(const Rgb& o) const noexcept { return {r + o.r, g + o.g, b + o.b}; }
  constexpr Rgb operator*(const Rgb& o) const noexcept { return {r * o.r, g * o.g, b * o.b}; }
  constexpr Rgb operator*(double s) const noexcept { return {r * s, g * s, b * s}; }
  friend constexpr bool operator==(const Rgb&, const Rgb&) = default;
};

/// The largest width or height an image may have.
inline constexpr int kMaxImageSide = 16384;

/// Row-major RGB samples stored as float, row 0 at the top.
class Image {
 public:
  /// Throws InvalidArgument unless 1 ≤ width, height ≤ kMaxImageSide.
  Image(int width, int height);

  int width() const noexcept { return width_; }
  int height() const noexcept { return height_; }
  Rgb at(int x, int y) const noexcept;
  void set(int x, int y, const Rgb& value) noexcept;
  /// r, g, b of pixel (x, y) at 3·(y·width + x).
  std::span<float> samples() noexcept { return samples_; }
  std::span<const float> samples() const noexcept { return samples_; }

 private:
  int width_;
  int height_;
  std::vector<float> samples_;
};

enum class ToneMap { none, aces };
inline constexpr std::size_t kToneMapCount = static_cast<std::size_t>(ToneMap::aces) + 1;  // aces: the last

/// "none" or "aces" ("" outside the enum).
constexpr const char* to_string(ToneMap tone_map) noexcept {
  switch (tone_map) {
    case ToneMap::none: return "none";
    case ToneMap::aces: return "aces";
  }
  return "";
}
static_assert(names_complete<ToneMap, kToneMapCount>([](ToneMap t) { return to_string(t); }));

/// How linear radiance becomes a display value: scaled by 2^exposure, then tone-mapped.
struct Display {
  double exposure = 0;  ///< stops
  ToneMap tone_map = ToneMap::none;
};

/// Narkowicz's fit of the ACES RRT + ODT curve: x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14),
/// clamped to [0, 1]; pre-exposed, so 1 maps to ≈ 0.8 (K. Narkowicz, "ACES Filmic Tone Mapping
/// Curve", blog post, 6 Jan 2016).
double aces_narkowicz(double x) noexcept;

/// The sRGB transfer curve, linear [0, 1] → encoded [0, 1] (IEC 61966-2-1): 12.92 L for
/// L ≤ 0.0031308, else 1.055 L^(1/2.4) − 0.055.
double srgb_encode(double linear) noexcept;
/// Its inverse: V/12.92 for V ≤ 0.04045, else ((V + 0.055)/1.055)^2.4.
double srgb_decode(double encoded) noexcept;

/// One linear channel as an 8-bit sRGB code: exposed, tone-mapped, clamped to [0, 1], encoded
/// and rounded to nearest. NaN gives 0.
std::uint8_t to_srgb8(double linear, const Display& display) noexcept;

/// Every sample of `image` through to_srgb8: r, g, b bytes, row-major, row 0 at the top.
std::vector<std::uint8_t> to_srgb8(const Image& image, const Display& display);

/// An 8-bit sRGB colour: what a display shows, no longer radiance.
struct Srgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
  friend constexpr bool operator==(const Srgb8&, const Srgb8&) = default;
};

/// Row-major 8-bit sRGB pixels, row 0 at the top: a picture composed for display (e.g. a
/// comparison panel), written as PNG as it is.
class Srgb8Image {
 public:
  /// Every pixel `fill`. Throws InvalidArgument unless 1 ≤ width, height ≤ kMaxImageSide.
  Srgb8Image(int width, int height, Srgb8 fill = {});

  int width() const noexcept { return width_; }
  int height() const noexcept { return height_; }
  Srgb8 at(int x, int y) const noexcept;
  void set(int x, int y, Srgb8 colour) noexcept;
  /// r, g, b of pixel (x, y) at 3·(y·width + x).
  std::span<std::uint8_t> bytes() noexcept { return bytes_; }
  std::span<const std::uint8_t> bytes() const noexcept { return bytes_; }

 private:
  int width_;
  int height_;
  std::vector<std::uint8_t> bytes_;
};

}  // namespace specula::render
