// deepcheck problems end to end: the Panda on MotionBenchMaker's small bookshelf; every written
// problem's scene reads back and its start and goal are collision free in it; a seed repeats.

#include "robot_files.h"
#include "tool_runner.h"

#include "common/test_paths.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/moveit_scene.h"
#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/robot_model.h"

#include <boost/test/unit_test.hpp>

#include <map>
#include <string>
#include <vector>

using namespace deepcheck;
using tool_test::quote;
using tool_test::Run;
using tool_test::Scratch;

namespace {

using tool_test::pandaDir;
using tool_test::pandaSrdf;
using tool_test::pandaUrdf;

std::string bookshelfArgs(const std::string& out, int count, int seed) {
  const std::string m = test::sharedDir() + "/scenes/motion_bench_maker/configs";
  return "problems --robot " + quote(pandaUrdf()) + " --srdf " + quote(pandaSrdf()) + " --package-path " +
         quote(pandaDir()) + " --scene " + quote(m + "/scenes/bookshelf/scene_small.yaml") + " --variation " +
         quote(m + "/scenes/bookshelf/variation_small.yaml") + " --queries " +
         quote(m + "/scenes/bookshelf/all_queries_small.yaml") + " --robot-config " + quote(m + "/robots/panda.yaml") +
         " --frame-alias base_link=panda_link0 --count " + std::to_string(count) + " --seed " + std::to_string(seed) +
         " --out " + quote(out);
}

/// The "key values..." lines of a problem file.
std::map<std::string, std::vector<std::string>> readProblem(const std::string& path) {
  std::map<std::string, std::vector<std::string>> out;
  for (const std::string& line : tool_test::lines(tool_test::readText(path))) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> f = tool_test::fields(line);
    const std::string key = f.front();
    out[key] = std::vector<std::string>(f.begin() + 1, f.end());
  }
  return out;
}

Eigen::VectorXd values(const std::vector<std::string>& words) {
  Eigen::VectorXd q(static_cast<Eigen::Index>(words.size()));
  for (std::size_t i = 0; i < words.size(); ++i) q[static_cast<Eigen::Index>(i)] = std::stod(words[i]);
  return q;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(tool_problems)

BOOST_AUTO_TEST_CASE(bookshelf_problems_are_collision_free_and_repeat_with_the_seed) {
  if (!test::haveShared("deepcheck problems on the bookshelf")) return;
  Scratch scratch;
  const Run r = scratch.run(bookshelfArgs(scratch.path("a"), 2, 5));
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(r.out.find("problem 2/2") != std::string::npos, r.out);
  checker::World world = tool_test::libraryWorld(pandaUrdf(), pandaSrdf(), pandaDir());
  for (const char* k : {"0000", "0001"}) {
    const auto problem = readProblem(scratch.path(std::string("a/problem_") + k + ".txt"));
    BOOST_REQUIRE_EQUAL(problem.at("scene").front(), std::string("scene_") + k + ".yaml");
    BOOST_REQUIRE_EQUAL(problem.at("variables").size(), static_cast<std::size_t>(world.robot().numVariables()));
    const auto scene = robots::loadPlanningScene(scratch.path("a/" + problem.at("scene").front()));
    BOOST_CHECK_EQUAL(scene.objects.size(), 7u);
    checker::PlanningSceneOptions placement;
    placement.frameAliases = {{"base_link", "panda_link0"}};
    const std::vector<int> ids = world.addPlanningScene(scene, placement);
    BOOST_CHECK(world.isFree(values(problem.at("start"))));
    BOOST_CHECK(world.isFree(values(problem.at("goal"))));
    for (int id : ids) world.removeObstacle(id);
  }
  const Run again = scratch.run(bookshelfArgs(scratch.path("b"), 2, 5));
  BOOST_TEST_REQUIRE(again.status == 0, again.err);
  for (const char* name : {"problem_0001.txt", "scene_0001.yaml"}) {
    BOOST_CHECK(tool_test::readText(scratch.path(std::string("a/") + name)) ==
                tool_test::readText(scratch.path(std::string("b/") + name)));
  }
}

BOOST_AUTO_TEST_CASE(a_planning_group_plans_the_arm_with_the_fingers_held) {
  if (!test::haveShared("deepcheck problems --group panda_arm")) return;
  Scratch scratch;
  const Run r = scratch.run(bookshelfArgs(scratch.path("g"), 1, 3) + " --group panda_arm");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const auto problem = readProblem(scratch.path("g/problem_0000.txt"));
  const std::vector<std::string> variables = problem.at("variables");
  BOOST_TEST_REQUIRE(variables.size() == 7u);
  for (int j = 0; j < 7; ++j)
    BOOST_TEST(variables[static_cast<std::size_t>(j)] == "panda_joint" + std::to_string(j + 1));
  // The start is the robot file's default state of the arm; its finger opening (0.065, beyond
  // this Panda's 0.04) is clamped, and the fingers are held there.
  const Eigen::VectorXd start = values(problem.at("start"));
  const Eigen::VectorXd expected = (Eigen::VectorXd(7) << 0, -0.785, 0, -2.356, 0, 1.571, 0.785).finished();
  BOOST_TEST((start - expected).cwiseAbs().maxCoeff() == 0.0);
  BOOST_TEST(r.err.find("'panda_finger_joint1' = 0.065 is held at 0.04") != std::string::npos, r.err);
  BOOST_TEST(values(problem.at("goal")).size() == 7);
  // --group needs the SRDF; a group variable cannot be locked.
  const Run noSrdf = scratch.run(
      "problems --robot r.urdf --group panda_arm --scene s.yaml --variation v.yaml "
      "--queries q.yaml --robot-config c.yaml --out d");
  BOOST_TEST(noSrdf.status == 2);
  BOOST_TEST(noSrdf.err.find("--group panda_arm needs --srdf") != std::string::npos, noSrdf.err);
  const Run locked = scratch.run(bookshelfArgs(scratch.path("h"), 1, 3) + " --group panda_arm --lock panda_joint1=0");
  BOOST_TEST(locked.status == 1);
  BOOST_TEST(locked.err.find("a variable of group 'panda_arm'") != std::string::npos, locked.err);
}

BOOST_AUTO_TEST_CASE(missing_and_bad_options_are_reported) {
  Scratch scratch;
  const Run missing = scratch.run("problems --robot x.urdf");
  BOOST_TEST(missing.status == 2);
  BOOST_TEST(missing.err.find("option --scene is required") != std::string::npos, missing.err);
  const Run alias = scratch.run("problems --frame-alias base_link");
  BOOST_TEST(alias.status == 2);
  BOOST_TEST(alias.err.find("--frame-alias") != std::string::npos, alias.err);
  const Run mesh = scratch.run(
      "problems --robot r.urdf --scene s.obj --variation v.yaml --queries q.yaml "
      "--robot-config c.yaml --out dir");
  BOOST_TEST(mesh.status == 2);
  BOOST_TEST(mesh.err.find("s.obj") != std::string::npos, mesh.err);
}

/// A scene URDF: a fixed table in front of the robot and a flap on a hinge far behind it.
const char* const kTableAndFlapUrdf = R"(<robot name="table_and_flap">
  <link name="root"/>
  <link name="table"><collision><origin xyz="0.6 0 0.2"/><geometry><box size="0.4 0.6 0.05"/></geometry></collision></link>
  <link name="flap"><collision><origin xyz="0 0.2 0"/><geometry><box size="0.02 0.4 0.3"/></geometry></collision></link>
  <joint name="table_joint" type="fixed"><parent link="root"/><child link="table"/></joint>
  <joint name="flap_joint" type="revolute"><origin xyz="-1 0 0.5"/><parent link="root"/><child link="flap"/>
    <axis xyz="0 0 1"/><limit lower="-1.5" upper="1.5" effort="1" velocity="1"/></joint>
</robot>)";

