// MoveIt planning-scene YAML (moveit_scene.h): the MotionBenchMaker scenes, a hand-written scene
// with every shape, frame resolution and the errors on bad files.
#include "deepcheck/robots/collision_geometry.h"
#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/mesh_loader.h"
#include "deepcheck/robots/moveit_scene.h"

#include "common/read_text.h"
#include "robots_test_util.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <regex>
#include <sstream>

namespace deepcheck::robots {
namespace {

namespace fs = std::filesystem;
using deepcheck::test::readText;
using test::checkThrows;
using test::loadPanda;

const std::string kTestData = std::string(DEEPCHECK_SOURCE_DIR) + "/tests/data";
const std::string kAllShapes = kTestData + "/moveit_scenes/all_shapes.yaml";
constexpr double kExact = 1e-12;  // values copied from the file, up to round-off

std::string mbmScenes() { return test::sharedDir() + "/scenes/motion_bench_maker/configs/scenes"; }

SceneLoadOptions testOptions() {
  SceneLoadOptions o;
  o.packageRoots = {kTestData};
  o.useRosPackagePath = false;
  return o;
}

const SceneObject& object(const PlanningScene& scene, const std::string& id) {
  const int i = scene.objectIndex(id);
  BOOST_REQUIRE_MESSAGE(i >= 0, "no object " << id << " in " << scene.source);
  return scene.objects[i];
}

void checkVector(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected) {
  BOOST_CHECK_MESSAGE((actual - expected).norm() <= kExact,
                      "got " << actual.transpose() << ", expected " << expected.transpose());
}

/// How many lines of `text` match `pattern`: an independent count of what the file declares.
int countLines(const std::string& text, const std::string& pattern) {
  const std::regex re(pattern);
  std::istringstream in(text);
  int n = 0;
  for (std::string line; std::getline(in, line);) n += std::regex_search(line, re) ? 1 : 0;
  return n;
}

PlanningScene parse(const std::string& yaml) {
  return parsePlanningScene(yaml, kTestData + "/moveit_scenes", testOptions(), "bad.yaml");
}

/// One object in base_link with the given primitives/meshes block (indented 6 spaces).
std::string oneObject(const std::string& body) {
  return "world:\n  collision_objects:\n    - header:\n        frame_id: base_link\n"
         "      id: thing\n" +
         body;
}

const std::string kIdentity = "orientation: [0, 0, 0, 1]";

}  // namespace

BOOST_AUTO_TEST_SUITE(robots_moveit_scene)

BOOST_AUTO_TEST_CASE(every_motion_bench_maker_scene_loads_as_written) {
  if (!test::haveShared("MotionBenchMaker scenes")) return;
  int files = 0;
  for (const auto& dir : fs::directory_iterator(mbmScenes())) {
    for (const auto& entry : fs::directory_iterator(dir.path())) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("scene", 0) != 0 || entry.path().extension() != ".yaml") continue;
      ++files;
      const PlanningScene scene = loadPlanningScene(entry.path().string());
      const std::string text = readText(entry.path().string());
      BOOST_TEST_CONTEXT(name) {
        BOOST_CHECK_EQUAL(int(scene.objects.size()), countLines(text, R"(^\s*(- )?id:)"));
        int primitives = 0;
        int shapes = 0;
        for (const SceneObject& o : scene.objects) {
          BOOST_CHECK_EQUAL(o.frameId, "base_link");
          for (const SceneShape& s : o.shapes) primitives += s.name.rfind("primitive", 0) == 0;
          shapes += int(o.shapes.size());
        }
        BOOST_CHECK_EQUAL(primitives, countLines(text, R"(^\s*(- )?type:)"));
        BOOST_CHECK_EQUAL(shapes, countLines(text, R"(^\s*(- )?position:)"));
      }
    }
  }
  BOOST_CHECK_EQUAL(files, 6);  // bookshelf small/tall/thin, box, cage, table
}

