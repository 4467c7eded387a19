// Allowed collisions (World::allowCollision, allowCollisionsWith; world.h): every query skips
// the allowed pairs and only them, names resolve to every kind of body, unknown names are errors
// with near matches; and the pairs no joint can change (World::fixedPairs), reported once.

#include "checker_test_util.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/moveit_scene.h"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace deepcheck::checker {
namespace {

using test::translation;

/// The arm with the crate, ball and post; progress (and fixed-pair reports) into `log`.
World armWorld(std::ostream* log = nullptr) {
  WorldOptions options = test::testWorldOptions();
  options.progress = log;
  World world(test::armRobot(), options);
  test::addCrateBallPost(world);
  return world;
}

bool isAllowed(const std::vector<std::pair<std::string, std::string>>& allowed, const Contact& c) {
  for (const auto& [a, b] : allowed) {
    if ((a == c.nameA && (b == c.nameB || b == "*")) || (b == c.nameA && a == c.nameB) || (a == c.nameB && b == "*")) {
      return true;
    }
  }
  return false;
}

/// Every body pair's contact of `world` at q (no allowed pair), one fresh context.
std::vector<Contact> allContacts(const World& world, const Eigen::VectorXd& q) {
  DistanceOptions all;
  all.contactMargin = std::numeric_limits<double>::infinity();
  auto context = world.makeContext();
  return world.signedDistance(q, context, all).contacts;
}

/// Tolerance of two measures of one pair by separate contexts (metres): the same algorithm on
/// the same pieces, possibly from other starts.
constexpr double kSameDistance = 1e-9;

BOOST_AUTO_TEST_SUITE(checker_allowed_collisions)

// With allowed pairs (robot-obstacle by plain name, robot-obstacle by full name, a self pair and
// a body allowed with anything), isFree, the closest pair and the contact list equal the brute
// force: every body pair of a world with nothing allowed, minus the allowed ones.
BOOST_AUTO_TEST_CASE(queries_equal_brute_force_over_pairs_not_allowed) {
  World reference = armWorld();
  World world = armWorld();
  // A rod held by the tool takes part too: against an obstacle and a link.
  const Obstacle rod = Obstacle::box("rod", Eigen::Vector3d(0.04, 0.04, 0.5), translation(0.0, 0.0, 0.2));
  reference.attach("tool", rod);
  world.attach("tool", rod);
  const std::vector<std::pair<std::string, std::string>> allowed = {
      {"link2", "obstacle/crate"}, {"tool", "obstacle/post"},          {"base", "link3"},
      {"obstacle/ball", "*"},      {"attached/rod", "obstacle/crate"}, {"link1", "attached/rod"}};
  world.allowCollision("crate", "link2");
  world.allowCollision("tool", "obstacle/post");
  world.disablePair("base", "link3");
  world.allowCollisionsWith("ball");
  world.allowCollision("rod", "crate");
  world.allowCollision("attached/rod", "link1");
  std::mt19937 rng(20261129);
  int free = 0, colliding = 0, changed = 0, rodChecked = 0, rodAllowed = 0;
  DistanceOptions contacts;
  contacts.contactMargin = std::numeric_limits<double>::infinity();
  for (const Eigen::VectorXd& q : test::randomConfigurations(world.robot(), 300, rng)) {
    std::vector<Contact> expected;
    const std::vector<Contact> everything = allContacts(reference, q);
    for (const Contact& c : everything) {
      const bool rod = c.nameA == "attached/rod" || c.nameB == "attached/rod";
      if (!isAllowed(allowed, c)) {
        expected.push_back(c);
        rodChecked += rod && c.distance <= 0.0;
      } else {
        rodAllowed += rod && c.distance <= 0.0;
      }
    }
    auto context = world.makeContext();
    const DistanceResult got = world.signedDistance(q, context, contacts);
    BOOST_TEST_REQUIRE(got.contacts.size() == expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
      BOOST_TEST(got.contacts[i].nameA == expected[i].nameA);
      BOOST_TEST(got.contacts[i].nameB == expected[i].nameB);
      BOOST_TEST(std::abs(got.contacts[i].distance - expected[i].distance) <= kSameDistance);
    }
    BOOST_TEST(std::abs(world.signedDistance(q, context).closest.distance - expected.front().distance) <=
               kSameDistance);
    const bool expectFree = expected.front().distance > 0.0;
    BOOST_TEST(world.isFree(q) == expectFree, "q = " << q.transpose());
    (expectFree ? free : colliding) += 1;
    changed += everything.front().distance <= 0.0 && expectFree;
  }
  // Both outcomes, and configurations that only the allowed pairs made collide.
  BOOST_TEST(free > 30);
  BOOST_TEST(colliding > 30);
  BOOST_TEST(changed > 0);
  // The rod's pairs overlap in both kinds: checked and allowed.
  BOOST_TEST(rodChecked > 0);
  BOOST_TEST(rodAllowed > 0);
}

BOOST_AUTO_TEST_CASE(allowed_pairs_are_listed_and_answered) {
  WorldOptions options = test::testWorldOptions();
  options.progress = nullptr;
  options.disabledPairs = {robots::DisabledPair("link1", "link3")};
  World world(test::armRobot(), options);
  test::addCrateBallPost(world);
  world.allowCollision("tool", "crate");
  world.allowCollisionsWith("ball");
  const auto listed = world.allowedCollisions();
  BOOST_TEST(listed.size() == 3u);
  BOOST_TEST((std::find(listed.begin(), listed.end(), std::make_pair(std::string("link1"), std::string("link3"))) !=
              listed.end()));
  BOOST_TEST(
      (std::find(listed.begin(), listed.end(), std::make_pair(std::string("ball"), std::string("*"))) != listed.end()));
  BOOST_TEST(world.collisionAllowed("link3", "link1"));  // the SRDF's pair, in the same table
  BOOST_TEST(world.collisionAllowed("obstacle/crate", "tool"));
  BOOST_TEST(world.collisionAllowed("link2", "obstacle/ball"));
  BOOST_TEST(world.collisionAllowed("ball", "*"));
  BOOST_TEST(!world.collisionAllowed("link2", "crate"));
  BOOST_TEST(world.summaryCounts().allowedCollisions == 3);
}

// A robot link's name names the link only: an SRDF pair (link1, link3) does not allow link1
// against an obstacle that happens to be called "link3" (it is "obstacle/link3" then).
BOOST_AUTO_TEST_CASE(a_robot_link_name_names_the_link_only) {
  WorldOptions options = test::testWorldOptions();
  options.progress = nullptr;
  options.disabledPairs = {robots::DisabledPair("link1", "link3")};
  World world(test::armRobot(), options);
  world.addObstacle(Obstacle::box("link3", Eigen::Vector3d(0.05, 0.05, 0.05), translation(0, 0, 0.3)));  // in link1
  const Eigen::VectorXd q0 = world.robot().defaultConfiguration();
  BOOST_TEST(!world.isFree(q0));
  BOOST_TEST(world.signedDistance(q0).closest.nameB == "obstacle/link3");
  BOOST_TEST(!world.collisionAllowed("link1", "obstacle/link3"));
  world.allowCollision("link1", "obstacle/link3");
  BOOST_TEST(world.isFree(q0));
}

BOOST_AUTO_TEST_CASE(unknown_names_are_errors_with_near_matches) {
  World world = armWorld();
  test::checkThrowsWith([&] { world.allowCollision("link1", "crat"); },
                        "no robot link, attached object, scene link or obstacle is named 'crat'");
  test::checkThrowsWith([&] { world.allowCollision("link1", "crat"); }, "near matches: 'crate'");
  test::checkThrowsWith([&] { world.allowCollision("lnk2", "crate"); }, "'link2'");
  test::checkThrowsWith([&] { world.allowCollisionsWith("toool"); }, "near matches: 'tool'");
  test::checkThrowsWith([&] { world.collisionAllowed("base", "wall"); }, "'wall'");
  BOOST_TEST(world.allowedCollisions().empty());  // nothing was added by the failed calls
}

// A planning-scene object of several shapes is named by its id (all its obstacles "<id>/<k>")
// and each shape by its own name.
BOOST_AUTO_TEST_CASE(an_object_id_names_all_its_shapes) {
  WorldOptions options = test::testWorldOptions();
  options.progress = nullptr;
  World world(test::armRobot(), options);
  robots::PlanningScene scene;
  scene.source = "test";
  robots::SceneObject shelf;
  shelf.id = "shelf";
  shelf.frameId = "base";
  for (int k = 0; k < 2; ++k) {
    robots::SceneShape s;
    s.geometry.type = robots::GeometryType::Box;
    s.geometry.boxSize = Eigen::Vector3d(0.2, 0.2, 0.2);
    s.X_FS = translation(0.35 * (k == 0 ? 1 : -1), 0.0, 0.5);
    shelf.shapes.push_back(s);
  }
  scene.objects.push_back(shelf);
  world.addPlanningScene(scene);
  world.allowCollision("link3", "shelf");
  BOOST_TEST(world.collisionAllowed("link3", "shelf/0"));
  BOOST_TEST(world.collisionAllowed("link3", "obstacle/shelf/1"));
  BOOST_TEST(!world.collisionAllowed("link2", "shelf/1"));
  world.allowCollision("link2", "shelf/1");
  BOOST_TEST(world.collisionAllowed("link2", "shelf/1"));
  BOOST_TEST(!world.collisionAllowed("link2", "shelf/0"));
}

// The arm's base (moved by no joint) sunk 2 mm into a table: reported once, by name, with the
// option that allows it; every configuration collides until it is allowed, and the clearance
// is the base's until then.
BOOST_AUTO_TEST_CASE(fixed_pair_reported_once_and_allowed) {
  std::ostringstream log;
  World world = armWorld(&log);
  world.addObstacle(Obstacle::box("table", Eigen::Vector3d(1.0, 1.0, 0.04), translation(0.0, 0.0, -0.018)));
  world.addObstacle(Obstacle::sphere("far", 0.1, translation(3.0, 0.0, 0.0)));  // a second change
  const std::vector<Contact> fixed = world.fixedPairs();
  BOOST_TEST_REQUIRE(fixed.size() == 1u);
  BOOST_TEST(fixed[0].nameA == "base");
  BOOST_TEST(fixed[0].nameB == "obstacle/table");
  BOOST_TEST(std::abs(fixed[0].distance + 0.002) <= kSameDistance);
  const std::string text = log.str();
  BOOST_TEST(text.find("base and obstacle/table are -0.002 m apart in every configuration (no joint moves base)") !=
                 std::string::npos,
             text);
  BOOST_TEST(text.find("--allow-collision base:obstacle/table") != std::string::npos, text);
  BOOST_TEST(std::count(text.begin(), text.end(), '\n') == 1, text);  // once

  std::mt19937 rng(7);
  const std::vector<Eigen::VectorXd> qs = test::randomConfigurations(world.robot(), 50, rng);
  for (const Eigen::VectorXd& q : qs) BOOST_TEST(!world.isFree(q));
  world.allowCollision("base", "table");
  BOOST_TEST(world.fixedPairs().empty());
  int free = 0;
  for (const Eigen::VectorXd& q : qs) {
    free += world.isFree(q);
    const Contact closest = world.signedDistance(q).closest;
    BOOST_TEST(!(closest.nameA == "base" && closest.nameB == "obstacle/table"));
  }
  BOOST_TEST(free > 0);
}

BOOST_AUTO_TEST_CASE(fixed_pairs_not_reported_while_reports_are_off) {
  std::ostringstream log;
  World world = armWorld(&log);
  const bool before = world.setFixedPairReports(false);
  BOOST_TEST(before);
  world.addObstacle(Obstacle::box("table", Eigen::Vector3d(1.0, 1.0, 0.04), translation(0.0, 0.0, -0.018)));
  world.allowCollision("base", "table");
  world.setFixedPairReports(true);
  BOOST_TEST(log.str().empty(), log.str());
}

BOOST_AUTO_TEST_SUITE_END()

}  // namespace
}  // namespace deepcheck::checker

