// RobotModel::withLockedVariables and lockAllBut: a copy of a model with some variables held at
// given values (robot_model.h, "Locked joints").

#include "deepcheck/robots/format_number.h"
#include "deepcheck/robots/robot_model.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace deepcheck::robots {
namespace {

/// X_JC of a moving joint at `value` (rad or m).
Eigen::Isometry3d jointMotion(const Joint& joint, double value) {
  Eigen::Isometry3d X_JC = Eigen::Isometry3d::Identity();
  if (joint.type == JointType::Prismatic) {
    X_JC.translation() = value * joint.axis;
  } else {
    X_JC.linear() = Eigen::AngleAxisd(value, joint.axis).toRotationMatrix();
  }
  return X_JC;
}

/// Why `name` cannot be locked: it is no variable of `model`.
std::string notAVariable(const RobotModel& model, const std::string& name) {
  const int j = model.jointIndex(name);
  if (j < 0) return "it is no joint of the robot";
  const Joint& joint = model.joint(j);
  if (joint.locked) return "it is already locked at " + formatNumber(joint.lockedValue);
  if (joint.isMimic()) {
    return "it is a mimic joint; lock '" + model.variableNames()[static_cast<std::size_t>(joint.variable)] +
           "', which it follows";
  }
  return "it is a fixed joint";
}

}  // namespace

RobotModel RobotModel::withLockedVariables(const std::map<std::string, double>& values) const {
  const std::string context = "robot '" + name_ + "' (" + source_ + "): cannot lock ";
  std::vector<bool> lock(static_cast<std::size_t>(numVariables()), false);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(numVariables());
  for (const auto& [name, value] : values) {
    const int v = variableIndex(name);
    if (v < 0) throw std::invalid_argument(context + "'" + name + "': " + notAVariable(*this, name));
    if (!std::isfinite(value) || value < lower_[v] || value > upper_[v]) {
      throw std::invalid_argument(context + "'" + name + "' at " + formatNumber(value) + ": outside its limits [" +
                                  formatNumber(lower_[v]) + ", " + formatNumber(upper_[v]) + "]");
    }
    lock[static_cast<std::size_t>(v)] = true;
    q[v] = value;
  }

  RobotModel out = *this;
  std::vector<int> renumbered(static_cast<std::size_t>(numVariables()), -1);
  out.variableJoints_.clear();
  out.variableNames_.clear();
  std::vector<double> lower, upper;
  for (int v = 0; v < numVariables(); ++v) {
    if (lock[static_cast<std::size_t>(v)]) continue;
    renumbered[static_cast<std::size_t>(v)] = static_cast<int>(out.variableJoints_.size());
    out.variableJoints_.push_back(variableJoints_[static_cast<std::size_t>(v)]);
    out.variableNames_.push_back(variableNames_[static_cast<std::size_t>(v)]);
    lower.push_back(lower_[v]);
    upper.push_back(upper_[v]);
  }
  out.lower_ = Eigen::Map<const Eigen::VectorXd>(lower.data(), static_cast<Eigen::Index>(lower.size()));
  out.upper_ = Eigen::Map<const Eigen::VectorXd>(upper.data(), static_cast<Eigen::Index>(upper.size()));

  for (Joint& joint : out.joints_) {
    if (joint.variable < 0) continue;
    if (!lock[static_cast<std::size_t>(joint.variable)]) {
      joint.variable = renumbered[static_cast<std::size_t>(joint.variable)];
      continue;
    }
    const double value = joint.multiplier * q[joint.variable] + joint.offset;
    joint.X_PJ = joint.X_PJ * jointMotion(joint, value);
    joint.type = JointType::Fixed;
    joint.locked = true;
    joint.lockedValue = value;
    joint.lower = joint.upper = 0.0;
    joint.variable = -1;
    joint.multiplier = 1.0;
    joint.offset = 0.0;
    joint.mimicJoint = -1;
  }
  return out;
}

RobotModel lockAllBut(const RobotModel& model, const std::vector<int>& keep,
                      const std::map<std::string, double>& values, const std::string& keepName) {
  std::vector<bool> kept(static_cast<std::size_t>(model.numVariables()), false);
  for (int v : keep) {
    if (v < 0 || v >= model.numVariables()) {
      throw std::invalid_argument("robot '" + model.name() + "': " + keepName + " has variable index " +
                                  std::to_string(v) + ", the robot has " + std::to_string(model.numVariables()));
    }
    kept[static_cast<std::size_t>(v)] = true;
  }
  std::map<std::string, double> locked = values;
  const Eigen::VectorXd q0 = model.defaultConfiguration();
  for (int v = 0; v < model.numVariables(); ++v) {
    const std::string& name = model.variableNames()[static_cast<std::size_t>(v)];
    if (kept[static_cast<std::size_t>(v)] && values.count(name) > 0) {
      throw std::invalid_argument("robot '" + model.name() + "': cannot lock '" + name + "': it is a variable of " +
                                  keepName);
    }
    if (!kept[static_cast<std::size_t>(v)]) locked.emplace(name, q0[v]);
  }
  return model.withLockedVariables(locked);
}

}  // namespace deepcheck::robots
