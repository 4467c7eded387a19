#include "deepcheck/robots/joint_angles.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace deepcheck::robots {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;  // exact: twice a double

/// The joint turns by a whole number of turns when its variable does.
bool turnsWithWholeTurns(const Joint& joint) {
  const double m = joint.multiplier;
  return joint.type == JointType::Continuous && m != 0.0 && m == std::round(m);
}

}  // namespace

double normalizeAngle(double x) {
  if (!std::isfinite(x)) return std::numeric_limits<double>::quiet_NaN();
  // std::remainder is exact and lands in [-pi, pi]; its ties (x an odd multiple of pi) go to
  // either end, so -pi is moved to pi to make the interval half open.
  const double r = std::remainder(x, kTwoPi);
  return r <= -M_PI ? r + kTwoPi : r;
}

bool isWrappingVariable(const RobotModel& model, int v) {
  if (v < 0 || v >= model.numVariables()) {
    throw std::invalid_argument("isWrappingVariable: robot '" + model.name() + "' has no variable " +
                                std::to_string(v) + " (it has " + std::to_string(model.numVariables()) + ")");
  }
  if (model.joint(model.variableJoint(v)).type != JointType::Continuous) return false;
  for (const Joint& joint : model.joints()) {
    if (joint.variable == v && !turnsWithWholeTurns(joint)) return false;
  }
  return true;
}

std::vector<bool> wrappingVariables(const RobotModel& model) {
  std::vector<bool> out(static_cast<std::size_t>(model.numVariables()));
  for (int v = 0; v < model.numVariables(); ++v) out[static_cast<std::size_t>(v)] = isWrappingVariable(model, v);
  return out;
}

void normalizeWrappingVariables(const RobotModel& model, Eigen::Ref<Eigen::VectorXd> q) {
  if (q.size() != model.numVariables()) {
    throw std::invalid_argument("normalizeWrappingVariables: " + std::to_string(q.size()) + " values for robot '" +
                                model.name() + "' with " + std::to_string(model.numVariables()) + " variables");
  }
  for (int v = 0; v < model.numVariables(); ++v) {
    if (isWrappingVariable(model, v)) q[v] = normalizeAngle(q[v]);
  }
}

}  // namespace deepcheck::robots
