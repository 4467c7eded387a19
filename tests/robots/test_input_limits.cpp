// Hostile and oversized input to the URDF, SRDF, mesh, package:// and planning-scene readers:
// each is answered by one std::invalid_argument naming the file and the value, never by a crash,
// a read outside the package roots or a load that does not end.

#include "robots_test_util.h"

#include "deepcheck/robots/mesh_loader.h"
#include "deepcheck/robots/moveit_scene.h"
#include "deepcheck/robots/package_path.h"
#include "deepcheck/robots/robot_model.h"
#include "deepcheck/robots/srdf.h"

#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <string>

using namespace deepcheck::robots;
using deepcheck::robots::test::checkThrows;
using deepcheck::robots::test::TempDir;

namespace {

/// `levels` nested <tag> elements, each opened and closed.
std::string nested(const std::string& tag, int levels) {
  std::string out;
  for (int i = 0; i < levels; ++i) out += "<" + tag + ">";
  for (int i = 0; i < levels; ++i) out += "</" + tag + ">";
  return out;
}

/// A one-link URDF; `extra` is placed inside <robot> after the link, `collision` inside the link.
std::string urdf(const std::string& extra, const std::string& collision = "") {
  return "<robot name=\"r\"><link name=\"base\">" + collision + "</link>" + extra + "</robot>";
}

std::string collisionAt(const std::string& xyz) {
  return "<collision><origin xyz=\"" + xyz + "\"/><geometry><sphere radius=\"1\"/></geometry></collision>";
}

/// A star: `links` links, all but the first joined to the first by a fixed joint.
std::string starUrdf(int links) {
  std::string out = "<robot name=\"star\"><link name=\"l0\"/>";
  for (int i = 1; i < links; ++i) {
    const std::string n = std::to_string(i);
    out += "<link name=\"l" + n + "\"/><joint name=\"j" + n + "\" type=\"fixed\"><parent link=\"l0\"/>" +
           "<child link=\"l" + n + "\"/></joint>";
  }
  return out + "</robot>";
}

const char* const kTetrahedronObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

/// A planning scene of `objects` objects that all alias the first one's list of `primitives`
/// boxes (objects * primitives shapes from a file of objects + 2 * primitives lines).
std::string aliasedScene(int objects, int primitives) {
  std::string out =
      "world:\n  collision_objects:\n    - id: o0\n      header: {frame_id: base}\n      primitives: &p\n";
  for (int i = 0; i < primitives; ++i) out += "        - {type: box, dimensions: [1, 1, 1]}\n";
  out += "      primitive_poses: &q\n";
  for (int i = 0; i < primitives; ++i) out += "        - {position: [0, 0, 0], orientation: [0, 0, 0, 1]}\n";
  for (int i = 1; i < objects; ++i) {
    out += "    - {id: o" + std::to_string(i) + ", header: {frame_id: base}, primitives: *p, primitive_poses: *q}\n";
  }
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(robots_input_limits)

BOOST_AUTO_TEST_CASE(deep_urdf_and_srdf_are_rejected_before_parsing) {
  const std::string deep = nested("a", 60000);
  checkThrows([&] { RobotModel::fromUrdfString(urdf(deep), "", {}, "deep.urdf"); },
              {"URDF 'deep.urdf'", "line 1", "nested 257 levels deep", "limit of 256"});
  checkThrows([&] { parseSrdfDisabledPairs("<robot>\n" + deep + "</robot>", "deep.srdf"); },
              {"SRDF 'deep.srdf'", "line 2", "nested 257 levels deep"});
}

BOOST_AUTO_TEST_CASE(nesting_at_the_limit_is_accepted) {
  // <robot> is level 1: 255 more levels reach the limit, 256 pass it.
  BOOST_TEST(parseSrdfDisabledPairs("<robot>" + nested("g", kMaxNestingDepth - 1) + "</robot>").empty());
  checkThrows([&] { parseSrdfDisabledPairs("<robot>" + nested("g", kMaxNestingDepth) + "</robot>", "s"); },
              {"SRDF 's'", "nested 257 levels deep"});
}

BOOST_AUTO_TEST_CASE(nesting_scan_skips_comments_cdata_and_attribute_values) {
  std::string hidden;
  for (int i = 0; i < 1000; ++i) hidden += "<a>";
  const std::string xml = "<?xml version=\"1.0\"?>\n<!-- " + hidden + " -->\n<robot name=\"r\" note=\"" + hidden +
                          "\"><![CDATA[" + hidden + "]]><link name=\"base\"/></robot>";
  BOOST_TEST(RobotModel::fromUrdfString(xml, "").numLinks() == 1);
}

BOOST_AUTO_TEST_CASE(ambiguous_markup_is_rejected) {
  // TinyXML ends these at the first '>', other parsers later: no single reading holds for both.
  checkThrows([&] { parseSrdfDisabledPairs("<robot>\n<?pi > " + nested("a", 300) + " ?></robot>", "pi.srdf"); },
              {"SRDF 'pi.srdf'", "line 2", "processing instruction"});
  checkThrows([&] { parseSrdfDisabledPairs("<!DOCTYPE robot [ <!ENTITY e \"x\"> ]>\n<robot/>", "dtd.srdf"); },
              {"SRDF 'dtd.srdf'", "line 1", "internal DTD subset"});
}

BOOST_AUTO_TEST_CASE(deep_xml_meshes_are_rejected_before_assimp) {
  TempDir dir;
  std::string nodes;
  for (int i = 0; i < 20000; ++i) nodes += "<node id=\"n" + std::to_string(i) + "\">";
  const std::string dae = dir.write("deep.dae",
                                    "<?xml version=\"1.0\"?>\n<COLLADA><library_visual_scenes>\n"
                                    "<visual_scene id=\"s\">" +
                                        nodes +
                                        "</visual_scene>"
                                        "</library_visual_scenes></COLLADA>");
  checkThrows([&] { loadMesh(dae); }, {"mesh file '" + dae + "'", "line 3", "nested 257 levels deep"});
  // Any file that starts with '<' is scanned, whatever its extension.
  const std::string x3d = dir.write("deep.mesh", "\n  " + nested("Group", 1000));
  checkThrows([&] { loadMesh(x3d); }, {"mesh file '" + x3d + "'", "levels deep"});
}

BOOST_AUTO_TEST_CASE(package_uri_may_not_leave_its_package) {
  TempDir dir;
  const std::string root = (dir.path() / "roots").string();
  dir.write("roots/mypkg/meshes/t.obj", kTetrahedronObj);
  const std::string uri = "package://mypkg/../../secret/outside.obj";
  std::string messages[2];
  for (int exists = 0; exists < 2; ++exists) {
    if (exists) dir.write("secret/outside.obj", kTetrahedronObj);
    try {
      resolveUriOrThrow(uri, {root}, "", "URDF 'r.urdf', link 'l'");
      BOOST_ERROR("no exception for " << uri);
    } catch (const std::invalid_argument& e) {
      messages[exists] = e.what();
    }
  }
  BOOST_TEST(messages[0] == messages[1]);  // nothing told about the file outside
  BOOST_TEST(messages[0].find(uri) != std::string::npos, messages[0]);
  BOOST_TEST(messages[0].find(root + "/mypkg'") != std::string::npos, messages[0]);
  BOOST_TEST(messages[0].find("outside its package root") != std::string::npos, messages[0]);
  BOOST_TEST(resolveUri("package://mypkg/meshes/../meshes/t.obj", {root}, "").found());
  checkThrows([&] { resolveUriOrThrow("package://mypkg//etc/passwd", {root}, "", "c"); }, {"malformed package URI"});
  checkThrows([&] { resolveUriOrThrow("package://../secret/outside.obj", {root}, "", "c"); },
              {"malformed package URI"});
}

// A symbolic link placed in the package (colcon --symlink-install links installed files back to
// the sources) is followed: only the path as written must stay in the package.
BOOST_AUTO_TEST_CASE(package_symlinks_are_followed) {
  TempDir dir;
  const std::string root = (dir.path() / "install").string();
  dir.write("install/mypkg/package.xml", "<package><name>mypkg</name></package>");
  const std::string source = dir.write("src/mypkg/meshes/t.obj", kTetrahedronObj);
  std::filesystem::create_directories(dir.path() / "install/mypkg/meshes");
  std::filesystem::create_symlink(source, dir.path() / "install/mypkg/meshes/t.obj");
  BOOST_TEST(resolveUri("package://mypkg/meshes/t.obj", {root}, "").found());
  checkThrows([&] { resolveUriOrThrow("package://mypkg/../../src/mypkg/meshes/t.obj", {root}, "", "URDF 'r.urdf'"); },
              {"URDF 'r.urdf'", "outside its package root", root + "/mypkg'"});
}

BOOST_AUTO_TEST_CASE(package_xml_name_is_read_from_its_start) {
  TempDir dir;
  const std::string root = (dir.path() / "roots").string();
  // Found: the name is in the first bytes, whatever follows. Not found: the name comes late.
  dir.write("roots/folder_a/package.xml", "<package><name>pkg_a</name>" + std::string(200000, ' ') + "</package>");
  dir.write("roots/folder_a/t.obj", kTetrahedronObj);
  dir.write("roots/folder_b/package.xml", "<package>" + std::string(200000, ' ') + "<name>pkg_b</name></package>");
  dir.write("roots/folder_b/t.obj", kTetrahedronObj);
  BOOST_TEST(resolveUri("package://pkg_a/t.obj", {root}, "").found());
  BOOST_TEST(!resolveUri("package://pkg_b/t.obj", {root}, "").found());
}

BOOST_AUTO_TEST_CASE(urdf_link_count_limit) {
  LoadOptions options;
  options.maxLinks = 10;
  BOOST_TEST(RobotModel::fromUrdfString(starUrdf(10), "", options).numLinks() == 10);
  checkThrows([&] { RobotModel::fromUrdfString(starUrdf(20), "", options, "star.urdf"); },
              {"URDF 'star.urdf'", "20 <link> elements", "LoadOptions::maxLinks = 10"});
  BOOST_TEST(RobotModel::fromUrdfString(starUrdf(2000), "").numLinks() == 2000);
}

BOOST_AUTO_TEST_CASE(huge_collision_origins_are_rejected_at_load) {
  for (const std::string value : {"1e300", "1e60"}) {
    checkThrows([&] { RobotModel::fromUrdfString(urdf("", collisionAt(value + " 0 0")), "", {}, "far.urdf"); },
                {"URDF 'far.urdf'", "link 'base', collision 0", "xyz=\"" + value + " 0 0\"", "out of range"});
  }
  checkThrows([&] { RobotModel::fromUrdfString(urdf("", collisionAt("0 inf 0")), "", {}, "inf.urdf"); },
              {"URDF 'inf.urdf'", "link 'base'", "non-finite", "component 1"});
}

BOOST_AUTO_TEST_CASE(huge_mesh_scale_is_named) {
  TempDir dir;
  const std::string mesh = dir.write("t.obj", kTetrahedronObj);
  checkThrows([&] { loadMesh(mesh, Eigen::Vector3d(1e300, 1, 1)); },
              {"mesh file '" + mesh + "'", "scale (1e+300 1 1)"});
  // Within range, but it places a vertex beyond it: the message names the vertex and the scale.
  const std::string wide =
      dir.write("wide.obj", "v 0 0 0\nv 1e6 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  checkThrows([&] { loadMesh(wide, Eigen::Vector3d(1e45, 1, 1)); }, {"vertex", "(1e+51 0 0)", "scale (1e+45 1 1)"});
  const std::string scaled =
      "<collision><geometry><mesh filename=\"t.obj\" scale=\"1e300 1 1\"/></geometry></collision>";
  checkThrows([&] { RobotModel::fromUrdfString(urdf("", scaled), dir.path().string(), {}, "big.urdf"); },
              {"URDF 'big.urdf'", "link 'base'", "scale=\"1e300 1 1\"", "out of range"});
}

BOOST_AUTO_TEST_CASE(mesh_file_size_limit) {
  TempDir dir;
  const std::string mesh = dir.write("t.obj", kTetrahedronObj);
  MeshLoadOptions options;
  options.maxFileBytes = 16;
  checkThrows([&] { loadMesh(mesh, Eigen::Vector3d::Ones(), options); },
              {"mesh file '" + mesh + "'", "MeshLoadOptions::maxFileBytes = 16"});
  BOOST_TEST(loadMesh(mesh).triangles.size() == 4u);
}

BOOST_AUTO_TEST_CASE(yaml_nesting_names_file_and_depth) {
  const std::string deep = "world: " + std::string(100000, '[') + std::string(100000, ']') + "\n";
  checkThrows([&] { parsePlanningScene(deep, "", {}, "deep.yaml"); },
              {"planning scene 'deep.yaml'", "line 1", "nested 257 levels deep", "limit of 256"});
}

BOOST_AUTO_TEST_CASE(scene_shape_count_stops_alias_expansion) {
  SceneLoadOptions options;
  options.maxShapes = 500;
  BOOST_TEST(parsePlanningScene(aliasedScene(5, 100), "", options).objects.size() == 5u);
  checkThrows([&] { parsePlanningScene(aliasedScene(100, 100), "", options, "bomb.yaml"); },
              {"planning scene 'bomb.yaml'", "object 'o5'", "600 shapes", "SceneLoadOptions::maxShapes = 500"});
  options.maxShapes = 50;
  checkThrows([&] { parsePlanningScene(aliasedScene(100, 1), "", options, "many.yaml"); },
              {"100 collision objects", "SceneLoadOptions::maxShapes = 50"});
}

BOOST_AUTO_TEST_CASE(scene_numbers_out_of_range) {
  const std::string scene =
      "world:\n  collision_objects:\n    - id: far\n      header: {frame_id: base}\n"
      "      primitives: [{type: box, dimensions: [1, 1, 1]}]\n"
      "      primitive_poses: [{position: [1e60, 0, 0], orientation: [0, 0, 0, 1]}]\n";
  checkThrows([&] { parsePlanningScene(scene, "", {}, "far.yaml"); },
              {"planning scene 'far.yaml'", "line 6", "object 'far'", "magnitude at most 1e+50", "'1e60'"});
}

BOOST_AUTO_TEST_SUITE_END()
