// The posed bound World::certifyMotion grows each pair by (PosedSpeeds, world_motion.cpp), and
// its form over a batch's lanes (batch_speeds.h): over a sub-motion q(tm) + s dq, |s| <= h, no
// point of a link geometry's pieces moves faster than S_g per unit of s. Checked on the pieces'
// vertices, sampled along random sub-motions (long and short, near the middle of a long motion
// and near its ends, and eight neighbouring ones as a batch's lanes) of the Panda, the bundled arm
// (also holding a long rod) and a robot with every kind of joint (a skew prismatic joint, a
// continuous one, a mimic). The configuration-free bound it starts from is the chain-length bound
// of planners/motion_bound.h.

#include "batch_speeds.h"
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

/// Along the sub-motion q1 + t dq, |t - tm| <= h (every 1/32 of its length), no vertex of link
/// geometry g moves farther between neighbouring samples than `speed` times their distance in t.
/// Returns the largest ratio of a move to that bound.
double worstMoveRatio(const World& world, int g, const Eigen::VectorXd& q1, const Eigen::VectorXd& dq, double tm,
                      double h, double speed) {
  const robots::RobotModel& model = world.robot();
  const detail::RobotData& robot = *robotOf(world);
  constexpr int kSamples = 32;
  const double bound = speed * (2.0 * h / kSamples);  // per step of t
  double worst = 0.0;
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
  return worst;
}

/// A random motion of `world`'s robot (q1, dq and its configuration-free bound) and a random half
/// length h of a sub-motion, 1/2 down to 1/256.
struct RandomMotion {
  Eigen::VectorXd q1, dq;
  ClearanceDemand motion;
  double h = 0.0;
};

RandomMotion randomMotion(const World& world, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  RandomMotion m;
  m.q1 = randomConfigurations(world.robot(), 1, rng)[0];
  m.dq = (randomConfigurations(world.robot(), 1, rng)[0] - m.q1) * (0.05 + 2.0 * unit(rng));
  m.motion.link = chainBound(world.robot(), world.linkExtents(), m.dq);
  m.h = std::ldexp(0.5, -static_cast<int>(unit(rng) * 8));
  return m;
}

/// Random sub-motions of random motions of `world`'s robot (long and short, near the middle of a
/// long motion and near its ends): PosedSpeeds' S_g bounds every vertex's speed. Returns the
/// largest ratio of a move to its bound.
double checkPosedSpeeds(const World& world, unsigned seed, int motions) {
  const detail::RobotData& robot = *robotOf(world);
  const std::unique_ptr<detail::Impl> c = contextImplOf(world);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  for (int m = 0; m < motions; ++m) {
    const RandomMotion r = randomMotion(world, rng);
    const double tm = r.h + (1.0 - 2.0 * r.h) * unit(rng);
    detail::prepare(*c->state, *c, r.q1 + tm * r.dq);
    detail::PosedSpeeds speeds;
    speeds.reset(*c, robot, r.motion, r.h, r.dq);
    for (int g = 0; g < static_cast<int>(robot.links.size()); ++g) {
      worst = std::max(worst, worstMoveRatio(world, g, r.q1, r.dq, tm, r.h, speeds.of(g)));
    }
  }
  return worst;
}

/// The bound stage's S_g over a batch of lanes (batch_speeds.h), for kLanes neighbouring
/// sub-motions of random motions as certifyMotion's first level makes them: it bounds every
/// vertex's speed over each lane's sub-motion, and the AVX2 build's lanes give the same bits as
/// the baseline build's. Returns the largest ratio of a move to its bound.
double checkLanesPosedSpeed(const World& world, unsigned seed, int motions) {
  const detail::RobotData& robot = *robotOf(world);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  detail::BatchPosesT<detail::BaselineLanes> baseline;
  detail::BatchPosesT<detail::Avx2Lanes> avx2;
  std::vector<detail::SpeedTerm> terms;
  double worst = 0.0;
  for (int m = 0; m < motions; ++m) {
    const RandomMotion r = randomMotion(world, rng);
    const double t0 = unit(rng);
    Eigen::MatrixXd qs(r.q1.size(), detail::kLanes);
    for (int l = 0; l < detail::kLanes; ++l) qs.col(l) = r.q1 + (t0 + 2.0 * r.h * l) * r.dq;
    detail::batchForwardKinematics(robot, qs, baseline);
    if (detail::batchAvx2Available()) detail::batchForwardKinematics(robot, qs, avx2);
    for (std::size_t g = 0; g < robot.links.size(); ++g) {
      const double speed = detail::lanesPosedSpeed(robot, baseline, r.motion, r.dq, r.h, g, terms);
      if (detail::batchAvx2Available()) {
        BOOST_TEST(detail::lanesPosedSpeed(robot, avx2, r.motion, r.dq, r.h, g, terms) == speed);
      }
      for (int l = 0; l < detail::kLanes; ++l) {
        const double ratio = worstMoveRatio(world, static_cast<int>(g), r.q1, r.dq, t0 + 2.0 * r.h * l, r.h, speed);
        worst = std::max(worst, ratio);
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

BOOST_AUTO_TEST_CASE(lanes_posed_speeds_bound_every_lane) {
  const World arm(robots::RobotModel::fromUrdfFile(bundledDataDir() + "/deepcheck_arm/urdf/deepcheck_arm.urdf",
                                                   bundledLoadOptions()),
                  testWorldOptions());
  BOOST_TEST(checkLanesPosedSpeed(arm, 21, 12) > 0.3);
  robots::RobotModel model = everyJointRobot();
  model.setBasePose(translation(0.3, 0.1, -0.2));
  const World every(model, testWorldOptions());
  BOOST_TEST(checkLanesPosedSpeed(every, 22, 30) > 0.3);
  if (!haveShared("the Panda")) return;
  const World panda(loadPanda(), testWorldOptions());
  BOOST_TEST(checkLanesPosedSpeed(panda, 23, 12) > 0.3);
}

BOOST_AUTO_TEST_SUITE_END()
