// Forward kinematics against the manufacturers' Denavit-Hartenberg parameters, Jacobians against
// central finite differences, and configuration checks.

#include "robots_test_util.h"

#include "common/random_configurations.h"

#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/robot_model.h"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace deepcheck::robots;
using deepcheck::robots::test::checkThrows;
using deepcheck::robots::test::haveShared;
using deepcheck::robots::test::loadPanda;
using deepcheck::robots::test::sharedDir;

namespace {

RobotModel loadUr5() {
  LoadOptions o;
  o.packageRoots = {sharedDir() + "/robots/ur5"};
  o.useRosPackagePath = false;
  return RobotModel::fromUrdfFile(
      sharedDir() + "/robots/ur5/example-robot-data/robots/ur_description/urdf/ur5_robot.urdf", o);
}

Eigen::Isometry3d rotX(double a) { return Eigen::Isometry3d(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX())); }
Eigen::Isometry3d rotZ(double a) { return Eigen::Isometry3d(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ())); }
Eigen::Isometry3d transX(double a) { return Eigen::Isometry3d(Eigen::Translation3d(a, 0, 0)); }
Eigen::Isometry3d transZ(double d) { return Eigen::Isometry3d(Eigen::Translation3d(0, 0, d)); }

/// Frames 1..8 (8 = flange) of the Panda from Franka's published modified (Craig) DH table:
/// T_{i-1,i} = RotX(alpha) TransX(a) RotZ(theta_i) TransZ(d).
std::vector<Eigen::Isometry3d> pandaDh(const Eigen::VectorXd& q) {
  struct Row {
    double a, d, alpha;
  };
  const Row rows[8] = {
      {0, 0.333, 0},    {0, 0, -M_PI / 2},    {0, 0.316, M_PI / 2}, {0.0825, 0, M_PI / 2}, {-0.0825, 0.384, -M_PI / 2},
      {0, 0, M_PI / 2}, {0.088, 0, M_PI / 2}, {0, 0.107, 0}};
  std::vector<Eigen::Isometry3d> frames;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 8; ++i) {
    const double theta = i < 7 ? q[i] : 0.0;
    T = T * rotX(rows[i].alpha) * transX(rows[i].a) * rotZ(theta) * transZ(rows[i].d);
    frames.push_back(T);
  }
  return frames;
}

/// The UR5's tool frame from Universal Robots' published standard DH parameters:
/// T_{i-1,i} = RotZ(theta_i) TransZ(d_i) TransX(a_i) RotX(alpha_i).
Eigen::Isometry3d ur5Dh(const Eigen::VectorXd& q) {
  const double d[6] = {0.089159, 0, 0, 0.10915, 0.09465, 0.0823};
  const double a[6] = {0, -0.425, -0.39225, 0, 0, 0};
  const double alpha[6] = {M_PI / 2, 0, 0, M_PI / 2, -M_PI / 2, 0};
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 6; ++i) T = T * rotZ(q[i]) * transZ(d[i]) * transX(a[i]) * rotX(alpha[i]);
  return T;
}

/// Compares the point and spatial Jacobians with central differences of forwardKinematics.
void checkJacobians(const RobotModel& m, const Eigen::VectorXd& q, int link, const Eigen::Vector3d& p_LQ) {
  const double h = 1e-6;
  const auto X_WL = forwardKinematics(m, q);
  const Eigen::Matrix3Xd J = pointJacobian(m, X_WL, link, p_LQ);
  Eigen::Matrix<double, 6, Eigen::Dynamic> S;
  spatialJacobian(m, X_WL, link, p_LQ, S);
  BOOST_TEST((S.bottomRows<3>() - J).norm() == 0.0);
  for (int v = 0; v < m.numVariables(); ++v) {
    Eigen::VectorXd qp = q, qm = q;
    qp[v] += h;
    qm[v] -= h;
    const Eigen::Isometry3d Xp = forwardKinematics(m, qp)[link];
    const Eigen::Isometry3d Xm = forwardKinematics(m, qm)[link];
    const Eigen::Vector3d dp = (Xp * p_LQ - Xm * p_LQ) / (2 * h);
    // Angular velocity: the rotation from Xm to Xp, as an axis times angle, over 2h.
    const Eigen::AngleAxisd dR(Xp.linear() * Xm.linear().transpose());
    const Eigen::Vector3d w = dR.axis() * dR.angle() / (2 * h);
    BOOST_CHECK_MESSAGE((J.col(v) - dp).norm() < 1e-7,
                        "link " << m.link(link).name << " variable " << m.variableNames()[v]
                                << ": J = " << J.col(v).transpose() << ", differences " << dp.transpose());
    BOOST_CHECK_MESSAGE((S.col(v).head<3>() - w).norm() < 1e-7,
                        "link " << m.link(link).name << " variable " << m.variableNames()[v] << ": angular J = "
                                << S.col(v).head<3>().transpose() << ", differences " << w.transpose());
  }
}

