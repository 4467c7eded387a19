#pragma once
// Exact reference signed distance, by brute force: the convex hull (Qhull) of all pairwise vertex
// differences b - a is the Minkowski difference M = B - A. If the origin is inside M, the depth is
// the smallest facet offset; otherwise the distance is the distance from the origin to M.
// O(nA * nB log(nA * nB)): for tests and benchmarks only, never for queries in a loop.

#include "deepcheck/deep/pair_frame.h"

namespace deepcheck::deep {

struct ExactResult {
  double distance = 0.0;  ///< signed: > 0 apart, < 0 penetration depth (negated)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit, from A towards B, world frame
  int minkowskiVertices = 0;  ///< vertices of the hull of differences
  int minkowskiFacets = 0;    ///< facets of that hull (after merging coplanar ones)
};

/// Exact signed distance between polytopes A and B (cores) with radii rA, rB >= 0.
/// Computed in the pair frame; the normal is returned in the world frame.
ExactResult exactSignedDistance(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA,
                                const ConvexPolytope& B, const Eigen::Isometry3d& X_WB,
                                double radiusA = 0.0, double radiusB = 0.0);

}  // namespace deepcheck::deep
