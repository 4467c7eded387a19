// MoveIt's scene formats as they come, on the command line: a `ros2 topic echo` dump of a
// planning scene, a .scene file (Export/Import), and the SRDF's virtual-joint frame as a built-in
// frame alias.

#include "robot_files.h"
#include "tool_runner.h"

#include "common/test_paths.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/format_number.h"
#include "deepcheck/robots/moveit_scene.h"

#include <boost/test/unit_test.hpp>

#include <string>
#include <vector>

using namespace deepcheck;
using namespace deepcheck::tool_test;

namespace {

const std::string kScenes = std::string(DEEPCHECK_SOURCE_DIR) + "/tests/data/moveit_scenes";

/// Distances of the same code on the same input; only the warm starts of the tool's query
/// context may differ, in the last digits.
constexpr double kSameAnswer = 1e-9;

const std::string kArmStretched = "0 -0.4 0 -1.6 0 1.2 0\n";

/// `check` of the bundled arm at kArmStretched with the scene and the extra arguments; the scene
/// clearance (fields 3 to 5 of the only line) compared with the library's world of the same scene
/// placed with `aliases`.
void checkAnswersAsTheLibrary(const std::string& scene, const std::string& extra, const robots::FrameAliases& aliases) {
  Scratch s;
  const Run r = s.run("check --robot " + quote(armUrdf()) + " --srdf " + quote(armSrdf()) + " --package-path " +
                          quote(test::bundledDataDir()) + " --scene " + quote(scene) + extra,
                      kArmStretched, "ROS_PACKAGE_PATH=");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const checker::World world = libraryWorld(armUrdf(), armSrdf(), test::bundledDataDir(), scene, aliases);
  Eigen::VectorXd q(7);
  q << 0, -0.4, 0, -1.6, 0, 1.2, 0;
  checker::DistanceOptions sceneQuery;
  sceneQuery.selfPairs = false;
  const checker::DistanceResult expected = world.signedDistance(q, sceneQuery);
  BOOST_TEST_REQUIRE(expected.found);
  const std::vector<std::string> f = fields(lines(r.out).at(0));
  BOOST_TEST_REQUIRE(f.size() == 9u, r.out);
  BOOST_TEST(std::abs(number(f[3]) - expected.closest.distance) < kSameAnswer, r.out);
  BOOST_TEST(f[5] == expected.closest.nameB, r.out);
  BOOST_TEST(contains(f[5], "obstacle/"), r.out);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(tool_scene_formats)

BOOST_AUTO_TEST_CASE(check_reads_a_topic_echo_dump) {
  checkAnswersAsTheLibrary(kScenes + "/monitored_planning_scene.yaml", "", {});
}

BOOST_AUTO_TEST_CASE(check_reads_a_scene_text_file_on_the_root_link) {
  checkAnswersAsTheLibrary(kScenes + "/bench.scene", "", {});
  checkAnswersAsTheLibrary(kScenes + "/old_format.scene", "", {});
  // --scene-pose does not place a .scene file either: its objects are in the model frame.
  Scratch s;
  const Run posed = s.run("check --robot " + quote(armUrdf()) + " --scene " + quote(kScenes + "/bench.scene") +
                          " --scene-pose 1 0 0 0 0 0");
  BOOST_TEST(posed.status == 2);
  BOOST_TEST(contains(posed.err, "--scene-pose after planning scene"), posed.err);
  // A bad .scene file is named with its line.
  const std::string bad = s.write("bad.scene", "s\n* a\n1\nbox\n1 -1 1\n0 0 0\n0 0 0 1\n0 0 0 0\n.\n");
  const Run r = s.run("check --robot " + quote(armUrdf()) + " --package-path " + quote(test::bundledDataDir()) +
                          " --scene " + quote(bad),
                      kArmStretched);
  BOOST_TEST(r.status == 1);
  BOOST_TEST(contains(r.err, "planning scene '" + bad + "', line 5, object 'a': box size y must be positive"), r.err);
}

BOOST_AUTO_TEST_CASE(the_virtual_joint_frame_needs_no_alias) {
  Scratch s;
  const std::string scene = s.write("crate.yaml",
                                    "world:\n  collision_objects:\n"
                                    "    - header: {frame_id: odom_combined}\n      id: crate\n"
                                    "      primitives: [{type: box, dimensions: [0.2, 0.2, 0.2]}]\n"
                                    "      primitive_poses: [{position: [0.6, 0, 0.1], orientation: [0, 0, 0, 1]}]\n");
  const std::string srdf = s.write("arm_base.srdf",
                                   "<robot name='deepcheck_arm'>\n"
                                   "  <virtual_joint name='base' type='fixed' parent_frame='odom_combined' "
                                   "child_link='base_link'/>\n</robot>\n");
  const std::string robot = "check --robot " + quote(armUrdf()) + " --package-path " + quote(test::bundledDataDir());
  const Run without = s.run(robot + " --scene " + quote(scene), kArmStretched);
  BOOST_TEST(without.status == 1);
  BOOST_TEST(contains(without.err, "unknown frame 'odom_combined'"), without.err);
  const Run with = s.run(robot + " --srdf " + quote(srdf) + " --scene " + quote(scene), kArmStretched);
  BOOST_TEST_REQUIRE(with.status == 0, with.err);
  const Run aliased =
      s.run(robot + " --scene " + quote(scene) + " --frame-alias odom_combined=base_link", kArmStretched);
  BOOST_TEST_REQUIRE(aliased.status == 0, aliased.err);
  BOOST_TEST(with.out == aliased.out);
  // The user's alias wins over the virtual joint's.
  const Run own =
      s.run(robot + " --srdf " + quote(srdf) + " --scene " + quote(scene) + " --frame-alias odom_combined=plinth",
            kArmStretched);
  BOOST_TEST(own.status == 1);
  BOOST_TEST(contains(own.err, "'plinth'"), own.err);
  // A malformed virtual joint is named with its line.
  const std::string bad = s.write("bad.srdf",
                                  "<robot name='a'>\n<virtual_joint name='v' type='wobbly' "
                                  "parent_frame='w' child_link='base_link'/>\n</robot>\n");
  const Run badRun = s.run(robot + " --srdf " + quote(bad) + " --scene " + quote(scene), kArmStretched);
  BOOST_TEST(badRun.status == 1);
  BOOST_TEST(contains(badRun.err, "line 2: <virtual_joint> 'v' has type 'wobbly'"), badRun.err);
}

// The dump's attached tool and allowed-collision matrix reach the world from the file: the tool
// rides on the hand with its touch links, the matrix's pairs are allowed, others are not.
BOOST_AUTO_TEST_CASE(a_topic_echo_dump_attaches_its_objects_and_allows_its_pairs) {
  const checker::World world =
      libraryWorld(armUrdf(), armSrdf(), test::bundledDataDir(), kScenes + "/monitored_planning_scene.yaml");
  const std::vector<checker::AttachedObjectInfo> attached = world.attachedObjects();
  BOOST_TEST_REQUIRE(attached.size() == 1u);
  BOOST_TEST(attached[0].object.name == "tool");
  BOOST_TEST(attached[0].link == "hand");
  BOOST_TEST(attached[0].touchLinks == (std::vector<std::string>{"hand", "left_finger", "right_finger"}));
  BOOST_TEST(world.collisionAllowed("base_link", "table"));
  BOOST_TEST(world.collisionAllowed("post", "link3"));
  BOOST_TEST(!world.collisionAllowed("link3", "table"));
}

BOOST_AUTO_TEST_CASE(info_describes_attached_objects_and_allowed_collisions) {
  Scratch s;
  const Run dump = s.run("info " + quote(kScenes + "/monitored_planning_scene.yaml"));
  BOOST_TEST_REQUIRE(dump.status == 0, dump.err);
  BOOST_TEST(contains(dump.out, "3 objects, 3 shapes, 1 attached objects, 1 allowed pairs"), dump.out);
  BOOST_TEST(contains(dump.out, "  tool (frame hand, line 40) on hand, touching hand left_finger right_finger"),
             dump.out);
  BOOST_TEST(contains(dump.out, "  base_link table\n  post anything\n"), dump.out);
  const Run text = s.run("info " + quote(kScenes + "/bench.scene"));
  BOOST_TEST_REQUIRE(text.status == 0, text.err);
  BOOST_TEST(contains(text.out, "3 objects, 4 shapes, 0 attached objects, 0 allowed pairs"), text.out);
  BOOST_TEST(contains(text.out, "  corner wedge (frame <model frame>, line 30)"), text.out);
  BOOST_TEST(contains(text.out, "allowed collisions:\n  none\n"), text.out);
}

BOOST_AUTO_TEST_SUITE_END()