const char* kMimicUrdf = R"(<robot name="mimic">
  <link name="base"/><link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="0.4 0 0" rpy="0.3 0 0"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/>
    <mimic joint="j1" multiplier="2" offset="0.1"/></joint>
  <joint name="j3" type="prismatic"><parent link="b"/><child link="c"/>
    <origin xyz="0.3 0 0"/><axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
    <mimic joint="j2" multiplier="-0.5" offset="0.2"/></joint>
</robot>)";

/// Every kind of joint motion forwardKinematics specialises: revolute and continuous joints about
/// +-x, +-y, +-z and a general axis, prismatic joints along a coordinate and a general axis, a
/// mimic, fixed joints, a branch, and joint origins with general rotations.
const char* kAxesUrdf = R"(<robot name="axes">
  <link name="base"/><link name="a"/><link name="b"/><link name="c"/><link name="d"/><link name="e"/>
  <link name="f"/><link name="g"/><link name="h"/><link name="i"/><link name="k"/><link name="m"/>
  <joint name="jx" type="revolute"><parent link="base"/><child link="a"/>
    <origin xyz="0.1 0.2 0.3" rpy="0.3 -0.2 0.7"/><axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="jmy" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="0.4 0 -0.1" rpy="1.1 0.4 -0.5"/><axis xyz="0 -1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="jz" type="continuous"><parent link="b"/><child link="c"/>
    <origin xyz="0 0.3 0.1" rpy="-1.5707963267948966 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="jg" type="revolute"><parent link="c"/><child link="d"/>
    <origin xyz="0.05 -0.2 0.3" rpy="0.2 0.9 -1.3"/><axis xyz="1 2 -3"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="jfix" type="fixed"><parent link="d"/><child link="e"/>
    <origin xyz="0.1 0.1 0.1" rpy="0.5 0.5 0.5"/></joint>
  <joint name="jpz" type="prismatic"><parent link="e"/><child link="f"/>
    <origin xyz="0 0 0.2" rpy="0 0.3 0"/><axis xyz="0 0 1"/><limit lower="-0.5" upper="0.5" effort="1" velocity="1"/></joint>
  <joint name="jpg" type="prismatic"><parent link="f"/><child link="g"/>
    <origin xyz="0.2 0 0" rpy="0.1 0.2 0.3"/><axis xyz="0.3 -0.4 1"/><limit lower="-0.5" upper="0.5" effort="1" velocity="1"/></joint>
  <joint name="jmx" type="revolute"><parent link="g"/><child link="h"/>
    <origin xyz="0.1 0 0"/><axis xyz="-1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="jy" type="revolute"><parent link="h"/><child link="i"/>
    <origin xyz="0 0.1 0" rpy="0.7 0 0"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/>
    <mimic joint="jx" multiplier="-1.5" offset="0.25"/></joint>
  <joint name="jmz" type="revolute"><parent link="a"/><child link="k"/>
    <origin xyz="0 0 0.4" rpy="0 0 2.1"/><axis xyz="0 0 -1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="jpmx" type="prismatic"><parent link="k"/><child link="m"/>
    <origin xyz="0.3 0 0"/><axis xyz="-1 0 0"/><limit lower="-0.5" upper="0.5" effort="1" velocity="1"/>
    <mimic joint="jmz" multiplier="0.1" offset="-0.05"/></joint>
</robot>)";

/// The plain definition (robot_model.h): X_WL[child] = X_WL[parent] * X_PJ * X_JC(value), with
/// general 4 x 4 products and an angle-axis matrix for every revolute joint.
std::vector<Eigen::Isometry3d> referenceKinematics(const RobotModel& m, const Eigen::VectorXd& q) {
  std::vector<Eigen::Isometry3d> X_WL(m.numLinks(), Eigen::Isometry3d::Identity());
  X_WL[0] = m.basePose();
  for (const Joint& joint : m.joints()) {
    Eigen::Matrix4d X_JC = Eigen::Matrix4d::Identity();
    if (joint.moves()) {
      const double value = joint.multiplier * q[joint.variable] + joint.offset;
      if (joint.type == JointType::Prismatic) {
        X_JC.block<3, 1>(0, 3) = value * joint.axis;
      } else {
        X_JC.block<3, 3>(0, 0) = Eigen::AngleAxisd(value, joint.axis).toRotationMatrix();
      }
    }
    const Eigen::Matrix4d X = X_WL[joint.parentLink].matrix() * joint.X_PJ.matrix() * X_JC;
    X_WL[joint.childLink] = Eigen::Isometry3d(X);
  }
  return X_WL;
}

