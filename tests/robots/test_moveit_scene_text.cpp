// MoveIt's .scene text format (moveit_scene.h: parseSceneText, writeSceneText): both versions of
// the format, the model frame, round trips and the errors on bad files.
#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/mesh_loader.h"
#include "deepcheck/robots/moveit_scene.h"

#include "robots_test_util.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

namespace deepcheck::robots {
namespace {

using test::checkThrows;

const std::string kScenes = std::string(DEEPCHECK_SOURCE_DIR) + "/tests/data/moveit_scenes";
constexpr double kExact = 1e-12;  // values copied from the file, up to round-off
/// A pose written with 17 digits and read back, X_FS = X_FO * (X_FO^-1 * X_FS): a few ulps.
constexpr double kRoundTrip = 1e-14;

PlanningScene parse(const std::string& text) { return parseSceneText(text, {}, "bad.scene"); }

/// A scene of the newer format with one object "thing" whose shape block (after the count) is
/// `shape`, pose and colour included.
std::string oneShape(const std::string& shape) { return "s\n* thing\n0 0 0\n0 0 0 1\n1\n" + shape + "0\n.\n"; }

const std::string kPoseAndColour = "0 0 0\n0 0 0 1\n0 0 0 0\n";

void checkClose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double tolerance) {
  BOOST_CHECK_MESSAGE((a.matrix() - b.matrix()).cwiseAbs().maxCoeff() <= tolerance, "poses differ:\n"
                                                                                        << a.matrix() << "\nand\n"
                                                                                        << b.matrix());
}

/// Same ids, frames, shapes (sizes, in-memory meshes exactly) and poses (within kRoundTrip).
void checkSame(const PlanningScene& a, const PlanningScene& b) {
  BOOST_CHECK_EQUAL(a.name, b.name);
  BOOST_REQUIRE_EQUAL(a.objects.size(), b.objects.size());
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    const SceneObject& x = a.objects[i];
    const SceneObject& y = b.objects[i];
    BOOST_CHECK_EQUAL(x.id, y.id);
    BOOST_CHECK_EQUAL(x.frameId, y.frameId);
    checkClose(x.X_FO, y.X_FO, kRoundTrip);
    BOOST_REQUIRE_EQUAL(x.shapes.size(), y.shapes.size());
    for (std::size_t k = 0; k < x.shapes.size(); ++k) {
      const SceneShape& s = x.shapes[k];
      const SceneShape& t = y.shapes[k];
      BOOST_CHECK(s.geometry.type == t.geometry.type);
      BOOST_CHECK_EQUAL(s.geometry.boxSize.transpose(), t.geometry.boxSize.transpose());
      BOOST_CHECK_EQUAL(s.geometry.radius, t.geometry.radius);
      BOOST_CHECK_EQUAL(s.geometry.length, t.geometry.length);
      BOOST_REQUIRE_EQUAL(bool(s.mesh), bool(t.mesh));
      if (s.mesh) {
        BOOST_CHECK(s.mesh->vertices == t.mesh->vertices);
        BOOST_CHECK(s.mesh->triangles == t.mesh->triangles);
      }
      checkClose(s.X_FS, t.X_FS, kRoundTrip);
    }
  }
}

void checkRoundTrip(const PlanningScene& scene) {
  checkSame(scene, parseSceneText(writeSceneText(scene), {}, "written.scene"));
}

