// State mappings (state_space.h): layouts the library does not understand are rejected by name;
// compounds of SO2 spaces (wrap-around joints), spaces named in another variable order and
// user-supplied mappings are read as the configurations they hold, by the validity checker, the
// motion validator and the path tools.

#include "bundled.h"

#include "deepcheck/fcl_reference/fcl_validity_checker.h"
#include "deepcheck/planners/motion_validator.h"
#include "deepcheck/planners/path_tools.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/planners/validity_checker.h"

#include <boost/test/unit_test.hpp>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/DiscreteStateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace dp = deepcheck::planners;
namespace ob = ompl::base;
namespace og = ompl::geometric;
using dp::test::bundledWorld;

namespace {

/// A compound of one SO2 space per variable of `model`, named `names[v]` when given.
ob::StateSpacePtr so2Compound(const deepcheck::robots::RobotModel& model, const std::vector<std::string>& names = {}) {
  auto space = std::make_shared<ob::CompoundStateSpace>();
  for (int v = 0; v < model.numVariables(); ++v) {
    auto so2 = std::make_shared<ob::SO2StateSpace>();
    if (!names.empty()) so2->setName(names[static_cast<std::size_t>(v)]);
    space->addSubspace(so2, 1.0);
  }
  space->setName("wrap_around_joints");
  space->lock();
  return space;
}

/// Sets the SO2 components of `state` to `values`, in component order.
void setComponents(ob::State* state, const Eigen::VectorXd& values) {
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    state->as<ob::CompoundState>()->as<ob::SO2StateSpace::StateType>(static_cast<unsigned int>(i))->value = values[i];
  }
}

/// The message of the std::invalid_argument `f` throws ("" when it throws nothing).
template <class F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

