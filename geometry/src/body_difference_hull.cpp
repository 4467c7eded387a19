// The Minkowski difference of two pieces as the hull of all their vertex differences
// (body_depth_internal.h): Qhull's facets, each offset refitted as the exact support value (the
// largest normal.x over the differences), so every point of M is inside every plane. The cheaper
// construction for pieces beyond about ten vertices (buildDifference chooses).

#include "body_depth_internal.h"

#include "deepcheck/geometry/qhull_hull.h"

#include <algorithm>
#include <limits>

namespace deepcheck::geometry::body {

bool buildDifferenceFromHull(const PosedPiece& A, const PosedPiece& B, Difference& out) {
  std::vector<Eigen::Vector3d> points;
  points.reserve(A.vertices.size() * B.vertices.size());
  for (const Eigen::Vector3d& b : B.vertices) {
    for (const Eigen::Vector3d& a : A.vertices) points.push_back(b - a);
  }
  QhullHull hull;
  try {
    QhullOptions options;
    options.searchAllPoints = false;
    hull = qhullHull(points, options, "Minkowski difference");
  } catch (const QhullError&) {
    return false;  // flat or degenerate: no interior, the pair never overlaps
  }
  for (std::size_t f = 0; f < hull.loops.size(); ++f) {
    const Eigen::Vector3d n = hull.normals[f].normalized();
    double h = -std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : points) h = std::max(h, n.dot(p));
    std::vector<Eigen::Vector3d> loop;  // Qhull's loops run counter-clockwise about the normal
    loop.reserve(hull.loops[f].size());
    for (const int i : hull.loops[f]) {
      const Eigen::Vector3d& p = points[static_cast<std::size_t>(i)];
      loop.push_back(p - (n.dot(p) - h) * n);
    }
    addFace(out, n, h, std::move(loop));
  }
  return true;
}

}  // namespace deepcheck::geometry::body