BOOST_AUTO_TEST_CASE(scene_urdf_joints_are_drawn_per_problem) {
  if (!test::haveShared("deepcheck problems on a scene URDF")) return;
  Scratch scratch;
  const std::string m = test::sharedDir() + "/scenes/motion_bench_maker/configs";
  scratch.write("scene.urdf", kTableAndFlapUrdf);
  scratch.write("variation.yaml",
                "- names: [World]\n  position: [0, 0, 0]\n  orientation: [0, 0, 0]\n  type: uniform\n");
  scratch.write("queries.yaml",
                "goal_queries:\n  - objects: [table]\n    tag: Above\n    offset:\n      position: [0, 0, 0.25]\n"
                "      orientation: [0, 0, 0, 1]\n      position_tol: [0.02, 0.02, 0.02]\n"
                "      orientation_tol: [0.02, 0.02, 0.02]\n    attached: \"False\"\n");
  const Run r = scratch.run("problems --robot " + quote(pandaUrdf()) + " --srdf " + quote(pandaSrdf()) +
                            " --package-path " + quote(pandaDir()) + " --scene " + quote(scratch.path("scene.urdf")) +
                            " --variation " + quote(scratch.path("variation.yaml")) + " --queries " +
                            quote(scratch.path("queries.yaml")) + " --robot-config " + quote(m + "/robots/panda.yaml") +
                            " --count 2 --seed 3 --out " + quote(scratch.path("out")));
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  checker::World world = tool_test::libraryWorld(pandaUrdf(), pandaSrdf(), pandaDir());
  std::vector<Eigen::Matrix3d> flapRotations;
  for (const char* k : {"0000", "0001"}) {
    const auto problem = readProblem(scratch.path(std::string("out/problem_") + k + ".txt"));
    const auto scene = robots::loadPlanningScene(scratch.path("out/" + problem.at("scene").front()));
    BOOST_REQUIRE_EQUAL(scene.objects.size(), 2u);
    BOOST_CHECK_EQUAL(scene.objects[0].id, "table");
    BOOST_CHECK_EQUAL(scene.objects[1].id, "flap");
    BOOST_CHECK_EQUAL(scene.objects[1].frameId, "panda_link0");  // the robot's root: no alias needed
    flapRotations.push_back(scene.objects[1].shapes[0].X_FS.linear());
    const std::vector<int> ids = world.addPlanningScene(scene, {});
    BOOST_CHECK(world.isFree(values(problem.at("goal"))));
    for (int id : ids) world.removeObstacle(id);
  }
  // The flap's joint is drawn for each problem: its two poses differ.
  BOOST_CHECK(!flapRotations[0].isApprox(flapRotations[1], 1e-6));
}

BOOST_AUTO_TEST_SUITE_END()
