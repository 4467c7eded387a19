#pragma once
// Convex hulls for the convex decomposition (internal): triangulated hulls through Qhull, and the
// containment-preserving vertex reduction (see decomposition.h).

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

namespace deepcheck::decomposition::detail {

/// Bit pattern of a position (-0 turned into +0): identifies a point exactly, to weld vertices
/// and to tell points apart across hull recomputations.
struct PositionKey {
  std::uint64_t bits[3];
  bool operator==(const PositionKey& o) const {
    return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
  }
};
struct PositionKeyHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t h = 0x84222325cbf29ce4ULL;
    for (std::uint64_t b : k.bits) h = (h ^ b) * 0x100000001b3ULL ^ (h >> 31);
    return static_cast<std::size_t>(h);
  }
};
inline PositionKey positionKey(const Eigen::Vector3d& p) {
  PositionKey key{};
  for (int k = 0; k < 3; ++k) {
    const double c = p[k] + 0.0;
    std::memcpy(&key.bits[k], &c, sizeof c);
  }
  return key;
}

/// A triangulated convex hull.
struct Hull {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside
  /// Plane of the hull facet each triangle belongs to: unit outward normal and offset (n.x = d).
  /// Triangles of one (merged, coplanar) facet share it exactly.
  std::vector<Eigen::Vector3d> normals;
  std::vector<double> offsets;
  double volume = 0.0;
  double area = 0.0;  ///< surface area (one side only for a flat hull)
};

/// The hull of `points` (any count, duplicates allowed). A flat input gives a polygon fanned into
/// triangles with one normal and volume 0; fewer than three non-collinear points give the extreme
/// points and no triangle.
Hull convexHull(const std::vector<Eigen::Vector3d>& points);

/// A convex polytope with at most `maxVertices` (>= 4) vertices that contains `hull`
/// (decomposition.h describes the method). Returns `hull` itself when it is small enough or not
/// solid. `excess` (if given) receives the largest distance from a vertex of the result to `hull`,
/// which bounds the distance from any point of the result to `hull`.
Hull reduceHullVertices(const Hull& hull, int maxVertices, double* excess = nullptr);

}  // namespace deepcheck::decomposition::detail
