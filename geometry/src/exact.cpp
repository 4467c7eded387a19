// Exact reference signed distance: the hull of all pairwise vertex differences (see exact.h).
//
// Steps:
//  1. In the pair frame P, form the nA * nB differences b - a (the points of M = B - A).
//  2. Classify M by its affine dimension (farthest point from the mean, farthest from that line,
//     farthest from that plane, each compared with max(tol::kFlatRelative * size(M),
//     tol::kCoordinateRoundoff * max|x|)), as polytope.cpp does for a single hull. Qhull runs only
//     on solids.
//  3. Solid: facets from Qhull with coplanar facets merged (Qhull's default 'C-0' in 3-d). Each
//     facet's plane is refitted from its own vertices (see facetPlane()). If every facet offset is
//     >= 0 the origin is inside M: the depth is the smallest offset d and, with u that facet's
//     outward normal, the normal from A to B is n = -u (M lies in {u.x <= d}, so translating B
//     by d * n = -d * u moves M into {u.x <= 0}: the shapes touch). Otherwise the distance is
//     that from the origin to the closest point c of M (pB - pA = c), n = c / |c|.
//  4. Flat, segment and point M: the distance from the origin to M, computed directly.
// Radii are subtracted at the end: sd(cores with radii) = sd(cores) - rA - rB with the same normal.

#include "deepcheck/geometry/exact.h"

#include "deepcheck/geometry/closest_point.h"
#include "deepcheck/geometry/qhull_hull.h"
#include "deepcheck/geometry/tolerances.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace deepcheck::geometry {
namespace {

/// Closest point to the origin on triangle (a, b, c).
Eigen::Vector3d closestOnTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return closestPointOnTriangle(Eigen::Vector3d::Zero(), a, b, c);
}

/// Closest point to the origin on segment [p, q].
Eigen::Vector3d closestOnSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  const Eigen::Vector3d e = q - p;
  const double ee = e.squaredNorm();
  if (!(ee > 0.0)) return p;
  return p + std::clamp(-p.dot(e) / ee, 0.0, 1.0) * e;
}

/// Closest point to the origin on a convex polygon given by its corners in order (fan).
Eigen::Vector3d closestOnPolygon(const std::vector<Eigen::Vector3d>& corners) {
  if (corners.size() == 1) return corners[0];
  if (corners.size() == 2) return closestOnSegment(corners[0], corners[1]);
  Eigen::Vector3d best = closestOnTriangle(corners[0], corners[1], corners[2]);
  for (std::size_t i = 2; i + 1 < corners.size(); ++i) {
    const Eigen::Vector3d x = closestOnTriangle(corners[0], corners[i], corners[i + 1]);
    if (x.squaredNorm() < best.squaredNorm()) best = x;
  }
  return best;
}

/// A unit vector orthogonal to the unit vector u (deterministic).
Eigen::Vector3d anyPerpendicular(const Eigen::Vector3d& u) {
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();
  int k = 0;
  u.cwiseAbs().minCoeff(&k);
  axis[k] = 1.0;
  return u.cross(axis).normalized();
}

/// Orders the points counter-clockwise about the unit normal u (seen from the side u points to).
void sortAround(std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& u) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : pts) c += p;
  c /= static_cast<double>(pts.size());
  const Eigen::Vector3d e1 = anyPerpendicular(u);
  const Eigen::Vector3d e2 = u.cross(e1);
  std::vector<std::pair<double, Eigen::Vector3d>> keyed;
  keyed.reserve(pts.size());
  for (const auto& p : pts) keyed.emplace_back(std::atan2(e2.dot(p - c), e1.dot(p - c)), p);
  std::sort(keyed.begin(), keyed.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  for (std::size_t i = 0; i < pts.size(); ++i) pts[i] = keyed[i].second;
}

/// Refits the plane of a facet from its ordered vertices.
///
/// Normal: Newell's method about the facet's centroid, i.e. the area-weighted mean of the fan
/// triangles' normals. For a triangle this is its exact plane; for a merged facet it uses all of
/// its vertices, where Qhull's hyperplane comes from the one simplex the facet grew from.
/// Offset: n . centroid, the mean of n.x over the vertices. The mean is the least-squares offset
/// for that normal: the independent round-off of the vertices (each b - a is rounded) averages out,
/// where the max over the vertices would keep the largest rounding error and bias the depth
/// upwards. A residual tilt delta of the normal moves the plane by (foot - centroid) . delta at the
/// foot point, no more than the max would (which adds max over vertices of (x - foot) . delta).
void facetPlane(MinkowskiFacet& facet, const Eigen::Vector3d& qhullNormal) {
  const auto& v = facet.vertices;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : v) c += p;
  c /= static_cast<double>(v.size());
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < v.size(); ++i) {
    n += (v[i] - c).cross(v[(i + 1) % v.size()] - c);
  }
  const double len = n.norm();
  // A Newell normal pointing away from Qhull's means the ordering failed (cannot happen for a
  // convex facet); keep Qhull's normal then.
  facet.normal = (len > 0.0 && n.dot(qhullNormal) > 0.0) ? Eigen::Vector3d(n / len) : qhullNormal;
  facet.offset = facet.normal.dot(c);
}