/// forwardKinematics against referenceKinematics on random configurations (beyond the limits
/// too, up to +-1200 and +-1.6e7: any finite value is accepted), to 1e-12 per entry of each pose
/// (relative to the size of its translation when that is above 1 m).
void checkAgainstReference(const RobotModel& m, std::mt19937& rng, int trials) {
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  std::vector<Eigen::Isometry3d> X_WL;
  for (int trial = 0; trial < trials; ++trial) {
    Eigen::VectorXd q = deepcheck::test::randomConfiguration(m, rng);
    if (trial % 4 == 3) {
      for (int v = 0; v < q.size(); ++v) q[v] = u(rng);
    }
    if (trial % 8 == 5) {  // far beyond the limits: the argument reduction of the sines
      for (int v = 0; v < q.size(); ++v) q[v] = 300.0 * u(rng);
    }
    if (trial % 16 == 9) {  // every other value beyond 2^20, where the library's sines take over
      for (int v = 0; v < q.size(); ++v) q[v] = (v % 2 == 0 ? 1.0 : 4.0e6) * u(rng);
    }
    if (trial == 1) {  // on and next to the quadrant boundaries of the sines
      for (int v = 0; v < q.size(); ++v) q[v] = std::nextafter((v - 3) * M_PI / 4, v % 2 ? 10.0 : -10.0);
    }
    forwardKinematics(m, q, X_WL);
    const std::vector<Eigen::Isometry3d> expected = referenceKinematics(m, q);
    for (int l = 0; l < m.numLinks(); ++l) {
      // Relative to the pose's size: prismatic joints driven 1000 m away round off at 1e-13 m.
      const double scale = std::max(1.0, expected[l].translation().cwiseAbs().maxCoeff());
      const double error = (X_WL[l].matrix() - expected[l].matrix()).cwiseAbs().maxCoeff() / scale;
      BOOST_CHECK_MESSAGE(error <= 1e-12, m.name() << " link " << m.link(l).name << " trial " << trial
                                                   << ": differs from the plain product by " << error);
      BOOST_CHECK(X_WL[l].matrix().row(3) == Eigen::RowVector4d(0, 0, 0, 1));
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(robots_kinematics)

BOOST_AUTO_TEST_CASE(matches_plain_product_every_joint_kind) {
  RobotModel m = RobotModel::fromUrdfString(kAxesUrdf, "", {}, "axes.urdf");
  BOOST_TEST(m.numVariables() == 8);
  std::mt19937 rng(31337);
  checkAgainstReference(m, rng, 400);
  Eigen::Isometry3d X_WR = Eigen::Isometry3d::Identity();
  X_WR.translation() = Eigen::Vector3d(-0.7, 1.0 / 3.0, 2.5);
  X_WR.linear() = Eigen::AngleAxisd(-1.2, Eigen::Vector3d(2, 1, -1).normalized()).toRotationMatrix();
  m.setBasePose(X_WR);
  checkAgainstReference(m, rng, 400);
}

BOOST_AUTO_TEST_CASE(matches_plain_product_real_robots) {
  const std::string data = std::string(DEEPCHECK_SOURCE_DIR) + "/robots/data";
  LoadOptions o;
  o.packageRoots = {data};
  o.useRosPackagePath = false;
  std::mt19937 rng(4242);
  checkAgainstReference(RobotModel::fromUrdfFile(data + "/deepcheck_arm/urdf/deepcheck_arm.urdf", o), rng, 500);
  checkAgainstReference(RobotModel::fromUrdfFile(data + "/scenes/shelf.urdf", o), rng, 5);
  if (!haveShared("matches_plain_product_real_robots (Panda, UR5)")) return;
  RobotModel panda = loadPanda();
  checkAgainstReference(panda, rng, 500);
  checkAgainstReference(loadUr5(), rng, 500);
  Eigen::Isometry3d X_WR = Eigen::Isometry3d::Identity();
  X_WR.translation() = Eigen::Vector3d(0.3, -1.0 / 3.0, 0.7);
  X_WR.linear() = Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, -1, 2).normalized()).toRotationMatrix();
  panda.setBasePose(X_WR);
  checkAgainstReference(panda, rng, 500);
}

BOOST_AUTO_TEST_CASE(panda_home_pose_matches_franka_dh) {
  if (!haveShared("panda_home_pose_matches_franka_dh")) return;
  const RobotModel m = loadPanda();
  Eigen::VectorXd q(8);
  q << 0, -M_PI / 4, 0, -3 * M_PI / 4, 0, M_PI / 2, M_PI / 4, 0.02;
  const auto X_WL = forwardKinematics(m, q);
  const auto dh = pandaDh(q);
  // The URDF writes pi/2 as 1.57079632679 (5e-12 short): agreement to 1e-9 m / rad.
  for (int i = 1; i <= 8; ++i) {
    const int link = m.linkIndex("panda_link" + std::to_string(i));
    BOOST_TEST_CONTEXT("panda_link" << i) {
      BOOST_TEST((X_WL[link].translation() - dh[i - 1].translation()).norm() < 1e-9);
      BOOST_TEST((X_WL[link].linear() - dh[i - 1].linear()).norm() < 1e-9);
    }
  }
  // The flange in the home pose, as published for the Panda's "ready" pose: about
  // (0.307, 0, 0.590) m, pointing down.
  const Eigen::Isometry3d& flange = X_WL[m.linkIndex("panda_link8")];
  BOOST_TEST((flange.translation() - Eigen::Vector3d(0.307, 0.0, 0.590)).norm() < 1e-3);
  BOOST_TEST((flange.linear() * Eigen::Vector3d::UnitZ() - Eigen::Vector3d(0, 0, -1)).norm() < 1e-9);
  // The hand is the flange turned by -pi/4 about z; the fingers sit 0.0584 m further, each
  // opened by q[7] along +-y of the hand.
  const Eigen::Isometry3d& hand = X_WL[m.linkIndex("panda_hand")];
  BOOST_TEST(hand.isApprox(flange * rotZ(-M_PI / 4), 1e-9));
  const Eigen::Vector3d left = hand * Eigen::Vector3d(0, 0.02, 0.0584);
  const Eigen::Vector3d right = hand * Eigen::Vector3d(0, -0.02, 0.0584);
  BOOST_TEST((X_WL[m.linkIndex("panda_leftfinger")].translation() - left).norm() < 1e-12);
  BOOST_TEST((X_WL[m.linkIndex("panda_rightfinger")].translation() - right).norm() < 1e-12);
}

BOOST_AUTO_TEST_CASE(panda_random_poses_match_franka_dh) {
  if (!haveShared("panda_random_poses_match_franka_dh")) return;
  const RobotModel m = loadPanda();
  std::mt19937 rng(20240611);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = deepcheck::test::randomConfiguration(m, rng);
    const auto X_WL = forwardKinematics(m, q);
    const auto dh = pandaDh(q);
    const int flange = m.linkIndex("panda_link8");
    BOOST_TEST((X_WL[flange].translation() - dh[7].translation()).norm() < 1e-9);
    BOOST_TEST((X_WL[flange].linear() - dh[7].linear()).norm() < 1e-9);
  }
}

