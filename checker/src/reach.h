#pragma once
// Where a robot's links can ever be: one sphere per link that contains every point of the link's
// collision pieces for every configuration within the joint limits. The world uses it to drop, at
// load time, the scene pieces that no link can reach.
//
// Bound. Let j0 be the first moving joint on the path from the root to link L. Everything above
// j0 is rigid, so its joint frame J0 has a fixed world pose; let o be J0's origin in the world.
// A point p of L is  p = o + R0 (t1 + R1 (t2 + ... + p_L))  (plus a prismatic joint's travel
// along its axis), where t_k is the translation of joint k's <origin> (X_PJ), R_k rotations, and
// p_L the point in L's frame. Rotations keep lengths, so by the triangle inequality
//     |p - o| <= sum_k |t_k| + sum_(prismatic k) travel_k + max |p_L|,
// the sums over the joints after j0 on the path (j0's own travel too when it is prismatic), and
// max |p_L| the largest distance from L's origin to a point of its pieces. A prismatic joint's
// travel is max(|v(lower)|, |v(upper)|) of its value v = multiplier * q + offset over the
// variable's limits: configurations outside the limits are not covered for prismatic joints
// (revolute and continuous joints are covered for every angle). A link without a moving joint
// above it never moves: its sphere is the bounding sphere of its pieces at their fixed pose.
//
// Frames: W the world (the robot's base pose included), metres.

#include "deepcheck/robots/collision_geometry.h"
#include "deepcheck/robots/robot_model.h"

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace deepcheck::checker {

struct ReachSphere {
  bool valid = false;  ///< false for a link without collision pieces
  Eigen::Vector3d center_W = Eigen::Vector3d::Zero();
  double radius = 0.0;
  bool fixed = false;  ///< the link never moves (no moving joint between it and the root)
  /// A prismatic joint's travel is in the radius: the sphere holds within the joint limits only.
  bool withinLimitsOnly = false;
};

/// One sphere per link (index by link). `pieces` is robots::collisionPieces(model) (one entry per
/// link). Throws std::invalid_argument when `pieces` does not have one entry per link.
std::vector<ReachSphere> linkReachSpheres(const robots::RobotModel& model,
                                          const std::vector<std::vector<robots::CollisionPiece>>& pieces);

/// The pairs (i, j), i < j, of `links` (link indices, each with a valid sphere in `spheres`) whose
/// reach spheres come within `margin` (metres) of each other, in increasing order: the only link
/// pairs that can ever be nearer than `margin`, at any configuration. A link whose sphere holds
/// within the joint limits only is paired with every other (configurations beyond the limits are
/// accepted by the queries). A tree over the spheres' boxes finds the pairs: the time grows with
/// their number, not with the square of the links'.
std::vector<std::pair<int, int>> pairsWithinReach(const std::vector<ReachSphere>& spheres,
                                                  const std::vector<int>& links, double margin);

}  // namespace deepcheck::checker
