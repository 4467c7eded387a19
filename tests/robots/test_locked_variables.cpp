// RobotModel::withLockedVariables: the locked model's kinematics and Jacobians are the full
// model's with the locked values inserted; mimic joints follow; bad requests are named.

#include "robots_test_util.h"

#include "common/random_configurations.h"

#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/robot_model.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace deepcheck::robots;
using deepcheck::robots::test::checkThrows;
using deepcheck::robots::test::haveShared;
using deepcheck::robots::test::loadBundledArm;
using deepcheck::robots::test::loadPanda;

namespace {

/// The full configuration of `full` for configuration `q` of `locked` (values by name; the
/// locked variables take `values`).
Eigen::VectorXd fullConfiguration(const RobotModel& full, const RobotModel& locked, const Eigen::VectorXd& q,
                                  const std::map<std::string, double>& values) {
  Eigen::VectorXd out(full.numVariables());
  for (int v = 0; v < full.numVariables(); ++v) {
    const std::string& name = full.variableNames()[static_cast<std::size_t>(v)];
    const int w = locked.variableIndex(name);
    out[v] = w >= 0 ? q[w] : values.at(name);
  }
  return out;
}

/// Link poses and the Jacobian of every link's origin agree between the two models on random
/// configurations of the locked one (1e-12).
void checkAgainstFull(const RobotModel& full, const std::map<std::string, double>& values, int trials) {
  const RobotModel locked = full.withLockedVariables(values);
  BOOST_TEST(locked.numVariables() == full.numVariables() - static_cast<int>(values.size()));
  std::mt19937 rng(7);
  for (int trial = 0; trial < trials; ++trial) {
    const Eigen::VectorXd q = deepcheck::test::randomConfiguration(locked, rng);
    const Eigen::VectorXd qFull = fullConfiguration(full, locked, q, values);
    const std::vector<Eigen::Isometry3d> X = forwardKinematics(locked, q);
    const std::vector<Eigen::Isometry3d> XFull = forwardKinematics(full, qFull);
    for (int l = 0; l < full.numLinks(); ++l) {
      BOOST_TEST_CONTEXT(full.name() << " link " << full.link(l).name << " trial " << trial) {
        BOOST_TEST((X[l].matrix() - XFull[l].matrix()).cwiseAbs().maxCoeff() <= 1e-12);
        const Eigen::Matrix3Xd J = pointJacobian(locked, X, l, Eigen::Vector3d::Zero());
        const Eigen::Matrix3Xd JFull = pointJacobian(full, XFull, l, Eigen::Vector3d::Zero());
        for (int w = 0; w < locked.numVariables(); ++w) {
          const int v = full.variableIndex(locked.variableNames()[static_cast<std::size_t>(w)]);
          BOOST_TEST((J.col(w) - JFull.col(v)).cwiseAbs().maxCoeff() <= 1e-12);
        }
      }
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(robots_locked_variables)

BOOST_AUTO_TEST_CASE(bundled_arm_matches_full_model) {
  const RobotModel arm = loadBundledArm();
  BOOST_REQUIRE(arm.numVariables() >= 3);
  const std::string first = arm.variableNames()[0];
  const std::string third = arm.variableNames()[2];
  const double value = 0.3 * arm.lowerLimits()[2] + 0.7 * arm.upperLimits()[2];
  checkAgainstFull(arm, {{first, arm.lowerLimits()[0]}, {third, value}}, 50);

  const RobotModel locked = arm.withLockedVariables({{third, value}});
  const Joint& joint = locked.joint(locked.jointIndex(third));
  BOOST_TEST(joint.locked);
  BOOST_TEST(joint.lockedValue == value);
  BOOST_TEST(!joint.moves());
  BOOST_TEST(locked.variableIndex(third) == -1);
  BOOST_TEST(locked.variableIndex(first) == 0);
  // The model it came from is unchanged.
  BOOST_TEST(arm.variableIndex(third) == 2);
  BOOST_TEST(arm.joint(arm.jointIndex(third)).moves());
}

BOOST_AUTO_TEST_CASE(panda_fingers_locked_with_their_mimic) {
  if (!haveShared("panda_fingers_locked_with_their_mimic")) return;
  const RobotModel panda = loadPanda();
  checkAgainstFull(panda, {{"panda_finger_joint1", 0.03}}, 50);
  const RobotModel arm = panda.withLockedVariables({{"panda_finger_joint1", 0.03}});
  BOOST_TEST(arm.numVariables() == 7);
  const Joint& mimic = arm.joint(arm.jointIndex("panda_finger_joint2"));
  BOOST_TEST(mimic.locked);
  BOOST_TEST(mimic.lockedValue == 0.03);
  BOOST_TEST(!mimic.isMimic());
  // Locking nothing gives the same model; locking everything leaves no variable.
  BOOST_TEST(panda.withLockedVariables({}).numVariables() == 8);
  std::map<std::string, double> all;
  for (const std::string& name : panda.variableNames()) all[name] = 0.0;
  BOOST_TEST(panda.withLockedVariables(all).numVariables() == 0);
}

BOOST_AUTO_TEST_CASE(mimic_chain_follows_the_remaining_variable) {
  // j2 mimics j1 and j3 mimics j2: locking nothing of the chain keeps them moving with j1's new
  // index, after another variable ahead of it is locked.
  const char* urdf = R"(<robot name="chain">
    <link name="base"/><link name="a"/><link name="b"/><link name="c"/><link name="d"/>
    <joint name="j0" type="revolute"><parent link="base"/><child link="a"/>
      <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0 0 0.5"/>
      <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    <joint name="j2" type="revolute"><parent link="b"/><child link="c"/><origin xyz="0.4 0 0"/>
      <axis xyz="1 0 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/>
      <mimic joint="j1" multiplier="2" offset="0.1"/></joint>
    <joint name="j3" type="prismatic"><parent link="c"/><child link="d"/><origin xyz="0.3 0 0"/>
      <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
      <mimic joint="j2" multiplier="-0.5" offset="0.2"/></joint>
  </robot>)";
  const RobotModel m = RobotModel::fromUrdfString(urdf, "", {}, "chain.urdf");
  checkAgainstFull(m, {{"j0", 0.4}}, 30);
  checkAgainstFull(m, {{"j1", -0.6}}, 5);
  const RobotModel locked = m.withLockedVariables({{"j1", -0.6}});
  BOOST_TEST(locked.joint(locked.jointIndex("j3")).lockedValue == -0.5 * (2 * -0.6 + 0.1) + 0.2);
}

BOOST_AUTO_TEST_CASE(bad_requests_are_named) {
  const RobotModel arm = loadBundledArm();
  const std::string name = arm.variableNames()[1];
  checkThrows(
      [&] {
        arm.withLockedVariables({{"no_such_joint", 0.0}});
      },
      {"cannot lock 'no_such_joint'", "no joint of the robot", arm.name()});
  checkThrows(
      [&] {
        arm.withLockedVariables({{name, arm.upperLimits()[1] + 0.5}});
      },
      {"cannot lock '" + name + "'", "outside its limits"});
  checkThrows(
      [&] {
        arm.withLockedVariables({{name, std::numeric_limits<double>::quiet_NaN()}});
      },
      {"cannot lock '" + name + "' at nan"});
  const RobotModel once = arm.withLockedVariables({{name, 0.0}});
  checkThrows([&] { once.withLockedVariables({{name, 0.0}}); }, {"already locked at 0"});
  if (!haveShared("bad_requests_are_named (Panda)")) return;
  const RobotModel panda = loadPanda();
  checkThrows(
      [&] {
        panda.withLockedVariables({{"panda_finger_joint2", 0.01}});
      },
      {"mimic joint", "lock 'panda_finger_joint1'"});
  checkThrows([&] { panda.withLockedVariables({{"panda_joint8", 0.0}}); }, {"fixed joint"});
}

BOOST_AUTO_TEST_CASE(lock_all_but_a_kept_set) {
  const RobotModel arm = loadBundledArm();
  BOOST_REQUIRE(arm.numVariables() >= 4);
  const std::string held = arm.variableNames()[1];
  const double value = 0.5 * (arm.lowerLimits()[1] + arm.upperLimits()[1]) + 0.1;
  const RobotModel kept = lockAllBut(arm, {0, 2}, {{held, value}}, "group 'test'");
  BOOST_TEST(kept.numVariables() == 2);
  BOOST_TEST(kept.variableNames()[0] == arm.variableNames()[0]);
  BOOST_TEST(kept.variableNames()[1] == arm.variableNames()[2]);
  BOOST_TEST(kept.joint(kept.jointIndex(held)).lockedValue == value);
  // The others are held at their defaults.
  const Eigen::VectorXd q0 = arm.defaultConfiguration();
  for (int v = 3; v < arm.numVariables(); ++v) {
    const std::string& name = arm.variableNames()[static_cast<std::size_t>(v)];
    BOOST_TEST(kept.joint(kept.jointIndex(name)).lockedValue == q0[v]);
  }
  checkThrows(
      [&] {
        lockAllBut(arm, {0, 1}, {{held, value}}, "group 'test'");
      },
      {"cannot lock '" + held + "'", "a variable of group 'test'"});
  checkThrows([&] { lockAllBut(arm, {0, 99}, {}, "group 'test'"); }, {"group 'test' has variable index 99"});
}

BOOST_AUTO_TEST_SUITE_END()
