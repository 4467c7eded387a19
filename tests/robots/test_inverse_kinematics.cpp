// Inverse kinematics: poses reached by forward kinematics of random configurations are solved
// (FK of the solution within the tolerances, the solution within the joint limits), an unreachable
// pose is reported as such with its best error, results depend only on the seed, and bad input is
// rejected with a message naming the value.

#include "robots_test_util.h"

#include "deepcheck/robots/inverse_kinematics.h"
#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/random_configuration.h"
#include "deepcheck/robots/robot_model.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <ostream>
#include <string>

namespace deepcheck::robots {
/// For Boost.Test messages.
inline std::ostream& operator<<(std::ostream& out, IkStatus status) { return out << toString(status); }
}  // namespace deepcheck::robots

using namespace deepcheck::robots;
using deepcheck::robots::test::checkThrows;
using deepcheck::robots::test::haveShared;
using deepcheck::robots::test::loadBundledArm;
using deepcheck::robots::test::loadPanda;

namespace {

/// The pose of `link` at a random configuration (generator seeded with `seed`): reachable.
Eigen::Isometry3d randomReachablePose(const RobotModel& model, const std::string& link, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  return forwardKinematics(model, randomConfiguration(model, rng))[model.linkIndex(link)];
}

bool withinLimits(const RobotModel& model, const Eigen::VectorXd& q) {
  return (q.array() >= model.lowerLimits().array()).all() && (q.array() <= model.upperLimits().array()).all();
}

/// `trials` poses of `link` from FK of random configurations; each solved from a random start
/// (never the configuration that made the pose). Requires at least `required` of them reached,
/// and checks every reported solution independently: FK within tolerance, within the limits.
void checkReachablePoses(const RobotModel& model, const std::string& link, int trials, int required) {
  std::mt19937_64 rng(7);
  const int index = model.linkIndex(link);
  int converged = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const Eigen::VectorXd qTarget = randomConfiguration(model, rng);
    const Eigen::Isometry3d X_WT = forwardKinematics(model, qTarget)[index];
    IkOptions options;
    options.seed = 1000 + trial;
    const IkResult result = solveInverseKinematics(model, link, X_WT, options);
    BOOST_TEST(withinLimits(model, result.q), "trial " << trial << ": outside the limits: " << result.q.transpose());
    const PoseError check = poseError(model, index, result.q, X_WT, options);
    BOOST_TEST(check.normalized == result.error.normalized);
    if (!result.converged()) {
      continue;
    }
    ++converged;
    BOOST_TEST(check.position <= options.positionTolerance, "trial " << trial << ": " << check.position << " m");
    BOOST_TEST(check.orientation <= options.orientationTolerance,
               "trial " << trial << ": " << check.orientation << " rad");
  }
  BOOST_TEST(converged >= required, converged << " of " << trials << " reached, " << required << " required");
}

}  // namespace

BOOST_AUTO_TEST_SUITE(robots_inverse_kinematics)

BOOST_AUTO_TEST_CASE(bundled_arm_reaches_random_reachable_poses) {
  checkReachablePoses(loadBundledArm(), "flange", 200, 198);
}

BOOST_AUTO_TEST_CASE(panda_reaches_random_reachable_poses) {
  if (!haveShared("panda_reaches_random_reachable_poses")) return;
  checkReachablePoses(loadPanda(), "panda_link8", 200, 198);
}

BOOST_AUTO_TEST_CASE(unreachable_pose_is_not_converged_with_best_error) {
  const RobotModel arm = loadBundledArm();
  // 5 m above the base: far beyond the arm's reach (about 1.3 m).
  const Eigen::Isometry3d X_WT(Eigen::Translation3d(0.0, 0.0, 5.0));
  IkOptions options;
  options.maxRestarts = 3;
  const IkResult result = solveInverseKinematics(arm, "flange", X_WT, options);
  BOOST_TEST(!result.converged());
  BOOST_TEST(result.status == IkStatus::NotConverged);
  BOOST_TEST(result.attempts == 4);
  BOOST_TEST(withinLimits(arm, result.q));
  // The best error is the error of the returned configuration, and the arm's straight-up
  // configuration gets within its reach of the target: the error is the gap, ~3.7 m.
  const PoseError check = poseError(arm, arm.linkIndex("flange"), result.q, X_WT, options);
  BOOST_TEST(check.position == result.error.position);
  const double reach = forwardKinematics(arm, Eigen::VectorXd::Zero(7))[arm.linkIndex("flange")].translation().norm();
  BOOST_TEST(result.error.position >= 5.0 - reach - 1e-9);
  BOOST_TEST(result.error.position <= 5.0 - reach + 0.05);
}

/// One prismatic joint along (1, 1, 1)/sqrt(3), travel [0, 1] m: the tip reaches exactly the
/// points t (1, 1, 1)/sqrt(3), t in [0, 1], with the world's orientation.
const char* const kDiagonalSliderUrdf = R"(<robot name="slider">
  <link name="base"/><link name="tip"/>
  <joint name="slide" type="prismatic"><parent link="base"/><child link="tip"/>
    <axis xyz="0.5773502691896258 0.5773502691896258 0.5773502691896258"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/></joint>
