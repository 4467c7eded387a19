// StateMapping: states of RealVector / SO2 / compound state spaces as robot configurations (see
// state_space.h).

#include "deepcheck/planners/state_space.h"

#include "deepcheck/robots/joint_angles.h"

#include <ompl/base/StateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>

#include <boost/math/constants/constants.hpp>

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace deepcheck::planners {

namespace {

namespace ob = ompl::base;

constexpr double kPi = boost::math::double_constants::pi;

/// One value of a state: the component path through compound states, then a RealVector index
/// (angular false) or an SO2 value (angular true).
struct Leaf {
  std::vector<unsigned int> components;
  unsigned int index = 0;
  bool angular = false;
  std::string name;
  int variable = -1;  ///< which robot variable it holds
};

std::string typeName(const ob::StateSpace& space) {
  switch (space.getType()) {
    case ob::STATE_SPACE_REAL_VECTOR:
      return "RealVector";
    case ob::STATE_SPACE_SO2:
      return "SO2";
    case ob::STATE_SPACE_SO3:
      return "SO3";
    case ob::STATE_SPACE_SE2:
      return "SE2";
    case ob::STATE_SPACE_SE3:
      return "SE3";
    case ob::STATE_SPACE_TIME:
      return "Time";
    case ob::STATE_SPACE_DISCRETE:
      return "Discrete";
    default:
      return space.isCompound() ? "Compound" : "unknown type";
  }
}

/// The layout of `space` for messages: type, name, dimension, and the components of a compound.
std::string layout(const ob::StateSpace& space) {
  std::string text =
      typeName(space) + " '" + space.getName() + "' (dimension " + std::to_string(space.getDimension()) + ")";
  if (const auto* compound = dynamic_cast<const ob::CompoundStateSpace*>(&space)) {
    text += " [";
    for (unsigned int i = 0; i < compound->getSubspaceCount(); ++i) {
      text += (i > 0 ? ", " : "") + layout(*compound->getSubspace(i));
    }
    text += "]";
  }
  return text;
}

/// Appends the values of `space` in depth-first order; false at a space that is neither
/// RealVector, SO2 nor a compound (`unknown` names it).
bool collectLeaves(const ob::StateSpace& space, std::vector<unsigned int>& components, std::vector<Leaf>& leaves,
                   std::string& unknown) {
  if (const auto* real = dynamic_cast<const ob::RealVectorStateSpace*>(&space)) {
    for (unsigned int d = 0; d < real->getDimension(); ++d) {
      leaves.push_back(Leaf{components, d, false, real->getDimensionName(d), -1});
    }
    return true;
  }
  if (dynamic_cast<const ob::SO2StateSpace*>(&space) != nullptr) {
    leaves.push_back(Leaf{components, 0, true, space.getName(), -1});
    return true;
  }
  if (const auto* compound = dynamic_cast<const ob::CompoundStateSpace*>(&space)) {
    for (unsigned int i = 0; i < compound->getSubspaceCount(); ++i) {
      components.push_back(i);
      const bool ok = collectLeaves(*compound->getSubspace(i), components, leaves, unknown);
      components.pop_back();
      if (!ok) return false;
    }
    return true;
  }
  unknown = typeName(space) + " '" + space.getName() + "'";
  return false;
}

/// Which variable each leaf holds: by name when every leaf is named after a variable, else in
/// order; empty string when fine, else the problem.
std::string assignVariables(std::vector<Leaf>& leaves, const robots::RobotModel& robot) {
  std::map<std::string, int> variables;
  for (int v = 0; v < robot.numVariables(); ++v) variables[robot.variableNames()[static_cast<std::size_t>(v)]] = v;
  std::string unmatched;
  int matched = 0;
  for (const Leaf& leaf : leaves) {
    if (variables.count(leaf.name) != 0) {
      ++matched;
    } else {
      unmatched += (unmatched.empty() ? "'" : ", '") + leaf.name + "'";
    }
  }
  if (matched == 0) {
    for (std::size_t i = 0; i < leaves.size(); ++i) leaves[i].variable = static_cast<int>(i);
    return "";
  }
  if (!unmatched.empty()) {
    return "some values are named after variables of robot '" + robot.name() + "' and others are not (" + unmatched +
           ")";
  }
  std::vector<bool> taken(leaves.size(), false);
  for (Leaf& leaf : leaves) {
    leaf.variable = variables[leaf.name];
    if (taken[static_cast<std::size_t>(leaf.variable)]) return "variable '" + leaf.name + "' is held twice";
    taken[static_cast<std::size_t>(leaf.variable)] = true;
  }
  return "";
}

const ob::State* component(const ob::State* state, const std::vector<unsigned int>& components) {
  for (unsigned int i : components) state = state->as<ob::CompoundState>()->components[i];
  return state;
}
ob::State* component(ob::State* state, const std::vector<unsigned int>& components) {
  for (unsigned int i : components) state = state->as<ob::CompoundState>()->components[i];
  return state;
}

/// The short way from one angle to another, in [-pi, pi]: x - 2 pi k, k the integer nearest
/// x / (2 pi). A difference of exactly +-pi keeps its sign (std::remainder's tie goes to k = 0), so
/// it goes the way OMPL's SO2StateSpace::interpolate goes (directly when |difference| <= pi); the
/// validator must certify the motion the planner takes, so this is not normalizeAngle's (-pi, pi].
double shortestTurn(double x) { return std::remainder(x, 2.0 * kPi); }

/// An angle as OMPL's SO2StateSpace holds it, in [-pi, pi): normalizeAngle's (-pi, pi] with pi
/// written as -pi, the same angle (OMPL's satisfiesBounds refuses pi, and its planners skip such a
/// start). configuration() maps it back with normalizeAngle.
double so2Value(double x) {
  const double angle = robots::normalizeAngle(x);
  return angle == kPi ? -kPi : angle;
}

}  // namespace

StateMapping StateMapping::custom(int numVariables, ToConfiguration toConfiguration, ToState toState,
                                  std::vector<bool> angular, std::string description) {
  if (numVariables < 1) {
    throw std::invalid_argument("StateMapping::custom: " + description + " needs at least one variable, got " +
                                std::to_string(numVariables));
  }
  if (!toConfiguration || !toState) {
    throw std::invalid_argument("StateMapping::custom: " + description + " needs both conversion functions");
  }
  if (!angular.empty() && angular.size() != static_cast<std::size_t>(numVariables)) {
    throw std::invalid_argument("StateMapping::custom: " + description + " marks " + std::to_string(angular.size()) +
                                " variables angular or not, for " + std::to_string(numVariables) + " variables");
  }
  StateMapping mapping;
  mapping.n_ = numVariables;
  mapping.toConfiguration_ = std::move(toConfiguration);
  mapping.toState_ = std::move(toState);
  mapping.angular_ = angular.empty() ? std::vector<bool>(static_cast<std::size_t>(numVariables), false) : angular;
  for (bool a : mapping.angular_) mapping.anyAngular_ = mapping.anyAngular_ || a;
  mapping.description_ = std::move(description);
  return mapping;
}

StateMapping StateMapping::realVector(int n, std::string description) {
  return custom(
      n, [n](const ob::State* s, Eigen::Ref<Eigen::VectorXd> q) { q = mapState(s, n); },
      [n](const Eigen::Ref<const Eigen::VectorXd>& q, ob::State* s) { mapState(s, n) = q; }, {},
      std::move(description));
}

Eigen::VectorXd StateMapping::configuration(const ompl::base::State* state) const {
  Eigen::VectorXd q(n_);
  toConfiguration_(state, q);
  return q;
}

void StateMapping::toState(const Eigen::Ref<const Eigen::VectorXd>& q, ompl::base::State* state) const {
  if (q.size() != n_) {
    throw std::invalid_argument("StateMapping (" + description_ + "): a configuration of " + std::to_string(q.size()) +
                                " values for " + std::to_string(n_) + " variables");
  }
  toState_(q, state);
}

Eigen::VectorXd StateMapping::displacement(const Eigen::Ref<const Eigen::VectorXd>& q1,
                                           const Eigen::Ref<const Eigen::VectorXd>& q2) const {
  Eigen::VectorXd dq = q2 - q1;
  if (anyAngular_) {
    for (int v = 0; v < n_; ++v) {
      if (angular_[static_cast<std::size_t>(v)]) dq[v] = shortestTurn(dq[v]);
    }
  }
  return dq;
}

Eigen::VectorXd StateMapping::along(const Eigen::Ref<const Eigen::VectorXd>& q,
                                    const Eigen::Ref<const Eigen::VectorXd>& dq, double s) const {
  Eigen::VectorXd out = q + s * dq;
  if (anyAngular_) {
    for (int v = 0; v < n_; ++v) {
      if (angular_[static_cast<std::size_t>(v)]) out[v] = robots::normalizeAngle(out[v]);
    }
  }
  return out;
}

StateMapping makeStateMapping(const ompl::base::StateSpace& space, const robots::RobotModel& robot) {
  const std::string what = "state space " + layout(space);
  std::vector<Leaf> leaves;
  std::vector<unsigned int> components;
  std::string unknown;
  const auto reject = [&](const std::string& why) {
    return std::invalid_argument(
        "StateMapping: " + what + " for robot '" + robot.name() + "': " + why +
        ". Understood: a RealVectorStateSpace, or compounds of RealVector and SO2 spaces, with one value per "
        "variable (" +
        std::to_string(robot.numVariables()) + "); any other layout needs a StateMapping::custom");
  };
  if (!collectLeaves(space, components, leaves, unknown))
    throw reject("its component " + unknown + " is not understood");
  if (leaves.size() != static_cast<std::size_t>(robot.numVariables())) {
    throw reject("it holds " + std::to_string(leaves.size()) + " values");
  }
  const std::string problem = assignVariables(leaves, robot);
  if (!problem.empty()) throw reject(problem);

  std::vector<bool> angular(leaves.size(), false);
  bool identity = true;
  for (std::size_t i = 0; i < leaves.size(); ++i) {
    angular[static_cast<std::size_t>(leaves[i].variable)] = leaves[i].angular;
    identity =
        identity && leaves[i].components.empty() && !leaves[i].angular && leaves[i].variable == static_cast<int>(i);
  }
  const int n = robot.numVariables();
  if (identity) {  // a plain RealVectorStateSpace in variable order: copy the values
    return StateMapping::realVector(n, what);
  }
  return StateMapping::custom(
      n,
      [leaves](const ob::State* s, Eigen::Ref<Eigen::VectorXd> q) {
        for (const Leaf& leaf : leaves) {
          const ob::State* c = component(s, leaf.components);
          q[leaf.variable] = leaf.angular ? robots::normalizeAngle(c->as<ob::SO2StateSpace::StateType>()->value)
                                          : c->as<ob::RealVectorStateSpace::StateType>()->values[leaf.index];
        }
      },
      [leaves](const Eigen::Ref<const Eigen::VectorXd>& q, ob::State* s) {
        for (const Leaf& leaf : leaves) {
          ob::State* c = component(s, leaf.components);
          if (leaf.angular) {
            c->as<ob::SO2StateSpace::StateType>()->value = so2Value(q[leaf.variable]);
          } else {
            c->as<ob::RealVectorStateSpace::StateType>()->values[leaf.index] = q[leaf.variable];
          }
        }
      },
      angular, what);
}

}  // namespace deepcheck::planners
