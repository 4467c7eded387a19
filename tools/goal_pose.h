#pragma once
// `deepcheck plan`'s pose goal on the command line:
//   --goal-pose LINK x y z qx qy qz qw [--position-tol M | --position-box X Y Z] [--orientation-tol RAD]
// A reader of its own (not in plan.cpp) so that the fuzz harness fuzz_goal_pose runs the code the
// program runs.

#include "deepcheck/robots/tolerances.h"

#include <Eigen/Geometry>

#include <optional>
#include <string>
#include <vector>

namespace deepcheck::tools {

/// A quaternion of --goal-pose whose norm is below this (dimensionless) has no direction to
/// normalize: zero, or so small that its direction is rounding noise. Any other is normalized.
constexpr double kMinQuaternionNorm = 1e-6;

/// `--goal-pose LINK x y z qx qy qz qw [--position-tol m] [--orientation-tol rad]`.
struct GoalPoseArg {
  std::string link;
  Eigen::Isometry3d X_WT = Eigen::Isometry3d::Identity();
  double positionTolerance = robots::tol::kIkPositionTolerance;        ///< metres
  double orientationTolerance = robots::tol::kIkOrientationTolerance;  ///< radians
  std::optional<Eigen::Vector3d> positionBox;                          ///< edge lengths, metres (--position-box)
};

/// Removes --goal-pose and its tolerances from `args`; empty when --goal-pose is absent (then the
/// tolerances are an error). Throws UsageError (common.h) for a missing or bad value: a link and 7
/// finite numbers, a quaternion of norm at least kMinQuaternionNorm (then normalized; MoveIt's
/// order x y z w), tolerances and edge lengths > 0, --position-tol and --position-box not both.
std::optional<GoalPoseArg> takeGoalPose(std::vector<std::string>& args);

}  // namespace deepcheck::tools