/// 3-d hull of `points` with Qhull: fills vertices and facets of `hull`. Coplanar facets are
/// merged by Qhull's 3-d default ('C-0'). Throws QhullError when Qhull fails.
void qhullSolid(const std::vector<Eigen::Vector3d>& points, MinkowskiHull& hull) {
  const QhullHull q = qhullHull(points, QhullOptions{}, "exact: the Minkowski difference");
  for (int id : q.vertices) hull.vertices.push_back(points[static_cast<std::size_t>(id)]);
  for (std::size_t k = 0; k < q.loops.size(); ++k) {
    MinkowskiFacet f;
    for (int id : q.loops[k]) f.vertices.push_back(points[static_cast<std::size_t>(id)]);
    sortAround(f.vertices, q.normals[k]);
    facetPlane(f, q.normals[k]);
    hull.facets.push_back(std::move(f));
  }
}

/// 2-d convex hull (Andrew's monotone chain) of points in the plane through `origin` with the
/// orthonormal in-plane axes e1, e2 and normal e1 x e2; returns the 3-d corners counter-clockwise
/// about that normal. Collinear boundary points are dropped.
std::vector<Eigen::Vector3d> planarHull(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& origin,
                                        const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) {
  struct P2 {
    double x, y;
    std::size_t i;
  };
  std::vector<P2> q;
  q.reserve(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    q.push_back({e1.dot(pts[i] - origin), e2.dot(pts[i] - origin), i});
  }
  std::sort(q.begin(), q.end(), [](const P2& a, const P2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  const auto cross = [](const P2& o, const P2& a, const P2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<P2> h(2 * q.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {  // lower chain
    while (k >= 2 && cross(h[k - 2], h[k - 1], q[i]) <= 0.0) --k;
    h[k++] = q[i];
  }
  for (std::size_t i = q.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && cross(h[k - 2], h[k - 1], q[i]) <= 0.0) --k;
    h[k++] = q[i];
  }
  h.resize(k > 1 ? k - 1 : k);
  std::vector<Eigen::Vector3d> corners;
  corners.reserve(h.size());
  for (const auto& p : h) corners.push_back(pts[p.i]);
  return corners;
}

/// Builds M from its points (frame P). `mean` is their mean (the centre difference).
MinkowskiHull buildHull(std::vector<Eigen::Vector3d> pts, const Eigen::Vector3d& mean) {
  MinkowskiHull hull;
  // Size of M about its mean; all flatness tests are relative to it.
  std::size_t far0 = 0;
  double size = 0.0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double d = (pts[i] - mean).norm();
    if (d > size) {
      size = d;
      far0 = i;
    }
  }
  // The points carry round-off relative to their magnitude (|t| may dwarf size(M) for shapes far
  // apart): a thickness below that is noise, as in polytope.cpp.
  double maxAbs = 0.0;
  for (const auto& p : pts) maxAbs = std::max(maxAbs, p.cwiseAbs().maxCoeff());
  const double flat = std::max(tol::kFlatRelative * size, tol::kCoordinateRoundoff * maxAbs);
  if (!(size > 0.0)) {
    hull.dimension = 0;
    hull.vertices.push_back(pts[0]);
    return hull;
  }

  // Line through the mean and the farthest point.
  const Eigen::Vector3d dir = (pts[far0] - mean) / size;
  std::size_t far1 = 0;
  double lineDist = -1.0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector3d r = pts[i] - mean;
    const double d = (r - r.dot(dir) * dir).norm();
    if (d > lineDist) {
      lineDist = d;
      far1 = i;
    }
  }
  if (lineDist <= flat) {
    hull.dimension = 1;
    std::size_t lo = 0;
    std::size_t hi = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const double s = dir.dot(pts[i] - mean);
      if (s < dir.dot(pts[lo] - mean)) lo = i;
      if (s > dir.dot(pts[hi] - mean)) hi = i;
    }
    hull.vertices = {pts[lo], pts[hi]};
    return hull;
  }

  // Plane through the mean spanned by dir and the farthest point from the line.
  const Eigen::Vector3d r1 = pts[far1] - mean;
  const Eigen::Vector3d e2 = (r1 - r1.dot(dir) * dir).normalized();
  const Eigen::Vector3d normal = dir.cross(e2).normalized();
  double planeDist = 0.0;
  for (const auto& p : pts) planeDist = std::max(planeDist, std::abs(normal.dot(p - mean)));
  if (planeDist <= flat) {
    hull.dimension = 2;
    hull.planeNormal = normal;
    hull.vertices = planarHull(pts, mean, dir, e2);
    return hull;
  }

  hull.dimension = 3;
  qhullSolid(pts, hull);
  return hull;
}