Eigen::Isometry3d pose(const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = p;
  X.linear() = q.normalized().toRotationMatrix();
  return X;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(robots_moveit_scene_text)

BOOST_AUTO_TEST_CASE(newer_format_has_object_poses_and_subframes) {
  const PlanningScene scene = loadPlanningScene(kScenes + "/bench.scene");
  BOOST_CHECK_EQUAL(scene.name, "bench");
  BOOST_REQUIRE_EQUAL(scene.objects.size(), 3u);
  const SceneObject& table = scene.objects[0];
  BOOST_CHECK_EQUAL(table.id, "table");
  BOOST_CHECK_EQUAL(table.frameId, kModelFrame);
  BOOST_CHECK_EQUAL(table.line, 2);
  BOOST_REQUIRE_EQUAL(table.shapes.size(), 1u);
  BOOST_CHECK(table.shapes[0].geometry.type == GeometryType::Box);
  BOOST_CHECK_SMALL((table.shapes[0].geometry.boxSize - Eigen::Vector3d(0.6, 1, 0.1)).norm(), kExact);
  checkClose(table.shapes[0].X_FS, pose({0.55, 0, -0.05}, Eigen::Quaterniond::Identity()), kExact);

  // Cylinder and cone dimensions are radius then length; the subframe after them is skipped.
  const SceneObject& post = scene.objects[1];
  BOOST_REQUIRE_EQUAL(post.shapes.size(), 2u);
  BOOST_CHECK(post.shapes[0].geometry.type == GeometryType::Cylinder);
  BOOST_CHECK_CLOSE(post.shapes[0].geometry.radius, 0.04, 1e-10);
  BOOST_CHECK_CLOSE(post.shapes[0].geometry.length, 0.5, 1e-10);
  BOOST_REQUIRE(post.shapes[1].mesh);
  BOOST_CHECK(post.shapes[1].geometry.type == GeometryType::Mesh);
  BOOST_CHECK(post.shapes[1].geometry.meshPath.empty());
  const TriangleMesh expectedCone = coneMesh(0.1, 0.04, SceneLoadOptions{}.coneMaxDeviation);
  BOOST_CHECK(post.shapes[1].mesh->vertices == expectedCone.vertices);
  checkClose(post.shapes[1].X_FS, pose({0.5, 0.35, 0.55}, Eigen::Quaterniond::Identity()), kExact);

  // An id is the rest of its line; a mesh is in memory, posed by object pose and shape pose.
  const SceneObject& wedge = scene.objects[2];
  BOOST_CHECK_EQUAL(wedge.id, "corner wedge");
  BOOST_REQUIRE(wedge.shapes.at(0).mesh);
  BOOST_CHECK_EQUAL(wedge.shapes[0].mesh->vertices.size(), 4u);
  BOOST_CHECK_EQUAL(wedge.shapes[0].mesh->triangles.size(), 4u);
  BOOST_CHECK_EQUAL(wedge.shapes[0].name, "shape 0 (mesh, 4 vertices, 4 triangles)");
  checkClose(wedge.X_FO, pose({0, -0.4, 0.2}, Eigen::Quaterniond(0.707107, 0, 0, 0.707107)), kExact);
  checkClose(wedge.shapes[0].X_FS, wedge.X_FO, kExact);
}

BOOST_AUTO_TEST_CASE(older_format_has_shapes_in_the_model_frame) {
  const PlanningScene scene = loadPlanningScene(kScenes + "/old_format.scene");
  BOOST_CHECK_EQUAL(scene.name, "(noname)+");
  BOOST_REQUIRE_EQUAL(scene.objects.size(), 2u);
  BOOST_CHECK(scene.objects[0].X_FO.isApprox(Eigen::Isometry3d::Identity(), 0.0));
  checkClose(scene.objects[0].shapes.at(0).X_FS, pose({0.6, 0, 0.1}, Eigen::Quaterniond::Identity()), kExact);
  const SceneShape& ball = scene.objects[1].shapes.at(0);
  BOOST_CHECK(ball.geometry.type == GeometryType::Sphere);
  BOOST_CHECK_CLOSE(ball.geometry.radius, 0.05, 1e-10);
  const Eigen::Quaterniond eighthTurn(Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ()));
  checkClose(ball.X_FS, pose({0.3, 0.3, 0.6}, eighthTurn), kExact);
  // The extension picks the format in any case.
  test::TempDir dir;
  const std::string upper = dir.write("OLD.SCENE", writeSceneText(scene));
  BOOST_CHECK_EQUAL(loadPlanningScene(upper).objects.size(), 2u);
  BOOST_CHECK(isSceneTextFile("a/b.Scene"));
  BOOST_CHECK(!isSceneTextFile("a.scene/b.yaml"));
  BOOST_CHECK(!isSceneTextFile("scene"));
}

