// Objects attached to robot links (World::attach, attachObstacle, detach; world.h): they move
// with their link in every query, are checked against the world and the robot's other links but
// not their own link and touch links, detach back to obstacles, come from planning scenes, and
// show in the HTML view.

#include "checker_test_util.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/moveit_scene.h"
#include "deepcheck/viewer/html_view.h"

#include <boost/test/unit_test.hpp>

#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace deepcheck::checker {
namespace {

using test::translation;

/// Accuracy of a distance between a sphere and a box found by the narrow phase (metres).
constexpr double kDistanceAccuracy = 1e-7;
/// Poses composed of the same transforms in another order (round-off only).
constexpr double kPoseExact = 1e-12;
/// Central-difference step (rad) and the agreement asked of the gradient with it.
constexpr double kGradientStep = 1e-6;
constexpr double kGradientAgreement = 1e-4;

World quietArm() {
  WorldOptions options = test::testWorldOptions();
  options.progress = nullptr;
  return World(test::armRobot(), options);
}

/// A box pose in the tool's frame that is not axis-aligned.
Eigen::Isometry3d boxInTool() {
  Eigen::Isometry3d X_LO = translation(0.0, 0.0, 0.1);
  X_LO.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  return X_LO;
}

/// The contact of bodies a and b in `contacts`; fails when absent.
Contact contactOf(const std::vector<Contact>& contacts, const std::string& a, const std::string& b) {
  for (const Contact& c : contacts) {
    if (c.nameA == a && c.nameB == b) return c;
  }
  BOOST_FAIL("no contact between " << a << " and " << b);
  return {};
}

DistanceResult withContacts(const World& world, const Eigen::VectorXd& q, bool gradient = false) {
  DistanceOptions options;
  options.contactMargin = 10.0;  // every pair of the arm's reach
  options.gradient = gradient;
  return world.signedDistance(q, options);
}

BOOST_AUTO_TEST_SUITE(checker_attached)

// A probe sphere placed on the box's x axis at a known gap from its face, by the forward
// kinematics of the tool: the attached box is where its link puts it, at every configuration.
BOOST_AUTO_TEST_CASE(moves_with_its_link) {
  World world = quietArm();
  const Eigen::Vector3d size(0.1, 0.06, 0.04);
  world.attach("tool", Obstacle::box("box", size, boxInTool()));
  const double radius = 0.02, gap = 0.07;
  const int probe = world.addObstacle(Obstacle::sphere("probe", radius, translation(5, 0, 0)));
  const int tool = world.robot().linkIndex("tool");
  std::mt19937 rng(11);
  for (const Eigen::VectorXd& q : test::randomConfigurations(world.robot(), 40, rng)) {
    const Eigen::Isometry3d X_WO = robots::forwardKinematics(world.robot(), q)[tool] * boxInTool();
    const Eigen::Vector3d p = X_WO * Eigen::Vector3d(size.x() / 2 + radius + gap, 0, 0);
    world.setObstaclePose(probe, translation(p.x(), p.y(), p.z()));
    const Contact c = contactOf(withContacts(world, q).contacts, "attached/box", "obstacle/probe");
    BOOST_TEST(std::abs(c.distance - gap) <= kDistanceAccuracy);
    BOOST_TEST(c.linkA == tool);
  }
}

// The gradient of an attached object's distance is that of its point fixed on the link.
BOOST_AUTO_TEST_CASE(gradient_matches_central_differences) {
  World world = quietArm();
  world.attach("tool", Obstacle::box("box", Eigen::Vector3d(0.1, 0.06, 0.04), boxInTool()));
  world.addObstacle(Obstacle::sphere("probe", 0.05, translation(0.35, 0.2, 0.9)));
  std::mt19937 rng(5);
  int checked = 0;
  for (const Eigen::VectorXd& q : test::randomConfigurations(world.robot(), 20, rng)) {
    const Contact c = contactOf(withContacts(world, q, true).contacts, "attached/box", "obstacle/probe");
    if (c.distance < 0.02) continue;  // keep to smooth, separated cases
    for (Eigen::Index v = 0; v < q.size(); ++v) {
      Eigen::VectorXd plus = q, minus = q;
      plus[v] += kGradientStep;
      minus[v] -= kGradientStep;
      const double dPlus = contactOf(withContacts(world, plus).contacts, "attached/box", "obstacle/probe").distance;
      const double dMinus = contactOf(withContacts(world, minus).contacts, "attached/box", "obstacle/probe").distance;
      BOOST_TEST(std::abs((dPlus - dMinus) / (2 * kGradientStep) - c.gradient[v]) <= kGradientAgreement);
    }
    ++checked;
  }
  BOOST_TEST(checked > 5);
}

// A rod held by the tool, down along the straight arm: it overlaps link2 and link1, not
// checked against the tool (its link) nor link3 (rigidly attached to the tool); touch links
// silence link2 and link1.
BOOST_AUTO_TEST_CASE(checked_against_other_links_but_not_its_own_or_touch_links) {
  const Eigen::VectorXd q0 = test::armRobot().defaultConfiguration();
  const Obstacle rod = Obstacle::box("rod", Eigen::Vector3d(0.04, 0.04, 0.6), translation(0, 0, -0.45));
  World world = quietArm();
  BOOST_TEST(world.isFree(q0));
  world.attach("tool", rod);
  BOOST_TEST(!world.isFree(q0));
  const std::vector<Contact> contacts = withContacts(world, q0).contacts;
  BOOST_TEST(contactOf(contacts, "link2", "attached/rod").distance < 0);
  BOOST_TEST(contactOf(contacts, "link1", "attached/rod").distance < 0);
  BOOST_TEST((contactOf(contacts, "link2", "attached/rod").bodyB.kind == BodyRef::Kind::Attached));
  for (const Contact& c : contacts) {
    BOOST_TEST(!(c.nameA == "tool" && c.nameB == "attached/rod"));
    BOOST_TEST(!(c.nameA == "link3" && c.nameB == "attached/rod"));
  }
  world.detach("rod", false);
  AttachOptions touching;
  touching.touchLinks = {"link2", "link1"};
  world.attach("tool", rod, touching);
  BOOST_TEST(world.isFree(q0));
  BOOST_TEST(world.attachedObjects().front().touchLinks == touching.touchLinks);
}

BOOST_AUTO_TEST_CASE(collides_with_obstacles_and_detaches) {
  const Eigen::VectorXd q0 = test::armRobot().defaultConfiguration();
  World world = quietArm();
  world.addObstacle(Obstacle::sphere("ball", 0.05, translation(0.3, 0.0, 1.1)));  // beside the tool
  BOOST_TEST(world.isFree(q0));
  world.attach("tool", Obstacle::box("box", Eigen::Vector3d(0.1, 0.1, 0.1), translation(0.3, 0, 0)));
  BOOST_TEST(!world.isFree(q0));
  const DistanceResult r = world.signedDistance(q0);
  BOOST_TEST(r.closest.nameA == "attached/box");
  BOOST_TEST(r.closest.nameB == "obstacle/ball");
  BOOST_TEST(world.summaryCounts().attachedObjects == 1);

  // Detached at q1: a static obstacle where the tool held it.
  Eigen::VectorXd q1 = q0;
  q1[0] = 1.0;
  const int id = world.detach("box", true, q1);
  BOOST_TEST(world.attachedObjects().empty());
  const Eigen::Isometry3d expected =
      robots::forwardKinematics(world.robot(), q1)[world.robot().linkIndex("tool")] * translation(0.3, 0, 0);
  BOOST_TEST((world.obstacle(id).X_WO.matrix() - expected.matrix()).norm() <= kPoseExact);
  BOOST_TEST(world.isFree(q0));
  const double toBox = contactOf(withContacts(world, q0).contacts, "tool", "obstacle/box").distance;
  BOOST_TEST(std::abs(toBox - 0.2) <= kDistanceAccuracy);  // 0.3 between centres, minus 0.05 and 0.05
}

// A scene box beyond the arm's reach is dropped at load; a long rod held by the tool reaches it,
// and the box is checked again.
BOOST_AUTO_TEST_CASE(scene_pieces_beyond_the_arm_come_back_for_a_long_object) {
  World world = quietArm();
  const robots::RobotModel lamp = robots::RobotModel::fromUrdfString(
      "<robot name='lamp'><link name='shade'><collision><origin xyz='0 0 2.6'/><geometry><box size='0.2 0.2 0.2'/>"
      "</geometry></collision></link></robot>",
      ".", {}, "lamp.urdf");
  world.addScene(lamp);
  BOOST_TEST(world.summaryCounts().scenePiecesDropped == 1);
  const Eigen::VectorXd q0 = world.robot().defaultConfiguration();  // straight up, the tool at z = 1.1
  world.attach("tool", Obstacle::box("pole", Eigen::Vector3d(0.04, 0.04, 1.6), translation(0, 0, 0.8)));
  BOOST_TEST(world.summaryCounts().scenePiecesDropped == 0);
  BOOST_TEST(!world.isFree(q0));
  const DistanceResult r = world.signedDistance(q0);
  BOOST_TEST(r.closest.nameA == "attached/pole");
  BOOST_TEST(r.closest.nameB == "scene/shade");
  // The pole (0.04 wide, its tip at 2.7) in the shade (0.2 wide, from 2.5): out sideways by 0.02 + 0.1.
  BOOST_TEST(std::abs(r.closest.distance + 0.12) <= kDistanceAccuracy);
}

BOOST_AUTO_TEST_CASE(an_obstacle_is_attached_where_it_is) {
  World world = quietArm();
  Eigen::VectorXd q0 = world.robot().defaultConfiguration();
  q0[1] = 0.4;
  const int tool = world.robot().linkIndex("tool");
  const Eigen::Isometry3d X_WT = robots::forwardKinematics(world.robot(), q0)[tool];
  const Eigen::Isometry3d X_WO = X_WT * translation(0.0, 0.0, 0.08);
  const int id = world.addObstacle(Obstacle::box("cup", Eigen::Vector3d(0.05, 0.05, 0.05), X_WO));
  AttachOptions at;
  at.q = q0;
  world.attachObstacle(id, "tool", at);
  BOOST_TEST(world.obstacleIds().empty());
  const AttachedObjectInfo info = world.attachedObjects().at(0);
  BOOST_TEST(info.link == "tool");
  BOOST_TEST((info.X_LO.matrix() - translation(0.0, 0.0, 0.08).matrix()).norm() <= kPoseExact);
}

BOOST_AUTO_TEST_CASE(bad_names_are_errors) {
  World world = quietArm();
  const Obstacle box = Obstacle::box("box", Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Isometry3d::Identity());
  test::checkThrowsWith([&] { world.attach("tol", box); }, "has no link 'tol'; near matches: 'tool'");
  AttachOptions touch;
  touch.touchLinks = {"lnk3"};
  test::checkThrowsWith([&] { world.attach("tool", box, touch); }, "touch link: robot 'arm' has no link 'lnk3'");
  world.attach("tool", box);
  test::checkThrowsWith([&] { world.attach("link3", box); }, "attach 'box': an object of that name is attached");
  test::checkThrowsWith([&] { world.detach("bx"); }, "detach: no attached object is named 'bx'; near matches: 'box'");
  test::checkThrowsWith([&] { world.attachObstacle(42, "tool"); }, "no obstacle with id 42");
  BOOST_TEST(world.attachedObjects().size() == 1u);
  // The attached object is a name for allowed collisions.
  world.allowCollision("box", "base");
  BOOST_TEST(world.collisionAllowed("attached/box", "base"));
}

// addPlanningScene attaches the scene's attached objects and allows its allowed collisions; the
// base sunk in the table is allowed by the scene, so no fixed pair is reported.
BOOST_AUTO_TEST_CASE(planning_scene_attached_objects_and_allowed_collisions) {
  std::ostringstream log;
  WorldOptions options = test::testWorldOptions();
  options.progress = &log;
  World world(test::armRobot(), options);
  robots::PlanningScene scene;
  scene.source = "in code";
  robots::SceneObject table;
  table.id = "table";
  table.frameId = "base";
  robots::SceneShape top;
  top.geometry.type = robots::GeometryType::Box;
  top.geometry.boxSize = Eigen::Vector3d(1.0, 1.0, 0.04);
  top.X_FS = translation(0, 0, -0.018);
  table.shapes.push_back(top);
  scene.objects.push_back(table);
  robots::AttachedObject held;
  held.linkName = "tool";
  held.object.id = "held";
  held.object.frameId = "tool";
  robots::SceneShape cube;
  cube.geometry.type = robots::GeometryType::Box;
  cube.geometry.boxSize = Eigen::Vector3d(0.05, 0.05, 0.05);
  cube.X_FS = translation(0, 0, 0.07);
  held.object.shapes.push_back(cube);
  held.touchLinks = {"link3"};
  scene.attached.push_back(held);
  scene.allowed.pairs = {{"base", "table"}};
  scene.allowed.always = {"held"};
  world.addPlanningScene(scene);

  const std::vector<AttachedObjectInfo> attached = world.attachedObjects();
  BOOST_TEST_REQUIRE(attached.size() == 1u);
  BOOST_TEST(attached[0].object.name == "held");
  BOOST_TEST(attached[0].link == "tool");
  BOOST_TEST((attached[0].X_LO.matrix() - translation(0, 0, 0.07).matrix()).norm() <= kPoseExact);
  BOOST_TEST(attached[0].touchLinks == std::vector<std::string>{"link3"});
  BOOST_TEST(world.collisionAllowed("base", "table"));
  BOOST_TEST(world.collisionAllowed("held", "*"));
  BOOST_TEST(world.fixedPairs().empty());
  BOOST_TEST(log.str().find("warning") == std::string::npos, log.str());

  robots::PlanningScene bad = scene;
  bad.objects.clear();
  bad.attached[0].object.id = "held2";
  bad.attached[0].linkName = "tol";
  test::checkThrowsWith([&] { world.addPlanningScene(bad); }, "no link 'tol'");
}

BOOST_AUTO_TEST_CASE(shown_in_the_html_view_on_its_link) {
  World world = quietArm();
  const int tool = world.robot().linkIndex("tool");
  const std::size_t toolPieces = world.linkPieces(tool).size();
  world.attach("tool", Obstacle::box("box", Eigen::Vector3d(0.1, 0.06, 0.04), boxInTool()));
  BOOST_TEST(world.linkPieces(tool).size() == toolPieces);  // the link's own pieces only
  Eigen::VectorXd q = world.robot().defaultConfiguration();
  q[0] = 0.7;
  q[1] = -0.3;
  const viewer::ViewScene view = viewer::viewOfWorld(world, {q});
  const Eigen::Isometry3d expected =
      robots::forwardKinematics(world.robot(), q)[world.robot().linkIndex("tool")] * boxInTool();
  int found = 0;
  for (const viewer::ViewBody& b : view.bodies) {
    if (b.name != "attached/box") continue;
    ++found;
    BOOST_TEST(b.layer == "attached");
    BOOST_TEST(!b.pieces.empty());
    BOOST_TEST_REQUIRE(b.track >= 0);
    const Eigen::Isometry3d& pose = view.frames.front().poses.at(static_cast<std::size_t>(b.track));
    BOOST_TEST((pose.matrix() - expected.matrix()).norm() <= kPoseExact);
  }
  BOOST_TEST(found == 1);
}

BOOST_AUTO_TEST_SUITE_END()

}  // namespace
}  // namespace deepcheck::checker
