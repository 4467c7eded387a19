// Problem generation as MotionBenchMaker does it: the variation, query and robot files, scene
// variation, and generated problems (collision free, goal at the query pose, reproducible).

#include "common/test_paths.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/problems/problem_generation.h"
#include "deepcheck/robots/kinematics.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

namespace deepcheck::problems {
namespace {

using namespace planners;

using deepcheck::test::haveShared;
using deepcheck::test::sharedDir;

std::string mbm() { return sharedDir() + "/scenes/motion_bench_maker/configs"; }
std::string pandaDir() { return sharedDir() + "/robots/panda"; }
std::string pandaUrdf() { return pandaDir() + "/moveit_resources_panda_description/urdf/panda.urdf"; }

void checkThrows(const std::function<void()>& f, const std::string& part) {
  try {
    f();
    BOOST_ERROR("expected std::invalid_argument mentioning '" << part << "'");
  } catch (const std::invalid_argument& e) {
    BOOST_CHECK_MESSAGE(std::string(e.what()).find(part) != std::string::npos, e.what());
  }
}

/// The query frame's x (MotionBenchMaker's approach direction) along the hand's z.
Eigen::Isometry3d handOffset() {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return X;
}

struct PandaBookshelf {
  std::shared_ptr<checker::World> world;
  std::shared_ptr<ompl::geometric::SimpleSetup> ss;
  robots::PlanningScene scene;
  std::vector<SceneVariation> variations;
  QuerySet queries;
  ProblemOptions options;

