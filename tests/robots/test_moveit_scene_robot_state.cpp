// A planning scene as MoveIt publishes it (`ros2 topic echo /monitored_planning_scene`): an empty
// octomap, attached objects (robot_state.attached_collision_objects) and the allowed collision
// matrix (moveit_scene.h), and the errors on bad ones.
#include "deepcheck/robots/moveit_scene.h"

#include "common/read_text.h"
#include "robots_test_util.h"

#include <boost/test/unit_test.hpp>

#include <array>
#include <set>
#include <string>

namespace deepcheck::robots {
namespace {

using deepcheck::test::readText;
using test::checkThrows;

const std::string kScenes = std::string(DEEPCHECK_SOURCE_DIR) + "/tests/data/moveit_scenes";
const std::string kDump = kScenes + "/monitored_planning_scene.yaml";
constexpr double kExact = 1e-12;  // values copied from the file, up to round-off
/// A pose written with 17 digits and read back: the rotation goes through a quaternion.
constexpr double kRoundTrip = 1e-15;

/// `text` with its only occurrence of `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  BOOST_REQUIRE_MESSAGE(at != std::string::npos && text.find(from, at + 1) == std::string::npos,
                        "'" << from << "' is not in the text exactly once");
  return text.replace(at, from.size(), to);
}

PlanningScene parse(const std::string& yaml) { return parsePlanningScene(yaml, kScenes, {}, "dump.yaml"); }

/// A scene with only this allowed_collision_matrix (indented 2 spaces).
PlanningScene parseMatrix(const std::string& body) {
  return parse("allowed_collision_matrix:\n" + body + "world: {}\n");
}

/// A sphere's primitives and primitive_poses, the second key after `indent`.
std::string sphere(const std::string& indent) {
  return "primitives: [{type: sphere, dimensions: [0.1]}]\n" + indent +
         "primitive_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]\n";
}

/// A scene with one attached object whose entry (after "  - ") is `entry`.
PlanningScene parseAttached(const std::string& entry) {
  return parse("robot_state:\n  attached_collision_objects:\n  - " + entry + "world: {}\n");
}

