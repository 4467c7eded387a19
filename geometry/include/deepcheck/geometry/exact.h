#pragma once
// Exact reference signed distance, by brute force: the convex hull (Qhull) of all pairwise vertex
// differences b - a is the Minkowski difference M = B - A. If the origin is inside M, the depth is
// the smallest facet offset; otherwise the distance is the distance from the origin to M.
// O(nA * nB log(nA * nB)): for tests and benchmarks only, never for queries in a loop.

#include "deepcheck/geometry/pair_frame.h"

#include <vector>

namespace deepcheck::geometry {

struct ExactResult {
  double distance = 0.0;                              ///< signed: > 0 apart, < 0 penetration depth (negated)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit, from A towards B, world frame
  int minkowskiVertices = 0;                          ///< vertices of the hull of differences
  int minkowskiFacets = 0;                            ///< facets of that hull (after merging coplanar ones)
};

/// One facet of the Minkowski difference hull, in frame P.
struct MinkowskiFacet {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit, outward from M
  /// The facet lies in {x : normal.x = offset}; offset > 0 when the origin is on M's side of it.
  /// Refitted from the facet's vertices (mean of normal.x over them), see exact.cpp.
  double offset = 0.0;
  std::vector<Eigen::Vector3d> vertices;  ///< counter-clockwise seen from outside
};

/// The Minkowski difference M = B - A of two posed polytopes, in frame P.
struct MinkowskiHull {
  /// Affine dimension of M: 0 point, 1 segment, 2 polygon, 3 solid. M counts as lower-dimensional
  /// when all its points lie within max(tol::kFlatRelative * size(M), tol::kCoordinateRoundoff *
  /// max|x|) of a plane, line or point (size(M): largest distance of a point from their mean).
  int dimension = 0;
  /// Hull vertices: dimension 0: one point; 1: the two ends; 2: polygon corners counter-clockwise
  /// about planeNormal; 3: the hull's vertices.
  std::vector<Eigen::Vector3d> vertices;
  /// dimension 3: the facets, coplanar ones merged. Empty otherwise.
  std::vector<MinkowskiFacet> facets;
  /// dimension 2: unit normal of the plane of M.
  Eigen::Vector3d planeNormal = Eigen::Vector3d::UnitZ();
};

/// Builds M = B - A in the pair frame (Qhull of all nA * nB vertex differences). Throws
/// QhullError (a std::runtime_error, qhull_hull.h) when Qhull fails.
MinkowskiHull minkowskiDifferenceHull(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame);

/// Exact signed distance between polytopes A and B (cores) with radii rA, rB >= 0.
/// Computed in the pair frame; the normal is returned in the world frame.
/// Lower-dimensional differences (coplanar polygons, parallel segments, points): a flat M that
/// contains the origin gives distance 0 with the plane's normal (oriented along the centre
/// difference of B minus A when it has a component along it); a segment or point M containing the
/// origin gives 0 with a normal perpendicular to it (arbitrary for a point).
/// Throws std::invalid_argument for negative or non-finite radii or bad poses.
ExactResult exactSignedDistance(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA, const ConvexPolytope& B,
                                const Eigen::Isometry3d& X_WB, double radiusA = 0.0, double radiusB = 0.0);

}  // namespace deepcheck::geometry
