// MoveIt planning scenes in a World (World::addPlanningScene): obstacles named after the objects,
// posed through the robot's links and the frame aliases.

#include "checker_test_util.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/moveit_scene.h"
#include "deepcheck/robots/pair_filter.h"

#include <boost/test/unit_test.hpp>

#include <string>
#include <vector>

namespace deepcheck::checker {
namespace {

using test::haveShared;
using test::sharedDir;

const std::string kSliderWall = std::string(DEEPCHECK_SOURCE_DIR) + "/tests/data/moveit_scenes/slider_wall.yaml";

Eigen::VectorXd slide(double x) { return Eigen::VectorXd::Constant(1, x); }

/// The Panda with its SRDF's disabled pairs.
World pandaWorld() {
  WorldOptions options = test::testWorldOptions();
  options.disabledPairs = robots::readSrdfDisabledPairs(
      sharedDir() + "/robots/panda/moveit_resources_panda_moveit_config/config/panda.srdf");
  return World(test::loadPanda(), options);
}

/// The Panda's configuration from its 7 arm joints (fingers at their default).
Eigen::VectorXd pandaArm(const robots::RobotModel& panda, const std::vector<double>& arm) {
  Eigen::VectorXd q = panda.defaultConfiguration();
  for (std::size_t j = 0; j < arm.size(); ++j) {
    const int v = panda.variableIndex("panda_joint" + std::to_string(j + 1));
    BOOST_REQUIRE(v >= 0);
    q[v] = arm[j];
  }
  return q;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_planning_scene)

BOOST_AUTO_TEST_CASE(hand_written_scene_names_and_poses_obstacles) {
  World world(test::sliderRobot(0.2), test::testWorldOptions());
  PlanningSceneOptions options;
  options.frameAliases = {{"world", "base"}};
  const std::vector<int> ids = world.addPlanningScene(robots::loadPlanningScene(kSliderWall), options);
  BOOST_REQUIRE_EQUAL(ids.size(), 3u);
  BOOST_CHECK_EQUAL(world.obstacle(ids[0]).name, "wall");
  BOOST_CHECK_EQUAL(world.obstacle(ids[1]).name, "post/0");
  BOOST_CHECK_EQUAL(world.obstacle(ids[2]).name, "post/1");
  BOOST_CHECK_SMALL((world.obstacle(ids[2]).X_WO.translation() - Eigen::Vector3d(-1.0, 0, 0.6)).norm(), 1e-12);
  // The cube (edge 0.2, centre at x) meets the wall (x in [0.95, 1.05]) from x = 0.85 on and
  // the post (radius 0.05 at x = -1) from x = -0.85 down.
  BOOST_CHECK(world.isFree(slide(0.0)));
  BOOST_CHECK(world.isFree(slide(0.8)));
  BOOST_CHECK(!world.isFree(slide(0.9)));
  BOOST_CHECK(!world.isFree(slide(-0.9)));
  const DistanceResult d = world.signedDistance(slide(0.9));
  BOOST_CHECK_EQUAL(d.closest.nameB, "obstacle/wall");
}

BOOST_AUTO_TEST_CASE(unknown_frame_leaves_the_world_unchanged) {
  World world(test::sliderRobot(0.2), test::testWorldOptions());
  test::checkThrowsWith([&] { world.addPlanningScene(robots::loadPlanningScene(kSliderWall)); }, "world");
  BOOST_CHECK(world.obstacleIds().empty());
}

BOOST_AUTO_TEST_CASE(bookshelf_small_with_the_panda) {
  if (!haveShared("the bookshelf scene with the Panda")) return;
  World world = pandaWorld();
  const robots::PlanningScene scene =
      robots::loadPlanningScene(sharedDir() + "/scenes/motion_bench_maker/configs/scenes/bookshelf/scene_small.yaml");
  PlanningSceneOptions options;
  options.frameAliases = {{"base_link", "panda_link0"}};
  const std::vector<int> ids = world.addPlanningScene(scene, options);
  BOOST_CHECK_EQUAL(ids.size(), 7u);  // 3 cans, 2 boards, 2 sides: one shape each
  BOOST_CHECK_EQUAL(world.summaryCounts().obstacles, 7);
  const robots::RobotModel& panda = world.robot();
  // MoveIt's "ready" pose: the hand in front of the base, below the bottom board (z = 0.98).
  BOOST_CHECK(world.isFree(pandaArm(panda, {0, -0.785, 0, -2.356, 0, 1.571, 0.785})));
  // Leaning forward by 1 rad, elbow bent: the arm passes under the bottom board.
  BOOST_CHECK(world.isFree(pandaArm(panda, {0, 1.0, 0, -0.5, 0, 1.0, 0.785})));
  // Leaning forward by 0.5 rad, nearly straight: the wrist goes up through the bottom board.
  const Eigen::VectorXd into = pandaArm(panda, {0, 0.5, 0, -0.1, 0, 1.0, 0.785});
  BOOST_CHECK(!world.isFree(into));
  const DistanceResult d = world.signedDistance(into);
  BOOST_CHECK_EQUAL(d.closest.nameB, "obstacle/shelf_bottom");
}

BOOST_AUTO_TEST_SUITE_END()

}  // namespace deepcheck::checker
