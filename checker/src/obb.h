#pragma once
// Oriented bounding boxes of convex pieces and the separating-axis test between two of them
// (Gottschalk, Lin, Manocha, "OBBTree", SIGGRAPH 1996: 15 candidate axes — the 3 face normals of
// each box and the 9 cross products of their edges).
//
// The box of a piece is aligned with the principal axes of its core's vertices
// (geometry::ConvexPolytope::principalAxes), spans the vertices' extent along them, and is grown by
// the piece's radius (a sphere or capsule core), so it contains the whole piece.
//
// Frames: an Obb is expressed in one frame F (R_FB: the box axes as columns, center_F: its
// centre); transform() moves it to another frame. Metres.

#include "deepcheck/checker/tolerances.h"
#include "deepcheck/geometry/polytope.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <limits>

namespace deepcheck::checker {

struct Obb {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  ///< box axes (columns), a rotation
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();  ///< half extents along the axes, >= 0

  /// The box of `core` grown by `radius`, in the core's frame (padded by tol::kBoundingRelative).
  static Obb ofPiece(const geometry::ConvexPolytope& core, double radius);

  /// This box seen from frame G when it is expressed in F and X_GF is the pose of F in G.
  Obb transformed(const Eigen::Isometry3d& X_GF) const {
    Obb b;
    b.R.noalias() = X_GF.linear() * R;
    b.center = X_GF * center;
    b.half = half;
    return b;
  }
};

/// Candidate axes of the separating-axis test, numbered: A's face normals 0-2, B's face normals
/// 3-5, the edge products A_i x B_j 6 + 3i + j.
constexpr int kObbAxes = 15;

/// The first axis, in the order above, that separates the boxes, or -1 when none does (they may
/// overlap). Conservative: near-parallel edge pairs, whose cross product is numerically
/// meaningless, never separate (tol::kObbParallel).
inline int separatingAxis(const Obb& a, const Obb& b) {
  // B's axes and centre in A's frame.
  const Eigen::Matrix3d R = a.R.transpose() * b.R;
  const Eigen::Vector3d t = a.R.transpose() * (b.center - a.center);
  const Eigen::Matrix3d absR = R.cwiseAbs().array() + tol::kObbParallel;
  // A's face normals.
  for (int i = 0; i < 3; ++i) {
    if (std::abs(t[i]) > a.half[i] + absR.row(i).dot(b.half)) return i;
  }
  // B's face normals.
  for (int j = 0; j < 3; ++j) {
    if (std::abs(t.dot(R.col(j))) > absR.col(j).dot(a.half) + b.half[j]) return 3 + j;
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
      if (std::abs(t[i2] * R(i1, j) - t[i1] * R(i2, j)) > ra + rb) return 6 + 3 * i + j;
    }
  }
  return -1;
}

/// True when some axis separates the boxes (they are disjoint).
inline bool separated(const Obb& a, const Obb& b) { return separatingAxis(a, b) >= 0; }

/// True when axis k (0 <= k < kObbAxes) separates the boxes: separatingAxis's test of that axis
/// alone, computing only the cosines and offsets it needs (a third of the work or less).
inline bool separatedAlong(const Obb& a, const Obb& b, int k) {
  const Eigen::Vector3d d = b.center - a.center;
  auto cosine = [&](int i, int j) { return a.R.col(i).dot(b.R.col(j)); };
  auto bound = [&](double c) { return std::abs(c) + tol::kObbParallel; };
  if (k < 3) {
    return std::abs(a.R.col(k).dot(d)) > a.half[k] + bound(cosine(k, 0)) * b.half[0] + bound(cosine(k, 1)) * b.half[1] +
                                             bound(cosine(k, 2)) * b.half[2];
  }
  const Eigen::Vector3d t = a.R.transpose() * d;
  if (k < 6) {
    const int j = k - 3;
    const Eigen::Vector3d c(cosine(0, j), cosine(1, j), cosine(2, j));
    return std::abs(t.dot(c)) > bound(c[0]) * a.half[0] + bound(c[1]) * a.half[1] + bound(c[2]) * a.half[2] + b.half[j];
  }
  const int i = (k - 6) / 3, j = (k - 6) % 3;
  const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
  const double c1 = cosine(i1, j), c2 = cosine(i2, j);
  const double ra = a.half[i1] * bound(c2) + a.half[i2] * bound(c1);
  const double rb = b.half[j1] * bound(cosine(i, j2)) + b.half[j2] * bound(cosine(i, j1));
  return std::abs(t[i2] * c1 - t[i1] * c2) > ra + rb;
}

/// separated() with the axis that last separated the same pair tried first: between nearby
/// configurations the same axis usually separates again, and testing it alone is cheaper than
/// the full test. `hint` is that axis (any value below kObbAxes), updated when another separates.
inline bool separated(const Obb& a, const Obb& b, std::uint8_t& hint) {
  if (separatedAlong(a, b, hint)) return true;
  const int k = separatingAxis(a, b);
  if (k < 0) return false;
  hint = static_cast<std::uint8_t>(k);
  return true;
}

}  // namespace deepcheck::checker
