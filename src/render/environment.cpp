#include "specula/render/environment.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "specula/brdf/directions.h"
#include "specula/exceptions.h"
#include "specula/render/image_io.h"
#include "specula/render/panel.h"

namespace specula::render {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kBelowOne = 1 - 0x1p-53;

/// Running sums of `weights` scaled to end at 1: weights.size() + 1 entries from 0; uniform steps
/// when every weight is 0.
std::vector<double> normalized_cdf(const std::vector<double>& weights) {
  std::vector<double> cdf(weights.size() + 1, 0.0);
  for (std::size_t i = 0; i < weights.size(); ++i) cdf[i + 1] = cdf[i] + weights[i];
  const double total = cdf.back();
  for (std::size_t i = 0; i < cdf.size(); ++i) cdf[i] = total > 0 ? cdf[i] / total : double(i) / weights.size();
  return cdf;
}

struct CdfPick {
  std::size_t cell;
  double offset;  ///< where u fell inside the cell, [0, 1)
};

/// The cell of `cdf` that u ∈ [0, 1) falls in (never one of zero width) and u's place inside it.
CdfPick pick(std::span<const double> cdf, double u) noexcept {
  const auto above = std::upper_bound(cdf.begin(), cdf.end() - 1, u);
  const auto cell = static_cast<std::size_t>(above - cdf.begin()) - 1;
  const double width = cdf[cell + 1] - cdf[cell];
  return {cell, std::clamp((u - cdf[cell]) / width, 0.0, kBelowOne)};
}

Vec3 lat_long_direction(double theta, double phi) noexcept {
  const double s = std::sin(theta);
  return {s * std::sin(phi), std::cos(theta), -s * std::cos(phi)};
}

}  // namespace

Environment Environment::uniform(const Rgb& radiance) {
  Environment e;
  e.constant_ = radiance;
  return e;
}

Environment Environment::lat_long(const Image& map) {
  Environment e;
  e.width_ = map.width();
  e.height_ = map.height();
  e.samples_.assign(map.samples().begin(), map.samples().end());
  const auto width = static_cast<std::size_t>(e.width_);
  std::vector<double> row_weights(e.height_), weights(width);
  e.column_cdf_.reserve((width + 1) * e.height_);
  for (int y = 0; y < e.height_; ++y) {
    const double sin_theta = std::sin(kPi * (y + 0.5) / e.height_);
    for (int x = 0; x < e.width_; ++x) {
      const Rgb c = map.at(x, y);
      if (!(c.r >= 0 && c.g >= 0 && c.b >= 0) || !std::isfinite(c.r + c.g + c.b))
        throw InvalidArgument(fmt::format("environment map pixel ({}, {}) is negative or not finite", x, y));
      weights[x] = luminance(c) * sin_theta;
      row_weights[y] += weights[x];
    }
    const std::vector<double> row = normalized_cdf(weights);
    e.column_cdf_.insert(e.column_cdf_.end(), row.begin(), row.end());
  }
  e.row_cdf_ = normalized_cdf(row_weights);
  for (const double w : row_weights) e.mean_weight_ += w;
  e.mean_weight_ /= double(width) * e.height_;
  return e;
}

Rgb Environment::pixel(std::size_t index) const noexcept {
  return {samples_[3 * index], samples_[3 * index + 1], samples_[3 * index + 2]};
}

std::size_t Environment::pixel_of(const Vec3& d) const noexcept {
  const double theta = std::acos(std::clamp(d.y, -1.0, 1.0));
  const double phi = std::atan2(d.x, -d.z);
  const int x = std::clamp(int((phi + kPi) / (2 * kPi) * width_), 0, width_ - 1);
  const int y = std::clamp(int(theta / kPi * height_), 0, height_ - 1);
  return std::size_t(y) * width_ + x;
}

Rgb Environment::radiance(const Vec3& direction) const noexcept {
  return is_uniform() ? constant_ : pixel(pixel_of(direction));
}

// Over (u, v) = ((φ + π)/2π, θ/π) the density is the pixel's weight over the mean weight;
// dω = 2π² sin θ du dv.
double Environment::pdf(const Vec3& normal, const Vec3& direction) const noexcept {
  if (is_uniform()) return std::max(0.0, dot(normal, direction)) / kPi;
  const double sin_theta = std::hypot(direction.x, direction.z);
  if (!(mean_weight_ > 0) || !(sin_theta > 0)) return 0;
  const std::size_t index = pixel_of(direction);
  const double row_sin = std::sin(kPi * (double(index / width_) + 0.5) / height_);
  return luminance(pixel(index)) * row_sin / mean_weight_ / (2 * kPi * kPi * sin_theta);
}

EnvironmentSample Environment::sample(const Vec3& normal, double u1, double u2) const noexcept {
  if (is_uniform()) {
    const double cos_theta = std::sqrt(1 - u1), sin_theta = std::sqrt(u1);
    const Vec3 d = Frame(normal).to_world(cos_theta, sin_theta, 2 * kPi * u2);
    return {d, constant_, cos_theta / kPi};
  }
  if (!(mean_weight_ > 0)) return {};
  const CdfPick row = pick(row_cdf_, u1);
  const std::size_t stride = std::size_t(width_) + 1;
  const CdfPick column = pick(std::span(column_cdf_).subspan(row.cell * stride, stride), u2);
  const double theta = kPi * (double(row.cell) + row.offset) / height_;
  const double phi = 2 * kPi * (double(column.cell) + column.offset) / width_ - kPi;
  const Vec3 d = lat_long_direction(theta, phi);
  return {d, pixel(row.cell * width_ + column.cell), pdf(normal, d)};
}

Environment read_environment(const std::filesystem::path& path) {
  return Environment::lat_long(read_image(path).image);
}

}  // namespace specula::render
