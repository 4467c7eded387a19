#pragma once
// Oriented bounding boxes of convex pieces and the separating-axis test between two of them
// (Gottschalk, Lin, Manocha, "OBBTree", SIGGRAPH 1996: 15 candidate axes — the 3 face normals of
// each box and the 9 cross products of their edges).
//
// The box of a piece is aligned with the principal axes of its core's vertices
// (deep::ConvexPolytope::principalAxes), spans the vertices' extent along them, and is grown by
// the piece's radius (a sphere or capsule core), so it contains the whole piece.
//
// Frames: an Obb is expressed in one frame F (R_FB: the box axes as columns, center_F: its
// centre); transform() moves it to another frame. Metres.

#include "deepcheck/checker/tolerances.h"
#include "deepcheck/deep/polytope.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace deepcheck::checker {

struct Obb {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  ///< box axes (columns), a rotation
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();   ///< half extents along the axes, >= 0

  /// The box of `core` grown by `radius`, in the core's frame (padded by tol::kBoundingRelative).
  static Obb ofPiece(const deep::ConvexPolytope& core, double radius);

  /// This box seen from frame G when it is expressed in F and X_GF is the pose of F in G.
  Obb transformed(const Eigen::Isometry3d& X_GF) const {
    Obb b;
    b.R.noalias() = X_GF.linear() * R;
    b.center = X_GF * center;
    b.half = half;
    return b;
  }
};

/// True when some axis separates the boxes (they are disjoint). Conservative: near-parallel edge
/// pairs, whose cross product is numerically meaningless, never separate (tol::kObbParallel).
inline bool separated(const Obb& a, const Obb& b) {
  // B's axes and centre in A's frame.
  const Eigen::Matrix3d R = a.R.transpose() * b.R;
  const Eigen::Vector3d t = a.R.transpose() * (b.center - a.center);
  const Eigen::Matrix3d absR = R.cwiseAbs().array() + tol::kObbParallel;
  // A's face normals.
  for (int i = 0; i < 3; ++i) {
    if (std::abs(t[i]) > a.half[i] + absR.row(i).dot(b.half)) return true;
  }
  // B's face normals.
  for (int j = 0; j < 3; ++j) {
    if (std::abs(t.dot(R.col(j))) > absR.col(j).dot(a.half) + b.half[j]) return true;
  }
  // Edge cross products A_i x B_j.
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    const int i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3;
      const int j2 = (j + 2) % 3;
      const double ra = a.half[i1] * absR(i2, j) + a.half[i2] * absR(i1, j);
      const double rb = b.half[j1] * absR(i, j2) + b.half[j2] * absR(i, j1);
      if (std::abs(t[i2] * R(i1, j) - t[i1] * R(i2, j)) > ra + rb) return true;
    }
  }
  return false;
}

}  // namespace deepcheck::checker
