#pragma once
// What the render tests share: a scratch directory and small files written into it, and the camera
// ray through a pixel centre worked out by hand.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <set>
#include <numbers>
#include <string>

#include "specula/render/scene.h"

namespace specula::testing {

/// A fresh, empty directory removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            fmt::format("specula-render-test-{}-{}-{}", ::getpid(), counter++,
                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  std::set<std::string> listing() const {
    std::set<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(path_)) names.insert(entry.path().filename().string());
    return names;
  }
  std::filesystem::path write(const std::string& name, const std::string& content) const {
    std::ofstream(path_ / name, std::ios::binary) << content;
    return path_ / name;
  }

 private:
  std::filesystem::path path_;
};

inline specula::Vec3 unit(const specula::Vec3& v) { return v * (1 / std::sqrt(dot(v, v))); }

/// The ray through the centre of pixel (x, y) of a width × height image, row 0 at the top.
inline specula::render::Ray pixel_ray(const specula::render::Camera& c, int x, int y, int width, int height) {
  const specula::Vec3 w = unit(c.look_at - c.position);
  const specula::Vec3 u = unit(cross(w, c.up));
  const specula::Vec3 v = cross(u, w);
  const double half_height = std::tan(c.vertical_fov_deg * std::numbers::pi / 360);
  const double half_width = half_height * width / height;
  const double sx = ((x + 0.5) / width * 2 - 1) * half_width;
  const double sy = (1 - (y + 0.5) / height * 2) * half_height;
  return {c.position, unit(w + u * sx + v * sy)};
}

}  // namespace specula::testing
