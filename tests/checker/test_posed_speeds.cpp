// The posed bound World::certifyMotion grows each pair by (PosedSpeeds, world_motion.cpp): over a
// sub-motion q(tm) + s dq, |s| <= h, no point of a link geometry's pieces moves faster than S_g
// per unit of s. Checked on the pieces' vertices, sampled along random sub-motions (long and short,
// near the middle of a long motion and near its ends) of the Panda, the bundled arm (also holding
// a long rod) and a robot with every kind of joint (a skew prismatic joint, a continuous one, a
// mimic). The configuration-free bound it starts from is the chain-length bound of
// planners/motion_bound.h.

#include "checker_test_util.h"
#include "world_clearance_internal.h"
#include "world_test_access.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/kinematics.h"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

using namespace deepcheck;
using namespace deepcheck::checker;
using namespace deepcheck::checker::test;

namespace {

/// Per link, how far its pieces can move over the straight motion by dq (metres, the
/// configuration-free chain-length bound): a revolute joint k moves them at |m dq| times at most
/// rho + the joint translations (and prismatic travels) between k and the link.
Eigen::VectorXd chainBound(const robots::RobotModel& model, const std::vector<double>& extents,
                           const Eigen::VectorXd& dq) {
  Eigen::VectorXd bound = Eigen::VectorXd::Zero(model.numLinks());
  for (int l = 0; l < model.numLinks(); ++l) {
    double reach = std::max(0.0, extents[static_cast<std::size_t>(l)]);
    for (int cur = l; model.link(cur).parentJoint >= 0; cur = model.link(cur).parentLink) {
      const robots::Joint& j = model.joint(model.link(cur).parentJoint);
      const bool prismatic = j.type == robots::JointType::Prismatic;
      if (j.moves() && j.variable >= 0) bound[l] += std::abs(j.multiplier * dq[j.variable]) * (prismatic ? 1.0 : reach);
      reach += j.X_PJ.translation().norm() + (prismatic ? std::max(std::abs(j.lower), std::abs(j.upper)) : 0.0);
    }
  }
  return bound;
}

/// The world positions of link geometry g's piece vertices at configuration q.
std::vector<Eigen::Vector3d> pieceVertices(const robots::RobotModel& model, const detail::RobotData& robot, int g,
                                           const Eigen::VectorXd& q) {
  const std::vector<Eigen::Isometry3d> X_WL = robots::forwardKinematics(model, q);
  const detail::LinkGeometry& lg = robot.links[static_cast<std::size_t>(g)];
  std::vector<Eigen::Vector3d> out;
  for (int i = lg.firstPiece; i < lg.firstPiece + lg.numPieces; ++i) {
    const detail::RobotPiece& p = robot.pieces[static_cast<std::size_t>(i)];
    const Eigen::Isometry3d X_WP = X_WL[p.link] * p.X_LP;
    for (int v = 0; v < p.core->numVertices(); ++v) out.push_back(X_WP * p.core->vertex(v));
  }
  return out;
}

/// Random sub-motions of random motions of `world`'s robot: at samples s along each (every 1/32
/// of its length), no vertex moves farther between neighbouring samples than S_g times their
/// distance in s. Returns the largest ratio of a move to that bound.
double checkPosedSpeeds(const World& world, unsigned seed, int motions) {
  const robots::RobotModel& model = world.robot();
  const detail::RobotData& robot = *robotOf(world);
  const std::unique_ptr<detail::Impl> c = contextImplOf(world);
  const std::vector<double> extents = world.linkExtents();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  constexpr int kSamples = 32;
  double worst = 0.0;
  for (int m = 0; m < motions; ++m) {
    const Eigen::VectorXd q1 = randomConfigurations(model, 1, rng)[0];
    const Eigen::VectorXd dq = (randomConfigurations(model, 1, rng)[0] - q1) * (0.05 + 2.0 * unit(rng));
    ClearanceDemand motion;
    motion.link = chainBound(model, extents, dq);
    const double h = std::ldexp(0.5, -static_cast<int>(unit(rng) * 8));  // 1/2 down to 1/256
    const double tm = h + (1.0 - 2.0 * h) * unit(rng);
    detail::prepare(*c->state, *c, q1 + tm * dq);
    detail::PosedSpeeds speeds;
    speeds.reset(*c, robot, motion, h, dq);
    for (int g = 0; g < static_cast<int>(robot.links.size()); ++g) {
      const double bound = speeds.of(g) * (2.0 * h / kSamples);  // per step of s
      std::vector<Eigen::Vector3d> before = pieceVertices(model, robot, g, q1 + (tm - h) * dq);
      for (int k = 1; k <= kSamples; ++k) {
        const std::vector<Eigen::Vector3d> after =
            pieceVertices(model, robot, g, q1 + (tm - h + 2.0 * h * k / kSamples) * dq);
        for (std::size_t v = 0; v < after.size(); ++v) {
          const double moved = (after[v] - before[v]).norm();
          BOOST_TEST(moved <= bound * (1.0 + 1e-9) + 1e-12,
                     "link geometry " << g << " moved " << moved << " in a step bounded by " << bound);
          if (bound > 0.0) worst = std::max(worst, moved / bound);
        }
        before = after;
      }
    }
  }
  return worst;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_posed_speeds)

BOOST_AUTO_TEST_CASE(posed_speeds_bound_the_robot_arm) {
  const World world(robots::RobotModel::fromUrdfFile(bundledDataDir() + "/deepcheck_arm/urdf/deepcheck_arm.urdf",
                                                     bundledLoadOptions()),
                    testWorldOptions());
  // Not vacuous: somewhere a vertex moves at more than half the bound.
  BOOST_TEST(checkPosedSpeeds(world, 11, 100) > 0.5);
}

BOOST_AUTO_TEST_CASE(posed_speeds_bound_an_attached_object) {
  // A long rod held off the hand: a link geometry of its own, far from the joints' axes.
  World world(robots::RobotModel::fromUrdfFile(bundledDataDir() + "/deepcheck_arm/urdf/deepcheck_arm.urdf",
                                               bundledLoadOptions()),
              testWorldOptions());
  world.attach("hand", Obstacle::box("rod", Eigen::Vector3d(0.04, 0.04, 0.7), translation(0.15, 0.05, 0.4)));
  BOOST_TEST(checkPosedSpeeds(world, 14, 100) > 0.5);
}

BOOST_AUTO_TEST_CASE(posed_speeds_bound_every_kind_of_joint) {
  robots::RobotModel model = everyJointRobot();
  Eigen::Isometry3d base = translation(0.3, 0.1, -0.2);
  base.linear() = Eigen::AngleAxisd(-0.4, Eigen::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix();
  model.setBasePose(base);
  const World world(model, testWorldOptions());
  BOOST_TEST(checkPosedSpeeds(world, 12, 300) > 0.5);
}

BOOST_AUTO_TEST_CASE(posed_speeds_bound_the_panda) {
  if (!haveShared("the Panda")) return;
  const World world(loadPanda(), testWorldOptions());
  BOOST_TEST(checkPosedSpeeds(world, 13, 200) > 0.5);
}

BOOST_AUTO_TEST_SUITE_END()