/// Bent forward into the shelf: joint 2 at 1.2 rad, the others 0 (the tool tests' colliding pose).
Eigen::VectorXd intoTheShelf() {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(7);
  q[1] = 1.2;
  return q;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(state_mapping)

BOOST_AUTO_TEST_CASE(layouts_that_are_not_understood_are_rejected_naming_the_space) {
  const auto world = bundledWorld("shelf");
  // SE3 + SO2 has the arm's dimension (7) but is not a joint space.
  auto se3 = std::make_shared<ob::CompoundStateSpace>();
  se3->setName("floating_base");
  se3->addSubspace(std::make_shared<ob::SE3StateSpace>(), 1.0);
  se3->addSubspace(std::make_shared<ob::SO2StateSpace>(), 1.0);
  se3->lock();
  auto si = std::make_shared<ob::SpaceInformation>(se3);
  std::string error = errorOf([&] { dp::StateValidityChecker(si, world); });
  BOOST_TEST(error.find("'floating_base'") != std::string::npos, error);
  BOOST_TEST(error.find("SE3") != std::string::npos, error);
  BOOST_TEST(error.find("SO3") != std::string::npos, error);  // the component that is not understood
  BOOST_TEST(error.find("StateMapping::custom") != std::string::npos, error);
  BOOST_TEST(!errorOf([&] { deepcheck::fcl_reference::FclStateValidityChecker(si, *world); }).empty());
  // A discrete space, and an SO2 compound with one value too few.
  auto discrete = std::make_shared<ob::SpaceInformation>(std::make_shared<ob::DiscreteStateSpace>(0, 6));
  error = errorOf([&] { dp::StateValidityChecker(discrete, world); });
  BOOST_TEST(error.find("Discrete") != std::string::npos, error);
  auto six = std::make_shared<ob::CompoundStateSpace>();
  for (int v = 0; v < 6; ++v) six->addSubspace(std::make_shared<ob::SO2StateSpace>(), 1.0);
  error = errorOf([&] { dp::StateValidityChecker(std::make_shared<ob::SpaceInformation>(six), world); });
  BOOST_TEST(error.find("holds 6 values") != std::string::npos, error);
  // Names of some variables but not all: which value is which cannot be told.
  std::vector<std::string> names = world->robot().variableNames();
  names[3] = "elbow";
  error = errorOf([&] { dp::makeStateMapping(*so2Compound(world->robot(), names), world->robot()); });
  BOOST_TEST(error.find("'elbow'") != std::string::npos, error);
  // A user mapping of the wrong size.
  const auto custom = dp::StateMapping::realVector(3, "three values");
  error = errorOf([&] {
    dp::StateValidityChecker(std::make_shared<ob::SpaceInformation>(dp::makeStateSpace(world->robot())), world, custom);
  });
  BOOST_TEST(error.find("three values") != std::string::npos, error);
}

BOOST_AUTO_TEST_CASE(a_compound_of_so2_spaces_is_read_as_the_joint_values) {
  // Each joint as an SO2 space (what a user writes for wrap-around joints). Read as a
  // RealVectorStateSpace, this state was valid with the clearance of the all-zeros configuration.
  const auto world = bundledWorld("shelf");
  auto si = std::make_shared<ob::SpaceInformation>(so2Compound(world->robot()));
  auto checker = std::make_shared<dp::StateValidityChecker>(si, world);
  si->setStateValidityChecker(checker);
  si->setup();
  const Eigen::VectorXd q = intoTheShelf();
  const double truth = world->signedDistance(q).closest.distance;
  BOOST_TEST_REQUIRE(truth < 0.0);
  ob::ScopedState<> state(si);
  setComponents(state.get(), q);
  BOOST_TEST((checker->mapping().configuration(state.get()) == q));
  BOOST_TEST(!checker->isValid(state.get()));
  BOOST_TEST(checker->clearance(state.get()) == truth);
  BOOST_TEST(checker->clearance(state.get()) < world->signedDistance(Eigen::VectorXd::Zero(7)).closest.distance);
  // Written back, angles are wrapped into [-pi, pi].
  Eigen::VectorXd turned = q;
  turned[0] = 3.5;
  checker->mapping().toState(turned, state.get());
  BOOST_TEST(state->as<ob::CompoundState>()->as<ob::SO2StateSpace::StateType>(0)->value == 3.5 - 2.0 * M_PI,
             boost::test_tools::tolerance(1e-12));
  // The valid-state overload pushes out into the same layout.
  setComponents(state.get(), dp::test::suggestedStart());
  BOOST_TEST(checker->isValid(state.get()));
}

BOOST_AUTO_TEST_CASE(motions_on_so2_joints_take_the_short_way_round) {
  // Joint 7 (limits +-3.054 rad) from 3.0 to -3.0: the SO2 space interpolates through pi, outside
  // the joint's limits, so the motion is invalid; the RealVector space goes the long way, through
  // 0, which is free.
  const auto world = bundledWorld("table");
  Eigen::VectorXd a = dp::test::suggestedStart();
  Eigen::VectorXd b = a;
  a[6] = 3.0;
  b[6] = -3.0;
  for (const bool wrap : {true, false}) {
    auto si = std::make_shared<ob::SpaceInformation>(wrap ? so2Compound(world->robot())
                                                          : ob::StateSpacePtr(dp::makeStateSpace(world->robot())));
    auto checker = std::make_shared<dp::StateValidityChecker>(si, world);
    si->setStateValidityChecker(checker);
    const auto bound = std::make_shared<const dp::LinkSpeedBound>(dp::LinkSpeedBound::forWorld(*world));
    si->setMotionValidator(std::make_shared<dp::ClearanceMotionValidator>(si, checker, bound));
    si->setup();
    ob::ScopedState<> s1(si), s2(si);
    checker->mapping().toState(a, s1.get());
    checker->mapping().toState(b, s2.get());
    BOOST_TEST_REQUIRE(si->isValid(s1.get()));
    BOOST_TEST_REQUIRE(si->isValid(s2.get()));
    const Eigen::VectorXd dq = checker->mapping().displacement(a, b);
    BOOST_TEST(std::abs(dq[6]) == (wrap ? 2.0 * M_PI - 6.0 : 6.0), boost::test_tools::tolerance(1e-12));
    BOOST_TEST(si->checkMotion(s1.get(), s2.get()) == !wrap, (wrap ? "SO2" : "RealVector"));
  }
}

BOOST_AUTO_TEST_CASE(values_named_after_variables_are_read_by_name) {
  // MoveIt-style: the values in another order than the URDF's, each named after its joint.
  const auto world = bundledWorld("shelf");
  std::vector<std::string> names = world->robot().variableNames();
  std::reverse(names.begin(), names.end());
  auto si = std::make_shared<ob::SpaceInformation>(so2Compound(world->robot(), names));
  const dp::StateValidityChecker checker(si, world);
  const Eigen::VectorXd q = intoTheShelf();
  ob::ScopedState<> state(si);
  setComponents(state.get(), q.reverse());
  BOOST_TEST((checker.mapping().configuration(state.get()) == q));
  BOOST_TEST(checker.clearance(state.get()) == world->signedDistance(q).closest.distance);
}

BOOST_AUTO_TEST_CASE(a_user_mapping_is_used_for_states_and_paths) {
  // A RealVector space holding the joints in reverse order, with a user mapping.
  const auto world = bundledWorld("table");
  const int n = world->robot().numVariables();
  auto space = dp::makeStateSpace(world->robot());  // same bounds in reverse order do not matter here
  auto si = std::make_shared<ob::SpaceInformation>(space);
  const dp::StateMapping reversed = dp::StateMapping::custom(
      n, [n](const ob::State* s, Eigen::Ref<Eigen::VectorXd> q) { q = dp::mapState(s, n).reverse(); },
      [n](const Eigen::Ref<const Eigen::VectorXd>& q, ob::State* s) { dp::mapState(s, n) = q.reverse(); }, {},
      "reversed joints");
  auto checker = std::make_shared<dp::StateValidityChecker>(si, world, reversed);
  si->setStateValidityChecker(checker);
  si->setup();
  const Eigen::VectorXd start = dp::test::suggestedStart();
  const Eigen::VectorXd goal = dp::test::suggestedGoal("table");
  og::PathGeometric path(si);
  ob::ScopedState<> state(si);
  for (const Eigen::VectorXd& q : {start, goal}) {
    reversed.toState(q, state.get());
    BOOST_TEST((dp::mapState(state.get(), n) == q.reverse()));
    path.append(state.get());
  }
  BOOST_TEST(checker->clearance(state.get()) == world->signedDistance(goal).closest.distance);
  const std::vector<Eigen::VectorXd> qs = dp::pathConfigurations(path);
  BOOST_TEST_REQUIRE(qs.size() == 2u);
  BOOST_TEST((qs[0] == start));
  BOOST_TEST((qs[1] == goal));
}

BOOST_AUTO_TEST_CASE(planning_on_so2_joints_gives_a_path_free_at_fine_resolution) {
  const auto world = bundledWorld("table");
  auto si = std::make_shared<ob::SpaceInformation>(so2Compound(world->robot()));
  auto checker = std::make_shared<dp::StateValidityChecker>(si, world);
  si->setStateValidityChecker(checker);
  si->setup();
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  ob::ScopedState<> start(si), goal(si);
  checker->mapping().toState(dp::test::suggestedStart(), start.get());
  checker->mapping().toState(dp::test::suggestedGoal("table"), goal.get());
  pdef->setStartAndGoalStates(start, goal);
  auto planner = std::make_shared<og::RRTConnect>(si);
  planner->setProblemDefinition(pdef);
  planner->setup();
  BOOST_TEST_REQUIRE(planner->solve(ob::timedPlannerTerminationCondition(20.0)) == ob::PlannerStatus::EXACT_SOLUTION);
  const auto& path = *pdef->getSolutionPath()->as<og::PathGeometric>();
  // Every state along the path (angles the short way round, as the planner moved), through the
  // world directly: within the limits and free up to the discrete checks' resolution.
  const dp::PathCheck fine = dp::checkPathFine(
      path, [&](const Eigen::VectorXd& q) { return checker->isValid(q); }, 0.002);
  BOOST_TEST(fine.invalidWaypoints == 0);
  BOOST_TEST(fine.statesChecked > static_cast<int>(path.getStateCount()));
}

BOOST_AUTO_TEST_SUITE_END()
