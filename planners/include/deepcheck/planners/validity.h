#pragma once
// When a configuration counts as valid: the one criterion shared by the state validity checker,
// the push-out, the motion validator and the path tools.
//
// With sd(q) the world's minimum signed distance over allowed pairs (checker/world.h: > 0 the
// distance, < 0 minus the penetration depth, metres):
//   valid(q)  <=>  sd(q) > threshold,   threshold = safetyMargin - penetrationTolerance.
// Both options default to 0: then valid means collision free (touching counts as a collision,
// as World::isFree says), tested with isFree's early exit. A safety margin asks for that much
// clearance; a penetration tolerance accepts configurations penetrating less than it (a planner
// may then cut through slight collisions that a later repair removes, path_tools.h). Setting
// both is allowed; only their difference matters.
//
// Joint limits are not part of this criterion: the StateValidityChecker checks the robot's URDF
// limits before it (validity_checker.h).

#include "deepcheck/checker/world.h"

#include <Eigen/Core>

namespace deepcheck::planners {

struct ValidityOptions {
  /// Accept configurations penetrating less than this (metres, >= 0).
  double penetrationTolerance = 0.0;
  /// Require at least this clearance (metres, >= 0).
  double safetyMargin = 0.0;

  /// safetyMargin - penetrationTolerance: a configuration is valid when sd > threshold().
  double threshold() const { return safetyMargin - penetrationTolerance; }
};

/// Throws std::invalid_argument, naming the option and its value, unless both options are finite
/// and >= 0.
void checkValidityOptions(const ValidityOptions& options);

/// The criterion above for q (numVariables() finite values; World errors otherwise). Thread safe
/// (uses the calling thread's context of `world`).
bool isConfigurationValid(const checker::World& world, const Eigen::Ref<const Eigen::VectorXd>& q,
                          const ValidityOptions& options);

/// min(sd(q), cap): the signed distance when it is below `cap`, else `cap`. Cheaper than the
/// exact distance when `cap` is small (pairs whose bounding volumes are farther than cap are not
/// measured). cap = +infinity gives the exact minimum signed distance.
double signedDistanceUpTo(const checker::World& world, const Eigen::Ref<const Eigen::VectorXd>& q, double cap);

/// The signed distance split by what the robot is near: `world` the minimum over robot-scene and
/// robot-obstacle pairs, `self` over robot self pairs, each capped like signedDistanceUpTo.
/// Objectives use it because an arm's wrist links (e.g. link5 and link7 of a 7-DOF arm) sit a few
/// centimetres apart in every configuration: a clearance goal on the overall minimum would be
/// unreachable and penalise every path alike.
struct SplitDistance {
  double world = 0.0;
  double self = 0.0;
};
/// With `selfPairs` false only the robot-world pairs are measured and `self` is +infinity.
SplitDistance splitSignedDistanceUpTo(const checker::World& world, const Eigen::Ref<const Eigen::VectorXd>& q,
                                      double cap, bool selfPairs = true);

}  // namespace deepcheck::planners
