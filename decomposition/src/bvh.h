#pragma once
// Point-to-triangle-soup distance for the convex decomposition (internal): a bounding-volume
// hierarchy of axis-aligned boxes over a part's triangles, queried with an optional half-space
// that clips the triangles on the fly (so one hierarchy serves every candidate cut of a part).

#include "deepcheck/geometry/closest_point.h"

#include <Eigen/Core>

#include <array>
#include <limits>
#include <vector>

namespace deepcheck::decomposition::detail {

/// The closed half-space {x : normal.x <= offset}.
struct Halfspace {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  double offset = 0.0;
  double signedDistance(const Eigen::Vector3d& p) const { return normal.dot(p) - offset; }
  Halfspace flipped() const { return {-normal, -offset}; }
};

using Triangle = std::array<Eigen::Vector3d, 3>;

using geometry::closestPointOnTriangle;

/// Parameter t > 0 where the ray origin + t dir meets the triangle (a, b, c), or -1 when it misses
/// (Moller-Trumbore; rays grazing the triangle's plane miss).
double rayTriangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, const Eigen::Vector3d& a,
                   const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Clips a convex polygon to a half-space (Sutherland-Hodgman). Points with signed distance <= 0
/// are kept; crossing points are interpolated. The result may have fewer than 3 points.
void clipPolygon(const std::vector<Eigen::Vector3d>& in, const Halfspace& keep, std::vector<Eigen::Vector3d>* out);

class TriangleBvh {
 public:
  TriangleBvh() = default;
  explicit TriangleBvh(std::vector<Triangle> triangles);

  bool empty() const { return triangles_.empty(); }
  int size() const { return static_cast<int>(triangles_.size()); }

  /// Distance from `p` to the union of the triangles, each clipped to `keep` (unclipped when
  /// `keep` is null). The search stops as soon as a distance <= `stopBelow` is found and returns
  /// it (then only "the distance is <= stopBelow" is known); otherwise the result is exact.
  /// Infinity when no triangle is left after clipping. `closest` receives the point found.
  double distance(const Eigen::Vector3d& p, const Halfspace* keep, double stopBelow,
                  Eigen::Vector3d* closest = nullptr) const;

 private:
  struct Node {
    Eigen::Vector3d lo;
    Eigen::Vector3d hi;
    int first = 0;  // leaf: first triangle; inner node: index of the left child (right = left + 1)
    int count = 0;  // leaf: number of triangles; inner node: 0
  };
  void buildNode(int node, int first, int count, const std::vector<Eigen::Vector3d>& centers, std::vector<int>& order);

  std::vector<Triangle> triangles_;
  std::vector<Node> nodes_;
};

}  // namespace deepcheck::decomposition::detail
