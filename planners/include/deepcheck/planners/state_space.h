#pragma once
// The joint space of a robots::RobotModel as an OMPL state space.
//
// One real dimension per variable of the model (robot_model.h: the revolute, continuous and
// prismatic joints that are not mimic joints, in joint order), named after the joint, bounded by
// the URDF limits. Continuous joints get the model's [-pi, pi] and are NOT wrapped around: the
// space is a box, the distance Euclidean (a motion from -3 to 3 rad goes the long way). Planning
// on such a joint is correct but may find longer paths than an SO(2) dimension would.
//
// A state's values are the configuration q in the model's variable order; toVector / mapState
// convert without reordering. Units: radians (revolute, continuous), metres (prismatic).

#include "deepcheck/robots/robot_model.h"

#include <Eigen/Core>

#include <ompl/base/State.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <memory>

namespace deepcheck::planners {

/// A RealVectorStateSpace with one bounded, named dimension per variable of `model`. The longest
/// valid segment fraction is set to tol::kDefaultSegmentFraction. Throws std::invalid_argument,
/// naming the variable and the values, when the model has no variable or a variable's limits are
/// not finite with lower < upper.
std::shared_ptr<ompl::base::RealVectorStateSpace> makeStateSpace(const robots::RobotModel& model);

/// A read-only view of a state of a RealVectorStateSpace of dimension n (no copy).
inline Eigen::Map<const Eigen::VectorXd> mapState(const ompl::base::State* state, int n) {
  return {state->as<ompl::base::RealVectorStateSpace::StateType>()->values, n};
}
/// A writable view of a state.
inline Eigen::Map<Eigen::VectorXd> mapState(ompl::base::State* state, int n) {
  return {state->as<ompl::base::RealVectorStateSpace::StateType>()->values, n};
}

/// Copies q into `state` (a state of a RealVectorStateSpace of dimension q.size()).
void copyToState(const Eigen::Ref<const Eigen::VectorXd>& q, ompl::base::State* state);

}  // namespace deepcheck::planners
