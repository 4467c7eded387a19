// End-to-end tests of MoveIt planning-scene YAML scenes on the command line (--scene S.yaml,
// --frame-alias): `deepcheck check` answers as the library's World::addPlanningScene does, and
// bad scene arguments are reported clearly.

#include "robot_files.h"
#include "tool_runner.h"

#include "common/test_paths.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/moveit_scene.h"
#include "deepcheck/robots/random_configuration.h"
#include "deepcheck/robots/robot_model.h"

#include <boost/test/unit_test.hpp>

#include <random>
#include <string>
#include <vector>

using namespace deepcheck;
using namespace deepcheck::tool_test;

namespace {

/// A scene whose object is given in frame 'world', which the bundled arm does not have.
const char* kWorldFrameScene =
    "world:\n"
    "  collision_objects:\n"
    "    - header:\n"
    "        frame_id: world\n"
    "      id: crate\n"
    "      primitives:\n"
    "        - type: box\n"
    "          dimensions: [0.2, 0.2, 0.2]\n"
    "      primitive_poses:\n"
    "        - position: [0.6, 0, 0.1]\n"
    "          orientation: [0, 0, 0, 1]\n";

/// Distances of the same code on the same input; only the warm starts of the tool's query
/// context may differ, in the last digits.
constexpr double kSameAnswer = 1e-9;

}  // namespace

BOOST_AUTO_TEST_SUITE(tool_planning_scene)

BOOST_AUTO_TEST_CASE(check_in_a_motion_bench_maker_scene_answers_as_the_library) {
  if (!test::haveShared("check in the MotionBenchMaker bookshelf")) return;
  checker::World world =
      libraryWorld(pandaUrdf(), pandaSrdf(), pandaDir(), bookshelfScene(), {{"base_link", "panda_link0"}});
  BOOST_TEST_REQUIRE(world.obstacleIds().size() == 7u);

  std::mt19937_64 rng(7);
  std::vector<Eigen::VectorXd> qs = {world.robot().defaultConfiguration()};
  for (int k = 0; k < 5; ++k) qs.push_back(robots::randomConfiguration(world.robot(), rng));
  std::string input;
  for (const Eigen::VectorXd& q : qs) {
    for (int v = 0; v < q.size(); ++v) input += formatNumber(q[v]) + " ";
    input += "\n";
  }
  Scratch s;
  const Run r =
      s.run("check --robot " + quote(pandaUrdf()) + " --srdf " + quote(pandaSrdf()) + " --package-path " +
                quote(pandaDir()) + " --scene " + quote(bookshelfScene()) + " --frame-alias base_link=panda_link0",
            input, "ROS_PACKAGE_PATH=");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(contains(r.err, "obstacles: 7"), r.err);
  const std::vector<std::string> out = lines(r.out);
  BOOST_TEST_REQUIRE(out.size() == qs.size());
  checker::DistanceOptions sceneQuery;
  sceneQuery.selfPairs = false;
  for (std::size_t i = 0; i < qs.size(); ++i) {
    const std::vector<std::string> f = fields(out[i]);
    BOOST_TEST_REQUIRE(f.size() == 9u, out[i]);
    const checker::DistanceResult expected = world.signedDistance(qs[i], sceneQuery);
    BOOST_TEST_REQUIRE(expected.found);
    BOOST_TEST(std::abs(number(f[3]) - expected.closest.distance) < kSameAnswer, out[i]);
    BOOST_TEST(f[4] == expected.closest.nameA, out[i]);
    BOOST_TEST(f[5] == expected.closest.nameB, out[i]);
    BOOST_TEST(contains(f[5], "obstacle/"), out[i]);
  }
}

BOOST_AUTO_TEST_CASE(an_unknown_frame_suggests_a_frame_alias) {
  Scratch s;
  const std::string scene = s.write("crate.yaml", kWorldFrameScene);
  const std::string robot = " --robot " + quote(armUrdf()) + " --package-path " + quote(test::bundledDataDir());
  const Run bad = s.run("check" + robot + " --scene " + quote(scene), "0 0 0 0 0 0 0\n");
  BOOST_TEST(bad.status == 1);
  BOOST_TEST(bad.out.empty(), bad.out);
  BOOST_TEST(contains(bad.err, scene), bad.err);
  BOOST_TEST(contains(bad.err, "object 'crate'"), bad.err);
  BOOST_TEST(contains(bad.err, "unknown frame 'world'"), bad.err);
  BOOST_TEST(contains(bad.err, "--frame-alias world=base_link"), bad.err);
  // With the alias the crate is 0.6 m along x of the arm's base: a straight-up arm is clear of it.
  const Run good =
      s.run("check" + robot + " --scene " + quote(scene) + " --frame-alias world=base_link", "0 0 0 0 0 0 0\n");
  BOOST_TEST_REQUIRE(good.status == 0, good.err);
  const std::vector<std::string> f = fields(lines(good.out).at(0));
  BOOST_TEST_REQUIRE(f.size() == 9u);
  BOOST_TEST(f[5] == "obstacle/crate");
  BOOST_TEST(number(f[3]) > 0.0);
  // An alias whose target is no link is named.
  const Run noLink =
      s.run("check" + robot + " --scene " + quote(scene) + " --frame-alias world=plinth", "0 0 0 0 0 0 0\n");
  BOOST_TEST(noLink.status == 1);
  BOOST_TEST(contains(noLink.err, "'plinth'"), noLink.err);
}