</robot>)";

BOOST_AUTO_TEST_CASE(position_box_admits_a_corner_the_sphere_does_not) {
  const RobotModel slider = RobotModel::fromUrdfString(kDiagonalSliderUrdf, "", {}, "slider.urdf");
  const Eigen::Vector3d u = Eigen::Vector3d::Ones().normalized();
  const int tip = slider.linkIndex("tip");
  IkOptions sphere;
  sphere.positionTolerance = 0.05;
  sphere.maxRestarts = 2;
  IkOptions box = sphere;
  box.positionBox = Eigen::Vector3d::Constant(0.1);
  // 6 cm beyond the end of travel along the diagonal: out of the 5 cm sphere, inside the 10 cm box
  // (5 cm from its centre to each face; 3.46 cm per axis).
  const Eigen::Isometry3d X_WT(Eigen::Translation3d(1.06 * u));
  const IkResult bySphere = solveInverseKinematics(slider, "tip", X_WT, sphere);
  BOOST_TEST(bySphere.status == IkStatus::NotConverged);
  BOOST_TEST(std::abs(bySphere.error.position - 0.06) < 1e-6);
  const IkResult byBox = solveInverseKinematics(slider, "tip", X_WT, box);
  BOOST_TEST_REQUIRE(byBox.converged());
  const Eigen::Vector3d reached = forwardKinematics(slider, byBox.q)[tip].translation();
  BOOST_TEST((reached - X_WT.translation()).cwiseAbs().maxCoeff() <= 0.05);
  BOOST_TEST(byBox.error.normalized == poseError(slider, tip, byBox.q, X_WT, box).normalized);
  // 9 cm beyond: outside the box's corner (8.66 cm away), so no solution, best end of travel.
  const IkResult tooFar = solveInverseKinematics(slider, "tip", Eigen::Isometry3d(Eigen::Translation3d(1.09 * u)), box);
  BOOST_TEST(tooFar.status == IkStatus::NotConverged);
  BOOST_TEST(std::abs(tooFar.q[0] - 1.0) < 1e-6);
  BOOST_TEST(std::abs(tooFar.error.normalized - 0.09 / std::sqrt(3.0) / 0.05) < 1e-6);
}

BOOST_AUTO_TEST_CASE(position_box_applies_to_its_frame_on_the_link) {
  // The box on a frame B 0.2 m along the slider's tip x axis, the box's axes turned 90 degrees
  // about z: B's origin is constrained, not the tip's, along B's target axes.
  const RobotModel slider = RobotModel::fromUrdfString(kDiagonalSliderUrdf, "", {}, "slider.urdf");
  const Eigen::Vector3d u = Eigen::Vector3d::Ones().normalized();
  const int tip = slider.linkIndex("tip");
  IkOptions box;
  box.positionBox = Eigen::Vector3d(0.02, 0.6, 0.6);
  box.boxPose = Eigen::Translation3d(0.2, 0.0, 0.0) * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ());
  // Target of the tip at 0.5 u: B's target origin at 0.5 u + (0.2, 0, 0); the box is thin along
  // B's x, which is the world's y. Reaching along u moves B's origin by t u; the thin axis bounds
  // |t - 0.5| / sqrt(3) <= 0.01.
  const Eigen::Isometry3d X_WT(Eigen::Translation3d(0.5 * u));
  box.initial = Eigen::VectorXd::Constant(1, 0.9);
  const IkResult r = solveInverseKinematics(slider, "tip", X_WT, box);
  BOOST_TEST_REQUIRE(r.converged());
  BOOST_TEST(std::abs(r.q[0] - 0.5) / std::sqrt(3.0) <= 0.01);
  BOOST_TEST(std::abs(r.q[0] - 0.5) > 1e-3);  // stopped at the box, not at the target
  const Eigen::Vector3d d =
      (X_WT * box.boxPose).inverse() * (forwardKinematics(slider, r.q)[tip] * box.boxPose.translation());
  BOOST_TEST(r.error.normalized == d.cwiseAbs().cwiseQuotient(0.5 * box.positionBox).maxCoeff());
}

BOOST_AUTO_TEST_CASE(joint_limits_are_respected_when_the_target_needs_more) {
  // Target made with joint 4 beyond its limit: the arm must stay within the limits anyway.
  const RobotModel arm = loadBundledArm();
  Eigen::VectorXd qBeyond = Eigen::VectorXd::Zero(7);
  qBeyond[1] = 0.5;
  qBeyond[3] = arm.upperLimits()[3] + 0.6;
  const int flange = arm.linkIndex("flange");
  const Eigen::Isometry3d X_WT = forwardKinematics(arm, qBeyond)[flange];
  IkOptions options;
  options.initial = Eigen::VectorXd::Zero(7);
  options.maxRestarts = 5;
  const IkResult result = solveInverseKinematics(arm, "flange", X_WT, options);
  BOOST_TEST(withinLimits(arm, result.q), result.q.transpose());
  if (result.converged()) {
    BOOST_TEST(poseError(arm, flange, result.q, X_WT, options).within());
  }
}