BOOST_AUTO_TEST_CASE(motion_bench_maker_values_match_the_files) {
  if (!test::haveShared("MotionBenchMaker scenes")) return;
  const PlanningScene shelf = loadPlanningScene(mbmScenes() + "/bookshelf/scene_small.yaml");
  BOOST_CHECK_EQUAL(shelf.objects.size(), 7u);
  const SceneShape& can = object(shelf, "Can1").shapes.at(0);
  BOOST_CHECK(can.geometry.type == GeometryType::Cylinder);
  BOOST_CHECK_CLOSE(can.geometry.length, 0.14, 1e-12);
  BOOST_CHECK_CLOSE(can.geometry.radius, 0.03, 1e-12);
  checkVector(can.X_FS.translation(), {0.9, 0, 1.08});
  BOOST_CHECK(can.X_FS.linear().isIdentity(kExact));
  const SceneShape& bottom = object(shelf, "shelf_bottom").shapes.at(0);
  BOOST_CHECK(bottom.geometry.type == GeometryType::Box);
  checkVector(bottom.geometry.boxSize, {1.2, 1, 0.04});
  checkVector(bottom.X_FS.translation(), {1, 0, 1});
  BOOST_CHECK_EQUAL(object(shelf, "Can1").line, 3);

  const PlanningScene table = loadPlanningScene(mbmScenes() + "/table/scene_table.yaml");
  checkVector(object(table, "Cube").shapes.at(0).geometry.boxSize, {0.25, 0.25, 0.25});
  checkVector(object(table, "Cube").shapes.at(0).X_FS.translation(), {0.75, 0.4, 0.85});
  checkVector(object(table, "Can1").shapes.at(0).X_FS.translation(), {0.85, 0, 0.8});

  // The cage states base_link as the planning frame through an identity fixed_frame_transform.
  const PlanningScene cage = loadPlanningScene(mbmScenes() + "/cage/scene_cage.yaml");
  checkVector(object(cage, "Cube1").shapes.at(0).geometry.boxSize, {0.07, 0.07, 0.07});
  checkVector(object(cage, "Cube1").shapes.at(0).X_FS.translation(), {0.8, 0, 0.52});
}

BOOST_AUTO_TEST_CASE(kitchen_names_meshes_the_data_set_lacks) {
  if (!test::haveShared("MotionBenchMaker kitchen")) return;
  // kitchen.yaml refers to objs/*.obj, which MotionBenchMaker ships as meshes/*.stl only.
  SceneLoadOptions o;
  o.packageRoots = {test::sharedDir() + "/scenes"};
  o.useRosPackagePath = false;
  checkThrows([&] { loadPlanningScene(mbmScenes() + "/kitchen/kitchen.yaml", o); },
              {"kitchen.yaml', line 7", "object 'diswasher'", "objs/dishwasher.obj",
               "searched:", "motion_bench_maker/configs/scenes/kitchen/objs/dishwasher.obj"});
}

BOOST_AUTO_TEST_CASE(panda_places_motion_bench_maker_objects_through_an_alias) {
  if (!test::haveShared("Panda with MotionBenchMaker scene")) return;
  RobotModel panda = loadPanda();
  const PlanningScene shelf = loadPlanningScene(mbmScenes() + "/bookshelf/scene_small.yaml");
  const Eigen::VectorXd q = panda.defaultConfiguration();
  checkThrows([&] { shapeWorldPoses(shelf, panda, q); },
              {"scene_small.yaml', line 3, object 'Can1'", "unknown frame 'base_link'", "panda_link0, panda_link1",
               "--frame-alias base_link=panda_link0"});
  Eigen::Isometry3d X_WR = Eigen::Isometry3d::Identity();
  X_WR.translation() = Eigen::Vector3d(0.1, -0.2, 0.3);
  X_WR.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  panda.setBasePose(X_WR);
  const auto poses = shapeWorldPoses(shelf, panda, q, {{"base_link", "panda_link0"}});
  BOOST_REQUIRE_EQUAL(poses.size(), shelf.objects.size());
  const int can = shelf.objectIndex("Can1");
  checkVector(poses[can][0].translation(), X_WR * Eigen::Vector3d(0.9, 0, 1.08));
  BOOST_CHECK(poses[can][0].linear().isApprox(X_WR.linear(), kExact));
}

