#pragma once
// The posed bound of World::certifyMotion (PosedSpeeds, world_motion.cpp) for all the bound
// stage's lanes at once (batch_bounds.h, BatchMargins): per link geometry g, one S_g such that at
// every lane l no point of g moves more than h S_g over the lane's sub-motion q_l + s dq,
// |s| <= h. It is PosedSpeeds' smaller of two bounds, the per-joint sum and the rigid one, with
// each distance from an axis, the centre's speed and the turning rate taken at its largest over
// the lanes. Both bounds grow with each of these, so each holds at every lane, and so does the
// smaller. Along a motion the lanes' poses differ little, so S_g stays well below the
// configuration-free bound, which assumes the worst pose of the whole chain.

#include "batch_kinematics.h"
#include "world_clearance_internal.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace deepcheck::checker::detail {

/// |p|^2 for every lane.
template <class L>
DC_LANES L laneSquaredNorm(const LanePointT<L>& p) {
  return p.x * p.x + p.y * p.y + p.z * p.z;
}

/// S_g of link geometry g over the lanes `poses` holds (all finite), for sub-motions of half
/// length h of `motion` along dq; `terms` is scratch.
template <class L>
double lanesPosedSpeed(const RobotData& robot, const BatchPosesT<L>& poses, const ClearanceDemand& motion,
                       const Eigen::VectorXd& dq, double h, std::size_t g, std::vector<SpeedTerm>& terms) {
  const LinkGeometry& lg = robot.links[g];
  const LanePointT<L>& center = poses.linkCenter[g];
  const double drift = h * motion.link[lg.link];
  const std::vector<int>& chain = robot.chains[g];
  terms.assign(chain.size(), SpeedTerm{});
  double perJoint = 0.0;
  double turning = 0.0;  // sum of the revolute |sigma_k|
  LanePointT<L> velocity{};
  LanePointT<L> angular{};
  for (std::size_t i = 0; i < chain.size(); ++i) {
    const robots::Joint& joint = robot.model.joint(chain[i]);
    const double sigma = dq[joint.variable] * joint.multiplier;
    const bool prismatic = joint.type == robots::JointType::Prismatic;
    terms[i] = SpeedTerm{std::abs(sigma), 0.0, prismatic};
    if (sigma == 0.0) continue;
    // The joint's axis in the world: its child link's rotation times the axis in that frame.
    const LanePoseT<L>& X = poses.links[joint.childLink];
    const Eigen::Vector3d& u = joint.axis;
    LanePointT<L> a;
    a.x = X.R[0] * u[0] + X.R[1] * u[1] + X.R[2] * u[2];
    a.y = X.R[3] * u[0] + X.R[4] * u[1] + X.R[5] * u[2];
    a.z = X.R[6] * u[0] + X.R[7] * u[1] + X.R[8] * u[2];
    if (prismatic) {
      perJoint += std::abs(sigma);
      velocity.x += sigma * a.x;
      velocity.y += sigma * a.y;
      velocity.z += sigma * a.z;
      continue;
    }
    const L rx = center.x - X.t[0], ry = center.y - X.t[1], rz = center.z - X.t[2];
    LanePointT<L> turn;  // a x (centre - joint origin)
    turn.x = a.y * rz - a.z * ry;
    turn.y = a.z * rx - a.x * rz;
    turn.z = a.x * ry - a.y * rx;
    terms[i].reach = std::sqrt(extremeLane(laneSquaredNorm(turn), true)) + lg.radius + drift;
    perJoint += std::abs(sigma) * terms[i].reach;
    velocity.x += sigma * turn.x;
    velocity.y += sigma * turn.y;
    velocity.z += sigma * turn.z;
    angular.x += sigma * a.x;
    angular.y += sigma * a.y;
    angular.z += sigma * a.z;
    turning += std::abs(sigma);
  }
  const double speed = std::sqrt(extremeLane(laneSquaredNorm(velocity), true));
  const double spin = std::sqrt(extremeLane(laneSquaredNorm(angular), true));
  const double rigid = speed + spin * lg.radius + h * rigidDrift(terms, turning);
  return std::min(perJoint, rigid);
}

}  // namespace deepcheck::checker::detail