BOOST_AUTO_TEST_CASE(ur5_matches_universal_robots_dh) {
  if (!haveShared("ur5_matches_universal_robots_dh")) return;
  const RobotModel m = loadUr5();
  // The DH base frame is the URDF's "base" link (base_link turned by pi), the DH tool frame is
  // "tool0".
  const int base = m.linkIndex("base");
  const int tool = m.linkIndex("tool0");
  {
    const auto X_WL = forwardKinematics(m, Eigen::VectorXd::Zero(6));
    const Eigen::Isometry3d X_BT = X_WL[base].inverse() * X_WL[tool];
    // Zero pose from the DH parameters: (a2 + a3, -(d4 + d6), d1 - d5).
    const Eigen::Vector3d expected(-0.425 - 0.39225, -(0.10915 + 0.0823), 0.089159 - 0.09465);
    BOOST_TEST((X_BT.translation() - expected).norm() < 1e-9);
    BOOST_TEST((X_BT.translation() - ur5Dh(Eigen::VectorXd::Zero(6)).translation()).norm() < 1e-9);
    BOOST_TEST((X_BT.linear() - ur5Dh(Eigen::VectorXd::Zero(6)).linear()).norm() < 1e-9);
  }
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = deepcheck::test::randomConfiguration(m, rng);
    const auto X_WL = forwardKinematics(m, q);
    const Eigen::Isometry3d X_BT = X_WL[base].inverse() * X_WL[tool];
    const Eigen::Isometry3d dh = ur5Dh(q);
    BOOST_TEST((X_BT.translation() - dh.translation()).norm() < 1e-9);
    BOOST_TEST((X_BT.linear() - dh.linear()).norm() < 1e-9);
  }
}