BOOST_AUTO_TEST_CASE(hand_written_scene_has_every_shape) {
  const PlanningScene scene = loadPlanningScene(kAllShapes, testOptions());
  BOOST_REQUIRE_EQUAL(scene.objects.size(), 4u);

  const SceneShape& crate = object(scene, "crate").shapes.at(0);
  checkVector(crate.geometry.boxSize, {0.4, 0.3, 0.2});
  checkVector(crate.X_FS.translation(), {0.5, -0.2, 0.1});
  // [0, 0, 0.7071, 0.7071] is normalised: a quarter turn about z, exactly.
  BOOST_CHECK(
      crate.X_FS.linear().isApprox(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix(), kExact));

  const SceneShape& ball = object(scene, "ball").shapes.at(0);
  BOOST_CHECK(ball.geometry.type == GeometryType::Sphere);
  BOOST_CHECK_CLOSE(ball.geometry.radius, 0.05, 1e-12);
  checkVector(ball.X_FS.translation(), {0.3, 0.3, 0.6});

  // The object pose (half a turn about x at [1, 0, 0.5]) comes first: X_FS = X_FO * X_OS.
  const SceneObject& can = object(scene, "can");
  BOOST_REQUIRE_EQUAL(can.shapes.size(), 2u);
  BOOST_CHECK(can.shapes[0].geometry.type == GeometryType::Cylinder);
  BOOST_CHECK_CLOSE(can.shapes[0].geometry.length, 0.12, 1e-12);
  BOOST_CHECK_CLOSE(can.shapes[0].geometry.radius, 0.03, 1e-12);
  checkVector(can.shapes[0].X_FS.translation(), {1, 0, 0.5});
  checkVector(can.shapes[1].X_FS.translation(), {1, 0, 0.39});
  checkVector(can.shapes[1].X_FS.linear() * Eigen::Vector3d::UnitZ(), {0, 0, -1});
  BOOST_CHECK(can.shapes[1].geometry.type == GeometryType::Mesh);
  BOOST_REQUIRE(can.shapes[1].mesh);
  BOOST_CHECK(can.shapes[1].geometry.meshPath.empty());
  BOOST_CHECK_EQUAL(can.shapes[1].line, 31);

  const SceneObject& wedge = object(scene, "wedge");
  BOOST_REQUIRE_EQUAL(wedge.shapes.size(), 2u);
  const std::string tetrahedron = fs::weakly_canonical(kTestData + "/moveit_scenes/meshes/tetrahedron.obj").string();
  for (const SceneShape& s : wedge.shapes) {
    BOOST_CHECK_EQUAL(s.geometry.meshPath, tetrahedron);  // relative and package:// resolve alike
  }
  checkVector(wedge.shapes[0].geometry.meshScale, {2, 2, 1});
  checkVector(wedge.shapes[1].geometry.meshScale, {1, 1, 1});
  checkVector(wedge.shapes[1].X_FS.translation(), {0, -0.5, 0});
  const TriangleMesh scaled = loadMesh(wedge.shapes[0].geometry.meshPath, wedge.shapes[0].geometry.meshScale);
  BOOST_CHECK_CLOSE(scaled.boundingBoxDiagonal(), std::sqrt(0.2 * 0.2 * 2 + 0.1 * 0.1), 1e-4);  // float OBJ
}

