// World::bodySignedDistance (body_distance.h): a link against a body of several pieces measured
// as one union, on the hard cases built as worlds (a box pressed into a slab of two
// touching boxes, a peg in a U of three boxes), against geometry::bodySignedDistance on the same posed
// pieces, link against link, the rounded-piece rule and the errors.

#include "checker_test_util.h"

#include "common/body_cases.h"

#include "deepcheck/checker/body_distance.h"
#include "deepcheck/geometry/body_depth.h"
#include "deepcheck/robots/kinematics.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace deepcheck;
using namespace deepcheck::checker;
using namespace deepcheck::checker::test;
using deepcheck::test::boxCollision;
using deepcheck::test::gantryQ;
using deepcheck::test::gantryRobot;
using deepcheck::test::sceneOf;
using deepcheck::test::slabCollisions;
using deepcheck::test::toolBox;
using deepcheck::test::uCollisions;

namespace {

const std::string kToolBox = toolBox();
const std::string kSlab = slabCollisions();
const std::string kU = uCollisions();

BodyRef sceneLink(const World& world, int scene, const std::string& link) {
  BodyRef b;
  b.kind = BodyRef::Kind::SceneLink;
  b.scene = scene;
  b.index = world.scene(scene).linkIndex(link);
  return b;
}

BodyRef robotLink(const World& world, const std::string& link) {
  BodyRef b;
  b.kind = BodyRef::Kind::RobotLink;
  b.index = world.robot().linkIndex(link);
  return b;
}

/// The world's answer for the tool against `other`, and the pairwise one (signedDistance's
/// closest pair, the only body near the tool).
struct Both {
  World::BodyContact body;
  Contact pairwise;
};

Both measure(const World& world, const Eigen::VectorXd& q, const BodyRef& other) {
  Both out;
  World::BodyDistanceOptions options;
  options.gradient = true;
  out.body = world.bodySignedDistance(q, robotLink(world, "tool"), other, options);
  const DistanceResult d = world.signedDistance(q);
  BOOST_REQUIRE(d.found);
  out.pairwise = d.closest;
  return out;
}

/// The geometry::Body of posed pieces: a robot link's (linkPieces, at its pose X_WL) or a world
/// body's (worldPieces, posed in the world).
geometry::Body linkBody(const World& world, int link) {
  geometry::Body b;
  for (const robots::CollisionPiece& p : world.linkPieces(link)) b.pieces.push_back({{p.core.get(), p.radius}, p.X_LP});
  return b;
}
geometry::Body worldBody(const std::vector<World::WorldPieceRef>& pieces, const BodyRef& body) {
  geometry::Body b;
  for (const World::WorldPieceRef& p : pieces) {
    if (p.body == body) b.pieces.push_back({{p.piece.core.get(), p.piece.radius}, p.piece.X_LP});
  }
  return b;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_body_distance)

// The slab case: the tool, 0.06 wide, 0.04 deep into the seam of two touching boxes, 0.005 off
// the seam. Each pair's own depth is sideways (0.025 and 0.035, less than the 0.04 up), in
// opposite directions; the slab's depth as one body is 0.04, straight up.
BOOST_AUTO_TEST_CASE(slab_of_two_touching_boxes_is_pushed_up_not_sideways) {
  World world(gantryRobot(kToolBox), testWorldOptions());
  world.addScene(sceneOf("slab", kSlab), Eigen::Isometry3d::Identity());
  const Both r = measure(world, gantryQ(0.005, 0, 0.01), sceneLink(world, 0, "slab"));
  const Contact& c = r.body.contact;
  BOOST_TEST(toString(r.body.method) == std::string("body"));
  BOOST_TEST(geometry::toString(r.body.depthStatus) == std::string("certified"));
  BOOST_TEST(geometry::toString(c.status) == std::string("penetrating"));
  BOOST_TEST(c.distance == -0.04, boost::test_tools::tolerance(1e-9));
  BOOST_TEST((c.normal - Eigen::Vector3d(0, 0, -1)).norm() < 1e-9, "normal " << c.normal.transpose());
  BOOST_TEST((c.pointB - c.pointA - c.distance * c.normal).norm() < 1e-9);
  BOOST_TEST(c.nameA == "tool");
  BOOST_TEST(c.nameB == "scene/slab");
  BOOST_TEST(c.linkA == world.robot().linkIndex("tool"));
  BOOST_TEST((c.bodyB == sceneLink(world, 0, "slab")));
  BOOST_TEST(r.body.overlappingPairs == 2);
  BOOST_TEST(r.body.pairDepth == 0.035, boost::test_tools::tolerance(1e-9));
  // Moving the tool up takes it out at rate 1; sideways, not at all.
  BOOST_TEST(c.gradient.size() == 5);
  BOOST_TEST(c.gradient[2] == 1.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(std::abs(c.gradient[0]) < 1e-9);
  BOOST_TEST(std::abs(c.gradient[1]) < 1e-9);
  // The pairwise answer: the deeper pair's 0.035, horizontal.
  BOOST_TEST(r.pairwise.distance == -0.035, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(std::abs(r.pairwise.normal.z()) < 1e-9, "pairwise normal " << r.pairwise.normal.transpose());
}

// The peg in a U: the tool 0.06 wide in a channel 0.05 wide, 0.03 below the walls' top. Each wall
// alone pushes it 0.004 or 0.006 sideways, towards the other wall; the U as one body lifts it 0.03.
BOOST_AUTO_TEST_CASE(peg_in_a_u_of_three_boxes_is_lifted_out) {
  World world(gantryRobot(kToolBox), testWorldOptions());
  world.addScene(sceneOf("u", kU), Eigen::Isometry3d::Identity());
  const Both r = measure(world, gantryQ(0.001, 0, 0.12), sceneLink(world, 0, "u"));
  const Contact& c = r.body.contact;
  BOOST_TEST(geometry::toString(r.body.depthStatus) == std::string("certified"));
  BOOST_TEST(c.distance == -0.03, boost::test_tools::tolerance(1e-9));
  BOOST_TEST((c.normal - Eigen::Vector3d(0, 0, -1)).norm() < 1e-9, "normal " << c.normal.transpose());
  BOOST_TEST(r.body.overlappingPairs == 2);
  BOOST_TEST(r.pairwise.distance == -0.006, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(std::abs(r.pairwise.normal.x()) == 1.0, boost::test_tools::tolerance(1e-9));
}

// Apart, the body answer is the nearest pair's distance, the same as signedDistance's.
BOOST_AUTO_TEST_CASE(separated_bodies_give_the_nearest_pair) {
  World world(gantryRobot(kToolBox), testWorldOptions());
  world.addScene(sceneOf("slab", kSlab), Eigen::Isometry3d::Identity());
  const Both r = measure(world, gantryQ(0.3, 0.1, 0.08), sceneLink(world, 0, "slab"));
  BOOST_TEST(geometry::toString(r.body.depthStatus) == std::string("separated"));
  BOOST_TEST(geometry::toString(r.body.contact.status) == std::string("separated"));
  BOOST_TEST(r.body.contact.distance == 0.03, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(r.pairwise.distance == 0.03, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(r.body.contact.gradient[2] == 1.0, boost::test_tools::tolerance(1e-9));
}

// An L-shaped tool of two boxes, turned and moved at random about the slab and the U: the world's
// answer is geometry::bodySignedDistance's on the pieces the world reports (linkPieces at the link's
// pose, worldPieces of the body).
BOOST_AUTO_TEST_CASE(agrees_with_the_body_depth_on_the_posed_pieces) {
  const std::string tool = kToolBox + boxCollision({0.1, 0.04, 0.04}, {0.08, 0, 0.03});
  World world(gantryRobot(tool), testWorldOptions());
  world.addScene(sceneOf("slab", kSlab), Eigen::Isometry3d::Identity());
  world.addScene(sceneOf("u", kU), translation(0.6, 0, 0));
  const int toolLink = world.robot().linkIndex("tool");
  const geometry::Body toolBody = linkBody(world, toolLink);
  BOOST_REQUIRE(toolBody.pieces.size() == 2);
  const std::vector<World::WorldPieceRef> pieces = world.worldPieces();
  std::mt19937_64 rng(38);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int overlapping = 0;
  int severalPairs = 0;
  for (int k = 0; k < 60; ++k) {
    const int scene = k % 2;
    const double x0 = scene == 0 ? 0.0 : 0.6;
    const double z0 = scene == 0 ? 0.02 : 0.1;
    const Eigen::VectorXd q =
        gantryQ(x0 + 0.1 * (2 * unit(rng) - 1), 0.1 * (2 * unit(rng) - 1), z0 + 0.06 * (2 * unit(rng) - 1),
                3.0 * (2 * unit(rng) - 1), 0.5 * (2 * unit(rng) - 1));
    const BodyRef other = sceneLink(world, scene, scene == 0 ? "slab" : "u");
    const World::BodyContact got = world.bodySignedDistance(q, robotLink(world, "tool"), other);
    const std::vector<Eigen::Isometry3d> X_WL = robots::forwardKinematics(world.robot(), q);
    const geometry::BodySignedDistanceResult want =
        geometry::bodySignedDistance(toolBody, X_WL[toolLink], worldBody(pieces, other), Eigen::Isometry3d::Identity());
    BOOST_TEST_CONTEXT("configuration " << k << ": " << q.transpose()) {
      BOOST_TEST(got.contact.distance == want.distance, boost::test_tools::tolerance(1e-9));
      BOOST_TEST((got.contact.normal - want.normal).norm() < 1e-9);
      BOOST_TEST((got.contact.pointA - want.pointA).norm() < 1e-9);
      BOOST_TEST((got.contact.pointB - want.pointB).norm() < 1e-9);
      BOOST_TEST(geometry::toString(got.depthStatus) == geometry::toString(want.status));
      BOOST_TEST(got.overlappingPairs == want.overlappingPairs);
    }
    overlapping += want.distance < 0.0 ? 1 : 0;
    severalPairs += want.overlappingPairs >= 2 ? 1 : 0;
  }
  // The draws must exercise the overlapping unions, not only separated bodies.
  BOOST_TEST(overlapping >= 20);
  BOOST_TEST(severalPairs >= 5);
}

// Link against link: a slab link of two boxes on one slider, a box link on another; the same
// answer as against the scene slab, and the gradient moves both links.
BOOST_AUTO_TEST_CASE(link_against_a_link_of_several_pieces) {
  const std::string xml =
      "<robot name='two'><link name='base'/>"
      "<link name='peg'>" +
      boxCollision({0.06, 0.1, 0.1}, {0, 0, 0}) +
      "</link>"
      "<link name='slab'>" +
      kSlab +
      "</link>"
      "<joint name='up' type='prismatic'><parent link='base'/><child link='peg'/><axis xyz='0 0 1'/>"
      "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint>"
      "<joint name='side' type='prismatic'><parent link='base'/><child link='slab'/><axis xyz='1 0 0'/>"
      "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint></robot>";
  World world(robots::RobotModel::fromUrdfString(xml, ".", {}, "two.urdf"), testWorldOptions());
  Eigen::VectorXd q(2);
  q << 0.01, -0.005;
  World::BodyDistanceOptions options;
  options.gradient = true;
  const World::BodyContact r = world.bodySignedDistance(q, robotLink(world, "peg"), robotLink(world, "slab"), options);
  const Contact& c = r.contact;
  BOOST_TEST(c.distance == -0.04, boost::test_tools::tolerance(1e-9));
  BOOST_TEST((c.normal - Eigen::Vector3d(0, 0, -1)).norm() < 1e-9);
  BOOST_TEST(c.nameB == "slab");
  BOOST_TEST((c.bodyB == robotLink(world, "slab")));
  const int up = world.robot().variableIndex("up");
  const int side = world.robot().variableIndex("side");
  BOOST_TEST(c.gradient[up] == 1.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(std::abs(c.gradient[side]) < 1e-9);
  // Measured the other way round, the normal turns and the distance stays.
  const World::BodyContact back = world.bodySignedDistance(q, robotLink(world, "slab"), robotLink(world, "peg"));
  BOOST_TEST(back.contact.distance == -0.04, boost::test_tools::tolerance(1e-9));
  BOOST_TEST((back.contact.normal - Eigen::Vector3d(0, 0, 1)).norm() < 1e-9);
}

// An attached object is a body of its own: a plate held 0.07 below the tool, pressed 0.02 into the
// slab across the seam, where each box alone would push it out sideways by less.
BOOST_AUTO_TEST_CASE(attached_object_against_a_body) {
  World world(gantryRobot(kToolBox), testWorldOptions());
  world.addScene(sceneOf("slab", kSlab), Eigen::Isometry3d::Identity());
  world.attach("tool", Obstacle::box("plate", Eigen::Vector3d(0.03, 0.1, 0.04), translation(0, 0, -0.07)));
  const int toolLink = world.robot().linkIndex("tool");
  BodyRef plate;
  plate.kind = BodyRef::Kind::Attached;
  plate.index = toolLink;
  plate.scene = 0;
  // The plate spans z in [-0.09, -0.05] about the tool frame and x in [-0.015, 0.015].
  const World::BodyContact r = world.bodySignedDistance(gantryQ(0.002, 0, 0.07), plate, sceneLink(world, 0, "slab"));
  BOOST_TEST(r.contact.distance == -0.02, boost::test_tools::tolerance(1e-9));
  BOOST_TEST((r.contact.normal - Eigen::Vector3d(0, 0, -1)).norm() < 1e-9, "normal " << r.contact.normal.transpose());
  BOOST_TEST(r.contact.nameA == "attached/plate");
  BOOST_TEST(r.contact.linkA == toolLink);
  BOOST_TEST(r.overlappingPairs == 2);
  BOOST_TEST(r.pairDepth == 0.017, boost::test_tools::tolerance(1e-9));
  // The tool itself is clear of the slab (its bottom 0.02 above it).
  BOOST_TEST(world.bodySignedDistance(gantryQ(0.002, 0, 0.07), robotLink(world, "tool"), sceneLink(world, 0, "slab"))
                     .contact.distance == 0.02,
             boost::test_tools::tolerance(1e-9));
  plate.scene = 1;
  checkThrowsWith([&] { world.bodySignedDistance(gantryQ(0, 0, 0.3), plate, sceneLink(world, 0, "slab")); },
                  "no object attached to link tool at position 1");
}

// A sphere has a radius: the pair is answered pairwise, as signedDistance answers it, and says so.
BOOST_AUTO_TEST_CASE(rounded_pieces_fall_back_to_the_pairwise_answer) {
  World world(gantryRobot(kToolBox), testWorldOptions());
  const int ball = world.addObstacle(Obstacle::sphere("ball", 0.05, translation(0, 0, -0.09)));
  BodyRef b;
  b.kind = BodyRef::Kind::Obstacle;
  b.index = ball;
  const Both r = measure(world, gantryQ(0, 0, 0.0), b);
  BOOST_TEST(toString(r.body.method) == std::string("pairwise"));
  BOOST_TEST(r.body.contact.distance == -0.01, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(r.body.contact.distance == r.pairwise.distance, boost::test_tools::tolerance(1e-12));
  BOOST_TEST((r.body.contact.normal - r.pairwise.normal).norm() < 1e-9);
  BOOST_TEST(r.body.contact.nameB == "obstacle/ball");
  BOOST_TEST(r.body.overlappingPairs == 1);
}

BOOST_AUTO_TEST_CASE(bad_bodies_are_named) {
  World world(gantryRobot(kToolBox), testWorldOptions());
  world.addScene(sceneOf("slab", kSlab), Eigen::Isometry3d::Identity());
  const Eigen::VectorXd q = gantryQ(0, 0, 0.3);
  const BodyRef tool = robotLink(world, "tool");
  const BodyRef slab = sceneLink(world, 0, "slab");
  BodyRef obstacle;
  obstacle.kind = BodyRef::Kind::Obstacle;
  obstacle.index = 99;
  checkThrowsWith([&] { world.bodySignedDistance(q, tool, obstacle); }, "no obstacle with id 99");
  checkThrowsWith([&] { world.bodySignedDistance(q, slab, tool); }, "must be a robot link or an attached object");
  checkThrowsWith([&] { world.bodySignedDistance(q, robotLink(world, "lz"), slab); },
                  "the robot link lz has no collision geometry");
  checkThrowsWith([&] { world.bodySignedDistance(q, tool, tool); }, "the same body");
  checkThrowsWith([&] { world.bodySignedDistance(gantryQ(0, 0, std::nan("")), tool, slab); }, "q[2] (z)");
}

BOOST_AUTO_TEST_SUITE_END()
