#pragma once
// Building ConvexPolytopes, internal: the builder (a friend of ConvexPolytope) and the geometric
// helpers its files and the invariant checks share. polytope_build.cpp classifies the input and
// builds points, segments and polygons; polytope_solid.cpp builds solids; polytope_topology.cpp
// checks the invariants; support.cpp holds the support mapping.
//
// Conventions (vertex neighbours and face rings, polygon faces) are documented in polytope.h.
//
// fromPoints, step by step:
//  1. Validate the input; shift it to a local origin (the centre of its bounding box) so that the
//     geometric predicates below work on coordinates of the size of the set, not of its position.
//  2. Flatness tolerance h = max(kFlatRelative * D, kCoordinateRoundoff * max|x|), D the extent of
//     the set (distance of a farthest-point pair found by sweeps).
//  3. Drop points within h of an earlier kept point (a hash grid of cell size h).
//  4. Classify: the farthest-point pair spans a line, the point farthest from it a plane, the point
//     farthest from that plane a thickness. Each is compared with h: Point, Segment, Polygon,
//     Polyhedron. All four kinds are decided here, before Qhull, which fails on flat input.
//  5. Polygon: Andrew's monotone chain on plane coordinates, dropping vertices within h of the line
//     through their neighbours; the plane is refitted and must hold every point within h,
//     otherwise the set is treated as a solid after all.
//  6. Polyhedron (makeSolid): Qhull, merging facets within h itself (C-h) unless the set is thin,
//     then our own pass over its facets: adjacent faces coplanar within kCoplanarAngle and h are
//     merged (the union's boundary becomes the new loop), vertices left on two faces only (inside
//     an edge) are removed, normals are fitted (fitPlane), and vertex rings are built by walking
//     around each vertex: from ring face F, the next neighbour is F's predecessor of v, and the
//     next ring face is the face holding the half-edge from v to that neighbour. Vertices that
//     are not extreme within h (at a straight or reflex face corner) are pruned and the hull
//     rebuilt, and the result is checked against every input point; when Qhull's merging leaves
//     something unresolved, the hull is rebuilt without it (C-0).
// Output vertices are always input points, bit for bit.
//
// Why all this: within a tolerance, noise in the input leaves slivers (facets whose three vertices
// are nearly collinear: their normals are arbitrary) and faces that are convex only within the
// tolerance. Both break what DEEP and hill climbing rely on, a vertex whose neighbours are all
// lower is the maximum, by far more than the tolerance (a reflex corner hides a whole wedge of
// directions). Inputs with noise from round-off up to 1e-7 of their size, points on the edges or
// faces of boxes, near-duplicates, thin slabs and needles, far from the origin, were used to
// tune it; the tests keep a sample of them.

#include "deepcheck/geometry/polytope.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace deepcheck::geometry {

using Eigen::Vector3d;