namespace deepcheck::checker {
namespace {

/// The UR5 of example-robot-data (shared data) on a table whose top is flush with its base
/// (z = 0), and the table's obstacle id.
World ur5OnTable(std::ostream* log) {
  robots::LoadOptions load;
  load.packageRoots = {test::sharedDir() + "/robots/ur5"};
  robots::RobotModel ur5 = robots::RobotModel::fromUrdfFile(
      test::sharedDir() + "/robots/ur5/example-robot-data/robots/ur_description/urdf/ur5_robot.urdf", load);
  WorldOptions options = test::testWorldOptions();
  options.progress = log;
  World world(std::move(ur5), options);
  world.addObstacle(Obstacle::box("table", Eigen::Vector3d(1.2, 0.8, 0.05), translation(0.0, 0.0, -0.025)));
  return world;
}

BOOST_AUTO_TEST_SUITE(checker_allowed_collisions_ur5)

// The user's case: the bolted base reads the same small penetration in every state, is reported
// once with the option that allows it, and once allowed no longer sets the clearance.
BOOST_AUTO_TEST_CASE(ur5_bolted_to_a_flush_table) {
  if (!test::haveShared("the UR5 on a table")) return;
  std::ostringstream log;
  World world = ur5OnTable(&log);
  const std::vector<Contact> fixed = world.fixedPairs();
  BOOST_TEST_REQUIRE(fixed.size() == 1u);
  BOOST_TEST(fixed[0].nameA == "base_link");
  BOOST_TEST(fixed[0].nameB == "obstacle/table");
  BOOST_TEST(fixed[0].distance <= 0.0);
  BOOST_TEST_MESSAGE("UR5 base_link - table: " << fixed[0].distance << " m");
  BOOST_TEST(log.str().find("--allow-collision base_link:obstacle/table") != std::string::npos, log.str());
  // One warning (the log may also hold progress lines of a cold decomposition cache).
  const std::string text = log.str();
  int warnings = 0;
  for (std::size_t at = text.find("warning:"); at != std::string::npos; at = text.find("warning:", at + 1)) ++warnings;
  BOOST_TEST(warnings == 1, text);

  std::mt19937 rng(2026);
  const std::vector<Eigen::VectorXd> qs = test::randomConfigurations(world.robot(), 200, rng);
  DistanceOptions worldOnly;
  worldOnly.selfPairs = false;
  int baseClosest = 0;
  std::vector<double> worldBefore;
  for (const Eigen::VectorXd& q : qs) {
    const DistanceResult r = world.signedDistance(q);
    baseClosest += r.closest.nameA == "base_link" && r.closest.nameB == "obstacle/table";
    worldBefore.push_back(world.signedDistance(q, worldOnly).closest.distance);
    BOOST_TEST(!world.isFree(q));
  }
  world.allowCollision("base_link", "table");
  BOOST_TEST(world.fixedPairs().empty());
  std::vector<double> clearance, worldAfter;
  int free = 0;
  for (const Eigen::VectorXd& q : qs) {
    const DistanceResult r = world.signedDistance(q);
    BOOST_TEST(!(r.closest.nameA == "base_link" && r.closest.nameB == "obstacle/table"));
    clearance.push_back(r.closest.distance);
    worldAfter.push_back(world.signedDistance(q, worldOnly).closest.distance);
    free += world.isFree(q);
  }
  for (auto* v : {&clearance, &worldBefore, &worldAfter}) std::sort(v->begin(), v->end());
  const std::size_t mid = qs.size() / 2;
  BOOST_TEST_MESSAGE("UR5 on the table, 200 random configurations: base_link - table the closest pair in "
                     << baseClosest << ", none free, before allowing it; after: " << free << " free, clearance median "
                     << clearance[mid] << " m, max " << clearance.back()
                     << " m; robot-world clearance median/max before " << worldBefore[mid] << "/" << worldBefore.back()
                     << " m, after " << worldAfter[mid] << "/" << worldAfter.back() << " m");
  BOOST_TEST(baseClosest > 0);
  BOOST_TEST(free > 0);
  // The robot-world clearance was capped by the base's constant -3 mm; it no longer is (what caps
  // it now is the shoulder over the table, which the pan joint turns without lifting: 2.4 cm).
  BOOST_TEST(worldBefore.back() <= fixed[0].distance + kSameDistance);
  BOOST_TEST(worldAfter.back() > 0.01);
}

BOOST_AUTO_TEST_SUITE_END()

}  // namespace
}  // namespace deepcheck::checker
