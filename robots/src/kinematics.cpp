#include "deepcheck/robots/kinematics.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace deepcheck::robots {
namespace {

/// X_JC for a joint at `value`.
Eigen::Isometry3d jointMotion(const Joint& joint, double value) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  switch (joint.type) {
    case JointType::Fixed: break;
    case JointType::Revolute:
    case JointType::Continuous: X.linear() = Eigen::AngleAxisd(value, joint.axis).toRotationMatrix(); break;
    case JointType::Prismatic: X.translation() = value * joint.axis; break;
  }
  return X;
}

void checkLink(const RobotModel& model, const std::vector<Eigen::Isometry3d>& X_WL, int link) {
  if (link < 0 || link >= model.numLinks()) {
    std::ostringstream msg;
    msg << "robot '" << model.name() << "': link index " << link << " out of range [0, "
        << model.numLinks() << ")";
    throw std::invalid_argument(msg.str());
  }
  if (static_cast<int>(X_WL.size()) != model.numLinks()) {
    std::ostringstream msg;
    msg << "robot '" << model.name() << "': " << X_WL.size() << " link poses given, the robot has "
        << model.numLinks() << " links";
    throw std::invalid_argument(msg.str());
  }
}

/// Adds the contribution of every moving joint between the root and `link` to the columns of
/// J (angular rows only when `angular`), for the point p_WQ.
template <typename AngularBlock, typename LinearBlock>
void accumulate(const RobotModel& model, const std::vector<Eigen::Isometry3d>& X_WL, int link,
                const Eigen::Vector3d& p_WQ, AngularBlock* angular, LinearBlock& linear) {
  for (int l = link; model.link(l).parentJoint >= 0; l = model.link(l).parentLink) {
    const Joint& joint = model.joint(model.link(l).parentJoint);
    if (!joint.moves()) continue;
    // The axis is the same in J and C; the child origin lies on a revolute axis.
    const Eigen::Isometry3d& X_WC = X_WL[joint.childLink];
    const Eigen::Vector3d a_W = X_WC.linear() * joint.axis;
    if (joint.type == JointType::Prismatic) {
      linear.col(joint.variable) += joint.multiplier * a_W;
    } else {
      linear.col(joint.variable) += joint.multiplier * a_W.cross(p_WQ - X_WC.translation());
      if (angular != nullptr) angular->col(joint.variable) += joint.multiplier * a_W;
    }
  }
}

}  // namespace

void checkConfiguration(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& q) {
  if (q.size() != model.numVariables()) {
    std::ostringstream msg;
    msg << "robot '" << model.name() << "': configuration has " << q.size()
        << " values, the robot has " << model.numVariables() << " variables (";
    for (int v = 0; v < model.numVariables(); ++v) {
      msg << (v ? ", " : "") << model.variableNames()[v];
    }
    msg << ")";
    throw std::invalid_argument(msg.str());
  }
  for (int v = 0; v < q.size(); ++v) {
    if (!std::isfinite(q[v])) {
      std::ostringstream msg;
      msg << "robot '" << model.name() << "': configuration value q[" << v << "] ("
          << model.variableNames()[v] << ") is " << q[v];
      throw std::invalid_argument(msg.str());
    }
  }
}

void forwardKinematics(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                       std::vector<Eigen::Isometry3d>& X_WL) {
  checkConfiguration(model, q);
  if (static_cast<int>(X_WL.size()) != model.numLinks()) X_WL.resize(model.numLinks());
  X_WL[0] = model.basePose();
  // Joint i is the parent joint of link i + 1, and parents precede children.
  for (int i = 0; i < model.numJoints(); ++i) {
    const Joint& joint = model.joint(i);
    const double value =
        joint.moves() ? joint.multiplier * q[joint.variable] + joint.offset : 0.0;
    X_WL[joint.childLink] = X_WL[joint.parentLink] * joint.X_PJ * jointMotion(joint, value);
  }
}

std::vector<Eigen::Isometry3d> forwardKinematics(const RobotModel& model,
                                                 const Eigen::Ref<const Eigen::VectorXd>& q) {
  std::vector<Eigen::Isometry3d> X_WL;
  forwardKinematics(model, q, X_WL);
  return X_WL;
}

void pointJacobian(const RobotModel& model, const std::vector<Eigen::Isometry3d>& X_WL, int link,
                   const Eigen::Vector3d& p_LQ, Eigen::Matrix3Xd& J_WQ) {
  checkLink(model, X_WL, link);
  if (J_WQ.cols() != model.numVariables()) J_WQ.resize(3, model.numVariables());
  J_WQ.setZero();
  const Eigen::Vector3d p_WQ = X_WL[link] * p_LQ;
  accumulate<Eigen::Matrix3Xd>(model, X_WL, link, p_WQ, nullptr, J_WQ);
}

Eigen::Matrix3Xd pointJacobian(const RobotModel& model, const std::vector<Eigen::Isometry3d>& X_WL,
                               int link, const Eigen::Vector3d& p_LQ) {
  Eigen::Matrix3Xd J;
  pointJacobian(model, X_WL, link, p_LQ, J);
  return J;
}

Eigen::Matrix3Xd pointJacobian(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                               int link, const Eigen::Vector3d& p_LQ) {
  return pointJacobian(model, forwardKinematics(model, q), link, p_LQ);
}

void spatialJacobian(const RobotModel& model, const std::vector<Eigen::Isometry3d>& X_WL, int link,
                     const Eigen::Vector3d& p_LQ, Eigen::Matrix<double, 6, Eigen::Dynamic>& J) {
  checkLink(model, X_WL, link);
  if (J.cols() != model.numVariables()) J.resize(6, model.numVariables());
  J.setZero();
  const Eigen::Vector3d p_WQ = X_WL[link] * p_LQ;
  auto angular = J.topRows<3>();
  auto linear = J.bottomRows<3>();
  accumulate(model, X_WL, link, p_WQ, &angular, linear);
}

}  // namespace deepcheck::robots
