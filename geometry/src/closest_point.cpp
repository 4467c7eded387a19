#include "deepcheck/geometry/closest_point.h"

#include <algorithm>
#include <utility>

namespace deepcheck::geometry {

using Eigen::Vector3d;

Vector3d closestPointOnTriangle(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d ab = b - a;
  const Vector3d ac = c - a;
  const Vector3d ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  // d1 - d3 = |ab|^2: when a == b (d1 = d3 = 0) edge ab is a point, and the other tests find
  // the closest point (dividing by d1 - d3 would give NaN).
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 > d3) return a + (d1 / (d1 - d3)) * ab;
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {
    // Degenerate (collinear) triangle not caught above: closest point of its three edges.
    Vector3d best = a;
    for (const auto& [e0, e1] : {std::pair<Vector3d, Vector3d>{a, b}, {b, c}, {c, a}}) {
      const Vector3d e = e1 - e0;
      const double len2 = e.squaredNorm();
      const double t = len2 > 0.0 ? std::clamp(e.dot(p - e0) / len2, 0.0, 1.0) : 0.0;
      const Vector3d q = e0 + t * e;
      if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
    }
    return best;
  }
  return a + (vb / sum) * ab + (vc / sum) * ac;
}

}  // namespace deepcheck::geometry