BOOST_AUTO_TEST_CASE(cone_pyramid_contains_the_cone_within_the_deviation) {
  const double height = 0.1;
  const double radius = 0.04;
  const double deviation = 1e-3;
  const TriangleMesh mesh = coneMesh(height, radius, deviation);
  const int sides = int(mesh.vertices.size()) - 1;
  BOOST_CHECK_EQUAL(sides, cylinderSides(radius, deviation));
  BOOST_CHECK_EQUAL(int(mesh.triangles.size()), 2 * sides - 2);
  checkVector(mesh.vertices.back(), {0, 0, height / 2});
  for (int k = 0; k < sides; ++k) {
    const Eigen::Vector3d& v = mesh.vertices[k];
    BOOST_CHECK_CLOSE(v.z(), -height / 2, 1e-12);
    const double out = v.head<2>().norm() - radius;  // how far the corner sticks out
    BOOST_CHECK(out > 0.0);
    BOOST_CHECK(out <= deviation);
  }
  // Every side's edge midpoint is tangent to the base circle: the pyramid contains the cone.
  for (int k = 0; k < sides; ++k) {
    const Eigen::Vector3d mid = 0.5 * (mesh.vertices[k] + mesh.vertices[(k + 1) % sides]);
    BOOST_CHECK_CLOSE(mid.head<2>().norm(), radius, 1e-9);
  }
  // Faces are counter-clockwise seen from outside: outward normals, so a positive volume.
  double volume = 0.0;
  for (const auto& t : mesh.triangles) {
    volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6.0;
  }
  const double apothemArea = sides * radius * radius * std::tan(M_PI / sides);
  BOOST_CHECK_CLOSE(volume, apothemArea * height / 3.0, 1e-9);
  checkThrows([] { coneMesh(0.0, 0.1, 1e-3); }, {"cone height 0"});
}

BOOST_AUTO_TEST_CASE(frame_aliases_parse_and_check_their_target) {
  const auto alias = parseFrameAlias("base_link=panda_link0");
  BOOST_CHECK_EQUAL(alias.first, "base_link");
  BOOST_CHECK_EQUAL(alias.second, "panda_link0");
  for (const char* bad : {"base_link", "=x", "x=", "a=b=c"}) {
    checkThrows([&] { parseFrameAlias(bad); }, {"must be NAME=LINK"});
  }
  LoadOptions armOptions;
  armOptions.packageRoots = {deepcheck::test::bundledDataDir()};
  armOptions.useRosPackagePath = false;
  const RobotModel arm = RobotModel::fromUrdfFile(
      deepcheck::test::bundledDataDir() + "/deepcheck_arm/urdf/deepcheck_arm.urdf", armOptions);
  const PlanningScene scene = loadPlanningScene(kAllShapes, testOptions());
  checkThrows(
      [&] {
        shapeWorldPoses(scene, arm, arm.defaultConfiguration(), {{"base_link", "nowhere"}});
      },
      {"object 'crate'", "aliased to 'nowhere'", "no link of robot"});
  // The bundled arm's root is called base_link: the file's frames are its links as written.
  const auto poses = shapeWorldPoses(scene, arm, arm.defaultConfiguration());
  BOOST_REQUIRE_EQUAL(poses.size(), 4u);
  BOOST_CHECK(poses[0][0].isApprox(scene.objects[0].shapes[0].X_FS, kExact));
  const PlanningScene table = parse(
      "world:\n  collision_objects:\n    - header: {frame_id: table_top}\n      id: cup\n"
      "      primitives: [{type: sphere, dimensions: [0.1]}]\n"
      "      primitive_poses: [{position: [0, 0, 0], " +
      kIdentity + "}]\n");
  checkThrows(
      [&] { shapeWorldPoses(table, arm, arm.defaultConfiguration()); },
      {"bad.yaml', line 3, object 'cup'", "unknown frame 'table_top'", "--frame-alias table_top=" + arm.link(0).name});
}