std::set<std::pair<std::string, std::string>> unorderedPairs(const AllowedCollisions& allowed) {
  std::set<std::pair<std::string, std::string>> out;
  for (const auto& [a, b] : allowed.pairs) out.insert(a < b ? std::make_pair(a, b) : std::make_pair(b, a));
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(robots_moveit_scene_robot_state)

BOOST_AUTO_TEST_CASE(topic_echo_dump_reads_objects_attached_objects_and_matrix) {
  const PlanningScene scene = loadPlanningScene(kDump);
  BOOST_REQUIRE_EQUAL(scene.objects.size(), 3u);
  const SceneObject& table = scene.objects[0];
  BOOST_CHECK_EQUAL(table.id, "table");
  BOOST_CHECK_EQUAL(table.frameId, "base_link");
  BOOST_REQUIRE_EQUAL(table.shapes.size(), 1u);
  BOOST_CHECK(table.shapes[0].geometry.type == GeometryType::Box);
  BOOST_CHECK_SMALL((table.shapes[0].geometry.boxSize - Eigen::Vector3d(0.6, 1.0, 0.1)).norm(), kExact);
  BOOST_CHECK_SMALL((table.shapes[0].X_FS.translation() - Eigen::Vector3d(0.55, 0, -0.05)).norm(), kExact);
  BOOST_CHECK_EQUAL(scene.objects[1].id, "post");
  // A mesh object as MoveIt publishes it: vertices and triangles inline.
  const SceneObject& bracket = scene.objects[2];
  BOOST_REQUIRE_EQUAL(bracket.shapes.size(), 1u);
  BOOST_REQUIRE(bracket.shapes[0].mesh);
  BOOST_CHECK(bracket.shapes[0].geometry.type == GeometryType::Mesh);
  BOOST_CHECK(bracket.shapes[0].geometry.meshPath.empty());
  BOOST_CHECK_EQUAL(bracket.shapes[0].name, "mesh 0 (inline, 4 vertices, 4 triangles)");
  BOOST_CHECK_EQUAL(bracket.shapes[0].mesh->vertices.size(), 4u);
  BOOST_CHECK_SMALL((bracket.shapes[0].mesh->vertices[3] - Eigen::Vector3d(0, 0, 0.1)).norm(), kExact);
  const std::array<int, 3> last = {1, 2, 3};
  BOOST_CHECK(bracket.shapes[0].mesh->triangles.at(3) == last);
  BOOST_CHECK_SMALL((bracket.shapes[0].X_FS.translation() - Eigen::Vector3d(0.45, -0.3, 0)).norm(), kExact);

  BOOST_REQUIRE_EQUAL(scene.attached.size(), 1u);
  const AttachedObject& tool = scene.attached[0];
  BOOST_CHECK_EQUAL(tool.linkName, "hand");
  BOOST_CHECK_EQUAL(tool.line, 38);
  BOOST_CHECK_EQUAL(tool.object.id, "tool");
  BOOST_CHECK_EQUAL(tool.object.frameId, "hand");
  BOOST_CHECK_SMALL((tool.object.X_FO.translation() - Eigen::Vector3d(0, 0, 0.1)).norm(), kExact);
  BOOST_REQUIRE_EQUAL(tool.object.shapes.size(), 1u);
  BOOST_CHECK(tool.object.shapes[0].geometry.type == GeometryType::Cylinder);
  BOOST_CHECK_SMALL(tool.object.shapes[0].geometry.length - 0.12, kExact);
  BOOST_CHECK_SMALL(tool.object.shapes[0].geometry.radius - 0.02, kExact);
  const std::vector<std::string> touch = {"hand", "left_finger", "right_finger"};
  BOOST_CHECK_EQUAL_COLLECTIONS(tool.touchLinks.begin(), tool.touchLinks.end(), touch.begin(), touch.end());

  // The matrix is symmetric in the file; the pair is kept once. A name that is nothing (yet) is
  // kept: the world resolves names.
  BOOST_REQUIRE_EQUAL(scene.allowed.pairs.size(), 1u);
  BOOST_CHECK_EQUAL(scene.allowed.pairs[0].first, "base_link");
  BOOST_CHECK_EQUAL(scene.allowed.pairs[0].second, "table");
  BOOST_REQUIRE_EQUAL(scene.allowed.always.size(), 1u);
  BOOST_CHECK_EQUAL(scene.allowed.always[0], "post");
}

BOOST_AUTO_TEST_CASE(octomap_with_data_is_refused_with_its_line) {
  const std::string dump = readText(kDump);
  const std::string withData = replaced(dump, "      data: []\n", "      data:\n      - 12\n      - -3\n");
  checkThrows([&] { parsePlanningScene(withData, kScenes, {}, "scan.yaml"); },
              {"planning scene 'scan.yaml', line 330", "octomap with data is not supported"});
  // An octomap without an inner octomap, or whose data is absent, is empty too.
  BOOST_CHECK_EQUAL(parse("world:\n  octomap: {header: {frame_id: a}}\n").objects.size(), 0u);
  BOOST_CHECK_EQUAL(parse("world:\n  octomap: {octomap: {id: OcTree, binary: true}}\n").objects.size(), 0u);
  checkThrows([] { parse("world:\n  octomap: {octomap: {data: [1]}}\n"); },
              {"dump.yaml', line 2", "octomap with data is not supported"});
  checkThrows([] { parse("world:\n  octomap: {octomap: {dat: []}}\n"); },
              {"line 2", "unknown key 'dat' in world.octomap.octomap"});
}

BOOST_AUTO_TEST_CASE(matrix_reads_the_upper_triangle_as_moveit_does) {
  const PlanningScene lowerOnly = parseMatrix(
      "  entry_names: [a, b, c]\n"
      "  entry_values:\n"
      "  - enabled: [true, false, true]\n"
      "  - enabled: [true, false, true]\n"
      "  - enabled: [false, false, false]\n");
  // (a, a) is the diagonal and (b, a) the lower triangle: only (a, c) and (b, c) count.
  const std::set<std::pair<std::string, std::string>> expected = {{"a", "c"}, {"b", "c"}};
  BOOST_CHECK(unorderedPairs(lowerOnly.allowed) == expected);
  BOOST_CHECK(lowerOnly.allowed.always.empty());
  const PlanningScene defaults = parseMatrix(
      "  default_entry_names: [x, y, z]\n"
      "  default_entry_values: [True, false, yes]\n");
  const std::vector<std::string> always = {"x", "z"};
  BOOST_CHECK_EQUAL_COLLECTIONS(defaults.allowed.always.begin(), defaults.allowed.always.end(), always.begin(),
                                always.end());
  BOOST_CHECK(parseMatrix("  entry_names: []\n  entry_values: []\n").allowed.pairs.empty());
}

BOOST_AUTO_TEST_CASE(bad_matrices_name_file_line_and_what) {
  checkThrows([] { parseMatrix("  entry_names: [a, b, c]\n  entry_values:\n  - enabled: [false, true, true]\n"); },
              {"dump.yaml', line 4", "entry_values has 1 entries, entry_names has 3"});
  checkThrows([] { parseMatrix("  entry_names: [a, b]\n"); },
              {"dump.yaml', line 2", "entry_values has 0 entries, entry_names has 2"});
  checkThrows(
      [] {
        parseMatrix(
            "  entry_names: [a, b]\n  entry_values:\n  - enabled: [false, true]\n"
            "  - enabled: [true]\n");
      },
      {"line 5", "entry_values[1].enabled has 1 entries, entry_names has 2"});
  checkThrows([] { parseMatrix("  entry_names: [a, b, a]\n"); }, {"line 2", "entry_names[2] 'a' is listed twice"});
  checkThrows([] { parseMatrix("  entry_names: [a]\n  entry_values:\n  - enabled: [maybe]\n"); },
              {"line 4", "entry_values[0].enabled[0] must be true or false, is 'maybe'"});
  checkThrows([] { parseMatrix("  default_entry_names: [a, b]\n  default_entry_values: [true]\n"); },
              {"line 3", "default_entry_values has 1 entries, default_entry_names has 2"});
  checkThrows([] { parseMatrix("  entry_name: [a]\n"); }, {"line 2", "unknown key 'entry_name'"});
}

BOOST_AUTO_TEST_CASE(bad_inline_meshes_name_file_line_and_object) {
  const auto mesh = [](const std::string& body) {
    return parse("world:\n  collision_objects:\n  - header: {frame_id: base_link}\n    id: m\n    meshes:\n    - " +
                 body + "\n    mesh_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]\n");
  };
  const std::string vertices = "vertices: [[0, 0, 0], [1, 0, 0], {x: 0, y: 1, z: 0}]";
  BOOST_CHECK_EQUAL(mesh(vertices + "\n      triangles: [[0, 1, 2]]").objects.at(0).shapes.at(0).mesh->triangles.size(),
                    1u);
  checkThrows([&] { mesh(vertices); }, {"dump.yaml', line 6, object 'm'", "missing 'triangles'"});
  checkThrows([&] { mesh(vertices + "\n      triangles: []"); }, {"line 7", "'triangles' must be a list, not empty"});
  checkThrows([&] { mesh(vertices + "\n      triangles: [{vertex_indices: [0, 1, 3]}]"); },
              {"line 7, object 'm'", "triangles[0][2] is 3, not one of the 3 vertices"});
  checkThrows([&] { mesh(vertices + "\n      triangles: [[0, 1]]"); },
              {"line 7", "triangles[0] must have three vertex indices"});
  checkThrows([&] { mesh(vertices + "\n      triangles: [[0, 1, -2]]"); }, {"line 7", "is -2, not one of"});
  checkThrows([&] { mesh(vertices + "\n      triangles: [[0, 1, 2]]\n      scale: [1, 1, 1]"); },
              {"line 8", "unknown key 'scale' in an inline mesh"});
  checkThrows([&] { mesh("vertices: [[0, 0, .nan]]\n      triangles: [[0, 0, 0]]"); },
              {"vertices[0][2] must be finite"});
  SceneLoadOptions small;
  small.maxInlineMeshElements = 3;
  checkThrows(
      [&] {
        parsePlanningScene(
            "world:\n  collision_objects:\n  - header: {frame_id: base_link}\n    id: m\n    meshes:\n    - " +
                vertices +
                "\n      triangles: [[0, 1, 2]]\n    mesh_poses: [{position: [0, 0, 0], "
                "orientation: [0, 0, 0, 1]}]\n",
            kScenes, small, "big.yaml");
      },
      {"big.yaml', line 7",
       "'triangles' has 1 entries, more than the 0 left of SceneLoadOptions::maxInlineMeshElements"});
}

BOOST_AUTO_TEST_CASE(bad_attached_objects_name_file_line_and_object) {
  const std::string object = "object:\n      header: {frame_id: hand}\n      id: tool\n      " + sphere("      ");
  BOOST_CHECK_EQUAL(parseAttached("link_name: hand\n    " + object).attached.size(), 1u);
  checkThrows([&] { parseAttached(object); }, {"dump.yaml', line 3, attached object 0", "missing 'link_name'"});
  checkThrows([&] { parseAttached("link_name: hand\n    touch_links: [a]\n"); },
              {"line 3, attached object 0", "missing 'object'"});
  checkThrows([&] { parseAttached("link_name: ''\n    " + object); }, {"line 3", "link_name is empty"});
  checkThrows([&] { parseAttached("link_name: hand\n    " + object + "    touch_links: hand\n"); },
              {"attached object 'tool'", "'touch_links' must be a list"});
  checkThrows([&] { parseAttached("link_name: hand\n    object:\n      header: {frame_id: hand}\n      id: tool\n"); },
              {"line 5, attached object 'tool'", "no primitives and no meshes"});
  checkThrows([&] { parseAttached("link_name: hand\n    posture: {}\n    " + object); },
              {"line 4, attached object 0", "unknown key 'posture' in an attached collision object"});
  // World objects and attached objects share one space of ids.
  checkThrows(
      [&] {
        parse("robot_state:\n  attached_collision_objects:\n  - link_name: hand\n    " + object +
              "world:\n  collision_objects:\n  - header: {frame_id: base_link}\n    id: tool\n    " + sphere("    "));
      },
      {"line 11, object 'tool'", "the id is used twice (first at line 5)"});
  checkThrows([] { parse("robot_state: {joint_state: {}, attached: []}\nworld: {}\n"); },
              {"line 1", "unknown key 'attached' in robot_state"});
}

BOOST_AUTO_TEST_CASE(dump_round_trips_through_the_writer) {
  const PlanningScene scene = loadPlanningScene(kDump);
  const std::string text = writePlanningScene(scene);
  const PlanningScene back = parsePlanningScene(text, "/", {}, "written.yaml");
  BOOST_REQUIRE_EQUAL(back.objects.size(), scene.objects.size());
  BOOST_REQUIRE_EQUAL(back.attached.size(), 1u);
  const AttachedObject& a = scene.attached[0];
  const AttachedObject& b = back.attached[0];
  BOOST_CHECK_EQUAL(b.linkName, a.linkName);
  BOOST_CHECK_EQUAL(b.object.id, a.object.id);
  BOOST_CHECK_EQUAL(b.object.frameId, a.object.frameId);
  BOOST_CHECK_EQUAL_COLLECTIONS(b.touchLinks.begin(), b.touchLinks.end(), a.touchLinks.begin(), a.touchLinks.end());
  BOOST_REQUIRE_EQUAL(b.object.shapes.size(), 1u);
  BOOST_CHECK_SMALL((b.object.shapes[0].X_FS.matrix() - a.object.shapes[0].X_FS.matrix()).cwiseAbs().maxCoeff(),
                    kRoundTrip);
  const SceneShape& mesh = scene.objects[2].shapes[0];
  const SceneShape& meshBack = back.objects.at(2).shapes.at(0);
  BOOST_REQUIRE(meshBack.mesh);
  BOOST_CHECK(meshBack.mesh->vertices == mesh.mesh->vertices);
  BOOST_CHECK(meshBack.mesh->triangles == mesh.mesh->triangles);
  BOOST_CHECK(unorderedPairs(back.allowed) == unorderedPairs(scene.allowed));
  BOOST_CHECK(back.allowed.always == scene.allowed.always);

  // Pairs in any order and names in several pairs come back as the same unordered pairs.
  PlanningScene allowed;
  allowed.allowed.pairs = {{"a", "b"}, {"c", "a"}, {"b", "c"}, {"d", "a"}};
  allowed.allowed.always = {"e"};
  const PlanningScene allowedBack = parsePlanningScene(writePlanningScene(allowed), "/", {}, "written.yaml");
  BOOST_CHECK(unorderedPairs(allowedBack.allowed) == unorderedPairs(allowed.allowed));
  BOOST_CHECK_EQUAL(allowedBack.allowed.pairs.size(), 4u);
  BOOST_CHECK(allowedBack.allowed.always == allowed.allowed.always);
}

BOOST_AUTO_TEST_SUITE_END()

}  // namespace deepcheck::robots
