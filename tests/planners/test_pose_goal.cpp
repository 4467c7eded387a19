// Pose goals: collision-free IK solutions in the bundled shelf, and RRTConnect planning to a pose
// inside a shelf compartment through the PoseGoal region (a planning run, a few seconds).

#include "bundled.h"

#include "deepcheck/planners/path_tools.h"
#include "deepcheck/planners/pose_goal.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/robots/kinematics.h"

#include <boost/test/unit_test.hpp>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <random>
#include <stdexcept>
#include <string>

namespace dp = deepcheck::planners;
namespace dr = deepcheck::robots;
namespace ob = ompl::base;
namespace og = ompl::geometric;
using dp::test::bundledWorld;

namespace {

/// A cap on the planning run, seconds: RRTConnect finds this path in well under a second.
constexpr double kPoseGoalTimeCap = 5.0;

/// The flange pose of the suggested shelf goal: the hand inside the middle-row compartment.
Eigen::Isometry3d shelfGoalPose(const dr::RobotModel& arm) {
  return dr::forwardKinematics(arm, dp::test::suggestedGoal("shelf"))[arm.linkIndex("flange")];
}

}  // namespace

BOOST_AUTO_TEST_SUITE(planners_pose_goal)

BOOST_AUTO_TEST_CASE(collision_free_solutions_only) {
  const auto world = bundledWorld("shelf");
  auto ss = dp::makeSimpleSetup(world, dp::test::bundledOptions());
  const auto checker = dp::validityCheckerOf(*ss);
  const dr::RobotModel& arm = world->robot();
  // Random flange poses of random configurations: every converged answer reaches the pose and is
  // valid; rejected solutions (in collision) are never returned as solutions.
  std::mt19937_64 rng(11);
  int converged = 0;
  int rejected = 0;
  for (int trial = 0; trial < 30; ++trial) {
    const Eigen::VectorXd qTarget = dp::test::randomConfiguration(arm, rng);
    const Eigen::Isometry3d X_WT = dr::forwardKinematics(arm, qTarget)[arm.linkIndex("flange")];
    dr::IkOptions options;
    options.seed = trial;
    options.maxRestarts = 10;
    const dr::IkResult result = dp::solveCollisionFree(*checker, "flange", X_WT, options);
    rejected += result.rejected;
    if (!result.converged()) continue;
    ++converged;
    BOOST_TEST(checker->isValid(result.q));
    BOOST_TEST(dr::poseError(arm, arm.linkIndex("flange"), result.q, X_WT, options).within());
  }
  BOOST_TEST(converged >= 10);
  BOOST_TEST(rejected >= 1);  // random configurations in the shelf scene often collide
}

BOOST_AUTO_TEST_CASE(pose_inside_a_board_has_no_valid_solution) {
  const auto world = bundledWorld("shelf");
  auto ss = dp::makeSimpleSetup(world, dp::test::bundledOptions());
  const auto checker = dp::validityCheckerOf(*ss);
  // The flange at the centre of the middle board (z 0.40 .. 0.42), in the middle of its depth:
  // the hand, fingers and flange all lie inside or through the board.
  Eigen::Isometry3d X_WT = shelfGoalPose(world->robot());
  X_WT.translation() = Eigen::Vector3d(0.78, 0.22, 0.41);
  dr::IkOptions options;
  options.maxRestarts = 10;
  const dr::IkResult result = dp::solveCollisionFree(*checker, "flange", X_WT, options);
  BOOST_TEST(!result.converged());
  BOOST_TEST(std::string(dr::toString(result.status)) == dr::toString(dr::IkStatus::Rejected));
  BOOST_TEST(!checker->isValid(result.q));
}

// Plans: labelled integration (tests/CMakeLists.txt).
BOOST_AUTO_TEST_CASE(rrt_connect_plans_to_a_pose_in_the_shelf, *boost::unit_test::label("integration")) {
  const auto world = bundledWorld("shelf");
  auto ss = dp::makeSimpleSetup(world, dp::test::bundledOptions());
  const dr::RobotModel& arm = world->robot();
  const Eigen::Isometry3d X_WT = shelfGoalPose(arm);
  ob::ScopedState<> start(ss->getStateSpace());
  dp::copyToState(dp::test::suggestedStart(), start.get());
  ss->setStartState(start);
  dp::PoseGoalOptions options;
  options.ik.seed = 5;
  auto goal = std::make_shared<dp::PoseGoal>(ss->getSpaceInformation(), "flange", X_WT, options);
  ss->setGoal(goal);
  ss->setPlanner(std::make_shared<og::RRTConnect>(ss->getSpaceInformation()));
  const ob::PlannerStatus status = ss->solve(kPoseGoalTimeCap);
  const bool exact = status == ob::PlannerStatus::EXACT_SOLUTION;
  BOOST_TEST_REQUIRE(exact, "status " << status.asString());
  const og::PathGeometric& path = ss->getSolutionPath();
  const ob::State* last = path.getState(path.getStateCount() - 1);
  const dr::PoseError error = goal->poseError(last);
  BOOST_TEST(error.position <= options.ik.positionTolerance, error.position << " m");
  BOOST_TEST(error.orientation <= options.ik.orientationTolerance, error.orientation << " rad");
  BOOST_TEST(goal->isSatisfied(last));
  BOOST_TEST(dp::validityCheckerOf(*ss)->isValid(last));
  BOOST_TEST(dp::checkPathWithPlanner(path).valid);
  BOOST_TEST(goal->ikCalls() >= 1);
}

BOOST_AUTO_TEST_CASE(bad_goals_are_named) {
  const auto world = bundledWorld("shelf");
  auto ss = dp::makeSimpleSetup(world, dp::test::bundledOptions());
  const Eigen::Isometry3d X_WT = shelfGoalPose(world->robot());
  const auto throwsWith = [&](const std::string& link, const dp::PoseGoalOptions& options, const std::string& part) {
    try {
      dp::PoseGoal goal(ss->getSpaceInformation(), link, X_WT, options);
      BOOST_ERROR("no exception for " << part);
    } catch (const std::invalid_argument& e) {
      BOOST_TEST(std::string(e.what()).find(part) != std::string::npos, e.what());
    }
  };
  throwsWith("tool0", {}, "no link named 'tool0'");
  dp::PoseGoalOptions options;
  options.ik.positionTolerance = -1.0;
  throwsWith("flange", options, "positionTolerance (m) is -1");
  options = {};
  options.maxGoalStates = 0;
  throwsWith("flange", options, "maxGoalStates is 0");
  auto plain = std::make_shared<ob::SpaceInformation>(ss->getStateSpace());
  plain->setStateValidityChecker([](const ob::State*) { return true; });
  BOOST_CHECK_THROW(dp::PoseGoal(plain, "flange", X_WT), std::invalid_argument);
}

BOOST_AUTO_TEST_SUITE_END()
