// Clearance objectives: the hinge state and motion costs, the combination with path length, and
// OMPL's MaximizeMinClearanceObjective on our clearance (with RRT*).

#include "bundled.h"

#include "deepcheck/planners/objectives.h"
#include "deepcheck/planners/path_tools.h"
#include "deepcheck/planners/planner_factory.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/state_space.h"

#include <boost/test/unit_test.hpp>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace dp = deepcheck::planners;
namespace ob = ompl::base;
namespace og = ompl::geometric;
using dp::test::bundledWorld;
using dp::test::randomConfiguration;

namespace {

/// Stops after `iterations` evaluations (RRT* evaluates it once per iteration): the same amount of
/// work on every machine, whatever its load, so that pinned seeds give the same trees.
ob::PlannerTerminationCondition iterationLimit(int iterations) {
  auto count = std::make_shared<int>(0);
  return ob::PlannerTerminationCondition([count, iterations] { return ++*count > iterations; });
}

}  // namespace

BOOST_AUTO_TEST_SUITE(objectives)

BOOST_AUTO_TEST_CASE(hinge_state_cost_is_max_of_zero_and_safe_distance_minus_clearance) {
  const auto world = bundledWorld("shelf");
  auto ss = dp::makeSimpleSetup(world, dp::test::bundledOptions());
  const auto checker = dp::validityCheckerOf(*ss);
  const dp::ClearanceHingeObjective hinge(ss->getSpaceInformation(), checker, 0.05);
  ob::ScopedState<> state(ss->getStateSpace());
  std::mt19937_64 rng(21);
  int inside = 0;
  int outside = 0;
  for (int i = 0; i < 200; ++i) {
    const Eigen::VectorXd q = randomConfiguration(world->robot(), rng);
    dp::copyToState(q, state.get());
    const dp::SplitDistance sd = checker->splitClearanceUpTo(q, std::numeric_limits<double>::infinity());
    BOOST_TEST(std::abs(std::min(sd.world, sd.self) - checker->clearance(q)) <= 1e-12);
    const double cost = hinge.stateCost(state.get()).value();
    BOOST_TEST(cost >= 0.0);
    if (sd.world >= 0.05 && sd.self >= 0.0) {
      ++outside;
      BOOST_TEST(cost == 0.0);
    } else {
      ++inside;
      // Penetrating states pay d_safe + depth; self pairs (d_self = 0) only their depth.
      BOOST_TEST(std::abs(cost - std::max(0.05 - sd.world, -sd.self)) <= 1e-9);
    }
  }
  BOOST_TEST(inside > 20);
  BOOST_TEST(outside > 20);
  BOOST_CHECK_THROW(dp::ClearanceHingeObjective(ss->getSpaceInformation(), checker, -0.01), std::invalid_argument);
  BOOST_CHECK_THROW(dp::ClearanceHingeObjective(ss->getSpaceInformation(), nullptr), std::invalid_argument);
  dp::ClearanceHingeObjective self(ss->getSpaceInformation(), checker, 0.05);
  BOOST_CHECK_THROW(self.setSelfSafeDistance(std::nan("")), std::invalid_argument);
  self.setSelfSafeDistance(0.01);
  const Eigen::VectorXd q = dp::test::suggestedStart();
  dp::copyToState(q, state.get());
  const dp::SplitDistance d = checker->splitClearanceUpTo(q, std::numeric_limits<double>::infinity());
  BOOST_TEST(self.stateCost(state.get()).value() == std::max({0.0, 0.05 - d.world, 0.01 - d.self}));
  BOOST_CHECK_THROW(dp::makeLengthClearanceObjective(ss->getSpaceInformation(), checker, 0.05, std::nan("")),
                    std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(motion_cost_integrates_the_hinge_and_the_bound_only_skips_zero_cost) {
  const auto world = bundledWorld("shelf");
  auto ss = dp::makeSimpleSetup(world, dp::test::bundledOptions());
  const auto si = ss->getSpaceInformation();
  const auto checker = dp::validityCheckerOf(*ss);
  const double resolution = 0.01;
  const dp::ClearanceHingeObjective plain(si, checker, 0.05, nullptr, resolution);
  const dp::ClearanceHingeObjective bounded(si, checker, 0.05, dp::linkSpeedBoundOf(*ss), resolution);
  ob::ScopedState<> a(si), b(si);
  std::mt19937_64 rng(22);
  int skipped = 0;
  // Penetration depths depend slightly on each query's warm start (DEEP may end a warm walk in a
  // local minimum, deep.h): the same state asked twice may differ where it penetrates. Costs must
  // agree to within kSpread relative, and bit for bit (1e-9) on most motions.
  constexpr double kSpread = 0.02;
  int inexact = 0;
  const auto same = [&](double x, double y) {
    const double d = std::abs(x - y);
    inexact += d > 1e-9;
    return d <= 1e-9 + kSpread * std::max(std::abs(x), std::abs(y));
  };
  for (int i = 0; i < 60; ++i) {
    const Eigen::VectorXd qa = randomConfiguration(world->robot(), rng);
    const Eigen::VectorXd qb = qa + 0.3 * (randomConfiguration(world->robot(), rng) - qa);
    dp::copyToState(qa, a.get());
    dp::copyToState(qb, b.get());
    const double withoutBound = plain.motionCost(a.get(), b.get()).value();
    const double withBound = bounded.motionCost(a.get(), b.get()).value();
    BOOST_TEST(same(withoutBound, withBound), withoutBound << " vs " << withBound);  // skips only zero costs
    skipped += withBound == 0.0;
    // The trapezoid rule on the same states by hand.
    const int segments = std::max(1, static_cast<int>(std::ceil((qb - qa).norm() / resolution)));
    double sum = 0.0;
    for (int k = 0; k <= segments; ++k) {
      const dp::SplitDistance d =
          checker->splitClearanceUpTo(qa + (double(k) / segments) * (qb - qa), std::numeric_limits<double>::infinity());
      const double h = std::max({0.0, 0.05 - d.world, -d.self});
      sum += (k == 0 || k == segments) ? 0.5 * h : h;
    }
    BOOST_TEST(same(withoutBound, sum * (qb - qa).norm() / segments));
  }
  BOOST_TEST_MESSAGE("motion costs: " << skipped << " of 60 skipped by the bound, " << inexact
                                      << " of 120 comparisons above 1e-9");
  BOOST_TEST(skipped > 5);
  BOOST_TEST(inexact <= 12);
}

BOOST_AUTO_TEST_CASE(length_clearance_objective_is_length_plus_weighted_hinge) {
  // A bare SpaceInformation, no SimpleSetup: this test draws no seed from OMPL's seed generator
  // (SimpleSetup's path simplifier would), so the planning tests after it keep their samples.
  const auto world = bundledWorld("shelf");
  auto si = std::make_shared<ob::SpaceInformation>(dp::makeStateSpace(world->robot()));
  auto checker = std::make_shared<dp::StateValidityChecker>(si, world);
  si->setStateValidityChecker(checker);
  si->setup();
  const double weight = 10.0;
  const auto combined = dp::makeLengthClearanceObjective(si, checker, 0.05, weight, nullptr, 0.01);
  const dp::ClearanceHingeObjective hinge(si, checker, 0.05, nullptr, 0.01);
  ob::ScopedState<> a(si), b(si);
  // From the suggested start into the shelf: the motion ends within d_safe of the shelf.
  dp::copyToState(dp::test::suggestedStart(), a.get());
  dp::copyToState(dp::test::suggestedGoal("shelf"), b.get());
  const double length = si->distance(a.get(), b.get());
  const double h = hinge.motionCost(a.get(), b.get()).value();
  BOOST_TEST(h > 0.0);
  BOOST_TEST(combined->motionCost(a.get(), b.get()).value() == length + weight * h,
             boost::test_tools::tolerance(1e-9));
  BOOST_TEST(combined->stateCost(b.get()).value() == weight * hinge.stateCost(b.get()).value(),
             boost::test_tools::tolerance(1e-9));
  // The path length's heuristic, admissible since the hinge is >= 0.
  BOOST_TEST(combined->motionCostHeuristic(a.get(), b.get()).value() == length);
}

BOOST_AUTO_TEST_CASE(maximize_min_clearance_objective_reads_our_clearance) {
  const auto world = bundledWorld("table");
  auto ss = dp::makeSimpleSetup(world, dp::test::bundledOptions());
  const auto objective = dp::makeMaxMinClearanceObjective(ss->getSpaceInformation());
  ob::ScopedState<> state(ss->getStateSpace());
  dp::copyToState(dp::test::suggestedStart(), state.get());
  BOOST_TEST(objective->stateCost(state.get()).value() == dp::validityCheckerOf(*ss)->clearance(dp::test::suggestedStart()));
  // RRT* maximizing the minimum clearance returns a path whose cost is its smallest clearance.
  dp::setStartAndGoal(*ss, dp::test::suggestedStart(), dp::test::suggestedGoal("table"));
  ss->setOptimizationObjective(objective);
  ss->setPlanner(dp::makePlanner("RRT*", ss->getSpaceInformation()));
  BOOST_TEST_REQUIRE(ss->solve(iterationLimit(300)) == ob::PlannerStatus::EXACT_SOLUTION);
  const og::PathGeometric& path = ss->getSolutionPath();
  const double cost = path.cost(objective).value();
  const auto checker = dp::validityCheckerOf(*ss);
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < path.getStateCount(); ++i) {
    smallest = std::min(smallest, checker->clearance(dp::mapState(path.getState(i), 7)));
  }
  BOOST_TEST(cost > 0.0);
  BOOST_TEST(cost <= smallest + 1e-12);  // the minimum over the waypoints and interpolated states
}

BOOST_AUTO_TEST_SUITE_END()