BOOST_AUTO_TEST_CASE(model_frame_is_the_robot_root) {
  RobotModel arm = test::loadBundledArm();
  Eigen::Isometry3d X_WR =
      pose({0.1, -0.2, 0.3}, Eigen::Quaterniond(Eigen::AngleAxisd(1.0 / 3.0, Eigen::Vector3d::UnitZ())));
  arm.setBasePose(X_WR);
  const PlanningScene scene = loadPlanningScene(kScenes + "/bench.scene");
  const auto poses = shapeWorldPoses(scene, arm, arm.defaultConfiguration());
  checkClose(poses.at(0).at(0), X_WR * scene.objects[0].shapes[0].X_FS, kExact);
  // An alias of the model frame wins over the root.
  const auto aliased = shapeWorldPoses(scene, arm, arm.defaultConfiguration(), {{kModelFrame, "link1"}});
  const std::vector<Eigen::Isometry3d> X_WL = forwardKinematics(arm, arm.defaultConfiguration());
  checkClose(aliased.at(0).at(0), X_WL[arm.linkIndex("link1")] * scene.objects[0].shapes[0].X_FS, kExact);
}

BOOST_AUTO_TEST_CASE(scenes_round_trip_through_the_writer) {
  checkRoundTrip(loadPlanningScene(kScenes + "/bench.scene"));
  checkRoundTrip(loadPlanningScene(kScenes + "/old_format.scene"));
  checkRoundTrip(PlanningScene{});
  // A written scene is read as the newer format even when it has one object without rotation.
  const std::string written = writeSceneText(loadPlanningScene(kScenes + "/old_format.scene"));
  BOOST_CHECK(written.find("* crate\n0 0 0\n0 0 0 1\n1\nbox\n") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(mesh_files_are_written_inline) {
  // The YAML scene's wedge (two tetrahedron.obj meshes, one scaled), moved to the model frame.
  SceneLoadOptions options;
  options.packageRoots = {std::string(DEEPCHECK_SOURCE_DIR) + "/tests/data"};
  options.useRosPackagePath = false;
  PlanningScene yaml = loadPlanningScene(kScenes + "/all_shapes.yaml", options);
  checkThrows([&] { writeSceneText(yaml); }, {"object 'crate' is in frame 'base_link'", "no frames"});
  for (SceneObject& o : yaml.objects) o.frameId = kModelFrame;
  const PlanningScene back = parseSceneText(writeSceneText(yaml), {}, "written.scene");
  const SceneObject& wedge = back.objects.at(static_cast<std::size_t>(back.objectIndex("wedge")));
  const SceneShape& original = yaml.objects[static_cast<std::size_t>(yaml.objectIndex("wedge"))].shapes.at(0);
  const TriangleMesh expected = loadMesh(original.geometry.meshPath, original.geometry.meshScale);
  BOOST_REQUIRE(wedge.shapes.at(0).mesh);
  BOOST_CHECK(wedge.shapes[0].mesh->vertices == expected.vertices);
  BOOST_CHECK(wedge.shapes[0].mesh->triangles == expected.triangles);
  checkClose(wedge.shapes[0].X_FS, original.X_FS, kRoundTrip);
}

BOOST_AUTO_TEST_CASE(what_a_scene_file_cannot_hold_is_refused) {
  PlanningScene scene = loadPlanningScene(kScenes + "/old_format.scene");
  PlanningScene attached = scene;
  attached.attached.push_back({"hand", scene.objects[0], {}, 0});
  checkThrows([&] { writeSceneText(attached); }, {"attached object 'crate'", "no attached objects"});
  PlanningScene allowed = scene;
  allowed.allowed.always = {"crate"};
  checkThrows([&] { writeSceneText(allowed); }, {"no allowed collisions"});
  scene.objects[0].id = "two\nlines";
  checkThrows([&] { writeSceneText(scene); }, {"no line breaks"});
}

BOOST_AUTO_TEST_CASE(bad_files_name_file_line_and_object) {
  const std::string box = "box\n1 1 1\n" + kPoseAndColour;
  BOOST_CHECK_EQUAL(parse(oneShape(box)).objects.size(), 1u);
  checkThrows([&] { parse("s\n* a\n1\n" + box); }, {"bad.scene', line 8", "the file ends where"});
  checkThrows([&] { parse("s\n+ a\n.\n"); }, {"bad.scene', line 2", "unknown marker '+'"});
  checkThrows([&] { parse("s\n*\n1\n" + box + ".\n"); }, {"line 2", "the object's id is empty"});
  checkThrows([&] { parse("s\n* a\n1\n" + box + "* a\n1\n" + box + ".\n"); },
              {"line 9, object 'a'", "the id is used twice (first at line 2)"});
  checkThrows([&] { parse(oneShape("box\n1 -1 1\n" + kPoseAndColour)); },
              {"line 7, object 'thing'", "box size y must be positive, is -1"});
  checkThrows([&] { parse(oneShape("box\n1 nan 1\n" + kPoseAndColour)); }, {"line 7", "box size y must be finite"});
  checkThrows([&] { parse(oneShape("box\n1 1e60 1\n" + kPoseAndColour)); }, {"line 7", "magnitude at most"});
  checkThrows([&] { parse(oneShape("box\n1 one 1\n" + kPoseAndColour)); }, {"line 7", "must be a number, is 'one'"});
  checkThrows([&] { parse(oneShape("plane\n0 0 1 0\n" + kPoseAndColour)); }, {"line 6, object 'thing'", "plane"});
  checkThrows([&] { parse(oneShape("torus\n1 1\n" + kPoseAndColour)); }, {"line 6", "unknown shape type 'torus'"});
  checkThrows([&] { parse(oneShape("sphere\n1\n0 0 0\n0 0 1 1\n0 0 0 0\n")); },
              {"line 9, object 'thing'", "has norm 1.41421"});
  checkThrows([&] { parse("s\n* thing\n0 0 0\n0 0 0 1\n0\n0\n.\n"); }, {"line 2", "the object has no shapes"});
  checkThrows([&] { parse(oneShape("mesh\n400 1\n0 0 0\n")); },
              {"line 7, object 'thing'", "the mesh's vertex count is 400, more than"});
  checkThrows([&] { parse(oneShape("mesh\n3 1\n0 0 0\n1 0 0\n0 1 0\n0 1 3\n" + kPoseAndColour)); },
              {"line 11", "mesh triangle 0 index 2 is 3, more than 2"});
  checkThrows([&] { parse(oneShape("mesh\n3 0\n0 0 0\n1 0 0\n0 1 0\n" + kPoseAndColour)); },
              {"line 7", "a mesh needs 3 vertices and a triangle or more"});
  checkThrows([&] { parse(oneShape("mesh\n-3 1\n")); }, {"line 7", "must be a count"});
  SceneLoadOptions fewShapes;
  fewShapes.maxShapes = 1;
  checkThrows([&] { parseSceneText("s\n* a\n1\n" + box + "* b\n1\n" + box + ".\n", fewShapes, "many.scene"); },
              {"many.scene', line 10, object 'b'", "the shape count is 1, more than 0"});
  checkThrows([] { loadPlanningScene("/nonexistent/x.scene"); }, {"'/nonexistent/x.scene'", "cannot read"});
}

BOOST_AUTO_TEST_SUITE_END()

}  // namespace deepcheck::robots
