#include "specula/render/bvh.h"

#include <algorithm>
#include <array>
#include <fmt/format.h>
#include <numeric>

#include "specula/exceptions.h"

namespace specula::render {
namespace {

constexpr std::size_t kLeafSize = 4;

double component(const Vec3& v, int axis) noexcept { return axis == 0 ? v.x : (axis == 1 ? v.y : v.z); }

Vec3 min_of(const Vec3& a, const Vec3& b) noexcept {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}

Vec3 max_of(const Vec3& a, const Vec3& b) noexcept {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}

int longest_axis(const Vec3& extent) noexcept {
  if (extent.x >= extent.y && extent.x >= extent.z) return 0;
  return extent.y >= extent.z ? 1 : 2;
}

Vec3 centroid(const Triangle& t) noexcept {
  return (t.vertices[0] + t.vertices[1] + t.vertices[2]) * (1.0 / 3);
}

}  // namespace

std::optional<TriangleHit> intersect(const Ray& ray, const Triangle& triangle, double t_min,
                                     double t_max) noexcept {
  const auto& [p0, p1, p2] = triangle.vertices;
  const Vec3 e1 = p1 - p0, e2 = p2 - p0;
  const Vec3 p = cross(ray.direction, e2);
  const double det = dot(e1, p);
  if (det == 0) return std::nullopt;  // the ray is parallel to the plane
  const double inv_det = 1 / det;
  const Vec3 s = ray.origin - p0;
  const double u = dot(s, p) * inv_det;
  if (!(u >= 0 && u <= 1)) return std::nullopt;
  const Vec3 q = cross(s, e1);
  const double v = dot(ray.direction, q) * inv_det;
  if (!(v >= 0 && u + v <= 1)) return std::nullopt;
  const double t = dot(e2, q) * inv_det;
  if (!(t > t_min && t < t_max)) return std::nullopt;
  return TriangleHit{t, &triangle, u, v};
}

Bvh::Bvh(std::vector<Triangle> triangles) : triangles_(std::move(triangles)) {
  if (triangles_.size() >= std::numeric_limits<std::uint32_t>::max())
    throw InvalidArgument(fmt::format("{} triangles are more than a BVH can hold", triangles_.size()));
  if (triangles_.empty()) return;
  std::vector<Vec3> centroids(triangles_.size());
  std::transform(triangles_.begin(), triangles_.end(), centroids.begin(), centroid);
  std::vector<std::uint32_t> order(triangles_.size());
  std::iota(order.begin(), order.end(), 0u);
  nodes_.reserve(triangles_.size());  // a median split leaves ≥ 2 triangles per leaf
  build(order, 0, order.size(), centroids, 1);
  std::vector<Triangle> ordered(triangles_.size());
  for (std::size_t i = 0; i < order.size(); ++i) ordered[i] = triangles_[order[i]];
  triangles_ = std::move(ordered);
}

std::size_t Bvh::build(std::vector<std::uint32_t>& order, std::size_t begin, std::size_t end,
                       const std::vector<Vec3>& centroids, std::size_t level) {
  const std::size_t index = nodes_.size();
  nodes_.emplace_back();
  Box box, centroid_box;
  for (std::size_t i = begin; i < end; ++i) {
    for (const Vec3& p : triangles_[order[i]].vertices) box = {min_of(box.min, p), max_of(box.max, p)};
    centroid_box = {min_of(centroid_box.min, centroids[order[i]]), max_of(centroid_box.max, centroids[order[i]])};
  }
  nodes_[index].box = box;
  depth_ = std::max(depth_, level);
  if (end - begin <= kLeafSize) {
    nodes_[index].first = static_cast<std::uint32_t>(begin);
    nodes_[index].count = static_cast<std::uint32_t>(end - begin);
    return index;
  }
  const int axis = longest_axis(centroid_box.max - centroid_box.min);
  const std::size_t middle = begin + (end - begin) / 2;
  std::nth_element(order.begin() + begin, order.begin() + middle, order.begin() + end,
                   [&](std::uint32_t a, std::uint32_t b) {
                     return component(centroids[a], axis) < component(centroids[b], axis);
                   });
  build(order, begin, middle, centroids, level + 1);
  nodes_[index].first = static_cast<std::uint32_t>(build(order, middle, end, centroids, level + 1));
  return index;
}

namespace {

// The slab test (Kay & Kajiya 1986): where the ray enters the box within (t_min, t_max), or +∞.
// A NaN slab (origin on a face, direction parallel to it) constrains nothing.
double entry_distance(const Vec3& lo, const Vec3& hi, const Ray& ray, const Vec3& inverse, double t_min,
                      double t_max) noexcept {
  auto clip = [&](double lo_t, double hi_t) {
    if (lo_t > hi_t) std::swap(lo_t, hi_t);
    if (lo_t > t_min) t_min = lo_t;
    if (hi_t < t_max) t_max = hi_t;
  };
  const Vec3& o = ray.origin;
  clip((lo.x - o.x) * inverse.x, (hi.x - o.x) * inverse.x);
  clip((lo.y - o.y) * inverse.y, (hi.y - o.y) * inverse.y);
  clip((lo.z - o.z) * inverse.z, (hi.z - o.z) * inverse.z);
  return t_min <= t_max ? t_min : std::numeric_limits<double>::infinity();
}

}  // namespace

template <class OnHit>
void Bvh::traverse(const Ray& ray, double t_min, double& t_max, OnHit on_hit) const noexcept {
  if (nodes_.empty()) return;
  const Vec3 inverse{1 / ray.direction.x, 1 / ray.direction.y, 1 / ray.direction.z};
  auto entry = [&](std::uint32_t node) {
    return entry_distance(nodes_[node].box.min, nodes_[node].box.max, ray, inverse, t_min, t_max);
  };
  struct Pending {
    std::uint32_t node;
    double t_entry;
  };
  // Each visit pops one node and pushes at most two, so the stack never exceeds depth + 1.
  std::array<Pending, 128> stack;
  std::size_t top = 0;
  stack[top++] = {0, entry(0)};
  while (top > 0) {
    const Pending pending = stack[--top];
    if (!(pending.t_entry < t_max)) continue;
    const Node& node = nodes_[pending.node];
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
        if (const auto hit = intersect(ray, triangles_[i], t_min, t_max)) {
          t_max = hit->t;
          if (on_hit(*hit)) return;
        }
      continue;
    }
    Pending near{pending.node + 1, entry(pending.node + 1)}, far{node.first, entry(node.first)};
    if (far.t_entry < near.t_entry) std::swap(near, far);
    stack[top++] = far;
    stack[top++] = near;
  }
}

std::optional<TriangleHit> Bvh::closest(const Ray& ray, double t_min, double t_max) const noexcept {
  std::optional<TriangleHit> best;
  traverse(ray, t_min, t_max, [&](const TriangleHit& hit) {
    best = hit;
    return false;
  });
  return best;
}

bool Bvh::occluded(const Ray& ray, double t_min, double t_max) const noexcept {
  bool blocked = false;
  traverse(ray, t_min, t_max, [&](const TriangleHit&) { return blocked = true; });
  return blocked;
}

}  // namespace specula::render