BOOST_AUTO_TEST_CASE(bad_files_name_file_line_and_object) {
  const std::string box = "      primitives:\n        - type: box\n          dimensions: [1, 1, 1]\n";
  const std::string pose = "      primitive_poses:\n        - position: [0, 0, 0]\n          " + kIdentity + "\n";
  checkThrows([&] { parse(oneObject(box)); }, {"bad.yaml', line 7, object 'thing'", "missing 'primitive_poses'"});
  checkThrows([&] { parse(oneObject(box + "      primitive_poses:\n        - position: [0, 0, 0]\n")); },
              {"line 10, object 'thing'", "missing 'orientation'"});
  checkThrows([&] { parse(oneObject("      primitives:\n        - type: torus\n          dimensions: [1]\n" + pose)); },
              {"line 7, object 'thing'", "unknown primitive type 'torus'"});
  checkThrows(
      [&] { parse(oneObject("      primitives:\n        - type: cylinder\n          dimensions: [1]\n" + pose)); },
      {"line 8, object 'thing'", "a cylinder needs 2 dimensions [height, radius], has 1"});
  checkThrows(
      [&] { parse(oneObject("      primitives:\n        - type: sphere\n          dimensions: [-0.1]\n" + pose)); },
      {"line 8, object 'thing'", "sphere radius must be positive, is -0.1"});
  checkThrows(
      [&] { parse(oneObject("      primitives:\n        - type: box\n          dimensions: [1, .nan, 1]\n" + pose)); },
      {"line 8, object 'thing'", "dimensions[1] must be finite, is '.nan'"});
  checkThrows(
      [&] {
        parse(
            oneObject(box + "      primitive_poses:\n        - position: [0, .inf, 0]\n          " + kIdentity + "\n"));
      },
      {"line 10, object 'thing'", "primitive_poses[0].position[1] must be finite"});
  checkThrows(
      [&] {
        parse(oneObject(
            box + "      primitive_poses:\n        - position: [0, 0, 0]\n          orientation: [0, 0, 1, 1]\n"));
      },
      {"line 11, object 'thing'", "has norm 1.41421", "not 1 (within 0.01)"});
  checkThrows(
      [&] {
        parse(oneObject(box + "      primitive_poses:\n        - position: [0, 0]\n          " + kIdentity + "\n"));
      },
      {"line 10", "position must have 3 numbers, has 2"});
  checkThrows(
      [&] {
        parse(
            oneObject("      meshes:\n        - resource: meshes/missing.stl\n      mesh_poses:\n        - position: "
                      "[0, 0, 0]\n          " +
                      kIdentity + "\n"));
      },
      {"line 7, object 'thing', mesh 0", "cannot find mesh 'meshes/missing.stl'", "missing.stl"});
  checkThrows(
      [&] {
        parse(
            oneObject("      meshes:\n        - resource: package://nopkg/a.stl\n      mesh_poses:\n        - "
                      "position: [0, 0, 0]\n          " +
                      kIdentity + "\n"));
      },
      {"object 'thing', mesh 0", "package 'nopkg'"});
}

