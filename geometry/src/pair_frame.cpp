// The pair frame P (see pair_frame.h): A's frame translated to A's centroid.

#include "deepcheck/geometry/pair_frame.h"

#include "deepcheck/geometry/input_range.h"
#include "deepcheck/geometry/tolerances.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace deepcheck::geometry {

namespace {

/// Whether pose X passes checkPose()'s tests, by a short computation with margins (every pose it
/// accepts passes them; a pose it rejects is checked again in full, which names the failure).
bool clearlyValid(const Eigen::Isometry3d& X) {
  const Eigen::Matrix4d& M = X.matrix();
  const Eigen::Vector3d c0 = M.col(0).head<3>(), c1 = M.col(1).head<3>(), c2 = M.col(2).head<3>();
  bool ok = true;
  for (int r = 0; r < 3; ++r) ok = ok && std::abs(M(r, 3)) <= range::kMaxCoordinate;  // false on NaN
  // R^T R - I within half the tolerance (round-off of the full test is far below the margin),
  // entry by entry; non-finite rotation entries fail these comparisons.
  const double half = 0.5 * tol::kOrthonormal;
  ok = ok && std::abs(c0.dot(c0) - 1.0) < half && std::abs(c1.dot(c1) - 1.0) < half &&
       std::abs(c2.dot(c2) - 1.0) < half && std::abs(c0.dot(c1)) < half && std::abs(c0.dot(c2)) < half &&
       std::abs(c1.dot(c2)) < half;
  // Orthonormal within the tolerance: det R is +-1 to far better than 0.5.
  return ok && c0.dot(c1.cross(c2)) > 0.5;
}

}  // namespace

void checkPose(const Eigen::Isometry3d& X, const char* what) {
  if (clearlyValid(X)) return;
  const Eigen::Matrix3d R = X.linear();
  const Eigen::Vector3d p = X.translation();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      const double x = c < 3 ? R(r, c) : p[r];
      if (!std::isfinite(x)) {
        std::ostringstream msg;
        msg << what << ": pose has a non-finite " << (c < 3 ? "rotation" : "translation") << " entry (" << r << ", "
            << c << ") = " << x;
        throw std::invalid_argument(msg.str());
      }
    }
  }
  range::checkTranslation(p, what);
  const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(error < tol::kOrthonormal)) {
    std::ostringstream msg;
    msg.precision(17);
    msg << what << ": rotation is not orthonormal (max |R^T R - I| = " << error << ")";
    throw std::invalid_argument(msg.str());
  }
  const double det = R.determinant();
  if (!(det > 0.0)) {
    std::ostringstream msg;
    msg.precision(17);
    msg << what << ": rotation is a reflection (det R = " << det << ")";
    throw std::invalid_argument(msg.str());
  }
}

PairFrame PairFrame::make(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA, const ConvexPolytope& B,
                          const Eigen::Isometry3d& X_WB) {
  checkPose(X_WA, "X_WA");
  checkPose(X_WB, "X_WB");
  return makeUnchecked(A, X_WA, B, X_WB);
}

PairFrame PairFrame::makeUnchecked(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA, const ConvexPolytope& B,
                                   const Eigen::Isometry3d& X_WB) {
  const Eigen::Matrix3d R_WA = X_WA.linear();
  const Eigen::Matrix3d R_WB = X_WB.linear();
  PairFrame frame;
  frame.R = R_WA.transpose() * R_WB;
  // The difference of the (possibly large) world positions comes first: it is exact when the two
  // are close, so a pair far from the world origin loses no digits beyond its poses' own.
  const Eigen::Vector3d p_AB_W = X_WB.translation() - X_WA.translation();
  frame.t = R_WA.transpose() * p_AB_W + (frame.R * B.center() - A.center());
  frame.X_WP = X_WA * Eigen::Translation3d(A.center());
  return frame;
}

double pairLengthScale(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame) {
  return std::max(A.lengthScale(), B.lengthScale()) + frame.t.norm();
}

}  // namespace deepcheck::geometry
