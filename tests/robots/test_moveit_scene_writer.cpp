// writePlanningScene: what it writes, loadPlanningScene reads back to the same objects.

#include "robots_test_util.h"

#include "deepcheck/robots/moveit_scene.h"

#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <string>

namespace deepcheck::robots {
namespace {

const std::string kTestData = std::string(DEEPCHECK_SOURCE_DIR) + "/tests/data/moveit_scenes";
/// A pose written with 17 digits and read back: the rotation goes through a quaternion.
constexpr double kRoundTrip = 1e-15;

/// Same ids, frames, shapes, sizes and poses (exactly: 17 digits are written).
void checkSame(const PlanningScene& a, const PlanningScene& b) {
  BOOST_REQUIRE_EQUAL(a.objects.size(), b.objects.size());
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    const SceneObject& x = a.objects[i];
    const SceneObject& y = b.objects[i];
    BOOST_CHECK_EQUAL(x.id, y.id);
    BOOST_CHECK_EQUAL(x.frameId, y.frameId);
    BOOST_REQUIRE_EQUAL(x.shapes.size(), y.shapes.size());
    for (std::size_t k = 0; k < x.shapes.size(); ++k) {
      const Geometry& g = x.shapes[k].geometry;
      const Geometry& h = y.shapes[k].geometry;
      BOOST_CHECK(g.type == h.type);
      BOOST_CHECK_EQUAL(g.boxSize.transpose(), h.boxSize.transpose());
      BOOST_CHECK_EQUAL(g.radius, h.radius);
      BOOST_CHECK_EQUAL(g.length, h.length);
      BOOST_CHECK_EQUAL(g.meshPath, h.meshPath);
      BOOST_CHECK_EQUAL(g.meshScale.transpose(), h.meshScale.transpose());
      BOOST_CHECK_SMALL((x.shapes[k].X_FS.matrix() - y.shapes[k].X_FS.matrix()).cwiseAbs().maxCoeff(), kRoundTrip);
    }
  }
}

void checkRoundTrip(const PlanningScene& scene) {
  checkSame(scene, parsePlanningScene(writePlanningScene(scene), "/", {}, "written.yaml"));
}

}  // namespace

BOOST_AUTO_TEST_SUITE(robots_moveit_scene_writer)

BOOST_AUTO_TEST_CASE(hand_written_scene_round_trips) {
  checkRoundTrip(loadPlanningScene(kTestData + "/slider_wall.yaml"));
  // A mesh given by a relative path is written with its resolved path; an object pose is folded
  // into the shape poses.
  checkRoundTrip(parsePlanningScene(
      "world:\n  collision_objects:\n"
      "    - header: {frame_id: base_link}\n      id: \"odd \\\"name\\\"\"\n"
      "      pose: {position: [1, 2, 3], orientation: [0, 0, 0.3826834323650898, 0.9238795325112867]}\n"
      "      meshes: [{resource: meshes/tetrahedron.obj, scale: [1, 2, 0.5]}]\n"
      "      mesh_poses: [{position: [0.1, 0, 0], orientation: [0, 0, 0, 1]}]\n",
      kTestData, {}, "mesh.yaml"));
  checkRoundTrip(PlanningScene{});
}

BOOST_AUTO_TEST_CASE(cones_are_written_as_their_pyramid) {
  const PlanningScene cone = parsePlanningScene(
      "world:\n  collision_objects:\n"
      "    - header: {frame_id: base_link}\n      id: tip\n"
      "      primitives: [{type: cone, dimensions: [0.2, 0.05]}]\n"
      "      primitive_poses: [{position: [0, 0, 0.3], orientation: [0, 0, 0, 1]}]\n",
      kTestData, {}, "cone.yaml");
  const PlanningScene back = parsePlanningScene(writePlanningScene(cone), "/", {}, "written.yaml");
  const SceneShape& pyramid = back.objects.at(0).shapes.at(0);
  BOOST_REQUIRE(pyramid.mesh);
  BOOST_CHECK(pyramid.mesh->vertices == cone.objects[0].shapes[0].mesh->vertices);
  BOOST_CHECK(pyramid.mesh->triangles == cone.objects[0].shapes[0].mesh->triangles);
  BOOST_CHECK_SMALL((pyramid.X_FS.matrix() - cone.objects[0].shapes[0].X_FS.matrix()).cwiseAbs().maxCoeff(),
                    kRoundTrip);
}

BOOST_AUTO_TEST_CASE(motion_bench_maker_scenes_round_trip) {
  if (!test::haveShared("round trip of the MotionBenchMaker scenes")) return;
  const std::string dir = test::sharedDir() + "/scenes/motion_bench_maker/configs/scenes/";
  for (const char* name : {"bookshelf/scene_small.yaml", "bookshelf/scene_tall.yaml", "box/scene_box.yaml",
                           "cage/scene_cage.yaml", "table/scene_table.yaml"}) {
    BOOST_TEST_CONTEXT(name) { checkRoundTrip(loadPlanningScene(dir + name)); }
  }
}

BOOST_AUTO_TEST_SUITE_END()

}  // namespace deepcheck::robots
