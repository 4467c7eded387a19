// World basics on small worlds with known answers: a cube on a slider against boxes and spheres,
// obstacles added, moved and removed, names, summary, and input errors.

#include "checker_test_util.h"

#include "deepcheck/checker/world.h"

#include <boost/test/unit_test.hpp>

#include <cmath>

using namespace deepcheck;
using namespace deepcheck::checker;
using namespace deepcheck::checker::test;

namespace {

/// Distances are computed by GJK / DEEP on exact boxes: round-off only.
constexpr double kExact = 1e-9;

Eigen::VectorXd at(double x) {
  Eigen::VectorXd q(1);
  q[0] = x;
  return q;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_world)

// A cube of edge 1/3 on the slider (centre at x = q) and a box of size 0.5 x 1 x 1 centred at
// x = 1: the faces are at q + 1/6 and 0.75, so sd = 0.75 - 1/6 - q = 7/12 - q, for both signs
// (while the penetration is shallower than along y or z), and d sd / dq = -1.
BOOST_AUTO_TEST_CASE(cube_against_box_known_distance) {
  World world(sliderRobot(1.0 / 3.0), testWorldOptions());
  world.addObstacle(Obstacle::box("wall", Eigen::Vector3d(0.5, 1.0, 1.0), translation(1.0, 0.0, 0.0)));
  auto context = world.makeContext();
  DistanceOptions options;
  options.gradient = true;
  for (double x : {-1.0, 0.0, 0.5, 7.0 / 12.0 - 0.01, 7.0 / 12.0 + 0.01, 0.7, 0.8}) {
    const DistanceResult r = world.signedDistance(at(x), context, options);
    BOOST_TEST_REQUIRE(r.found);
    BOOST_TEST(std::abs(r.closest.distance - (7.0 / 12.0 - x)) < kExact, "x " << x << " sd " << r.closest.distance);
    BOOST_TEST(r.closest.nameA == "cube");
    BOOST_TEST(r.closest.nameB == "obstacle/wall");
    BOOST_TEST((r.closest.normal - Eigen::Vector3d::UnitX()).norm() < 1e-9);
    BOOST_TEST((r.closest.pointB - r.closest.pointA - r.closest.distance * r.closest.normal).norm() < kExact);
    BOOST_TEST_REQUIRE(r.closest.gradient.size() == 1);
    BOOST_TEST(std::abs(r.closest.gradient[0] + 1.0) < 1e-9);
    BOOST_TEST(world.isFree(at(x), context) == (x < 7.0 / 12.0));
  }
}

BOOST_AUTO_TEST_CASE(cube_against_sphere_and_cylinder) {
  World world(sliderRobot(0.4), testWorldOptions());
  // A sphere of radius 1/3 at (1, 0, 0): sd = 1 - 1/3 - 0.2 - q.
  world.addObstacle(Obstacle::sphere("ball", 1.0 / 3.0, translation(1.0, 0.0, 0.0)));
  // A cylinder along z at x = -1, radius 0.3: its prism contains it and touches it along the
  // tangent line facing +x only if a side faces +x; the distance is within the 1 mm deviation.
  world.addObstacle(Obstacle::cylinder("post", 0.3, 1.0, translation(-1.0, 0.0, 0.0)));
  const double sdBall = 1.0 - 1.0 / 3.0 - 0.2;
  DistanceResult r = world.signedDistance(at(0.1));
  BOOST_TEST(std::abs(r.closest.distance - (sdBall - 0.1)) < kExact);
  BOOST_TEST(r.closest.nameB == "obstacle/ball");
  r = world.signedDistance(at(-0.3));
  BOOST_TEST(r.closest.nameB == "obstacle/post");
  const double sdPost = (-0.3 - 0.2) - (-1.0 + 0.3);  // = 0.2 for the true cylinder
  BOOST_TEST(r.closest.distance <= sdPost + kExact);
  BOOST_TEST(r.closest.distance >= sdPost - 1e-3 - kExact);
}

BOOST_AUTO_TEST_CASE(add_move_remove_obstacles) {
  World world(sliderRobot(0.2), testWorldOptions());
  auto context = world.makeContext();
  BOOST_TEST(world.isFree(at(0.0), context));
  DistanceResult r = world.signedDistance(at(0.0), context);
  BOOST_TEST(!r.found);  // no pair at all
  const int a = world.addObstacle(Obstacle::box("a", Eigen::Vector3d(0.2, 0.2, 0.2), translation(0.5, 0, 0)));
  const int b = world.addObstacle(Obstacle::sphere("b", 0.1, translation(0, 0.6, 0)));
  BOOST_TEST(a != b);
  BOOST_TEST((world.obstacleIds() == std::vector<int>{a, b}));
  BOOST_TEST(!world.isFree(at(0.35), context));
  BOOST_TEST(world.isFree(at(0.0), context));
  r = world.signedDistance(at(0.0), context);
  BOOST_TEST(std::abs(r.closest.distance - 0.3) < kExact);  // box a: 0.4 - 0.1; ball b: 0.6 - 0.1 - 0.1 = 0.4
  BOOST_TEST(r.closest.nameB == "obstacle/a");
  // Move a away: b is the nearest now.
  world.setObstaclePose(a, translation(3.0, 0, 0));
  r = world.signedDistance(at(0.0), context);
  BOOST_TEST(std::abs(r.closest.distance - 0.4) < kExact);
  BOOST_TEST(r.closest.nameB == "obstacle/b");
  BOOST_TEST(world.isFree(at(0.35), context));
  BOOST_TEST(!world.isFree(at(2.85), context));
  // Remove b: the ball no longer counts, the box does.
  world.removeObstacle(b);
  BOOST_TEST((world.obstacleIds() == std::vector<int>{a}));
  r = world.signedDistance(at(0.0), context);
  BOOST_TEST(std::abs(r.closest.distance - 2.8) < kExact);
  // Ids are never reused; unknown ids are errors naming the id.
  const int c = world.addObstacle(Obstacle::sphere("c", 0.1, translation(0, -1, 0)));
  BOOST_TEST(c != b);
  checkThrowsWith([&] { world.removeObstacle(b); }, std::to_string(b));
  checkThrowsWith([&] { world.setObstaclePose(12345, Eigen::Isometry3d::Identity()); }, "12345");
  // The same answers from a fresh context (no warm start) and from the thread's own context.
  auto fresh = world.makeContext();
  BOOST_TEST(world.signedDistance(at(0.0), fresh).closest.distance == world.signedDistance(at(0.0)).closest.distance);
}

BOOST_AUTO_TEST_CASE(mesh_obstacle_in_memory) {
  // A tetrahedron as a mesh obstacle; its single convex piece is itself.
  World world(sliderRobot(0.2), testWorldOptions());
  world.addObstacle(Obstacle::fromMesh("tetra", tetrahedronMesh(), translation(0.5, -0.1, -0.1)));
  // The tetrahedron's face x = 0.5 (its vertex plane) faces the cube's face x = q + 0.1.
  const DistanceResult r = world.signedDistance(at(0.0));
  BOOST_TEST(std::abs(r.closest.distance - 0.4) < kExact);
  BOOST_TEST(r.closest.nameB == "obstacle/tetra");
}

BOOST_AUTO_TEST_CASE(contact_list_within_margin) {
  World world(sliderRobot(0.2), testWorldOptions());
  world.addObstacle(Obstacle::box("near", Eigen::Vector3d(0.2, 0.2, 0.2), translation(0.5, 0, 0)));  // sd 0.3
  world.addObstacle(Obstacle::box("mid", Eigen::Vector3d(0.2, 0.2, 0.2), translation(0, 0.65, 0)));  // sd 0.45
  world.addObstacle(Obstacle::box("far", Eigen::Vector3d(0.2, 0.2, 0.2), translation(0, -1.5, 0)));  // sd 1.3
  DistanceOptions options;
  options.contactMargin = 0.5;
  const DistanceResult r = world.signedDistance(at(0.0), options);
  BOOST_TEST_REQUIRE(r.contacts.size() == 2u);
  BOOST_TEST(r.contacts[0].nameB == "obstacle/near");
  BOOST_TEST(r.contacts[1].nameB == "obstacle/mid");
  BOOST_TEST(std::abs(r.contacts[0].distance - 0.3) < kExact);
  BOOST_TEST(std::abs(r.contacts[1].distance - 0.45) < kExact);
  BOOST_TEST(r.closest.nameB == "obstacle/near");
  // maxDistance: nothing within 0.2.
  DistanceOptions limited;
  limited.maxDistance = 0.2;
  BOOST_TEST(!world.signedDistance(at(0.0), limited).found);
}

BOOST_AUTO_TEST_CASE(scene_links_are_named_scene_slash_link) {
  const std::string sceneXml =
      "<robot name='room'><link name='floor'><collision><origin xyz='0 0 -0.5'/><geometry>"
      "<box size='4 4 0.2'/></geometry></collision></link>"
      "<link name='shelf'><collision><geometry><box size='0.2 0.2 0.2'/></geometry></collision></link>"
      "<joint name='shelf_slide' type='prismatic'><parent link='floor'/><child link='shelf'/>"
      "<axis xyz='1 0 0'/><limit lower='0' upper='2' effort='1' velocity='1'/></joint></robot>";
  World world(sliderRobot(0.2), testWorldOptions());
  SceneSpec placement;
  placement.q = Eigen::VectorXd::Constant(1, 0.6);  // the shelf at x = 0.6
  world.addScene(robots::RobotModel::fromUrdfString(sceneXml, ".", {}, "room.urdf"), placement);
  const DistanceResult r = world.signedDistance(at(0.0));
  BOOST_TEST(r.closest.nameB == "scene/floor");  // floor top at -0.4, cube bottom at -0.1: 0.3
  BOOST_TEST(std::abs(r.closest.distance - 0.3) < kExact);
  BOOST_TEST((r.closest.bodyB.kind == BodyRef::Kind::SceneLink));
  BOOST_TEST(world.bodyName(r.closest.bodyB) == "scene/floor");
  BOOST_TEST(!world.isFree(at(0.45)));  // the shelf at 0.6, edge 0.2: faces at 0.5 and q + 0.1
  BOOST_TEST(world.isFree(at(0.35)));
  // A scene configuration of the wrong size is an error naming the scene.
  SceneSpec bad;
  bad.q = Eigen::VectorXd::Zero(3);
  checkThrowsWith([&] { world.addScene(robots::RobotModel::fromUrdfString(sceneXml, ".", {}, "room.urdf"), bad); },
                  "room");
}

BOOST_AUTO_TEST_CASE(summary_counts_and_text) {
  World world(armRobot(), testWorldOptions());
  world.addObstacle(Obstacle::box("table", Eigen::Vector3d(1, 1, 0.1), translation(0.6, 0, 0.3)));
  const World::Summary s = world.summaryCounts();
  BOOST_TEST(s.robotLinks == 6);
  BOOST_TEST(s.robotLinksWithGeometry == 5);  // the elbow has none
  BOOST_TEST(s.robotPieces == 5);
  BOOST_TEST(s.obstacles == 1);
  BOOST_TEST(s.obstaclePieces == 1);
  const std::string text = world.summary();
  for (const char* word :
       {"robot 'arm'", "6 links", "5 with geometry", "5 pieces", "self pairs", "kept", "dropped", "obstacles: 1"}) {
    BOOST_TEST(text.find(word) != std::string::npos, "summary lacks '" << word << "':\n" << text);
  }
}

BOOST_AUTO_TEST_CASE(bad_input_is_rejected_with_a_message) {
  World world(armRobot(), testWorldOptions());
  checkThrowsWith([&] { world.isFree(Eigen::VectorXd::Zero(2)); }, "2");
  Eigen::VectorXd q = Eigen::VectorXd::Zero(3);
  q[1] = std::nan("");
  checkThrowsWith([&] { world.isFree(q); }, "j2");
  checkThrowsWith([&] { world.signedDistance(q); }, "j2");
  checkThrowsWith(
      [&] { world.addObstacle(Obstacle::box("flat", Eigen::Vector3d(1, 0, 1), Eigen::Isometry3d::Identity())); },
      "flat");
  checkThrowsWith([&] { world.addObstacle(Obstacle::sphere("neg", -1.0, Eigen::Isometry3d::Identity())); }, "neg");
  checkThrowsWith([&] { world.addObstacle(Obstacle::sphere("", 1.0, Eigen::Isometry3d::Identity())); }, "name");
  Eigen::Isometry3d skew = Eigen::Isometry3d::Identity();
  skew.linear()(0, 1) = 0.5;
  checkThrowsWith([&] { world.addObstacle(Obstacle::sphere("skewed", 0.1, skew)); }, "skewed");
  Eigen::Isometry3d mirrored = Eigen::Isometry3d::Identity();
  mirrored.linear()(2, 2) = -1.0;
  checkThrowsWith([&] { world.addObstacle(Obstacle::sphere("mirrored", 0.1, mirrored)); }, "mirrored");
  checkThrowsWith([&] { world.addObstacle(Obstacle::sphere("lost", 0.1, translation(0, std::nan(""), 0))); }, "lost");
  const int kept = world.addObstacle(Obstacle::sphere("kept", 0.1, translation(0, 1, 0)));
  checkThrowsWith([&] { world.setObstaclePose(kept, skew); }, "kept");
  BOOST_TEST(world.obstacle(kept).X_WO.isApprox(translation(0, 1, 0)));  // unchanged
  checkThrowsWith(
      [&] { world.addObstacle(Obstacle::meshFile("missing", "no/such/file.stl", Eigen::Isometry3d::Identity())); },
      "missing");
  checkThrowsWith([&] { world.disablePair("link1", "no_such_link"); }, "no_such_link");
  WorldOptions badOptions = testWorldOptions();
  badOptions.disabledPairs = {{"base", "nope", robots::DisableReason::User}};
  checkThrowsWith([&] { World w(armRobot(), badOptions); }, "nope");
  // A context of another world.
  World other(armRobot(), testWorldOptions());
  auto foreign = other.makeContext();
  checkThrowsWith([&] { world.isFree(Eigen::VectorXd::Zero(3), foreign); }, "another world");
}

BOOST_AUTO_TEST_SUITE_END()
