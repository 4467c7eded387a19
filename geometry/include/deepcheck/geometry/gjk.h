#pragma once
// GJK distance between two convex polytopes (Gilbert, Johnson, Keerthi 1988), with witness points.
//
// Works in the pair frame P (see pair_frame.h) on the Minkowski difference M = B - A, whose
// support point in direction d is support_B(d) - support_A(-d). The simplex is kept as pairs of
// vertex indices (a, b) so witness points are exact convex combinations of hull vertices.
// The sub-simplex step uses signed volumes (Montanari, Petrinic, Barbieri 2017) rather than
// Johnson's distance subalgorithm, which loses accuracy on thin simplices.
//
// Outputs, all in frame P:
//   distance   >= 0, the Euclidean distance between the polytopes (0 when they overlap);
//   pointA/B   closest points, pointB - pointA = distance * normal;
//   normal     unit, from A towards B (undefined, zero, when overlapping).
//
// Tolerances scale with the pair length scale L = max(A.lengthScale(), B.lengthScale()) + |t|
// (t: B's centre in P), as tolerances.h describes. Distances below kContactRelative * L are
// contact: the status is then Touching or Overlapping and the distance 0. Overlapping is reported
// only when the origin is certified to lie inside M: a tetrahedron of support points encloses it
// with every face farther than kContactRelative * L, or else four probe points around it at
// distance kFlatRelative * L are all enclosed. Otherwise (a penetration thinner than that, or a
// flat overlap: coplanar polygons, crossing segments) the status is Touching.

#include "deepcheck/geometry/pair_frame.h"

#include <array>

namespace deepcheck::geometry {

enum class GjkStatus {
  Separated,      ///< distance > 0, converged to kGjkRelative
  Overlapping,    ///< the origin is certified inside M (see above): distance 0, normal zero
  Touching,       ///< distance below kContactRelative * L: treated as contact; distance is 0,
                  ///< pointB - pointA is the residual (below tolerance) and normal its
                  ///< direction when it is non-zero (else zero)
  MaxIterations,  ///< iteration cap hit; distance is an upper bound
};

const char* toString(GjkStatus s);

/// Four points of M = B - A, as vertex index pairs (a[i] of A, b[i] of B).
struct MinkowskiTetrahedron {
  std::array<int, 4> a{};
  std::array<int, 4> b{};
};

/// Warm-start state for one pair: the last separating direction and support vertices. The caller
/// owns it (one per pair and per thread); a default-constructed cache means "cold".
/// A query starts from `direction` when it is finite and non-zero, else from the centroid
/// difference t, else from +x; on exit it stores there the last v (the current closest point of
/// M, pointing from A towards B) whose support in -v was taken, and the last support vertices.
struct GjkCache {
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  ///< last search direction (frame P), zero = none
  int hintA = 0;
  int hintB = 0;
  /// The tetrahedron that enclosed the origin when the last query ended enclosing it
  /// (`enclosed`), for enclosesOrigin at a nearby pose.
  MinkowskiTetrahedron enclosing;
  bool enclosed = false;
};

struct GjkResult {
  GjkStatus status = GjkStatus::MaxIterations;
  double distance = 0.0;
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero();
  Eigen::Vector3d pointB = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  int iterations = 0;
  /// Final simplex as vertex index pairs (A index, B index) with barycentric weights.
  int simplexSize = 0;
  std::array<int, 4> simplexA{};
  std::array<int, 4> simplexB{};
  std::array<double, 4> weights{};
};

/// Distance between A and B (cores only, no radii) in the pair frame. `cache` may be null.
/// No heap allocation.
GjkResult gjkDistance(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                      GjkCache* cache = nullptr);

/// True when the points of M named by t, at this frame's poses, form a tetrahedron that encloses
/// the origin, by the test GJK's own enclosing step makes: A and B then overlap. A certificate
/// only (false says nothing): four vertex pairs, no support query, for a pair that overlapped at
/// a nearby pose (GjkCache::enclosing). The indices must be vertices of A and B.
bool enclosesOrigin(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                    const MinkowskiTetrahedron& t);

/// Fast boolean: true when A and B overlap or touch within kContactRelative * L. Stops as soon as
/// a separating axis or an enclosing simplex is found. Returns true (the safe answer) in the
/// rare case the iteration cap is hit undecided.
bool gjkOverlap(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, GjkCache* cache = nullptr);

/// Fast boolean: true when the distance between A and B is at most `within` (> 0), or cannot be
/// shown larger (touching within kContactRelative * L, or the iteration cap). Stops as soon as
/// GJK's lower bound exceeds `within` (false) or its simplex comes within it (true); at
/// convergence, false only when the lower bound exceeds `within`, so false is a proof. For
/// shapes with radii: the cores' distance against the sum of the radii.
bool gjkWithin(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, double within,
               GjkCache* cache = nullptr);

/// What gjkBound found: `within` (the distance is at most `near`, or cannot be shown larger, as
/// gjkWithin says), else `lower`, a lower bound on the distance, above `near`.
struct GjkBound {
  bool within = true;
  double lower = 0.0;
};

/// For a distance tested against two thresholds near <= far: within when gjkWithin(near) would be
/// true; otherwise a lower bound above `near` (the largest v.w / |v| of the run), which stops
/// improving once it exceeds `far` or lies within the fraction tol::kGjkBoundGap of the distance.
/// Cores only, as gjkWithin.
GjkBound gjkBound(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, double near, double far,
                  GjkCache* cache = nullptr);

}  // namespace deepcheck::geometry