BOOST_AUTO_TEST_CASE(deterministic_for_a_seed) {
  const RobotModel arm = loadBundledArm();
  const Eigen::Isometry3d X_WT = randomReachablePose(arm, "flange", 3);
  IkOptions options;
  options.seed = 42;
  const IkResult a = solveInverseKinematics(arm, "flange", X_WT, options);
  const IkResult b = solveInverseKinematics(arm, "flange", X_WT, options);
  BOOST_TEST_REQUIRE(a.converged());
  BOOST_TEST(a.q == b.q);
  BOOST_TEST(a.iterations == b.iterations);
  // Other seeds start elsewhere and, the arm being redundant, end elsewhere.
  bool different = false;
  for (std::uint64_t seed = 43; seed < 48 && !different; ++seed) {
    options.seed = seed;
    const IkResult c = solveInverseKinematics(arm, "flange", X_WT, options);
    different = c.converged() && (c.q - a.q).norm() > 1e-3;
  }
  BOOST_TEST(different);
}

BOOST_AUTO_TEST_CASE(acceptance_test_filters_solutions) {
  const RobotModel arm = loadBundledArm();
  const Eigen::Isometry3d X_WT = randomReachablePose(arm, "flange", 5);
  IkOptions options;
  options.maxRestarts = 10;
  // Only solutions with joint 1 positive: accepted ones satisfy it.
  const IkResult some =
      solveInverseKinematics(arm, "flange", X_WT, options, [](const Eigen::VectorXd& q) { return q[0] > 0.0; });
  BOOST_TEST_REQUIRE(some.converged());
  BOOST_TEST(some.q[0] > 0.0);
  // Rejecting everything: never converged, every reached pose counted as rejected.
  int calls = 0;
  const IkResult none = solveInverseKinematics(arm, "flange", X_WT, options, [&](const Eigen::VectorXd&) {
    ++calls;
    return false;
  });
  BOOST_TEST(none.status == IkStatus::Rejected);
  BOOST_TEST(none.rejected == calls);
  BOOST_TEST(none.rejected >= 1);
  BOOST_TEST(none.error.within());
}

BOOST_AUTO_TEST_CASE(bad_input_is_named) {
  const RobotModel arm = loadBundledArm();
  const Eigen::Isometry3d X_WT(Eigen::Translation3d(0.3, 0.0, 0.5));
  checkThrows([&] { solveInverseKinematics(arm, "gripper", X_WT); }, {"gripper", "flange", "link1"});
  Eigen::Isometry3d nan = X_WT;
  nan.translation().x() = std::numeric_limits<double>::quiet_NaN();
  checkThrows([&] { solveInverseKinematics(arm, "flange", nan); }, {"flange", "not a finite rigid transform"});
  Eigen::Isometry3d sheared = X_WT;
  sheared.linear()(0, 1) = 0.1;
  checkThrows([&] { solveInverseKinematics(arm, "flange", sheared); }, {"not a finite rigid transform"});
  checkThrows([&] { poseFromQuaternion(Eigen::Vector3d(0.3, 0, 0.5), 0, 0, 0.5, 0.5); },
              {"not a unit quaternion", "0.707"});
  checkThrows([&] { poseFromQuaternion(Eigen::Vector3d(0.3, 0, 0.5), 0, 0, 0, std::nan("")); }, {"not finite"});
  const Eigen::Isometry3d fromQuaternion = poseFromQuaternion(Eigen::Vector3d(0.3, 0, 0.5), 0, 0, 0.7071, 0.7071);
  BOOST_TEST(std::abs(fromQuaternion.linear().determinant() - 1.0) < 1e-12);
  IkOptions options;
  options.positionTolerance = 0.0;
  checkThrows([&] { solveInverseKinematics(arm, "flange", X_WT, options); }, {"positionTolerance (m)", "is 0"});
  options = {};
  options.orientationTolerance = -1e-3;
  checkThrows([&] { solveInverseKinematics(arm, "flange", X_WT, options); }, {"orientationTolerance (rad)", "-0.001"});
  options = {};
  options.positionBox = Eigen::Vector3d(0.05, 0.0, 0.05);
  checkThrows([&] { solveInverseKinematics(arm, "flange", X_WT, options); },
              {"positionBox (m)", "(0.05, 0, 0.05)", "all zero"});
  options.positionBox = Eigen::Vector3d(0.05, std::nan(""), 0.05);
  checkThrows([&] { solveInverseKinematics(arm, "flange", X_WT, options); }, {"positionBox (m)", "nan"});
  options.positionBox = Eigen::Vector3d::Constant(0.05);
  options.boxPose = sheared;
  checkThrows([&] { solveInverseKinematics(arm, "flange", X_WT, options); },
              {"boxPose", "not a finite rigid transform"});
  options = {};
  options.maxIterations = 0;
  checkThrows([&] { solveInverseKinematics(arm, "flange", X_WT, options); }, {"maxIterations"});
  options = {};
  options.initial = Eigen::VectorXd::Zero(3);
  checkThrows([&] { solveInverseKinematics(arm, "flange", X_WT, options); }, {"3 values"});
}

BOOST_AUTO_TEST_SUITE_END()
