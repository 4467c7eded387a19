// Wrap-around variables and angle normalization (robots/joint_angles.h).

#include "deepcheck/robots/joint_angles.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <string>

using namespace deepcheck::robots;

namespace {

/// A continuous joint 'a', a continuous mimic of it with `multiplier`, and a revolute 'r'.
RobotModel mimicRobot(const std::string& multiplier) {
  const std::string xml =
      "<robot name='m'><link name='base'/><link name='l1'/><link name='l2'/><link name='l3'/>"
      "<joint name='a' type='continuous'><parent link='base'/><child link='l1'/><axis xyz='0 0 1'/></joint>"
      "<joint name='b' type='continuous'><parent link='l1'/><child link='l2'/><axis xyz='0 0 1'/>"
      "<mimic joint='a' multiplier='" +
      multiplier +
      "'/></joint>"
      "<joint name='r' type='revolute'><parent link='l2'/><child link='l3'/><axis xyz='0 0 1'/>"
      "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint></robot>";
  return RobotModel::fromUrdfString(xml, ".", {}, "m.urdf");
}

}  // namespace

BOOST_AUTO_TEST_SUITE(robots_joint_angles)

BOOST_AUTO_TEST_CASE(angles_are_normalized_to_minus_pi_exclusive_pi_inclusive) {
  BOOST_TEST(normalizeAngle(4.0) == 4.0 - 2.0 * M_PI);
  BOOST_TEST(normalizeAngle(-M_PI) == M_PI);
  BOOST_TEST(normalizeAngle(M_PI) == M_PI);
  BOOST_TEST(normalizeAngle(3.0 * M_PI) == M_PI, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(std::isnan(normalizeAngle(INFINITY)));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> any(-100.0, 100.0);
  for (int i = 0; i < 1000; ++i) {
    const double x = any(rng);
    const double y = normalizeAngle(x);
    BOOST_TEST((y > -M_PI && y <= M_PI));
    BOOST_TEST(normalizeAngle(y) == y);                       // idempotent, exactly
    BOOST_TEST(std::abs(std::cos(y) - std::cos(x)) < 1e-12);  // the same angle
    BOOST_TEST(std::abs(std::sin(y) - std::sin(x)) < 1e-12);
  }
}

BOOST_AUTO_TEST_CASE(a_variable_wraps_only_when_every_joint_it_drives_turns_whole_turns) {
  const RobotModel whole = mimicRobot("-2");
  BOOST_TEST(isWrappingVariable(whole, 0));
  BOOST_TEST(!isWrappingVariable(whole, 1));  // revolute
  const RobotModel half = mimicRobot("0.5");
  BOOST_TEST(!isWrappingVariable(half, 0));  // 2 pi of 'a' turns 'b' by pi: not the same pose
  Eigen::VectorXd q(2);
  q << 4.0, 4.0;
  normalizeWrappingVariables(whole, q);
  BOOST_TEST(q[0] == 4.0 - 2.0 * M_PI);
  BOOST_TEST(q[1] == 4.0);
  BOOST_CHECK_THROW(isWrappingVariable(whole, 2), std::invalid_argument);
}

BOOST_AUTO_TEST_SUITE_END()
