#pragma once
// Ray casting against triangles: a bounding volume hierarchy built by median split on the
// longest axis of the centroids' box, traversed iteratively, nearer child first.
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "specula/render/scene.h"

namespace specula::render {

struct TriangleHit {
  double t;                   ///< distance along the ray (its direction is unit)
  const Triangle* triangle;   ///< inside the Bvh that found it
  double u, v;                ///< barycentric weights of vertices 1 and 2
};

/// Möller-Trumbore ray/triangle intersection (Möller & Trumbore 1997, "Fast, Minimum Storage
/// Ray/Triangle Intersection"): the hit with t_min < t < t_max, if any; both faces count.
std::optional<TriangleHit> intersect(const Ray& ray, const Triangle& triangle, double t_min,
                                     double t_max) noexcept;

class Bvh {
 public:
  explicit Bvh(std::vector<Triangle> triangles);

  /// The nearest hit with t_min < t < t_max.
  std::optional<TriangleHit> closest(const Ray& ray, double t_min = 0,
                                     double t_max = std::numeric_limits<double>::infinity()) const noexcept;
  /// Whether any triangle is hit with t_min < t < t_max (shadow rays: stops at the first).
  bool occluded(const Ray& ray, double t_min, double t_max) const noexcept;

  std::size_t size() const noexcept { return triangles_.size(); }
  std::size_t node_count() const noexcept { return nodes_.size(); }
  /// The longest root-to-leaf path in nodes.
  std::size_t depth() const noexcept { return depth_; }

  struct Box {
    Vec3 min{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
             std::numeric_limits<double>::infinity()};
    Vec3 max = -min;
  };
  /// A leaf holds triangles()[first, first + count); an inner node (count == 0) has its left
  /// child right after it and its right child at `first`. Node 0 is the root.
  struct Node {
    Box box;
    std::uint32_t first = 0;
    std::uint32_t count = 0;
  };

  /// The flattened tree and the triangles in leaf order, for a traversal elsewhere (the GL
  /// renderer copies both into textures).
  std::span<const Node> nodes() const noexcept { return nodes_; }
  std::span<const Triangle> triangles() const noexcept { return triangles_; }

 private:
  /// Builds the node of order[begin, end) and its subtree; returns its index.
  std::size_t build(std::vector<std::uint32_t>& order, std::size_t begin, std::size_t end,
                    const std::vector<Vec3>& centroids, std::size_t level);
  template <class OnHit>
  void traverse(const Ray& ray, double t_min, double& t_max, OnHit on_hit) const noexcept;

  std::vector<Triangle> triangles_;
  std::vector<Node> nodes_;
  std::size_t depth_ = 0;
};

}  // namespace specula::render
