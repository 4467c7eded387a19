// Optimizing planners with the clearance objective (objectives.h: path length + the clearance
// hinge) on a real arm: RRT*, BIT* and PRM* each find a valid, certified path on an easy UR5
// problem within a planning time of 2 s. Before prepareForCostlyObjective shortened RRT*'s range
// and the objective sampled BIT*'s informed set directly, RRT* asked the hinge integral of the
// motion to most of its tree for every new node and BIT* sampled by rejection for seconds past its
// time budget (docs/planners.md, "Optimizing planners and the clearance objective").

#include "deepcheck/planners/objectives.h"
#include "deepcheck/planners/path_tools.h"
#include "deepcheck/planners/planner_factory.h"
#include "deepcheck/planners/setup.h"
#include "shared_robots.h"

#include <boost/test/unit_test.hpp>

#include <ompl/base/ScopedState.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>

#include <memory>
#include <string>

namespace dp = deepcheck::planners;
namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

/// The UR5 of the shared data (its SRDF) and a pole, radius 4 cm, 0.4 m tall, 0.55 m in front of
/// it; loaded once.
std::shared_ptr<const deepcheck::checker::World> ur5WithPole() {
  static std::shared_ptr<const deepcheck::checker::World> cached;
  if (cached) return cached;
  const dp::test::SharedRobot ur5 = dp::test::sharedUr5();
  auto world = dp::loadWorld(ur5.urdf, {}, ur5.options);
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  X_WO.translation() = Eigen::Vector3d(0.55, 0.0, 0.2);
  world->addObstacle(deepcheck::checker::Obstacle::cylinder("pole", 0.04, 0.4, X_WO));
  cached = world;
  return cached;
}

/// Plans the easy problem (the arm raised, to a pose 2.5 rad round) with `planner` and the
/// clearance objective set as `deepcheck plan --objective clearance` sets it, for 2 s.
void planWithClearance(const std::string& planner) {
  auto ss = dp::makeSimpleSetup(ur5WithPole());
  Eigen::VectorXd start(6), goal(6);
  start << 0, -1.57, 1.57, 0, 0, 0;
  goal << 2.5, -1.0, 1.0, 0.5, 0.5, 0;
  dp::setStartAndGoal(*ss, start, goal);
  const ob::SpaceInformationPtr& si = ss->getSpaceInformation();
  ss->setOptimizationObjective(
      dp::makeLengthClearanceObjective(si, dp::validityCheckerOf(*ss), dp::tol::kDefaultSafeDistance,
                                       dp::tol::kDefaultHingeWeight, dp::linkSpeedBoundOf(*ss)));
  const ob::PlannerPtr p = dp::makePlanner(planner, si);
  dp::prepareForCostlyObjective(*p);
  ss->setPlanner(p);
  BOOST_TEST_REQUIRE(ss->solve(2.0) == ob::PlannerStatus::EXACT_SOLUTION, planner);
  og::PathGeometric& path = ss->getSolutionPath();
  BOOST_TEST(dp::checkPathWithPlanner(path).valid, planner);
  BOOST_TEST(dp::certifyPath(*ss, path).valid, planner);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(planners_clearance_planners)

BOOST_AUTO_TEST_CASE(rrt_star_solves_an_easy_ur5_problem_with_the_clearance_objective,
                     *boost::unit_test::label("integration")) {
  if (!deepcheck::test::haveShared("rrt_star_solves_an_easy_ur5_problem_with_the_clearance_objective")) return;
  planWithClearance("RRT*");
}

BOOST_AUTO_TEST_CASE(bit_star_solves_an_easy_ur5_problem_with_the_clearance_objective,
                     *boost::unit_test::label("integration")) {
  if (!deepcheck::test::haveShared("bit_star_solves_an_easy_ur5_problem_with_the_clearance_objective")) return;
  planWithClearance("BIT*");
}

BOOST_AUTO_TEST_CASE(prm_star_solves_an_easy_ur5_problem_with_the_clearance_objective,
                     *boost::unit_test::label("integration")) {
  if (!deepcheck::test::haveShared("prm_star_solves_an_easy_ur5_problem_with_the_clearance_objective")) return;
  planWithClearance("PRM*");
}

// The two cases below plan nothing but load the UR5 and draw from OMPL's pinned random sequence;
// labelled integration so that the unit run's draws stay as they were (see docs/testing.md: the
// simplification case of test_objectives.cpp depends on them).
BOOST_AUTO_TEST_CASE(costly_objectives_shorten_rrt_stars_range_unless_it_is_set,
                     *boost::unit_test::label("integration")) {
  if (!deepcheck::test::haveShared("costly_objectives_shorten_rrt_stars_range_unless_it_is_set")) return;
  auto ss = dp::makeSimpleSetup(ur5WithPole());
  const ob::SpaceInformationPtr& si = ss->getSpaceInformation();
  og::RRTstar rrtStar(si);
  BOOST_TEST(dp::prepareForCostlyObjective(rrtStar));
  BOOST_TEST(rrtStar.getRange() == dp::tol::kCostlyObjectiveRangeFraction * si->getMaximumExtent());
  BOOST_TEST(rrtStar.getRange() < 1.2);  // 28.8 rad across: OMPL's 0.2 would be 5.76 rad
  og::RRTstar chosen(si);
  chosen.setRange(3.0);
  dp::prepareForCostlyObjective(chosen);
  BOOST_TEST(chosen.getRange() == 3.0);  // a range the user set is kept
}

BOOST_AUTO_TEST_CASE(the_clearance_objective_samples_the_informed_set_of_path_length_directly,
                     *boost::unit_test::label("integration")) {
  if (!deepcheck::test::haveShared("the_clearance_objective_samples_the_informed_set_of_path_length_directly")) return;
  auto ss = dp::makeSimpleSetup(ur5WithPole());
  Eigen::VectorXd start(6), goal(6);
  start << 0, -1.57, 1.57, 0, 0, 0;
  goal << 2.5, -1.0, 1.0, 0.5, 0.5, 0;
  dp::setStartAndGoal(*ss, start, goal);
  const ob::SpaceInformationPtr& si = ss->getSpaceInformation();
  const auto objective = dp::makeLengthClearanceObjective(si, dp::validityCheckerOf(*ss));
  ss->setOptimizationObjective(objective);
  const ob::InformedSamplerPtr sampler = objective->allocInformedStateSampler(ss->getProblemDefinition(), 100);
  BOOST_TEST_REQUIRE(sampler->hasInformedMeasure());  // the rejection sampler has none
  // Every sample within a cost bound c lies on a path at most c long: start -> x -> goal.
  const double c = 1.2 * si->distance(ss->getProblemDefinition()->getStartState(0),
                                      ss->getProblemDefinition()->getGoal()->as<ob::GoalState>()->getState());
  ob::ScopedState<> x(si);
  for (int i = 0; i < 100; ++i) {
    BOOST_TEST_REQUIRE(sampler->sampleUniform(x.get(), ob::Cost(c)));
    const double through =
        si->distance(ss->getProblemDefinition()->getStartState(0), x.get()) +
        si->distance(x.get(), ss->getProblemDefinition()->getGoal()->as<ob::GoalState>()->getState());
    BOOST_TEST(through <= c * (1.0 + 1e-9));
  }
}

BOOST_AUTO_TEST_SUITE_END()
