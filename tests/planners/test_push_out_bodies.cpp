// Push-out with the body depth (PushOutOptions::bodyDepth) against the pairwise depth, on the hard
// cases of issue 38 (tests/common/body_cases.h): a box tool pressed into a slab of two touching
// boxes, a peg lowered into a U of three boxes, each body one scene link of several pieces.

#include "bundled.h"

#include "common/body_cases.h"

#include "deepcheck/planners/push_out.h"
#include "deepcheck/planners/validity.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <memory>
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

BOOST_AUTO_TEST_CASE(body_depth_is_asked_for) { BOOST_TEST(!dp::PushOutOptions{}.bodyDepth); }

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
  BOOST_TEST((!pairwise.success() || pairwise.iterations > 1), "pairwise: " << pairwise.status << " in "
                                                                           << pairwise.iterations << " iterations");
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
  BOOST_TEST((!pairwise.success() || pairwise.iterations > 1), "pairwise: " << pairwise.status << " in "
                                                                           << pairwise.iterations << " iterations");
}

BOOST_AUTO_TEST_SUITE_END()
