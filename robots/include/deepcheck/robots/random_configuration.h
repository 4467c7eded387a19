#pragma once
// Seeded random configurations that are the same on every platform: the uniform numbers are made
// from the raw output of std::mt19937_64 (std::uniform_real_distribution's algorithm is each
// standard library's own). Used by the collision-pair filter's samples (pair_filter.h) and the
// planners' tests.

#include "deepcheck/robots/robot_model.h"

#include <Eigen/Core>

#include <random>

namespace deepcheck::robots {

/// Uniform in [0, 1) from the top 53 bits of one 64-bit draw.
inline double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

/// A configuration drawn uniformly within the limits (continuous joints in [-pi, pi]), one
/// uniform01 per variable, in variable order.
inline Eigen::VectorXd randomConfiguration(const RobotModel& model, std::mt19937_64& rng) {
  const Eigen::VectorXd& lo = model.lowerLimits();
  const Eigen::VectorXd& hi = model.upperLimits();
  Eigen::VectorXd q(model.numVariables());
  for (int v = 0; v < q.size(); ++v) q[v] = lo[v] + uniform01(rng) * (hi[v] - lo[v]);
  return q;
}

}  // namespace deepcheck::robots
