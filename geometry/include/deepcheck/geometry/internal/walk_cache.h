#pragma once
// Warm-start state of the Gauss-map walk for one pair, held by PairCache (signed_distance.h).

#include <Eigen/Core>

namespace deepcheck::geometry::detail {

/// The facets where the last query's walks ended (the best first): when the pair moves, the
/// global minimum usually stays in its basin or switches to one of these competitors, so a warm
/// query restarts from each of them instead of from all cold start directions.
struct WalkCache {
  static constexpr int kBasins = 4;
  bool valid = false;
  int count = 0;               ///< basins stored (the first is the last answer)
  int hubA[kBasins] = {};      ///< vertex of A of each basin's hub pair
  int hubB[kBasins] = {};      ///< vertex of B of each basin's hub pair
  Eigen::Vector3d u[kBasins];  ///< outward facet normal of M at each basin, frame P
  int warmQueries = 0;         ///< warm queries since the last cold one
};

}  // namespace deepcheck::geometry::detail
