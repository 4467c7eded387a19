#pragma once
// Pose goals: a link of the robot at a pose X_WT (within a position and an orientation tolerance)
// instead of a joint vector, by inverse kinematics (robots/inverse_kinematics.h) whose solutions
// must also be valid for the planner's validity checker (collision free, within the URDF joint
// limits, with its safety margin). States are read and written through the checker's
// StateMapping (state_space.h).
//
//   auto goal = std::make_shared<PoseGoal>(ss->getSpaceInformation(), "flange", X_WT, options);
//   ss->setGoal(goal);  // after setStartState; any planner, bidirectional ones included
//   ss->solve(1.0);
//
// PoseGoal is an ompl::base::GoalLazySamples: a thread started with the goal solves the IK again
// and again (seeds options.ik.seed, +1, +2, ...) and adds every valid solution as a goal state,
// so RRTConnect, BiEST and the like grow trees from them; it stops after
// PoseGoalOptions::maxGoalStates solutions or maxFailedSamples IK calls in a row without a new one.
// isSatisfied(state) is forward kinematics: the link within both tolerances at that state.
// distanceGoal(state) is the normalized pose error (robots::PoseError::normalized: dimensionless,
// at most 1 exactly when satisfied), so OMPL's approximate solutions are ranked by pose error; the
// goal's threshold is 1.
//
// Errors: std::invalid_argument naming the value (unknown link, bad pose or options; a space
// whose validity checker is not a deepcheck StateValidityChecker).

#include "deepcheck/planners/tolerances.h"
#include "deepcheck/planners/validity_checker.h"
#include "deepcheck/robots/inverse_kinematics.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <ompl/base/goals/GoalLazySamples.h>

#include <atomic>
#include <memory>
#include <string>

namespace deepcheck::planners {

/// IK solved with the checker's isValid(q) as acceptance test: converged() only for a
/// configuration that reaches the pose and is valid (collision free, within the bounds).
robots::IkResult solveCollisionFree(const StateValidityChecker& checker, const std::string& link,
                                    const Eigen::Isometry3d& X_WT, const robots::IkOptions& options = {});

struct PoseGoalOptions {
  /// Tolerances of the goal, IK iterations and restarts, the seed of the first sample.
  robots::IkOptions ik;
  int maxGoalStates = tol::kPoseGoalMaxStates;
  int maxFailedSamples = tol::kPoseGoalMaxFailedSamples;
  double minSeparation = tol::kPoseGoalMinSeparation;  ///< rad, between goal states
};

class PoseGoal : public ompl::base::GoalLazySamples {
 public:
  /// `si`'s validity checker must be a StateValidityChecker; its world's robot is the model. The
  /// sampling thread starts here.
  PoseGoal(const ompl::base::SpaceInformationPtr& si, const std::string& link, const Eigen::Isometry3d& X_WT,
           const PoseGoalOptions& options = {});
  /// Stops the sampling thread before the members it uses go.
  ~PoseGoal() override;

  bool isSatisfied(const ompl::base::State* state) const override;
  bool isSatisfied(const ompl::base::State* state, double* distance) const override;
  double distanceGoal(const ompl::base::State* state) const override;

  /// The pose error of `state` (tolerances of options.ik).
  robots::PoseError poseError(const ompl::base::State* state) const;
  const Eigen::Isometry3d& targetPose() const { return X_WT_; }
  const std::string& linkName() const { return linkName_; }
  /// IK calls made by the sampling thread so far, and how many found no valid solution.
  int ikCalls() const { return ikCalls_.load(); }
  int ikFailures() const { return ikFailures_.load(); }

 private:
  bool sample(ompl::base::State* state);

  std::shared_ptr<const StateValidityChecker> checker_;
  std::string linkName_;
  int link_ = -1;
  Eigen::Isometry3d X_WT_;
  PoseGoalOptions options_;
  std::atomic<int> ikCalls_{0};
  std::atomic<int> ikFailures_{0};
  // Used by the sampling thread only.
  int failuresInRow_ = 0;            // IK calls since the last new goal state
  int stateCountAtLastSample_ = -1;  // goal states when the last solution was handed over
};

}  // namespace deepcheck::planners
