// Push-out with the body depth (PushOutOptions::bodyDepth) against the pairwise depth, on the hard
// cases (tests/common/body_cases.h): a box tool pressed into a slab of two touching boxes, a peg
// lowered into a U of three boxes, each body one scene link of several pieces; and the cap on a
// body query's cost on random starts of the bundled arm.

#include "bundled.h"

#include "common/body_cases.h"

#include "deepcheck/planners/push_out.h"
#include "deepcheck/planners/validity.h"
#include "deepcheck/robots/random_configuration.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>

namespace dc = deepcheck::checker;
namespace dp = deepcheck::planners;
namespace dt = deepcheck::test;

namespace {

std::shared_ptr<const dc::World> gantryIn(const std::string& link, const std::string& collisions) {
  auto world = std::make_shared<dc::World>(dt::gantryRobot(dt::toolBox()));
  world->addScene(dt::sceneOf(link, collisions), Eigen::Isometry3d::Identity());
  return world;
}

dp::PushOutResult pushOut(const std::shared_ptr<const dc::World>& world, const Eigen::VectorXd& q, bool bodyDepth) {
  dp::PushOutOptions options;
  options.bodyDepth = bodyDepth;
  return dp::PushOut(world, {}, options).run(q);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(planners_push_out_bodies)

BOOST_AUTO_TEST_CASE(body_depth_is_the_default_with_a_finite_cap) {
  const dp::PushOutOptions options;
  BOOST_TEST(options.bodyDepth);
  BOOST_TEST(std::isfinite(options.bodyBuildCost));
  BOOST_TEST(options.bodyBuildCost > 0.0);
  for (double bad : {-1.0, std::numeric_limits<double>::quiet_NaN()}) {
    dp::PushOutOptions o;
    o.bodyBuildCost = bad;
    BOOST_CHECK_EXCEPTION(dp::checkPushOutOptions(o), std::invalid_argument, [](const std::invalid_argument& e) {
      return std::string(e.what()).find("bodyBuildCost") != std::string::npos;
    });
  }
}

// The tool 0.04 deep in the slab, 0.005 off the seam: each pair's depth points sideways (into the
// other box), the slab's as one body straight up. The body answer lifts the tool out in one step,
// hardly moving it sideways; the pairwise one needs more.
BOOST_AUTO_TEST_CASE(slab_is_left_in_one_step_with_the_body_depth) {
  const auto world = gantryIn("slab", dt::slabCollisions());
  const Eigen::VectorXd start = dt::gantryQ(0.005, 0, 0.01);
  const dp::PushOutResult body = pushOut(world, start, true);
  BOOST_TEST(body.status == dp::PushOutStatus::Repaired);
  BOOST_TEST(body.iterations == 1);
  BOOST_TEST(body.initialDistance == -0.04, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(dp::isConfigurationValid(*world, body.q, {}));
  BOOST_TEST(body.q[2] > 0.05);                       // the tool's bottom above the slab's top
  BOOST_TEST(std::abs(body.q[0] - start[0]) < 1e-3);  // not pushed sideways
  const dp::PushOutResult pairwise = pushOut(world, start, false);
  BOOST_TEST((!pairwise.success() || pairwise.iterations > 1),
             "pairwise: " << pairwise.status << " in " << pairwise.iterations << " iterations");
  BOOST_TEST(pairwise.initialDistance == -0.035, boost::test_tools::tolerance(1e-9));
}

// The peg 0.03 below the top of the U's walls, each wall overlapping it by about 0.005: the walls
// push it towards each other; the U as one body lifts it out in one step.
BOOST_AUTO_TEST_CASE(peg_is_lifted_out_of_the_u_in_one_step_with_the_body_depth) {
  const auto world = gantryIn("u", dt::uCollisions());
  const Eigen::VectorXd start = dt::gantryQ(0.001, 0, 0.12);
  const dp::PushOutResult body = pushOut(world, start, true);
  BOOST_TEST(body.status == dp::PushOutStatus::Repaired);
  BOOST_TEST(body.iterations == 1);
  BOOST_TEST(body.q[2] > 0.15);  // the peg's bottom above the walls
  const dp::PushOutResult pairwise = pushOut(world, start, false);
  BOOST_TEST((!pairwise.success() || pairwise.iterations > 1),
             "pairwise: " << pairwise.status << " in " << pairwise.iterations << " iterations");
}

// Random colliding starts of the bundled arm (links and scene objects of many pieces), as deep as
// the push-out starts from, pushed out with the pairwise depth and with the body depth under no
// cap, the default cap and a cap of 0 (every body query that needs a Minkowski difference falls
// back on the pairwise answer): a start the push-out calls repaired is valid, and every start the
// pairwise push-out repairs, the body-depth push-out repairs too (its pairwise retry).
BOOST_AUTO_TEST_CASE(body_depth_push_outs_repair_what_the_pairwise_one_does) {
  const auto world = dp::test::bundledWorld("shelf");
  std::mt19937_64 rng(20261129);
  const double inf = std::numeric_limits<double>::infinity();
  const double caps[] = {inf, dp::PushOutOptions{}.bodyBuildCost, 0.0};
  int starts = 0;
  int repaired = 0;
  while (starts < 40) {
    const Eigen::VectorXd q = deepcheck::robots::randomConfiguration(world->robot(), rng);
    const double sd = dp::signedDistanceUpTo(*world, q, 1e-3);
    if (!(sd < 0.0 && sd >= -dp::PushOutOptions{}.maxDepth)) continue;
    ++starts;
    dp::PushOutOptions pairwiseOptions;
    pairwiseOptions.bodyDepth = false;
    const dp::PushOutResult pairwise = dp::PushOut(world, {}, pairwiseOptions).run(q);
    repaired += pairwise.success() ? 1 : 0;
    for (double cap : caps) {
      dp::PushOutOptions options;
      options.bodyBuildCost = cap;
      const dp::PushOutResult r = dp::PushOut(world, {}, options).run(q);
      BOOST_TEST_CONTEXT("cap " << cap << " start " << starts) {
        if (pairwise.success()) BOOST_TEST(r.success());
        if (r.success()) BOOST_TEST(dp::isConfigurationValid(*world, r.q, {}));
        BOOST_TEST((r.status == dp::PushOutStatus::TooDeep) == (pairwise.status == dp::PushOutStatus::TooDeep));
      }
    }
  }
  BOOST_TEST(repaired >= 30);
}

BOOST_AUTO_TEST_SUITE_END()