BOOST_AUTO_TEST_CASE(bad_structure_is_reported) {
  checkThrows([] { parse("world: [unclosed\n"); }, {"bad.yaml', line 2", "malformed YAML"});
  checkThrows([] { parse(""); }, {"bad.yaml'", "expected a map with 'world'"});
  checkThrows([] { parse("wrld:\n  collision_objects: []\n"); }, {"line 1", "unknown key 'wrld'"});
  checkThrows([] { parse(oneObject("      primitive:\n        - type: box\n")); },
              {"line 6, object 'thing'", "unknown key 'primitive' in a collision object"});
  checkThrows([] { parse(oneObject("")); }, {"line 3, object 'thing'", "no primitives and no meshes"});
  checkThrows([] { parse("world:\n  collision_objects:\n    - id: a\n"); }, {"line 3, object 'a'", "missing 'header'"});
  checkThrows([] { parse("world:\n  collision_objects:\n    - header: {frame_id: x}\n"); },
              {"line 3, object 0", "missing 'id'"});
  const std::string sphere =
      "      primitives: [{type: sphere, dimensions: [1]}]\n"
      "      primitive_poses: [{position: [0, 0, 0], " +
      kIdentity + "}]\n";
  checkThrows([&] { parse(oneObject(sphere) + "    - header: {frame_id: a}\n      id: thing\n" + sphere); },
              {"line 8, object 'thing'", "used twice (first at line 3)"});
  checkThrows([&] { parse(oneObject(sphere + "      operation: remove\n")); },
              {"object 'thing'", "operation 'remove' is not supported"});
  checkThrows([&] { parse(oneObject(sphere + "      planes: [{coef: [0, 0, 1, 0]}]\n")); },
              {"object 'thing'", "'planes' is not supported"});
  checkThrows([] { parse("world:\n  octomap: {octomap: {id: x, data: [3]}}\n"); },
              {"octomap with data is not supported"});
  checkThrows(
      [] {
        parse(
            "fixed_frame_transforms:\n  - child_frame_id: a\n    transform: {translation: [1, 0, 0], rotation: [0, 0, "
            "0, 1]}\nworld: {}\n");
      },
      {"line 2", "fixed_frame_transforms[0] is not the identity"});
  checkThrows([] { loadPlanningScene("/nonexistent/scene.yaml"); },
              {"planning scene '/nonexistent/scene.yaml'", "cannot read"});
  BOOST_CHECK(parse("world:\n  collision_objects: []\n").objects.empty());
}

BOOST_AUTO_TEST_CASE(scene_urdf_becomes_objects_posed_at_its_joints) {
  const RobotModel scene = RobotModel::fromUrdfString(R"(<robot name="cupboard">
  <link name="root"/>
  <link name="body"><collision><origin xyz="0.5 0 1"/><geometry><box size="0.4 1 0.6"/></geometry></collision>
    <collision><origin xyz="0.5 0 0.6"/><geometry><box size="0.4 1 0.02"/></geometry></collision></link>
  <link name="door"><collision><origin xyz="0 -0.25 0"/><geometry><box size="0.02 0.5 0.6"/></geometry></collision></link>
  <link name="marker"/>
  <joint name="body_joint" type="fixed"><parent link="root"/><child link="body"/></joint>
  <joint name="door_joint" type="revolute"><origin xyz="0.3 0.5 1"/><parent link="body"/><child link="door"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="0" effort="1" velocity="1"/></joint>
  <joint name="marker_joint" type="fixed"><parent link="root"/><child link="marker"/></joint>
</robot>)",
                                                      "", {}, "cupboard.urdf");
  Eigen::VectorXd q(1);
  q << -M_PI / 2;
  const PlanningScene s = planningSceneFromUrdf(scene, q, "world");
  BOOST_TEST(s.source == "cupboard.urdf");
  // Links without collision geometry (root, marker) make no object.
  BOOST_REQUIRE_EQUAL(s.objects.size(), 2u);
  BOOST_TEST(s.objects[0].id == "body");
  BOOST_TEST(s.objects[0].frameId == "world");
  BOOST_TEST(s.objects[0].shapes.size() == 2u);
  BOOST_TEST(s.objects[0].X_FO.isApprox(Eigen::Isometry3d::Identity()));
  // The door turned by -90 degrees about z at its hinge: its centre, 0.25 m along -y of the
  // door, lies 0.25 m along -x of the hinge.
  const Eigen::Vector3d centre = s.objects[1].shapes[0].X_FS.translation();
  BOOST_TEST((centre - Eigen::Vector3d(0.05, 0.5, 1.0)).norm() < 1e-12, centre.transpose());
  BOOST_TEST(s.objects[1].shapes[0].X_FS.isApprox(forwardKinematics(scene, q)[scene.linkIndex("door")] *
                                                  scene.link(scene.linkIndex("door")).collisions[0].X_LG));
  checkThrows([&] { planningSceneFromUrdf(scene, Eigen::VectorXd::Zero(2), "world"); }, {"2 values"});
}

BOOST_AUTO_TEST_SUITE_END()

}  // namespace deepcheck::robots