namespace detail {

inline std::uint64_t edgeKey(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

/// Newell's area vector of a closed loop: twice the vector area, along the normal for which the
/// loop is counter-clockwise. Computed relative to the first vertex to keep digits.
template <class Loop, class Coord>
Vector3d newellVector(const Loop& loop, const Coord& coord) {
  Vector3d sum = Vector3d::Zero();
  const int k = static_cast<int>(loop.size());
  if (k < 3) return sum;
  const Vector3d origin = coord(loop[0]);
  for (int i = 1; i + 1 < k; ++i) {
    sum += (coord(loop[i]) - origin).cross(coord(loop[i + 1]) - origin);
  }
  return sum;
}

/// Position i in verts of the point coord(verts[i]) farthest from `from` (the first on ties).
template <class Verts, class Coord>
int farthestFrom(const Verts& verts, const Coord& coord, const Vector3d& from) {
  int best = 0;
  double bestD = -1.0;
  const int k = static_cast<int>(verts.size());
  for (int i = 0; i < k; ++i) {
    const double d = (coord(verts[i]) - from).squaredNorm();
    if (d > bestD) {
      bestD = d;
      best = i;
    }
  }
  return best;
}

/// Andrew's monotone chain: the boundary of the 2-d convex hull of `sorted` (points sorted by x,
/// then y), counter-clockwise, each corner once. The chain keeps corner m between o and e when
/// keep(o, m, e) (a strict left turn, possibly by more than a tolerance).
template <class P, class Keep>
std::vector<P> monotoneChain(const std::vector<P>& sorted, const Keep& keep) {
  std::vector<P> hull;
  hull.reserve(2 * sorted.size());
  for (int pass = 0; pass < 2; ++pass) {  // lower chain, then upper chain
    const std::size_t base = hull.size();
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      const P& x = pass == 0 ? sorted[i] : sorted[sorted.size() - 1 - i];
      while (hull.size() >= base + 2 && !keep(hull[hull.size() - 2], hull.back(), x)) {
        hull.pop_back();
      }
      hull.push_back(x);
    }
    hull.pop_back();  // the next chain's first point
  }
  return hull;
}

/// A plane fitted to a set of points: unit normal, the thickness of the set along it (band) and
/// the width of the set (largest distance from its longest chord: a sliver has a small width).
struct PlaneFit {
  Vector3d normal = Vector3d::Zero();
  double band = std::numeric_limits<double>::infinity();
  double width = 0.0;
};

/// Plane of a (nearly) planar set, well conditioned on slivers, unlike Newell's vector, whose
/// round-off (eps * length^2) tilts a sliver's normal in any direction by eps * length / width:
/// here the frame comes from the set's longest chord u (two farthest-point sweeps) and the point
/// farthest from that chord, so the only poorly determined component is a rotation about u, which
/// moves the points by at most width * angle = eps * length. The plane is then refined by least
/// squares in that frame. The normal is oriented along `orient`; it is zero for collinear sets.
template <class Verts, class Coord>
PlaneFit fitPlane(const Verts& verts, const Coord& coord, const Vector3d& orient) {
  PlaneFit fit;
  const int k = static_cast<int>(verts.size());
  if (k < 3) return fit;
  const Vector3d a = coord(verts[farthestFrom(verts, coord, coord(verts[0]))]);
  const Vector3d chord = coord(verts[farthestFrom(verts, coord, a)]) - a;
  if (!(chord.norm() > 0.0)) return fit;
  const Vector3d u = chord.normalized();
  Vector3d across = Vector3d::Zero();
  for (int i = 0; i < k; ++i) {
    const Vector3d x = coord(verts[i]) - a;
    const Vector3d r = x - x.dot(u) * u;
    if (r.squaredNorm() > across.squaredNorm()) across = r;
  }
  fit.width = across.norm();
  if (!(fit.width > 0.0)) return fit;
  const Vector3d w = across / fit.width;
  Vector3d n = u.cross(w).normalized();
  // Least squares z = alpha * s + beta * t + gamma in the frame (u, w, n) about a.
  Vector3d mean = Vector3d::Zero();
  for (int i = 0; i < k; ++i) {
    const Vector3d x = coord(verts[i]) - a;
    mean += Vector3d(x.dot(u), x.dot(w), x.dot(n));
  }
  mean /= static_cast<double>(k);
  double ss = 0.0, st = 0.0, tt = 0.0, sz = 0.0, tz = 0.0;
  for (int i = 0; i < k; ++i) {
    const Vector3d x = coord(verts[i]) - a;
    const Vector3d y = Vector3d(x.dot(u), x.dot(w), x.dot(n)) - mean;
    ss += y.x() * y.x();
    st += y.x() * y.y();
    tt += y.y() * y.y();
    sz += y.x() * y.z();
    tz += y.y() * y.z();
  }
  const double det = ss * tt - st * st;
  if (det > 0.0) {
    const double alpha = (sz * tt - tz * st) / det;
    const double beta = (ss * tz - st * sz) / det;
    n = (n - alpha * u - beta * w).normalized();
  }
  if (orient.dot(n) < 0.0) n = -n;
  fit.normal = n;
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (int i = 0; i < k; ++i) {
    const double z = n.dot(coord(verts[i]) - a);
    lo = std::min(lo, z);
    hi = std::max(hi, z);
  }
  fit.band = hi - lo;
  return fit;
}

/// Normal of a face loop, counter-clockwise about it (see fitPlane).
template <class Loop, class Coord>
Vector3d fitNormal(const Loop& loop, const Coord& coord) {
  return fitPlane(loop, coord, newellVector(loop, coord)).normal;
}

/// The error of a hull whose facets do not form a closed, consistently oriented surface.
[[noreturn]] inline void throwTopologyError(const std::string& name, const std::string& what) {
  throw std::runtime_error(name + ": inconsistent hull topology (" + what + ")");
}

}  // namespace detail

/// Builds polytopes; a friend of ConvexPolytope. One builder per fromPoints call.
class PolytopeBuilder {
 public:
  PolytopeBuilder(const std::vector<Vector3d>& points, const std::string& name) : points_(points), name_(name) {}

  ConvexPolytope build();

 private:
  ConvexPolytope makePoint(int i) const;
  ConvexPolytope makeSegment(int a, int b) const;
  bool makePolygon(const Vector3d& normal, ConvexPolytope* out) const;
  struct SolidAttempt {
    ConvexPolytope hull;
    bool covers = false;  // holds every input point within hullTolerance()
    bool clean = false;   // and has no redundant vertex left
  };
  ConvexPolytope makeSolid(double thickness) const;
  SolidAttempt pruneRounds(bool merge) const;
  ConvexPolytope makePolyhedron(const std::vector<int>& ids, double qhullMerge, std::vector<int>* vertexIds,
                                std::vector<int>* redundant) const;
  bool covers(const ConvexPolytope& p, const std::vector<int>& vertexIds) const;
  void dropNearDuplicates();
  ConvexPolytope assembleSolid(const std::vector<std::vector<int>>& faces, std::vector<int>* vertexIds) const;
  void buildRings(ConvexPolytope& p) const;
  void findRedundant(const ConvexPolytope& p, const std::vector<int>& vertexIds, std::vector<int>* redundant) const;
  [[noreturn]] void topologyError(const std::string& what) const { detail::throwTopologyError(name_, what); }

  const std::vector<Vector3d>& points_;
  const std::string& name_;
  std::vector<Vector3d> q_;  // points relative to the local origin
  std::vector<int> ids_;     // kept points (near-duplicates dropped), indices into points_
  double h_ = 0.0;           // flatness tolerance (absolute)
  Vector3d lineDir_ = Vector3d::UnitX();
  Vector3d planeNormal_ = Vector3d::UnitZ();  // normal of the plane through three extreme points
};

}  // namespace deepcheck::geometry
