// isFree's fast paths: the centroid test (a robot piece's centroid inside a world piece decides
// an overlap without GJK; turned off through world_test_access.h) gives the same answers as GJK
// alone, on random configurations and short motions of the Panda in the kitchen and of the arm
// among primitive and mesh obstacles; the tetrahedron kept from a pair's last overlap (re-tested
// before GJK) gives the answers of contexts that never saw an earlier query; and a robot pose
// that left the doubles is reported, not answered (the narrow phase no longer checks poses
// itself).

#include "checker_test_util.h"
#include "world_test_access.h"

#include "deepcheck/checker/world.h"

#include <boost/test/unit_test.hpp>

#include <limits>
#include <random>
#include <vector>

using namespace deepcheck;
using namespace deepcheck::checker;
using namespace deepcheck::checker::test;

namespace {

/// Random configurations, then short motions (31 states 0.01 rad apart) from random starts, so
/// that warm starts and the re-test of the last overlapping pair are exercised too.
std::vector<Eigen::VectorXd> configurations(const robots::RobotModel& m, int random, int motions, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<Eigen::VectorXd> qs = randomConfigurations(m, random, rng);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int k = 0; k < motions; ++k) {
    Eigen::VectorXd q = randomConfiguration(m, rng);
    Eigen::VectorXd step(q.size());
    for (int v = 0; v < q.size(); ++v) step[v] = g(rng);
    step *= 0.01 / step.cwiseAbs().maxCoeff();
    for (int s = 0; s <= 30; ++s) qs.push_back(q + s * step);
  }
  return qs;
}

/// isFree with the centroid test against without it on qs (compareIsFree); returns the stats of
/// `with`.
QueryStats compareAnswers(const World& with, const World& without, const std::vector<Eigen::VectorXd>& qs,
                          int* colliding) {
  QueryStats withStats, withoutStats;
  *colliding = compareIsFree(with, without, qs, "the centroid test", &withStats, &withoutStats);
  BOOST_TEST(withoutStats.centroidInside == 0u);
  return withStats;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_isfree_fast_paths)

BOOST_AUTO_TEST_CASE(panda_kitchen_same_answers_with_and_without_centroid_test) {
  if (!haveShared("panda_kitchen_same_answers_with_and_without_centroid_test")) return;
  WorldOptions options = testWorldOptions();
  World with(loadPanda(), options);
  World without(loadPanda(), options);
  disableCentroidTest(without);
  with.addScene(loadKitchen());
  without.addScene(loadKitchen());
  const std::vector<Eigen::VectorXd> qs = configurations(with.robot(), 6000, 100, 41);
  int colliding = 0;
  const QueryStats stats = compareAnswers(with, without, qs, &colliding);
  BOOST_TEST(colliding > 1000);
  BOOST_TEST(colliding < static_cast<int>(qs.size()) - 1000);
  BOOST_TEST(stats.centroidInside > 300u);                   // the test decides many overlaps
  BOOST_TEST(stats.centroidInside < stats.narrowPhase / 2);  // and GJK still runs on the rest
}

BOOST_AUTO_TEST_CASE(arm_obstacles_same_answers_with_and_without_centroid_test) {
  // Boxes (a tilted one, and a lid over the arm), a sphere (a point core: no faces, never tested), a cylinder
  // prism and a mesh; obstacles moved between rounds.
  WorldOptions options = testWorldOptions();
  World with(armRobot(), options);
  World without(armRobot(), options);
  disableCentroidTest(without);
  Eigen::Isometry3d tilted = translation(0.35, 0.1, 0.55);
  tilted.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const robots::TriangleMesh tetra = tetrahedronMesh();
  std::vector<int> ids;
  for (World* w : {&with, &without}) {
    ids.push_back(w->addObstacle(Obstacle::box("crate", Eigen::Vector3d(0.4, 0.5, 0.45), tilted)));
    w->addObstacle(Obstacle::box("lid", Eigen::Vector3d(0.6, 0.6, 0.2), translation(0.0, 0.0, 1.05)));
    w->addObstacle(Obstacle::sphere("ball", 0.15, translation(-0.3, -0.25, 0.7)));
    w->addObstacle(Obstacle::cylinder("post", 0.08, 0.8, translation(0.0, 0.45, 0.4)));
    w->addObstacle(Obstacle::fromMesh("tetra", tetra, translation(-0.4, 0.3, 0.2)));
  }
  int colliding = 0;
  QueryStats stats = compareAnswers(with, without, configurations(with.robot(), 3000, 60, 42), &colliding);
  BOOST_TEST(colliding > 300);
  BOOST_TEST(stats.centroidInside > 50u);
  // Move the crate and compare again (the test reads the pieces' new poses).
  Eigen::Isometry3d moved = translation(-0.45, 0.4, 0.6);
  moved.linear() = Eigen::AngleAxisd(-1.1, Eigen::Vector3d(0.3, -1, 0.2).normalized()).toRotationMatrix();
  with.setObstaclePose(ids[0], moved);
  without.setObstaclePose(ids[1], moved);
  stats = compareAnswers(with, without, configurations(with.robot(), 2000, 30, 43), &colliding);
  BOOST_TEST(colliding > 200);
  BOOST_TEST(stats.centroidInside > 20u);
}

BOOST_AUTO_TEST_CASE(kept_enclosing_tetrahedra_give_the_answers_of_fresh_contexts) {
  // Motions through the obstacles, queried with one context (its pairs' tetrahedra kept from
  // query to query, even between incoherent ones) and, as the reference, each with a new context.
  WorldOptions options = testWorldOptions();
  World world(armRobot(), options);
  disableCentroidTest(world);  // every overlap decided by GJK or by a kept tetrahedron
  world.addObstacle(Obstacle::box("crate", Eigen::Vector3d(0.4, 0.5, 0.45), translation(0.35, 0.1, 0.55)));
  world.addObstacle(Obstacle::box("lid", Eigen::Vector3d(0.6, 0.6, 0.2), translation(0.0, 0.0, 1.05)));
  world.addObstacle(Obstacle::fromMesh("tetra", tetrahedronMesh(), translation(-0.4, 0.3, 0.2)));
  const std::vector<Eigen::VectorXd> qs = configurations(world.robot(), 200, 60, 44);
  World::Context kept = world.makeContext();
  int colliding = 0;
  for (const Eigen::VectorXd& q : qs) {
    World::Context fresh = world.makeContext();
    const bool reference = world.isFree(q, fresh);
    BOOST_CHECK_MESSAGE(world.isFree(q, kept) == reference, "q = " << q.transpose() << ": reference " << reference);
    BOOST_TEST(fresh.stats().enclosedAgain == 0u);
    colliding += !reference;
  }
  BOOST_TEST(colliding > 300);
  BOOST_TEST(kept.stats().enclosedAgain > 100u);
}

BOOST_AUTO_TEST_CASE(link_pose_beyond_the_doubles_is_reported) {
  // Two sliders in series along x: q = (1e308, 1e308) moves the cube to infinity (each value is a
  // finite double, their sum is not). isFree must not answer (free or not) from such a pose.
  World world = sliderPairWorld();
  Eigen::VectorXd q(2);
  q << 1e308, 1e308;
  checkThrowsWith([&] { world.isFree(q); }, "not finite");
}

BOOST_AUTO_TEST_SUITE_END()
