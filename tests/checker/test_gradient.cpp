// The gradient of the signed distance with respect to q against central finite differences, on
// configurations where the distance is differentiable: the same closest pair at q - h and q + h,
// and one-sided differences that agree (no contact change, no parallel faces, no tie between
// pairs in between). Robot-world pairs (only A moves) and self pairs (both move) both occur.

#include "checker_test_util.h"

#include "deepcheck/checker/world.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>

using namespace deepcheck;
using namespace deepcheck::checker;
using namespace deepcheck::checker::test;

namespace {

/// Finite-difference step (radians or metres).
constexpr double kStep = 1e-6;
/// One-sided differences closer than this count as "smooth here" (units of distance per radian).
constexpr double kSmooth = 1e-5;
/// Agreement of the gradient with the central difference. The central difference's truncation
/// error is O(h^2 * curvature) ~ 1e-12, its round-off ~ 1e-15 / h ~ 1e-9; the distance itself
/// carries GJK / DEEP round-off of the same order.
constexpr double kAgree = 1e-6;

struct GradientStats {
  int components = 0;
  int checked = 0;
  int separated = 0;
  int penetrating = 0;
  int selfPairs = 0;
  int worldPairs = 0;
};

/// Checks the gradient at q (component by component); returns false when q was skipped.
void checkAt(const World& world, World::Context& context, const Eigen::VectorXd& q, GradientStats& stats) {
  DistanceOptions withGradient;
  withGradient.gradient = true;
  const DistanceResult r = world.signedDistance(q, context, withGradient);
  if (!r.found) return;
  const Contact& c = r.closest;
  bool any = false;
  for (int v = 0; v < q.size(); ++v) {
    ++stats.components;
    Eigen::VectorXd qp = q;
    Eigen::VectorXd qm = q;
    qp[v] += kStep;
    qm[v] -= kStep;
    const DistanceResult rp = world.signedDistance(qp, context);
    const DistanceResult rm = world.signedDistance(qm, context);
    if (rp.closest.nameA != c.nameA || rp.closest.nameB != c.nameB || rm.closest.nameA != c.nameA ||
        rm.closest.nameB != c.nameB) {
      continue;
    }
    const double forward = (rp.closest.distance - c.distance) / kStep;
    const double backward = (c.distance - rm.closest.distance) / kStep;
    if (std::abs(forward - backward) > kSmooth) continue;
    const double central = (rp.closest.distance - rm.closest.distance) / (2 * kStep);
    BOOST_TEST(std::abs(c.gradient[v] - central) < kAgree,
               "q " << q.transpose() << " variable " << v << " pair " << c.nameA << " / " << c.nameB << " sd "
                    << c.distance << ": gradient " << c.gradient[v] << " central difference " << central);
    ++stats.checked;
    any = true;
  }
  if (!any) return;
  (c.distance > 0 ? stats.separated : stats.penetrating)++;
  (c.bodyB.kind == BodyRef::Kind::RobotLink ? stats.selfPairs : stats.worldPairs)++;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_gradient)

BOOST_AUTO_TEST_CASE(arm_against_obstacles_and_itself) {
  World world(armRobot(), testWorldOptions());
  addCrateBallPost(world);
  auto context = world.makeContext();
  std::mt19937 rng(20240611);
  GradientStats stats;
  for (int i = 0; i < 300; ++i) checkAt(world, context, randomConfiguration(world.robot(), rng), stats);
  // Most configurations are differentiable; both signs and both kinds of pair were exercised.
  BOOST_TEST(stats.checked > stats.components / 2);
  BOOST_TEST(stats.separated > 10);
  BOOST_TEST(stats.penetrating > 10);
  BOOST_TEST(stats.worldPairs > 10);
}

BOOST_AUTO_TEST_CASE(self_pairs_move_both_links) {
  // No obstacles: only self pairs; the arm folded back over its base.
  World world(armRobot(), testWorldOptions());
  auto context = world.makeContext();
  std::mt19937 rng(7);
  GradientStats stats;
  for (int i = 0; i < 300; ++i) checkAt(world, context, randomConfiguration(world.robot(), rng), stats);
  BOOST_TEST(stats.selfPairs > 50);
  BOOST_TEST(stats.checked > stats.components / 2);
  BOOST_TEST(stats.penetrating > 5);
}

BOOST_AUTO_TEST_CASE(moving_along_the_gradient_increases_the_distance) {
  World world(armRobot(), testWorldOptions());
  world.addObstacle(Obstacle::box("wall", Eigen::Vector3d(0.1, 2, 2), translation(0.45, 0, 0.5)));
  auto context = world.makeContext();
  std::mt19937 rng(11);
  DistanceOptions withGradient;
  withGradient.gradient = true;
  int tested = 0;
  for (int i = 0; i < 200; ++i) {
    const Eigen::VectorXd q = randomConfiguration(world.robot(), rng);
    const DistanceResult r = world.signedDistance(q, context, withGradient);
    const double g = r.closest.gradient.norm();
    if (!r.found || g < 1e-3) continue;
    const double step = 1e-4;
    const DistanceResult moved = world.signedDistance(q + step * r.closest.gradient / g, context);
    // First order: sd grows by about step * |g| (the minimum may switch pairs: at most that much).
    BOOST_TEST(moved.closest.distance > r.closest.distance + 0.5 * step * g - 1e-7,
               "q " << q.transpose() << " sd " << r.closest.distance << " -> " << moved.closest.distance);
    ++tested;
  }
  BOOST_TEST(tested > 100);
}

BOOST_AUTO_TEST_CASE(panda_in_the_kitchen) {
  if (!haveShared("panda_in_the_kitchen")) return;
  World world(loadPanda(), testWorldOptions());
  world.addScene(loadKitchen());
  auto context = world.makeContext();
  std::mt19937 rng(3);
  GradientStats stats;
  for (int i = 0; i < 150; ++i) checkAt(world, context, randomConfiguration(world.robot(), rng), stats);
  BOOST_TEST(stats.checked > stats.components / 3);
  BOOST_TEST(stats.separated > 5);
  BOOST_TEST(stats.penetrating > 5);
}

BOOST_AUTO_TEST_SUITE_END()
