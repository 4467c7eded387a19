#pragma once
// How fast the robot's geometry can move per unit change of each joint: the bound that lets a
// motion validator step by the clearance (conservative advancement).
//
// speed(i, v) bounds the speed of EVERY point of link i's collision pieces per unit speed of
// variable v, for every configuration (within the limits for prismatic joints):
//   - revolute or continuous joint k driven by v (multiplier m): a point p moves at
//     |m| |a x (p - o_k)| <= |m| |p - o_k|, o_k the joint's origin; and |p - o_k| is at most
//     rho_i + sum over the joints between k and link i of (|t| + travel), where rho_i is the
//     largest distance from link i's origin to a point of its pieces, t a joint's <origin>
//     translation and travel a prismatic joint's largest |value| (the triangle inequality over
//     the kinematic chain: rotations keep lengths);
//   - prismatic joint k: every point of the subtree moves at |m|;
//   - a variable driving several joints of the chain (mimics) sums their contributions;
//   - 0 when v moves no joint between the root and link i.
// Along the straight joint-space motion q(s) = q + s dq, s in [0, 1], no point of link i moves
// farther than D_i(dq) = sum_v speed(i, v) |dq_v|. dq must be the displacement the motion takes:
// for a continuous joint planned as an SO2 component, the short way round (StateMapping::
// displacement, state_space.h: 0.283 rad from 3.0 to -3.0, not -6.0). The bound of the raw
// difference would be sound but 21 times too large there; the bound of the short turn applied to
// a motion that went the long way would not be.
//
// Pair bounds. The World's signed distance is the minimum over pairs of convex pieces; for one
// pair it changes by at most the relative displacement of the two pieces (for overlapping pieces
// too: a separating translation of the old pose, extended by the displacement, separates the new
// one). A robot-world pair (link i, a fixed body) moves by at most D_i. A self pair (a, b) moves
// RELATIVELY only through the joints below their nearest common ancestor link c (the joints above
// move both rigidly together), so
//     B_ab(dq) = sum over v of (speed(a, v) [v drives a joint on the path c..a]
//                              + speed(b, v) [v drives a joint on the path c..b]) |dq_v|;
// the wrist pair (link5, link7) of a 7-DOF arm moves only through joints 6 and 7. With
//     B(dq) = max( max_i D_i, max_{(a, b) checked} B_ab(dq) ),
// |sd(q + dq) - sd(q)| <= B(dq), and a motion whose clearance at its start is c is collision free
// for the first c / B(dq) of it; per pair, the pair's own clearance over its own bound.
//
// rho_i is the World's bound on the pieces link i carries (World::linkExtents: the bounding
// spheres of the pieces it checks, objects attached to the link included), so it bounds the
// geometry the World actually checks. A bound made before an object was attached does not
// cover it: make it again (the certified motion validator does, on World::version()). Frames:
// link frames L (robot_model.h); metres and radians.

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/robot_model.h"

#include <Eigen/Core>

#include <memory>
#include <utility>
#include <vector>

namespace deepcheck::planners {

class LinkSpeedBound;
/// Shared pointer, named as OMPL names its own.
using LinkSpeedBoundPtr = std::shared_ptr<LinkSpeedBound>;

class LinkSpeedBound {
 public:
  /// `linkExtent[i]` is rho_i for a link with geometry, negative for a link without (it takes no
  /// part). `selfPairs` are the checked self pairs (link indices). Throws std::invalid_argument
  /// for sizes that do not match the model, a non-finite extent or an unknown link.
  LinkSpeedBound(const robots::RobotModel& model, const std::vector<double>& linkExtent,
                 std::vector<std::pair<int, int>> selfPairs);

  /// The bound for a World's robot, the pieces it checks now (World::linkExtents) and its checked
  /// self pairs.
  static LinkSpeedBound forWorld(const checker::World& world);

  /// speed(i, v): links x variables, metres per radian (or per metre); 0 rows for links without
  /// geometry.
  const Eigen::MatrixXd& speeds() const { return speed_; }
  const std::vector<double>& linkExtents() const { return extent_; }
  /// The checked self pairs it was made with.
  const std::vector<std::pair<int, int>>& selfPairs() const { return selfPairs_; }

  /// D_i(dq): the farthest any point of link i moves along q -> q + dq (metres).
  double linkDisplacement(int link, const Eigen::Ref<const Eigen::VectorXd>& dq) const;

  /// B(dq): a bound on |sd(q + s dq) - sd(q)| for s in [0, 1], for every q (metres).
  double pairDisplacement(const Eigen::Ref<const Eigen::VectorXd>& dq) const;

  /// The bound of one pair: D_linkA for a world pair (linkB < 0), B_ab for a self pair (any order;
  /// a pair that is not checked gets the conservative D_a + D_b).
  double pairDisplacement(int linkA, int linkB, const Eigen::Ref<const Eigen::VectorXd>& dq) const;

  /// Every bound of the motion dq at once, as World::isClear takes them: link[i] = D_i(dq) and
  /// self(a, b) = self(b, a) = the pair bound above (D_a + D_b for a pair that is not checked,
  /// e.g. an attached object's). Resizes both to the robot's number of links.
  void displacements(const Eigen::Ref<const Eigen::VectorXd>& dq, Eigen::VectorXd& link, Eigen::MatrixXd& self) const;

 private:
  void checkMotion(const Eigen::Ref<const Eigen::VectorXd>& dq) const;

  Eigen::MatrixXd speed_;
  std::vector<double> extent_;
  std::vector<int> geometryLinks_;
  std::vector<std::pair<int, int>> selfPairs_;
  Eigen::MatrixXd selfSpeed_;    ///< one row per self pair: the relative speeds B_ab
  Eigen::MatrixXi selfPairRow_;  ///< links x links: row of selfSpeed_, -1 when not checked
};

}  // namespace deepcheck::planners
