// Minkowski differences of piece pairs as explicit polytopes, for the body depth (body_depth.h).

#include "body_depth_internal.h"

#include "deepcheck/deep/qhull_hull.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepcheck::deep::body {

bool buildDifference(const PosedPiece& A, const PosedPiece& B, Difference& out) {
  std::vector<Eigen::Vector3d> pointsA;
  std::vector<Eigen::Vector3d> points;
  pointsA.reserve(static_cast<std::size_t>(A.core->numVertices()));
  for (const Eigen::Vector3d& v : A.core->vertices()) pointsA.push_back(A.X_PP * v);
  points.reserve(pointsA.size() * static_cast<std::size_t>(B.core->numVertices()));
  for (const Eigen::Vector3d& v : B.core->vertices()) {
    const Eigen::Vector3d b = B.X_PP * v;
    for (const Eigen::Vector3d& a : pointsA) points.push_back(b - a);
  }
  QhullHull hull;
  try {
    QhullOptions options;
    options.searchAllPoints = false;
    hull = qhullHull(points, options, "Minkowski difference");
  } catch (const QhullError&) {
    return false;  // flat or degenerate: no interior, the pair never overlaps
  }
  out.normals.clear();
  out.offsets.clear();
  out.faces.clear();
  for (std::size_t f = 0; f < hull.loops.size(); ++f) {
    const Eigen::Vector3d n = hull.normals[f].normalized();
    // The exact support value of M in n: every difference point is inside the plane, so
    // membership below is decided against M itself, not against Qhull's rounded facet.
    double h = -std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : points) h = std::max(h, n.dot(p));
    std::vector<Eigen::Vector3d> loop;
    loop.reserve(hull.loops[f].size());
    for (const int i : hull.loops[f]) {
      const Eigen::Vector3d& p = points[static_cast<std::size_t>(i)];
      loop.push_back(p - (n.dot(p) - h) * n);
    }
    out.normals.push_back(n);
    out.offsets.push_back(h);
    out.faces.push_back(std::move(loop));
  }
  return true;
}

double planeExcess(const Difference& d, const Eigen::Vector3d& x) {
  double worst = -std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < d.normals.size(); ++f) worst = std::max(worst, d.normals[f].dot(x) - d.offsets[f]);
  return worst;
}

double rayExit(const Difference& d, const Eigen::Vector3d& u) {
  double exit = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < d.normals.size(); ++f) {
    const double rate = d.normals[f].dot(u);
    if (rate > 0) exit = std::min(exit, d.offsets[f] / rate);
  }
  return exit;
}

bool insideAnother(const std::vector<Difference>& diffs, int skip, const Eigen::Vector3d& x,
                   double tol) {
  for (std::size_t k = 0; k < diffs.size(); ++k) {
    if (static_cast<int>(k) == skip) continue;
    const Difference& d = diffs[k];
    bool inside = true;
    for (std::size_t f = 0; f < d.normals.size() && inside; ++f) inside = d.normals[f].dot(x) - d.offsets[f] < -tol;
    if (inside) return true;
  }
  return false;
}

}  // namespace deepcheck::deep::body
