#include "obb.h"

namespace deepcheck::checker {

Obb Obb::ofPiece(const geometry::ConvexPolytope& core, double radius) {
  Obb b;
  b.R = core.principalAxes();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const Eigen::Vector3d& v : core.vertices()) {
    const Eigen::Vector3d p = b.R.transpose() * v;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  b.center = b.R * (0.5 * (lo + hi));
  b.half = (0.5 * (hi - lo)).array() + radius;
  // Round-off of the projections and of posing the box later.
  b.half.array() += tol::kBoundingRelative * (b.half.norm() + b.center.norm());
  return b;
}

}  // namespace deepcheck::checker