  /// The Panda's variables, or only those of `group` (the others at the robot file's values).
  explicit PandaBookshelf(const std::string& group = "") {
    SetupOptions o;
    o.packageRoots = {pandaDir()};
    o.useRosPackagePath = false;
    o.srdf = pandaDir() + "/moveit_resources_panda_moveit_config/config/panda.srdf";
    if (!group.empty()) {
      robots::LoadOptions load;
      load.packageRoots = o.packageRoots;
      load.useRosPackagePath = false;
      const robots::RobotModel full = robots::RobotModel::fromUrdfFile(pandaUrdf(), load);
      o.group = group;
      o.lockedVariables = lockedOutsideGroup(full, loadRobotConfig(mbm() + "/robots/panda.yaml"), o.srdf, group);
    }
    o.world.decompositionCacheDir = std::string(DEEPCHECK_BINARY_DIR) + "/planners_test_cache";
    world = loadWorld(pandaUrdf(), {}, o);
    ss = makeSimpleSetup(world, o);
    scene = robots::loadPlanningScene(mbm() + "/scenes/bookshelf/scene_small.yaml");
    variations = loadSceneVariations(mbm() + "/scenes/bookshelf/variation_small.yaml");
    queries = loadQueries(mbm() + "/scenes/bookshelf/easy_queries_small.yaml");
    options.tipLink = "panda_hand";
    options.eeOffset = handOffset();
    options.frameAliases = {{"base_link", "panda_link0"}};
    options.start = configurationOf(world->robot(), loadRobotConfig(mbm() + "/robots/panda.yaml"));
    options.seed = 7;
  }
  std::vector<Problem> generate(int n) {
    return generateProblems(*world, *validityCheckerOf(*ss), scene, variations, queries, options, n);
  }
};

}  // namespace

BOOST_AUTO_TEST_SUITE(planners_problem_generation)

BOOST_AUTO_TEST_CASE(files_are_read) {
  const auto v = parseSceneVariations(
      "- names: [\"World\"]\n  position: [0.1, 0.1, 0.4]\n  orientation: [0, 0, 1.57]\n  type: \"uniform\"\n"
      "- names: [a, b]\n  position: [0, 0.45, 0]\n  orientation: [0, 0, 0]\n  type: gaussian\n",
      "v.yaml");
  BOOST_REQUIRE_EQUAL(v.size(), 2u);
  BOOST_CHECK_EQUAL(v[0].names.front(), "World");
  BOOST_CHECK_EQUAL(v[0].orientation.z(), 1.57);
  BOOST_CHECK(!v[0].normal);
  BOOST_CHECK(v[1].normal);
  BOOST_CHECK_EQUAL(v[1].line, 5);
  const QuerySet q = parseQueries(
      "start_queries:\n  - objects: [t]\n    tag: Under\n    offset:\n      position: [-0.5, 0, -0.3]\n"
      "      orientation: [0, 0, 0, 1]\n      position_tol: [0.01, 0.02, 0.03]\n      orientation_tol: [0.01, 0.01, "
      "0.01]\n"
      "    attached: \"False\"\n"
      "goal_queries:\n  - objects: [a, b]\n    tag: Front\n    offset:\n      position: [-0.2, 0, 0.05]\n"
      "      orientation: [0, 0.707, 0, 0.707]\n      position_tol: [0.01, 0.01, 0.01]\n      orientation_tol: [0.01, "
      "0.01, 0.01]\n",
      "q.yaml");
  BOOST_REQUIRE_EQUAL(q.start.size(), 1u);
  BOOST_REQUIRE_EQUAL(q.goal.size(), 2u);
  BOOST_CHECK_EQUAL(q.goal[1].name(), "b_Front");
  Eigen::Isometry3d eeOffset = Eigen::Isometry3d::Identity();
  eeOffset.translation() = Eigen::Vector3d(0, 0, 0.1);
  const deepcheck::robots::IkOptions ik = queryIkOptions(q.start[0], {}, eeOffset);
  BOOST_CHECK_SMALL((ik.positionBox - Eigen::Vector3d(0.01, 0.02, 0.03)).norm(), 1e-15);
  BOOST_CHECK(ik.boxPose.isApprox(eeOffset));
  BOOST_CHECK_SMALL(ik.orientationTolerance - 0.01, 1e-15);
  BOOST_CHECK_SMALL((q.goal[0].offset.translation() - Eigen::Vector3d(-0.2, 0, 0.05)).norm(), 1e-15);
}

BOOST_AUTO_TEST_CASE(bad_files_name_file_line_and_value) {
  checkThrows(
      [] {
        parseSceneVariations("- names: [a]\n  position: [0, 0]\n  orientation: [0, 0, 0]\n  type: uniform\n", "v.yaml");
      },
      "variation file 'v.yaml', line 2: position must be a list of 3 numbers");
  checkThrows(
      [] {
        parseSceneVariations("- names: [a]\n  position: [0, 0, 0]\n  orientation: [0, 0, 0]\n  type: beta\n", "v.yaml");
      },
      "line 4: unknown variation type 'beta'");
  checkThrows(
      [] {
        parseSceneVariations("- names: [a]\n  position: [0, .nan, 0]\n  orientation: [0, 0, 0]\n  type: uniform\n",
                             "v.yaml");
      },
      "must be finite, not '.nan'");
  checkThrows([] { parseQueries("goal_queries:\n  - objects: [a]\n    tag: F\n", "q.yaml"); },
              "query file 'q.yaml', line 2: missing 'offset'");
  checkThrows([] { parseQueries("goal_querys: []\n", "q.yaml"); }, "unknown key 'goal_querys'");
  checkThrows([] { parseRobotConfig("robot_state:\n  joint_state:\n    name: [a, b]\n    position: [1]\n", "r.yaml"); },
              "robot configuration 'r.yaml', line 4: joint_state position must be a list of 2 numbers");
}

BOOST_AUTO_TEST_CASE(bad_structure_is_the_files_error) {
  // A key looked up in a scalar or a list (yaml-cpp's BadSubscript) is an error naming the file.
  checkThrows([] { parseRobotConfig("robot_state: 3\n", "r.yaml"); },
              "robot configuration 'r.yaml', line 1: 'joint_state' must be a key of a map, not of a scalar ('3')");
  checkThrows([] { parseRobotConfig("robot_state:\n  joint_state: [a, b]\n", "r.yaml"); },
              "robot configuration 'r.yaml', line 2: 'name' must be a key of a map, not of a list");
  checkThrows([] { parseQueries("goal_queries:\n  - objects: [a]\n    tag: F\n    offset: x\n", "q.yaml"); },
              "query file 'q.yaml', line 4: 'position' must be a key of a map, not of a scalar ('x')");
  checkThrows([] { parseRobotConfig("robot_state:\n", "r.yaml"); }, "robot configuration 'r.yaml'");
  checkThrows([] { parseRobotConfig("urdf: a\nrobot_state: {joint_state: {name: [j], position: [[1]]}}\n", "r.yaml"); },
              "robot configuration 'r.yaml', line 2: joint_state position entry must be a number");
}

BOOST_AUTO_TEST_CASE(variation_moves_world_and_objects) {
  robots::PlanningScene s = robots::parsePlanningScene(
      "world:\n  collision_objects:\n"
      "    - header: {frame_id: base_link}\n      id: a\n      primitives: [{type: box, dimensions: [1, 1, 1]}]\n"
      "      primitive_poses: [{position: [1, 0, 0], orientation: [0, 0, 0, 1]}]\n",
      ".", {}, "s.yaml");
  std::mt19937_64 rng(1);
  const auto v = parseSceneVariations(
      "- names: [World]\n  position: [0, 0, 0]\n  orientation: [0, 0, 0]\n  type: uniform\n"
      "- names: [a]\n  position: [0, 0.5, 0]\n  orientation: [0, 0, 0]\n  type: uniform\n",
      "v.yaml");
  const robots::PlanningScene varied = varyScene(s, v, rng, "v.yaml");
  const Eigen::Vector3d p = varied.objects[0].shapes[0].X_FS.translation();
  BOOST_CHECK_EQUAL(p.x(), 1.0);
  BOOST_CHECK(std::abs(p.y()) <= 0.5 && p.y() != 0.0);
  checkThrows(
      [&] {
        varyScene(s,
                  parseSceneVariations(
                      "- names: [b]\n  position: [0, 0, 0]\n  orientation: [0, 0, 0]\n  type: uniform\n", "v.yaml"),
                  rng, "v.yaml");
      },
      "variation file 'v.yaml', line 1: object 'b' is not in the planning scene 's.yaml'");
}

BOOST_AUTO_TEST_CASE(bookshelf_problems_are_valid_and_reproducible) {
  if (!haveShared("problem generation on the bookshelf")) return;
  PandaBookshelf setup;
  const std::vector<Problem> problems = setup.generate(3);
  BOOST_REQUIRE_EQUAL(problems.size(), 3u);
  const auto checker = validityCheckerOf(*setup.ss);
  const robots::RobotModel& panda = setup.world->robot();
  const int tip = panda.linkIndex(setup.options.tipLink);
  for (const Problem& p : problems) {
    // Collision free in its own scene.
    const std::vector<int> ids = setup.world->addPlanningScene(p.scene, {setup.options.frameAliases, {}});
    BOOST_CHECK(checker->isValid(p.start));
    BOOST_CHECK(checker->isValid(p.goal));
    for (int id : ids) setup.world->removeObstacle(id);
    // The end effector (the query frame on the tip) at the query pose, recomputed from the
    // varied scene's Can3: within the query's tolerance box (half edge 0.005 m, along the query
    // frame's axes) and orientation tolerance (0.01 rad).
    const ObjectQuery& q = setup.queries.goal.front();
    const Eigen::Isometry3d& ee = setup.options.eeOffset;
    const Eigen::Isometry3d X_WT = queryPose(p.scene, q, panda, setup.options.start, setup.options.frameAliases, ee);
    const Eigen::Isometry3d X_WL = robots::forwardKinematics(panda, p.goal)[static_cast<std::size_t>(tip)];
    const Eigen::Vector3d inBox = (X_WT * ee).inverse() * (X_WL * ee).translation();
    BOOST_CHECK_LE(inBox.cwiseAbs().maxCoeff(), 0.005);
    BOOST_CHECK_LE(Eigen::AngleAxisd(X_WL.linear().transpose() * X_WT.linear()).angle(), 0.01);
    BOOST_CHECK(p.goalError.within());
  }
  PandaBookshelf again;
  const std::vector<Problem> repeated = again.generate(3);
  for (std::size_t i = 0; i < problems.size(); ++i) {
    BOOST_CHECK_EQUAL(problems[i].goal.transpose(), repeated[i].goal.transpose());
    BOOST_CHECK(problems[i].scene.objects[0].shapes[0].X_FS.isApprox(repeated[i].scene.objects[0].shapes[0].X_FS, 0.0));
  }
  again.options.seed = 8;
  BOOST_CHECK(again.generate(1).front().goal != problems.front().goal);
}

BOOST_AUTO_TEST_CASE(a_planning_group_moves_its_joints_only, *boost::unit_test::label("integration")) {
  if (!haveShared("problem generation for the panda_arm group")) return;
  PandaBookshelf setup("panda_arm");
  const robots::RobotModel& arm = setup.world->robot();
  BOOST_REQUIRE_EQUAL(arm.numVariables(), 7);
  // The fingers are held at the robot file's 0.065 m, clamped to this Panda's 0.04 m.
  const robots::Joint& finger = arm.joint(arm.jointIndex("panda_finger_joint1"));
  BOOST_CHECK(finger.locked);
  BOOST_CHECK_EQUAL(finger.lockedValue, 0.04);
  const std::vector<Problem> problems = setup.generate(2);
  const auto checker = validityCheckerOf(*setup.ss);
  for (const Problem& p : problems) {
    BOOST_REQUIRE_EQUAL(p.goal.size(), 7);
    const std::vector<int> ids = setup.world->addPlanningScene(p.scene, {setup.options.frameAliases, {}});
    BOOST_CHECK(checker->isValid(p.start));
    BOOST_CHECK(checker->isValid(p.goal));
    // The 7-variable setup plans it, and the path is certified.
    setStartAndGoal(*setup.ss, p.start, p.goal);
    setup.ss->setup();
    BOOST_REQUIRE(setup.ss->solve(10.0) == ompl::base::PlannerStatus::EXACT_SOLUTION);
    BOOST_CHECK(certifyPath(*setup.ss, setup.ss->getSolutionPath()).valid);
    setup.ss->clear();
    for (int id : ids) setup.world->removeObstacle(id);
  }
  // A group variable cannot also be held.
  checkThrows(
      [&] {
        SetupOptions o;
        o.packageRoots = {pandaDir()};
        o.useRosPackagePath = false;
        o.srdf = pandaDir() + "/moveit_resources_panda_moveit_config/config/panda.srdf";
        o.group = "panda_arm";
        o.lockedVariables = {{"panda_joint4", -2.0}};
        loadWorld(pandaUrdf(), {}, o);
      },
      "cannot lock 'panda_joint4': it is a variable of group 'panda_arm'");
  // A world built without the group does not pass for one built with it.
  PandaBookshelf full;
  SetupOptions o;
  o.srdf = pandaDir() + "/moveit_resources_panda_moveit_config/config/panda.srdf";
  o.group = "panda_arm";
  checkThrows([&] { makeSimpleSetup(full.world, o); }, "moves 8 variables, group 'panda_arm' only 7");
  o.group.clear();
  o.lockedVariables = {{"panda_finger_joint1", 0.04}};
  checkThrows([&] { makeSimpleSetup(full.world, o); }, "the options hold 'panda_finger_joint1' at 0.04");
  o.lockedVariables = {{"panda_finger_joint1", 0.03}};  // the group's world holds it at 0.04
  checkThrows([&] { makeSimpleSetup(setup.world, o); }, "hold 'panda_finger_joint1' at 0.0299");
}

BOOST_AUTO_TEST_CASE(drawn_scenes_are_the_ones_varied) {
  if (!haveShared("problem generation from drawn scenes")) return;
  PandaBookshelf setup;
  // Every draw moves the scene's last object 10 m away, a little further each time: the
  // problems' scenes are the drawn ones (then varied by at most the variation file's offsets).
  const std::size_t last = setup.scene.objects.size() - 1;
  BOOST_REQUIRE(setup.scene.objects[last].id != "Can3");
  int draws = 0;
  setup.options.drawScene = [&](std::mt19937_64&) {
    robots::PlanningScene s = setup.scene;
    ++draws;
    for (robots::SceneShape& shape : s.objects[last].shapes) {
      shape.X_FS.translation() += Eigen::Vector3d(10.0 + 0.001 * draws, 0.0, 0.0);
    }
    return s;
  };
  const std::vector<Problem> problems = setup.generate(2);
  BOOST_REQUIRE_EQUAL(problems.size(), 2u);
  BOOST_CHECK_EQUAL(draws, problems[0].attempts + problems[1].attempts);
  // The variation turns and shifts the whole scene about the robot's base by centimetres:
  // compare distances from the base, drawn against nominal.
  const Eigen::Vector3d nominal = setup.scene.objects[last].shapes[0].X_FS.translation();
  const double drawn = (nominal + Eigen::Vector3d(10.0, 0.0, 0.0)).norm();
  for (const Problem& p : problems) {
    BOOST_CHECK_LT(std::abs(p.scene.objects[last].shapes[0].X_FS.translation().norm() - drawn), 0.5);
  }
}

BOOST_AUTO_TEST_CASE(unreachable_queries_name_the_closest_inverse_kinematics) {
  if (!haveShared("problem generation error for unreachable queries")) return;
  PandaBookshelf setup;
  // Every goal 3 m beyond its object: out of the Panda's reach.
  for (ObjectQuery& q : setup.queries.goal) q.offset.translation().x() -= 3.0;
  setup.options.maxAttempts = 2;
  setup.options.ik.maxRestarts = 2;
  try {
    setup.generate(1);
    BOOST_ERROR("expected std::runtime_error");
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    BOOST_CHECK_MESSAGE(what.find("no collision-free start and goal in 2 varied scenes") != std::string::npos, what);
    BOOST_CHECK_MESSAGE(what.find("closest inverse kinematics: query '") != std::string::npos, what);
    BOOST_CHECK_MESSAGE(what.find("not converged") != std::string::npos, what);
  }
}

BOOST_AUTO_TEST_SUITE_END()

}  // namespace deepcheck::problems
