#include "specula/render/image.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "specula/exceptions.h"

namespace specula::render {
namespace {

void check_image_size(int width, int height) {
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
    throw InvalidArgument(fmt::format("image size {}x{} is invalid: width and height must be in [1, {}]",
                                      width, height, kMaxImageSide));
}

}  // namespace

Image::Image(int width, int height) : width_(width), height_(height) {
  check_image_size(width, height);
  samples_.resize(3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
}

Rgb Image::at(int x, int y) const noexcept {
  const float* p = &samples_[3 * (static_cast<std::size_t>(y) * width_ + x)];
  return {p[0], p[1], p[2]};
}

void Image::set(int x, int y, const Rgb& value) noexcept {
  float* p = &samples_[3 * (static_cast<std::size_t>(y) * width_ + x)];
  p[0] = static_cast<float>(value.r);
  p[1] = static_cast<float>(value.g);
  p[2] = static_cast<float>(value.b);
}

double aces_narkowicz(double x) noexcept {
  return std::clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

double srgb_encode(double linear) noexcept {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
}

double srgb_decode(double encoded) noexcept {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

namespace {

// to_srgb8 after the exposure's scale.
std::uint8_t exposed_to_srgb8(double x, ToneMap tone_map) noexcept {
  if (tone_map == ToneMap::aces) x = aces_narkowicz(x);
  if (!(x > 0)) return 0;  // NaN too
  return static_cast<std::uint8_t>(std::lround(255 * srgb_encode(std::min(x, 1.0))));
}

}  // namespace

std::uint8_t to_srgb8(double linear, const Display& display) noexcept {
  return exposed_to_srgb8(linear * std::exp2(display.exposure), display.tone_map);
}

std::vector<std::uint8_t> to_srgb8(const Image& image, const Display& display) {
  const auto samples = image.samples();
  const double scale = std::exp2(display.exposure);
  std::vector<std::uint8_t> bytes(samples.size());
  const std::size_t row = 3 * static_cast<std::size_t>(image.width());
  tbb::parallel_for(std::size_t{0}, static_cast<std::size_t>(image.height()), [&](std::size_t y) {
    for (std::size_t i = y * row; i < (y + 1) * row; ++i) bytes[i] = exposed_to_srgb8(samples[i] * scale, display.tone_map);
  });
  return bytes;
}

Srgb8Image::Srgb8Image(int width, int height, Srgb8 fill) : width_(width), height_(height) {
  check_image_size(width, height);
  bytes_.resize(3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (std::size_t i = 0; i < bytes_.size(); i += 3) {
    bytes_[i] = fill.r;
    bytes_[i + 1] = fill.g;
    bytes_[i + 2] = fill.b;
  }
}

Srgb8 Srgb8Image::at(int x, int y) const noexcept {
  const std::uint8_t* p = &bytes_[3 * (static_cast<std::size_t>(y) * width_ + x)];
  return {p[0], p[1], p[2]};
}

void Srgb8Image::set(int x, int y, Srgb8 colour) noexcept {
  std::uint8_t* p = &bytes_[3 * (static_cast<std::size_t>(y) * width_ + x)];
  p[0] = colour.r;
  p[1] = colour.g;
  p[2] = colour.b;
}

}  // namespace specula::render
