#pragma once
// Forward kinematics and point Jacobians of a RobotModel.
//
// Frames and order as in robot_model.h: X_WL[i] is the pose of link i in the world W, for the
// configuration q (one value per variable, in variableNames() order) and the model's base pose:
//   X_WL[root] = X_WR,   X_WL[child] = X_WL[parent] * X_PJ * X_JC(value),
// value = multiplier * q[variable] + offset (mimic joints included).
//
// The point Jacobian of a point Q fixed on link L (position p_LQ in L) is the 3 x nq matrix
// J with  d/dt p_WQ = J * dq/dt,  i.e. column v = d p_WQ / d q_v, expressed in W. The spatial
// Jacobian is 6 x nq: rows 0-2 the angular velocity of L in W, rows 3-5 the translational
// velocity of Q in W (Drake's [w; v] order). For a revolute joint with unit axis a_W through the
// child origin o_W, column v gains multiplier * a_W x (p_WQ - o_W) (and multiplier * a_W in the
// angular rows); for a prismatic one, multiplier * a_W (and nothing in the angular rows). A
// variable that drives several joints of the chain (mimics) sums their contributions.
//
// Every function checks its input and throws std::invalid_argument: q must have numVariables()
// finite entries (the message gives the index, the variable's name and the value), link indices
// must exist, and precomputed poses must have one entry per link.

#include "deepcheck/robots/robot_model.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace deepcheck::robots {

/// Throws std::invalid_argument unless q has model.numVariables() finite entries.
void checkConfiguration(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& q);

/// Poses X_WL of all links (index by link). Allocation-free once X_WL has numLinks() entries.
void forwardKinematics(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                       std::vector<Eigen::Isometry3d>& X_WL);
std::vector<Eigen::Isometry3d> forwardKinematics(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& q);

/// 3 x nq translational Jacobian of point Q (p_LQ in link L), expressed in W, from the poses of
/// forwardKinematics() for the same q. Allocation-free once J_WQ has the right size.
void pointJacobian(const RobotModel& model, const std::vector<Eigen::Isometry3d>& X_WL, int link,
                   const Eigen::Vector3d& p_LQ, Eigen::Matrix3Xd& J_WQ);
Eigen::Matrix3Xd pointJacobian(const RobotModel& model, const std::vector<Eigen::Isometry3d>& X_WL, int link,
                               const Eigen::Vector3d& p_LQ);
/// Same, computing the poses for q first.
Eigen::Matrix3Xd pointJacobian(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& q, int link,
                               const Eigen::Vector3d& p_LQ);

/// 6 x nq spatial Jacobian [angular; translational of Q], expressed in W.
void spatialJacobian(const RobotModel& model, const std::vector<Eigen::Isometry3d>& X_WL, int link,
                     const Eigen::Vector3d& p_LQ, Eigen::Matrix<double, 6, Eigen::Dynamic>& J);

}  // namespace deepcheck::robots
