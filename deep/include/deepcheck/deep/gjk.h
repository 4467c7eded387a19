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

#include "deepcheck/deep/pair_frame.h"

#include <array>

namespace deepcheck::deep {

enum class GjkStatus {
  Separated,        ///< distance > 0, converged to kGjkRelative
  Overlapping,      ///< the simplex enclosed the origin: distance is 0
  Touching,         ///< distance below kContactRelative * L: treated as contact
  MaxIterations,    ///< iteration cap hit; distance is an upper bound
};

const char* toString(GjkStatus s);

/// Warm-start state for one pair: the last separating direction and support vertices. The caller
/// owns it (one per pair and per thread); a default-constructed cache means "cold".
struct GjkCache {
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  ///< last search direction (frame P), zero = none
  int hintA = 0;
  int hintB = 0;
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
GjkResult gjkDistance(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                      GjkCache* cache = nullptr);

/// Fast boolean: true when A and B overlap or touch within kContactRelative * L. Stops as soon as
/// a separating axis or an enclosing simplex is found.
bool gjkOverlap(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                GjkCache* cache = nullptr);

}  // namespace deepcheck::deep
