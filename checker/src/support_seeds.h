#pragma once
// Starting vertices for the narrow phase's first support queries of a cold pair.
//
// deep::ConvexPolytope::support climbs the vertex graph from a hint (the GJK cache keeps the last
// support vertices, so warm queries climb a step or two). A cold query (random configurations:
// the caches are reset) would climb from vertex 0, across half the hull on a 150-vertex link
// mesh. GJK's first direction is the centroid difference, which the checker knows before the
// call: each piece keeps the support vertices of the 26 directions of a cube's faces, edges and
// corners, and a cold pair starts from the one nearest the direction it will ask for. Only where
// the climb starts changes: the support found, hence the answer, is the same.

#include "deepcheck/deep/polytope.h"

#include <Eigen/Core>

#include <array>
#include <cmath>

namespace deepcheck::checker::detail {

class SupportSeeds {
 public:
  SupportSeeds() = default;
  /// The seeds of `core` (in its own frame); none for hulls small enough to be searched by brute
  /// force (start() then returns 0).
  static SupportSeeds of(const deep::ConvexPolytope& core) {
    SupportSeeds s;
    if (core.numVertices() <= 16) return s;
    s.used_ = true;
    for (int k = 0; k < 27; ++k) {
      const Eigen::Vector3d dir(k / 9 - 1, (k / 3) % 3 - 1, k % 3 - 1);
      s.vertex_[k] = dir.squaredNorm() > 0 ? core.supportBruteForce(dir.normalized()) : 0;
    }
    return s;
  }

  /// A vertex near the support of `dir` (core frame): each coordinate of the cube direction is
  /// the sign of dir's, or 0 where |dir_i| is below tan(22.5 deg) of the largest.
  int start(const Eigen::Vector3d& dir) const {
    if (!used_) return 0;
    const double m = 0.41421356 * dir.cwiseAbs().maxCoeff();
    auto code = [m](double x) { return x > m ? 2 : (x < -m ? 0 : 1); };
    return vertex_[code(dir.x()) * 9 + code(dir.y()) * 3 + code(dir.z())];
  }

 private:
  bool used_ = false;
  std::array<int, 27> vertex_{};
};

}  // namespace deepcheck::checker::detail