std::vector<Eigen::Vector3d> differencePoints(const ConvexPolytope& A, const ConvexPolytope& B,
                                              const PairFrame& frame) {
  std::vector<Eigen::Vector3d> a(static_cast<std::size_t>(A.numVertices()));
  std::vector<Eigen::Vector3d> b(static_cast<std::size_t>(B.numVertices()));
  for (int i = 0; i < A.numVertices(); ++i) a[static_cast<std::size_t>(i)] = PairFrame::vertexA(A, i);
  for (int j = 0; j < B.numVertices(); ++j) b[static_cast<std::size_t>(j)] = frame.vertexB(B, j);
  std::vector<Eigen::Vector3d> pts;
  pts.reserve(a.size() * b.size());
  for (const auto& pb : b) {
    for (const auto& pa : a) pts.push_back(pb - pa);
  }
  return pts;
}

/// Mean of the difference points: centroid of B's vertices minus centroid of A's, in P.
Eigen::Vector3d meanDifference(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame) {
  Eigen::Vector3d ma = Eigen::Vector3d::Zero();
  Eigen::Vector3d mb = Eigen::Vector3d::Zero();
  for (int i = 0; i < A.numVertices(); ++i) ma += PairFrame::vertexA(A, i);
  for (int j = 0; j < B.numVertices(); ++j) mb += frame.vertexB(B, j);
  return mb / B.numVertices() - ma / A.numVertices();
}

void checkRadius(double r, const char* what) {
  if (!std::isfinite(r) || r < 0.0) {
    throw std::invalid_argument(std::string("exactSignedDistance: ") + what + " must be finite and >= 0, got " +
                                std::to_string(r));
  }
}

}  // namespace

MinkowskiHull minkowskiDifferenceHull(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame) {
  return buildHull(differencePoints(A, B, frame), meanDifference(A, B, frame));
}

ExactResult exactSignedDistance(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA, const ConvexPolytope& B,
                                const Eigen::Isometry3d& X_WB, double radiusA, double radiusB) {
  checkRadius(radiusA, "radiusA");
  checkRadius(radiusB, "radiusB");
  const PairFrame frame = PairFrame::make(A, X_WA, B, X_WB);
  const Eigen::Vector3d mean = meanDifference(A, B, frame);
  const MinkowskiHull hull = buildHull(differencePoints(A, B, frame), mean);

  const double L = pairLengthScale(A, B, frame);
  const double contact = tol::kContactRelative * L;

  double distance = 0.0;
  Eigen::Vector3d n_P = Eigen::Vector3d::UnitZ();
  ExactResult result;
  result.minkowskiVertices = static_cast<int>(hull.vertices.size());

  if (hull.dimension == 3) {
    result.minkowskiFacets = static_cast<int>(hull.facets.size());
    std::size_t best = 0;
    for (std::size_t f = 1; f < hull.facets.size(); ++f) {
      if (hull.facets[f].offset < hull.facets[best].offset) best = f;
    }
    const MinkowskiFacet& minFacet = hull.facets[best];
    if (minFacet.offset >= 0.0) {
      distance = -minFacet.offset;
      n_P = -minFacet.normal;
    } else {
      // Outside: the closest point of M lies on a facet whose plane separates it from the origin.
      Eigen::Vector3d c = closestOnPolygon(minFacet.vertices);
      for (const auto& facet : hull.facets) {
        if (facet.offset >= 0.0) continue;
        const Eigen::Vector3d x = closestOnPolygon(facet.vertices);
        if (x.squaredNorm() < c.squaredNorm()) c = x;
      }
      distance = c.norm();
      // Within contact distance c's direction is round-off; the facet normal is the continuous
      // continuation of the inside case.
      n_P = distance > contact ? Eigen::Vector3d(c / distance) : Eigen::Vector3d(-minFacet.normal);
    }
  } else {
    Eigen::Vector3d c;
    Eigen::Vector3d fallback;
    if (hull.dimension == 2) {
      result.minkowskiFacets = 2;
      c = closestOnPolygon(hull.vertices);
      fallback = hull.planeNormal;
    } else if (hull.dimension == 1) {
      c = closestOnSegment(hull.vertices[0], hull.vertices[1]);
      const Eigen::Vector3d line = (hull.vertices[1] - hull.vertices[0]).normalized();
      const Eigen::Vector3d off = mean - mean.dot(line) * line;
      fallback = off.norm() > contact ? Eigen::Vector3d(off.normalized()) : anyPerpendicular(line);
    } else {
      c = hull.vertices[0];
      fallback = Eigen::Vector3d::UnitZ();
    }
    distance = c.norm();
    if (distance > contact) {
      n_P = c / distance;
    } else {
      // The origin is on M: orient the fallback along the centre difference so that swapping A
      // and B flips it; a canonical sign when the centre difference is orthogonal to it.
      const double s = fallback.dot(mean);
      if (std::abs(s) > contact) {
        n_P = s > 0.0 ? fallback : Eigen::Vector3d(-fallback);
      } else {
        int k = 0;
        fallback.cwiseAbs().maxCoeff(&k);
        n_P = fallback[k] > 0.0 ? fallback : Eigen::Vector3d(-fallback);
      }
    }
  }

  result.distance = distance - radiusA - radiusB;
  result.normal = (frame.X_WP.linear() * n_P).normalized();
  return result;
}

}  // namespace deepcheck::geometry