BOOST_AUTO_TEST_CASE(bad_scene_arguments_are_reported) {
  Scratch s;
  const std::string scene = s.write("crate.yaml", kWorldFrameScene);
  const std::string robot = " --robot " + quote(armUrdf());
  const Run extension = s.run("check" + robot + " --scene " + quote(s.path("crate.stl")));
  BOOST_TEST(extension.status == 2);
  BOOST_TEST(contains(extension.err, "scene '" + s.path("crate.stl") + "': unknown scene type '.stl'"), extension.err);
  const Run posed = s.run("check" + robot + " --scene " + quote(scene) + " --scene-pose 1 0 0 0 0 0");
  BOOST_TEST(posed.status == 2);
  BOOST_TEST(contains(posed.err, "--scene-pose after planning scene '" + scene + "'"), posed.err);
  const Run aliasAlone = s.run("check" + robot + " --frame-alias world=base_link");
  BOOST_TEST(aliasAlone.status == 2);
  BOOST_TEST(contains(aliasAlone.err, "--frame-alias needs a planning-scene --scene"), aliasAlone.err);
  const Run twice =
      s.run("check" + robot + " --scene " + quote(scene) + " --frame-alias world=base_link --frame-alias world=link1");
  BOOST_TEST(twice.status == 2);
  BOOST_TEST(contains(twice.err, "frame 'world' mapped twice"), twice.err);
  const Run malformed = s.run("view" + robot + " --scene " + quote(scene) + " --frame-alias world --out x.html");
  BOOST_TEST(malformed.status == 2);
  BOOST_TEST(contains(malformed.err, "--frame-alias: "), malformed.err);
}

BOOST_AUTO_TEST_CASE(info_describes_a_planning_scene_as_read) {
  Scratch s;
  const std::string scene =
      s.write("shapes.yaml",
              "world:\n"
              "  collision_objects:\n"
              "    - header: {frame_id: base_link}\n"
              "      id: things\n"
              "      primitives:\n"
              "        - {type: box, dimensions: [0.1, 0.2, 0.3]}\n"
              "        - {type: sphere, dimensions: [0.05]}\n"
              "        - {type: cylinder, dimensions: [0.4, 0.02]}\n"
              "      primitive_poses:\n"
              "        - {position: [1, 2, 3], orientation: [0, 0, 0, 1]}\n"
              "        - {position: [0, 0, 0.5], orientation: [0, 0, 1, 0]}\n"
              "        - {position: [0, 0, 0], orientation: [0, 0, 0, 1]}\n"
              "      meshes: [{resource: package://deepcheck_arm/meshes/base.stl, scale: [2, 2, 2]}]\n"
              "      mesh_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]\n");
  const Run r =
      s.run("info " + quote(scene) + " --package-path " + quote(test::bundledDataDir()), "", "ROS_PACKAGE_PATH=");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const std::vector<std::string> out = lines(r.out);
  BOOST_TEST_REQUIRE(out.size() == 12u, r.out);
  BOOST_TEST(out[0] == "planning scene '" + scene + "'");
  BOOST_TEST(out[1] == "1 objects, 4 shapes, 0 attached objects, 0 allowed pairs");
  BOOST_TEST(out[4] == "  things (frame base_link, line 3)");
  BOOST_TEST(contains(out[5], "box 0.1 x 0.2 x 0.3 m at 1 2 3  0 0 0 1"), out[5]);
  BOOST_TEST(contains(out[6], "sphere radius 0.05 m at 0 0 0.5  0 0 1 0"), out[6]);
  BOOST_TEST(contains(out[7], "cylinder length 0.4 m radius 0.02 m at 0 0 0  0 0 0 1"), out[7]);
  BOOST_TEST(contains(out[8], "deepcheck_arm/meshes/base.stl scale 2 2 2 at 0 0 0  0 0 0 1"), out[8]);
  BOOST_TEST(out[10] == "allowed collisions:");
  BOOST_TEST(out[11] == "  none");
  const Run pairs = s.run("info " + quote(scene) + " --samples 10");
  BOOST_TEST(pairs.status == 2);
  BOOST_TEST(contains(pairs.err, "describe robots, not planning scenes"), pairs.err);
}

BOOST_AUTO_TEST_SUITE_END()
