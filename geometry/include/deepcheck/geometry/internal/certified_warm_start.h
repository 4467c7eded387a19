#pragma once
// Warm-start state of the certified expansion for one pair, held by PairCache (signed_distance.h)
// and used by certified_warm.cpp (internal/certified.h).

#include "deepcheck/geometry/polytope.h"

#include <Eigen/Core>

namespace deepcheck::geometry::detail {

/// Warm start of the certified method for one pair: the surface of a cold query (faces as vertex
/// index pairs, at most kMaxFaces), kept with each face's unit normal n0 and offset
/// min_k n0.p_k over its corners p_k at that query's pose, the reference (certified_warm.cpp).
///
/// After a motion, every vertex b - a of M has moved by the shift t - t0 plus a turn of length at
/// most |R - R0|_F r_B, in all at most delta = |R - R0|_F r_B + |t - t0| (pair frame: A is fixed,
/// B's vertices lie within r_B of its centroid). Moving the vertices straight from their reference
/// positions to their new ones keeps n0.x > 0 on a face whose corners all have n0.q > 0 (their new
/// positions q; at least offset - delta, and at least offset + n0.(t - t0) - |R - R0|_F r_B), so
/// that face never crosses the origin; when none does, the moved surface (closed, though no longer
/// convex) still winds once around the origin, every ray from it meets the surface at a point of
/// M, and the depth is at least the smallest lower bound on a face's distance: those two, min_k
/// n0.q_k, or the distance to the face's plane through its moved corners. A query makes one
/// support query, in the exact normal of the facet of M named by the face that certified last
/// time (facetOfFace); faces whose bound already reaches that upper bound are not touched, the few
/// below are evaluated at their new corners, and one more support in the nearest face's normal
/// settles most queries without expanding. When it does not, expandWarm() expands the moved
/// surface best-first as a cold query would and makes the result the new reference. A face that
/// could have crossed the origin sends the query cold (which then becomes the new reference).
struct CertifiedWarmStart {
  static constexpr int kMaxFaces = 96;
  static constexpr int kMaxVertices = kMaxFaces / 2 + 2;  ///< a closed surface of F faces has F/2 + 2 vertices
  bool valid = false;
  const ConvexPolytope* A = nullptr;  ///< the pair the surface belongs to (checked before use)
  const ConvexPolytope* B = nullptr;
  int numVertices = 0;
  int numFaces = 0;
  int a[kMaxVertices];
  int b[kMaxVertices];
  int face[kMaxFaces][3];
  int adj[kMaxFaces][3];              ///< neighbours, as ExpansionSurface::Face::adj
  double offset[kMaxFaces];           ///< min over the face's corners of normal.p at the reference (all > 0)
  Eigen::Vector3d normal[kMaxFaces];  ///< unit face normals at the reference pose, frame P
  Eigen::Matrix3d R0 = Eigen::Matrix3d::Identity();  ///< the reference pair frame
  Eigen::Vector3d t0 = Eigen::Vector3d::Zero();
  int last = 0;  ///< the face that certified the last answer
  int hintA = 0;
  int hintB = 0;
  /// A valid surface of the pair (A, B): only then do its index pairs name vertices of theirs.
  bool belongsTo(const ConvexPolytope& a, const ConvexPolytope& b) const { return valid && A == &a && B == &b; }
};

}  // namespace deepcheck::geometry::detail
