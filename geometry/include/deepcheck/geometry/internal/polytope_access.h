#pragma once
// Parts of a ConvexPolytope (polytope.h) that only deep's own algorithms and tests use: the
// certified expansion's probe directions and the supports stored for them, the prefetch before
// many support climbs, the direction index's start, and the invariant check.

#include "deepcheck/geometry/polytope.h"

#include <Eigen/Core>

#include <string>

namespace deepcheck::geometry::detail {

/// The certified expansion's probe directions: twelve unit vectors, the vertices of a regular
/// icosahedron in a generic orientation, fixed in every polytope's frame.
constexpr int kProbeDirections = 12;
const Eigen::Vector3d& probeDirection(int i);

struct PolytopeAccess {
  static_assert(ConvexPolytope::kProbeDirections == kProbeDirections);
  static int probeSupport(const ConvexPolytope& P, int i) { return P.probeSupport_[i]; }
  static void prefetchSupportData(const ConvexPolytope& P) { P.prefetchSupportData(); }
  static int supportStart(const ConvexPolytope& P, const Eigen::Vector3d& dir) { return P.supportStart(dir); }
  static std::string validate(const ConvexPolytope& P) { return P.validate(); }
};

/// A vertex of P maximizing probeDirection(i), computed once when the hull is built: a query's
/// start without GJK reads the first shape's supports here instead of climbing.
inline int probeSupport(const ConvexPolytope& P, int i) { return PolytopeAccess::probeSupport(P, i); }

/// Asks the processor to bring the arrays support() reads (vertices, vertex rings, direction
/// index) towards its caches, without waiting for them. A query about to climb many times calls
/// it first, so that on a hull out of cache the loads overlap instead of each climb step waiting
/// on memory in turn.
inline void prefetchSupportData(const ConvexPolytope& P) { PolytopeAccess::prefetchSupportData(P); }

/// The direction index's starting vertex for dir (a vertex whose support region is near dir), or
/// -1 when the hull has no index (small hulls) or dir is zero or not finite.
inline int supportStart(const ConvexPolytope& P, const Eigen::Vector3d& dir) {
  return PolytopeAccess::supportStart(P, dir);
}

/// Checks the invariants (Euler characteristic, ring order, convexity within tolerance): an empty
/// string when they hold, else a description.
inline std::string validate(const ConvexPolytope& P) { return PolytopeAccess::validate(P); }

}  // namespace deepcheck::geometry::detail
