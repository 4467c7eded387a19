#pragma once
// The joint space of a robots::RobotModel as an OMPL state space, and how states of any state
// space the library is given map to configurations.
//
// makeStateSpace: one value per variable of the model (robot_model.h: the revolute, continuous
// and prismatic joints that are not mimic joints, in joint order), named after the variable.
//   - No variable wraps (robots/joint_angles.h): a RealVectorStateSpace bounded by the URDF
//     limits, its distance Euclidean.
//   - Some variables wrap (continuous joints): a CompoundStateSpace, in variable order, of an
//     SO2StateSpace per wrapping variable (named after it) and a bounded RealVectorStateSpace per
//     run of the other variables (its dimensions named after them). ScopedState's values and
//     indices are then still the variables in order. An SO2 value lies in OMPL's [-pi, pi): the
//     mappings write the angle pi as -pi and read it back as pi (configurations are in (-pi, pi]);
//     distances, interpolation and motions take the short way round: from 3.0 to -3.0 rad is
//     0.283 rad through pi, not 6 rad through 0. The distance is OMPL's compound distance, the
//     SUM of the components' distances (Euclidean within a RealVector run, |wrapped difference|
//     per SO2); each component's valid segment is the segment fraction of its own extent (pi for
//     SO2).
//   OMPL 1.5's PathLengthDirectInfSampler accepts only RealVector, SE2 and SE3 spaces: the
//   informed planners (BIT*, InformedRRT*) with OMPL's PathLengthOptimizationObjective cannot
//   plan on such a compound; makePathLengthObjective (objectives.h) samples it uniformly.

// StateMapping: everything in deepcheck::planners that reads a configuration from an OMPL state
// or writes one into it (validity checker, motion validator, samplers, objectives, push-out of
// the endpoints, path tools) goes through the StateMapping of its validity checker.
// makeStateMapping(space, robot) understands, and otherwise REJECTS with std::invalid_argument
// naming the space and its layout (an SE3 or SO3 component, a discrete space, MoveIt's
// model-based spaces, a value count that is not the robot's number of variables):
//   - a RealVectorStateSpace (makeStateSpace's): one value per dimension;
//   - a CompoundStateSpace, nested ones included, whose leaves are RealVectorStateSpaces and
//     SO2StateSpaces: one value per RealVector dimension, one angular value per SO2 space (a
//     continuous joint, or a revolute joint planned with wrap-around), in depth-first order.
// Which value is which variable: by name when every value is named after a variable (the
// RealVector dimension's name, the SO2 space's name; e.g. MoveIt's variable order, which may
// differ from the URDF's), else in order (value i is variable i). Names that match some
// variables but not all are rejected, naming the others. Any other layout takes a user-supplied
// conversion: StateMapping::custom.
//
// Motions between two states are straight lines in configuration space, the angular variables
// taking the short way round (through +-pi) and wrapped back into (-pi, pi]: how OMPL's
// RealVector and SO2 spaces interpolate. A custom mapping must describe a space that
// interpolates that way too (mark its angular variables), or the motion validator certifies
// another motion than the planner's.
//
// Units: radians (revolute, continuous), metres (prismatic).
#include "deepcheck/robots/robot_model.h"

#include <Eigen/Core>

#include <ompl/base/State.h>
#include <ompl/base/StateSpace.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace deepcheck::planners {

/// The joint space of `model` (see the header comment): a RealVectorStateSpace when no variable
/// wraps, else a compound with SO2 components. The longest valid segment fraction is set to
/// tol::kDefaultSegmentFraction. Throws std::invalid_argument, naming the variable and the values,
/// when the model has no variable or a bounded variable's limits are not finite with lower < upper.
ompl::base::StateSpacePtr makeStateSpace(const robots::RobotModel& model);

/// A read-only view of a state of a RealVectorStateSpace of dimension n (no copy): for the spaces
/// of makeStateSpace of robots without wrapping variables only (any other layout: StateMapping).
inline Eigen::Map<const Eigen::VectorXd> mapState(const ompl::base::State* state, int n) {
  return {state->as<ompl::base::RealVectorStateSpace::StateType>()->values, n};
}
/// A writable view of a state.
inline Eigen::Map<Eigen::VectorXd> mapState(ompl::base::State* state, int n) {
  return {state->as<ompl::base::RealVectorStateSpace::StateType>()->values, n};
}

/// Copies q into `state` (a state of a RealVectorStateSpace of dimension q.size(), as made by
/// makeStateSpace for a robot without wrapping variables; any other layout: StateMapping::toState).
void copyToState(const Eigen::Ref<const Eigen::VectorXd>& q, ompl::base::State* state);

/// States of one state space as configurations of one robot, and back (see the header comment).
/// Copyable; const methods are thread safe.
class StateMapping {
 public:
  /// Writes the configuration of a state into q (already of numVariables() values).
  using ToConfiguration = std::function<void(const ompl::base::State*, Eigen::Ref<Eigen::VectorXd>)>;
  /// Writes configuration q into a state.
  using ToState = std::function<void(const Eigen::Ref<const Eigen::VectorXd>&, ompl::base::State*)>;

  /// A user-supplied mapping of `numVariables` (>= 1) values. `angular[v]` marks the variables
  /// the space treats as angles on a circle (motions take the short way round, values wrap into
  /// (-pi, pi]); empty: none. `description` names the mapping in messages. Throws
  /// std::invalid_argument for a count < 1, empty functions or an `angular` of another size.
  static StateMapping custom(int numVariables, ToConfiguration toConfiguration, ToState toState,
                             std::vector<bool> angular = {}, std::string description = "custom state mapping");

  /// The values of a RealVectorStateSpace of n dimensions, in order (no angular variable).
  static StateMapping realVector(int n, std::string description);

  int numVariables() const { return n_; }
  /// The configuration of `state`.
  Eigen::VectorXd configuration(const ompl::base::State* state) const;
  /// Writes q (numVariables() values) into `state`.
  void toState(const Eigen::Ref<const Eigen::VectorXd>& q, ompl::base::State* state) const;
  /// q2 - q1, the angular variables the short way round (in [-pi, pi]).
  Eigen::VectorXd displacement(const Eigen::Ref<const Eigen::VectorXd>& q1,
                               const Eigen::Ref<const Eigen::VectorXd>& q2) const;
  /// q + s dq, the angular variables normalized into (-pi, pi]: the state at fraction s of the motion
  /// from q along displacement dq.
  Eigen::VectorXd along(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& dq,
                        double s) const;
  const std::vector<bool>& angular() const { return angular_; }
  /// The layout, for messages (e.g. "RealVector 'arm_joint_space' (7)").
  const std::string& description() const { return description_; }

 private:
  friend StateMapping makeStateMapping(const ompl::base::StateSpace& space, const robots::RobotModel& robot);
  StateMapping() = default;

  int n_ = 0;
  ToConfiguration toConfiguration_;
  ToState toState_;
  std::vector<bool> angular_;
  bool anyAngular_ = false;
  std::string description_;
};

/// The mapping of `space` for `robot` (see the header comment); throws std::invalid_argument
/// naming the space and its layout when the layout is not understood.
StateMapping makeStateMapping(const ompl::base::StateSpace& space, const robots::RobotModel& robot);

}  // namespace deepcheck::planners