BOOST_AUTO_TEST_CASE(jacobians_match_finite_differences) {
  if (!haveShared("jacobians_match_finite_differences")) return;
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  RobotModel panda = loadPanda();
  Eigen::Isometry3d X_WR = Eigen::Isometry3d::Identity();
  X_WR.translation() = Eigen::Vector3d(0.3, -1.0 / 3.0, 0.7);
  X_WR.linear() = Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, -1, 2).normalized()).toRotationMatrix();
  panda.setBasePose(X_WR);
  const RobotModel ur5 = loadUr5();
  for (const RobotModel* m : std::vector<const RobotModel*>{&panda, &ur5}) {
    for (int trial = 0; trial < 5; ++trial) {
      const Eigen::VectorXd q = deepcheck::test::randomConfiguration(*m, rng);
      for (int link = 0; link < m->numLinks(); ++link) {
        checkJacobians(*m, q, link, Eigen::Vector3d(u(rng), u(rng), u(rng)));
      }
    }
  }
  // The overload that takes q agrees with the one that takes poses.
  const Eigen::VectorXd q = deepcheck::test::randomConfiguration(panda, rng);
  const int hand = panda.linkIndex("panda_hand");
  const Eigen::Vector3d p(0.01, 0.02, 0.1);
  BOOST_TEST((pointJacobian(panda, q, hand, p) - pointJacobian(panda, forwardKinematics(panda, q), hand, p)).norm() ==
             0.0);
  // The right finger follows the left finger's variable through the mimic joint: opposite axes.
  const Eigen::Matrix3Xd Jl = pointJacobian(panda, q, panda.linkIndex("panda_leftfinger"), p);
  const Eigen::Matrix3Xd Jr = pointJacobian(panda, q, panda.linkIndex("panda_rightfinger"), p);
  BOOST_TEST((Jl.col(7) + Jr.col(7)).norm() < 1e-15);
  BOOST_TEST(Jl.col(7).norm() == 1.0, boost::test_tools::tolerance(1e-14));
  // A link before any joint does not move.
  BOOST_TEST(pointJacobian(panda, q, 0, p).norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(jacobian_of_mimic_chain) {
  const RobotModel m = RobotModel::fromUrdfString(kMimicUrdf, "", {}, "mimic.urdf");
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = Eigen::VectorXd::Constant(1, u(rng));
    checkJacobians(m, q, m.linkIndex("c"), Eigen::Vector3d(u(rng), u(rng), u(rng)));
  }
}

BOOST_AUTO_TEST_CASE(forward_kinematics_reuses_output) {
  const RobotModel m = RobotModel::fromUrdfString(kMimicUrdf, "", {}, "mimic.urdf");
  std::vector<Eigen::Isometry3d> X_WL;
  forwardKinematics(m, Eigen::VectorXd::Constant(1, 0.2), X_WL);
  const Eigen::Isometry3d* data = X_WL.data();
  forwardKinematics(m, Eigen::VectorXd::Constant(1, -0.4), X_WL);
  BOOST_TEST(X_WL.data() == data);  // same storage: no reallocation
  BOOST_TEST(X_WL.size() == 4u);
}

BOOST_AUTO_TEST_CASE(error_bad_configuration) {
  const RobotModel m = RobotModel::fromUrdfString(kMimicUrdf, "", {}, "mimic.urdf");
  checkThrows([&] { forwardKinematics(m, Eigen::VectorXd::Zero(3)); }, {"mimic", "3 values", "1 variables", "j1"});
  checkThrows([&] { forwardKinematics(m, Eigen::VectorXd::Constant(1, std::numeric_limits<double>::quiet_NaN())); },
              {"q[0]", "j1", "nan"});
  checkThrows(
      [&] {
        pointJacobian(m, Eigen::VectorXd::Constant(1, std::numeric_limits<double>::infinity()), 1,
                      Eigen::Vector3d::Zero());
      },
      {"q[0]", "inf"});
  const auto X_WL = forwardKinematics(m, Eigen::VectorXd::Zero(1));
  checkThrows([&] { pointJacobian(m, X_WL, 7, Eigen::Vector3d::Zero()); }, {"link index 7"});
  checkThrows([&] { pointJacobian(m, std::vector<Eigen::Isometry3d>(2), 1, Eigen::Vector3d::Zero()); },
              {"2 link poses", "4 links"});
}

BOOST_AUTO_TEST_SUITE_END()
