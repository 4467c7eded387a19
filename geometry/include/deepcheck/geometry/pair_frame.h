#pragma once
// The pair-local frame in which every pair query is computed.
//
// Naming follows Drake: X_WA is the pose of frame A in the world W, p_AB the position of B's
// origin in A, R_AB the orientation of B in A. For a pair (A, B) we work in "frame P": A's own
// frame translated to A's centroid. Coordinates there are of the size of the shapes, never of the
// size of the world, so a pair 1e4 m from the origin loses no digits beyond those of the pose
// difference itself. B's vertices (relative to B's centroid) map into P by x_P = R * x + t.

#include "deepcheck/geometry/polytope.h"

#include <Eigen/Geometry>

namespace deepcheck::geometry {

struct PairFrame {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  ///< orientation of B's centroid frame in P
  Eigen::Vector3d t = Eigen::Vector3d::Zero();      ///< position of B's centroid in P

  /// Builds the frame for A at X_WA and B at X_WB. Throws std::invalid_argument for a pose with
  /// NaN/infinite entries, a translation beyond range::kMaxCoordinate (input_range.h) or a
  /// rotation that is not orthonormal (message names which pose).
  static PairFrame make(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA, const ConvexPolytope& B,
                        const Eigen::Isometry3d& X_WB);
  /// make() without the pose checks, for callers whose poses are rigid by construction (the
  /// checker's, from forward kinematics and validated world poses). The same frame as make() on
  /// valid poses; anything on invalid ones.
  static PairFrame makeUnchecked(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA, const ConvexPolytope& B,
                                 const Eigen::Isometry3d& X_WB);

  /// Pose of P in the world, to map results back: x_W = X_WP * x_P.
  Eigen::Isometry3d X_WP = Eigen::Isometry3d::Identity();

  /// A's vertex v in P.
  static const Eigen::Vector3d& vertexA(const ConvexPolytope& A, int v) { return A.localVertex(v); }
  /// B's vertex v in P.
  Eigen::Vector3d vertexB(const ConvexPolytope& B, int v) const { return R * B.localVertex(v) + t; }
  /// A direction of P expressed in B's frame.
  Eigen::Vector3d toB(const Eigen::Vector3d& dir_P) const { return R.transpose() * dir_P; }
  /// A direction of B's frame expressed in P.
  Eigen::Vector3d fromB(const Eigen::Vector3d& dir_B) const { return R * dir_B; }
};

/// The pair's length scale L, which relative tolerances scale by (tolerances.h): the larger
/// bounding radius plus the centre distance.
double pairLengthScale(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame);

/// Throws std::invalid_argument unless X has finite entries, a translation within
/// range::kMaxCoordinate and an orthonormal rotation (|R^T R - I| < 1e-6); `what` names the pose
/// in the message.
void checkPose(const Eigen::Isometry3d& X, const char* what);

}  // namespace deepcheck::geometry
