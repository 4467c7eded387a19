// End-to-end tests of `deepcheck plan --goal-pose`: the bundled arm among the objects of a
// hand-written planning scene, and the Panda in MotionBenchMaker's small bookshelf (skipped
// without ../shared), plan to a pose of a link; the path's last configuration reaches it within
// the tolerances and every waypoint is free in the world the library builds from the same files.
// Bad pose goals are reported.

#include "robot_files.h"
#include "tool_runner.h"

#include "common/test_paths.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/robot_model.h"

#include <boost/test/unit_test.hpp>

#include <Eigen/Geometry>

#include <string>
#include <vector>

using namespace deepcheck;
using namespace deepcheck::tool_test;

namespace {

/// A box beside the arm, a sphere behind it and a cylinder post in front, in frame 'world'
/// (aliased to the arm's base_link).
const char* kObjects =
    "world:\n"
    "  collision_objects:\n"
    "    - header: {frame_id: world}\n"
    "      id: crate\n"
    "      primitives: [{type: box, dimensions: [0.3, 0.3, 0.6]}]\n"
    "      primitive_poses: [{position: [0, -0.6, 0.3], orientation: [0, 0, 0, 1]}]\n"
    "    - header: {frame_id: world}\n"
    "      id: ball\n"
    "      primitives: [{type: sphere, dimensions: [0.1]}]\n"
    "      primitive_poses: [{position: [-0.5, 0, 0.5], orientation: [0, 0, 0, 1]}]\n"
    "    - header: {frame_id: world}\n"
    "      id: post\n"
    "      primitives: [{type: cylinder, dimensions: [0.4, 0.03]}]\n"
    "      primitive_poses: [{position: [0.35, 0.35, 0.2], orientation: [0, 0, 0, 1]}]\n";

const std::string kArmStart = " --start 0 -0.4 0 -1.6 0 1.2 0";

/// The bundled arm's goal of robots/data/README.md's table problem.
Eigen::VectorXd armGoal() {
  Eigen::VectorXd goal(7);
  goal << -0.14, 0.61, 0.24, -0.77, -0.14, 1.77, -2.23;
  return goal;
}

/// The command-line words of the bundled arm among the objects of `scene`, from kArmStart.
std::string armArgs(const std::string& scene) {
  return " --robot " + quote(armUrdf()) + " --srdf " + quote(armSrdf()) + " --package-path " +
         quote(test::bundledDataDir()) + " --scene " + quote(scene) + " --frame-alias world=base_link" + kArmStart;
}

/// " LINK x y z qx qy qz qw" of the pose X of `link`.
std::string poseWords(const std::string& link, const Eigen::Isometry3d& X) {
  const Eigen::Quaterniond r(X.rotation());
  const Eigen::Vector3d p = X.translation();
  return " " + link + " " + formatNumber(p.x()) + " " + formatNumber(p.y()) + " " + formatNumber(p.z()) + " " +
         formatNumber(r.x()) + " " + formatNumber(r.y()) + " " + formatNumber(r.z()) + " " + formatNumber(r.w());
}

/// " LINK x y z qx qy qz qw" of the link's pose at q.
std::string poseWords(const robots::RobotModel& robot, const std::string& link, const Eigen::VectorXd& q) {
  return poseWords(link, robots::forwardKinematics(robot, q)[static_cast<std::size_t>(robot.linkIndex(link))]);
}

/// The waypoints of a path file; each must have the robot's variable count.
std::vector<Eigen::VectorXd> readPath(const std::string& file, int variables) {
  std::vector<Eigen::VectorXd> path;
  for (const std::string& line : lines(readText(file))) {
    const std::vector<std::string> f = fields(line);
    BOOST_TEST_REQUIRE(static_cast<int>(f.size()) == variables, line);
    Eigen::VectorXd q(variables);
    for (int v = 0; v < variables; ++v) q[v] = std::stod(f[static_cast<std::size_t>(v)]);
    path.push_back(q);
  }
  return path;
}

/// Plans to the pose of `link` at qGoal; checks the exit status, the report, that the last
/// waypoint reaches the pose within the default tolerances (robots::tol) and that every
/// waypoint is free in `world`.
void planToPose(const Scratch& s, const std::string& args, const checker::World& world, const std::string& link,
                const Eigen::VectorXd& qGoal) {
  BOOST_TEST_REQUIRE(world.isFree(qGoal), "the goal configuration must be free");
  const std::string out = s.path("path.txt");
  const Run r = s.run(
      "plan" + args + " --goal-pose" + poseWords(world.robot(), link, qGoal) + " --seed 2 --time 5 --out " + quote(out),
      "", "ROS_PACKAGE_PATH=");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(r.err.find("goal pose of " + link + ": reached within") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("certified") != std::string::npos, r.err);
  const std::vector<Eigen::VectorXd> path = readPath(out, world.robot().numVariables());
  BOOST_TEST_REQUIRE(path.size() >= 2u);
  for (const Eigen::VectorXd& q : path) BOOST_TEST(world.isFree(q));
  const int index = world.robot().linkIndex(link);
  const auto reached = robots::forwardKinematics(world.robot(), path.back())[static_cast<std::size_t>(index)];
  const auto target = robots::forwardKinematics(world.robot(), qGoal)[static_cast<std::size_t>(index)];
  BOOST_TEST((reached.translation() - target.translation()).norm() <= robots::tol::kIkPositionTolerance);
  BOOST_TEST(Eigen::AngleAxisd(reached.rotation() * target.rotation().transpose()).angle() <=
             robots::tol::kIkOrientationTolerance);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(tool_plan_pose)

BOOST_AUTO_TEST_CASE(the_bundled_arm_reaches_a_pose_among_planning_scene_objects) {
  Scratch s;
  const std::string scene = s.write("objects.yaml", kObjects);
  const checker::World world =
      libraryWorld(armUrdf(), armSrdf(), test::bundledDataDir(), scene, {{"world", "base_link"}});
  planToPose(s, armArgs(scene), world, "flange", armGoal());
}

BOOST_AUTO_TEST_CASE(the_panda_reaches_a_pose_in_the_bookshelf) {
  if (!test::haveShared("plan --goal-pose in the MotionBenchMaker bookshelf")) return;
  Scratch s;
  const checker::World world =
      libraryWorld(pandaUrdf(), pandaSrdf(), pandaDir(), bookshelfScene(), {{"base_link", "panda_link0"}});
  Eigen::VectorXd goal(8);
  goal << -2.2643608956862633, -1.7277648984445335, -0.61333232404950022, -1.887547154810622, 2.6237618279716743,
      1.1520985734847371, -1.8950207790478606, 0.02;
  planToPose(s,
             " --robot " + quote(pandaUrdf()) + " --srdf " + quote(pandaSrdf()) + " --package-path " +
                 quote(pandaDir()) + " --scene " + quote(bookshelfScene()) + " --frame-alias base_link=panda_link0" +
                 " --start 0 -0.785 0 -2.356 0 1.571 0.785 0.04",
             world, "panda_hand", goal);
}

BOOST_AUTO_TEST_CASE(a_position_box_is_met_along_the_goal_axes) {
  Scratch s;
  const std::string scene = s.write("objects.yaml", kObjects);
  const checker::World world =
      libraryWorld(armUrdf(), armSrdf(), test::bundledDataDir(), scene, {{"world", "base_link"}});
  // The goal pose 8 cm along its own x from a reachable one; the box is 20 cm along x, 2 mm
  // across: the flange ends inside it, short of the centre.
  const int flange = world.robot().linkIndex("flange");
  Eigen::Isometry3d X_WT = robots::forwardKinematics(world.robot(), armGoal())[static_cast<std::size_t>(flange)];
  X_WT.translation() += X_WT.rotation() * Eigen::Vector3d(0.08, 0.0, 0.0);
  const Eigen::Vector3d p = X_WT.translation();
  const std::string out = s.path("path.txt");
  const Run run = s.run("plan" + armArgs(scene) + " --goal-pose" + poseWords("flange", X_WT) +
                            " --position-box 0.2 0.002 0.002 --seed 2 --time 5 --out " + quote(out),
                        "", "ROS_PACKAGE_PATH=");
  BOOST_TEST_REQUIRE(run.status == 0, run.err);
  const std::vector<Eigen::VectorXd> path = readPath(out, world.robot().numVariables());
  const Eigen::Isometry3d reached =
      robots::forwardKinematics(world.robot(), path.back())[static_cast<std::size_t>(flange)];
  const Eigen::Vector3d d = X_WT.inverse() * reached.translation();
  BOOST_TEST(std::abs(d.x()) <= 0.1);
  BOOST_TEST(std::abs(d.y()) <= 0.001);
  BOOST_TEST(std::abs(d.z()) <= 0.001);
  BOOST_TEST((reached.translation() - p).norm() > robots::tol::kIkPositionTolerance);  // not the sphere's answer
}

BOOST_AUTO_TEST_CASE(bad_pose_goals_are_reported) {
  Scratch s;
  const std::string scene = s.write("objects.yaml", kObjects);
  const std::string arm = armArgs(scene) + " --out " + quote(s.path("path.txt"));
  const auto fails = [&](const std::string& args, int status, const std::string& part) {
    const Run r = s.run("plan" + arm + args, "", "ROS_PACKAGE_PATH=");
    BOOST_TEST(r.status == status, args << ": " << r.err);
    BOOST_TEST(r.err.find(part) != std::string::npos, args << ": " << r.err);
  };
  fails(" --goal-pose flange 0.5 0 0.5 0 0 0 1 --goal 0 0 0 0 0 0 0", 2, "--goal and --goal-pose exclude each other");
  fails(" --goal-pose flange 0.5 0 0.5 0 0 0 0", 2, "the quaternion qx qy qz qw = 0 0 0 0 is zero");
  fails(" --goal-pose flange 0.5 0 0.5 0 0", 2, "--goal-pose needs a link and 7 numbers");
  fails(" --goal-pose flange 0.5 0 0.5 0 0 0 1 --position-tol 0", 2, "--position-tol must be > 0 m");
  fails(" --goal 0 0 0 0 0 0 0.1 --orientation-tol 0.1", 2,
        "--position-tol, --position-box and --orientation-tol need --goal-pose");
  fails(" --goal-pose flange 0.5 0 0.5 0 0 0 1 --position-box 0.1 0.1", 2, "--position-box needs 3 edge lengths");
  fails(" --goal-pose flange 0.5 0 0.5 0 0 0 1 --position-box 0.1 0 0.1", 2, "edge lengths must be > 0 m, got 0");
  fails(" --goal-pose flange 0.5 0 0.5 0 0 0 1 --position-box 0.1 0.1 0.1 --position-tol 0.1", 2,
        "--position-tol and --position-box exclude each other");
  fails(" --goal-pose tool0 0.5 0 0.5 0 0 0 1", 1, "no link named 'tool0'");
  // 5 m away: out of reach; the best attempt's error is reported.
  fails(" --goal-pose flange 5 0 0.5 0 0 0 1", 1,
        "no inverse kinematics solution for link 'flange' reaches the goal pose: the best attempt is ");
  // A quaternion component beyond 1e154 (its square overflows) still gives a direction: the
  // pose is accepted (w = 1e200: the identity) and only found out of reach.
  fails(" --goal-pose flange 5 0 0.5 0 0 0 1e200", 1,
        "no inverse kinematics solution for link 'flange' reaches the goal pose: the best attempt is ");
  // 5 m away with a 10 cm box: the report names the box.
  fails(" --goal-pose flange 5 0 0.5 0 0 0 1 --position-box 0.1 0.1 0.1", 1,
        "(tolerances box 0.1 0.1 0.1 m, 0.001 rad)");
  // Inside the crate: reachable, but only in collision.
  fails(" --goal-pose flange 0 -0.6 0.3 1 0 0 0", 1,
        "no collision-free inverse kinematics solution for link 'flange' at the goal pose: the ");
}

BOOST_AUTO_TEST_SUITE_END()
