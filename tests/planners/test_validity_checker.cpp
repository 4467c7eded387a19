// State space and state validity checker: agreement with the World, clearance sign, options,
// the valid-state overload, thread safety.

#include "bundled.h"

#include "deepcheck/planners/state_space.h"
#include "deepcheck/planners/validity_checker.h"

#include <boost/test/unit_test.hpp>

#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace dp = deepcheck::planners;
namespace ob = ompl::base;
using dp::test::bundledWorld;

namespace {

/// Two evaluations of the same distance with different warm starts (another thread's context, the
/// same context later) agree to round-off: metres, absolute.
constexpr double kSameDistance = 1e-9;

bool mentions(const std::exception& e, const std::string& word) {
  return std::string(e.what()).find(word) != std::string::npos;
}

std::vector<Eigen::VectorXd> randomConfigurations(const deepcheck::robots::RobotModel& model, int count,
                                                  std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Eigen::VectorXd> out;
  for (int i = 0; i < count; ++i) out.push_back(dp::test::randomConfiguration(model, rng));
  return out;
}

/// The first configuration whose signed distance is in [lo, hi).
Eigen::VectorXd configurationWithDistance(const deepcheck::checker::World& world, double lo, double hi) {
  for (const Eigen::VectorXd& q : randomConfigurations(world.robot(), 200000, 99)) {
    const double sd = dp::signedDistanceUpTo(world, q, hi + 1.0);
    if (sd >= lo && sd < hi) return q;
  }
  throw std::runtime_error("no configuration with the wanted distance");
}

ob::SpaceInformationPtr spaceFor(const deepcheck::checker::World& world) {
  return std::make_shared<ob::SpaceInformation>(dp::makeStateSpace(world.robot()));
}

}  // namespace

BOOST_AUTO_TEST_SUITE(planners_validity_checker)

BOOST_AUTO_TEST_CASE(state_space_has_the_urdf_limits_and_names) {
  const auto world = bundledWorld("shelf");
  const auto& model = world->robot();
  // No continuous joint: a plain RealVectorStateSpace (state_space.h).
  const auto space = std::dynamic_pointer_cast<ob::RealVectorStateSpace>(dp::makeStateSpace(model));
  BOOST_TEST_REQUIRE(space != nullptr);
  BOOST_TEST(space->getDimension() == 7u);
  for (int v = 0; v < 7; ++v) {
    BOOST_TEST(space->getBounds().low[v] == model.lowerLimits()[v]);
    BOOST_TEST(space->getBounds().high[v] == model.upperLimits()[v]);
    BOOST_TEST(space->getDimensionName(v) == model.variableNames()[v]);
  }
  BOOST_TEST(space->getLongestValidSegmentFraction() == dp::tol::kDefaultSegmentFraction);

  ob::ScopedState<> state(space);
  const Eigen::VectorXd q = dp::test::suggestedStart();
  dp::copyToState(q, state.get());
  BOOST_TEST((dp::mapState(state.get(), 7) == q));
  BOOST_TEST(state[3] == q[3]);
}

BOOST_AUTO_TEST_CASE(a_robot_without_variables_is_rejected_by_name) {
  deepcheck::robots::LoadOptions load;
  load.useRosPackagePath = false;
  const auto shelf = deepcheck::robots::RobotModel::fromUrdfFile(dp::test::sceneUrdf("shelf"), load);
  BOOST_CHECK_EXCEPTION(dp::makeStateSpace(shelf), std::invalid_argument,
                        [](const std::invalid_argument& e) { return mentions(e, "shelf_scene"); });
}

BOOST_AUTO_TEST_CASE(agrees_with_the_world_and_clearance_is_the_signed_distance) {
  const auto world = bundledWorld("shelf");
  const auto si = spaceFor(*world);
  const dp::StateValidityChecker checker(si, world);
  BOOST_TEST(checker.getSpecs().clearanceComputationType == ob::StateValidityCheckerSpecs::APPROXIMATE);
  BOOST_TEST(checker.getSpecs().hasValidDirectionComputation);
  ob::ScopedState<> state(si);
  int valid = 0;
  int invalid = 0;
  for (const Eigen::VectorXd& q : randomConfigurations(world->robot(), 300, 5)) {
    dp::copyToState(q, state.get());
    const bool free = world->isFree(q);
    const double sd = world->signedDistance(q).closest.distance;
    BOOST_TEST(checker.isValid(state.get()) == free);
    // The same query again (warm-started now): equal up to round-off (see below for depths).
    const double clearance = checker.clearance(state.get());
    double dist = 0.0;
    BOOST_TEST(checker.isValid(state.get(), dist) == free);
    if (free) {
      BOOST_TEST(std::abs(clearance - sd) <= kSameDistance);
      BOOST_TEST(std::abs(dist - sd) <= kSameDistance);
    } else {
      BOOST_TEST(clearance <= 0.0);
      BOOST_TEST(dist <= 0.0);
    }
    // Negative clearance is the penetration depth: invalid states have sd <= 0.
    if (free) {
      ++valid;
      BOOST_TEST(sd > 0.0);
    } else {
      ++invalid;
      BOOST_TEST(sd <= 0.0);
    }
  }
  BOOST_TEST(valid > 30);  // both outcomes in the sample
  BOOST_TEST(invalid > 30);
}

BOOST_AUTO_TEST_CASE(states_outside_the_limits_are_invalid) {
  const auto world = bundledWorld("shelf");
  const auto si = spaceFor(*world);
  const dp::StateValidityChecker checker(si, world);
  ob::ScopedState<> state(si);
  Eigen::VectorXd q = dp::test::suggestedStart();
  dp::copyToState(q, state.get());
  BOOST_TEST(checker.isValid(state.get()));
  q[0] = world->robot().upperLimits()[0] + 0.01;
  dp::copyToState(q, state.get());
  BOOST_TEST(!checker.isValid(state.get()));
}

// A NaN or infinite value anywhere in a state: invalid through every overload, clearance
// -infinity, never an exception.
BOOST_AUTO_TEST_CASE(non_finite_states_are_invalid_with_the_worst_clearance) {
  const auto world = bundledWorld("shelf");
  const auto si = spaceFor(*world);
  const dp::StateValidityChecker checker(si, world);
  ob::ScopedState<> state(si);
  ob::ScopedState<> pushed(si);
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (double bad : {std::nan(""), inf, -inf}) {
    for (int v = 0; v < world->robot().numVariables(); ++v) {
      Eigen::VectorXd q = dp::test::suggestedStart();
      q[v] = bad;
      dp::copyToState(q, state.get());
      BOOST_TEST(!checker.isValid(state.get()));
      BOOST_TEST(checker.clearance(state.get()) == -inf);
      double dist = 0.0;
      BOOST_TEST(!checker.isValid(state.get(), dist));
      BOOST_TEST(dist == -inf);
      bool available = true;
      BOOST_TEST(checker.clearance(state.get(), pushed.get(), available) == -inf);
      BOOST_TEST(!available);
      BOOST_TEST(checker.splitClearanceUpTo(q, 1.0).world == -inf);
    }
  }
}

BOOST_AUTO_TEST_CASE(penetration_tolerance_and_safety_margin) {
  const auto world = bundledWorld("shelf");
  const auto si = spaceFor(*world);
  ob::ScopedState<> state(si);

  const Eigen::VectorXd penetrating = configurationWithDistance(*world, -0.015, -0.005);
  dp::copyToState(penetrating, state.get());
  dp::ValidityOptions tolerant;
  tolerant.penetrationTolerance = 0.02;
  dp::ValidityOptions slightlyTolerant;
  slightlyTolerant.penetrationTolerance = 0.002;
  BOOST_TEST(!dp::StateValidityChecker(si, world).isValid(state.get()));
  BOOST_TEST(dp::StateValidityChecker(si, world, tolerant).isValid(state.get()));
  BOOST_TEST(!dp::StateValidityChecker(si, world, slightlyTolerant).isValid(state.get()));

  const Eigen::VectorXd near = configurationWithDistance(*world, 0.01, 0.03);
  dp::copyToState(near, state.get());
  dp::ValidityOptions smallMargin;
  smallMargin.safetyMargin = 0.005;
  dp::ValidityOptions largeMargin;
  largeMargin.safetyMargin = 0.05;
  BOOST_TEST(dp::StateValidityChecker(si, world, smallMargin).isValid(state.get()));
  BOOST_TEST(!dp::StateValidityChecker(si, world, largeMargin).isValid(state.get()));
  // Both overloads decide alike.
  double dist = 0.0;
  BOOST_TEST(!dp::StateValidityChecker(si, world, largeMargin).isValid(state.get(), dist));
  BOOST_TEST(dist > 0.01);
}

BOOST_AUTO_TEST_CASE(bad_options_are_rejected_by_name) {
  const auto world = bundledWorld("shelf");
  const auto si = spaceFor(*world);
  dp::ValidityOptions negative;
  negative.safetyMargin = -0.01;
  BOOST_CHECK_EXCEPTION(dp::StateValidityChecker(si, world, negative), std::invalid_argument,
                        [](const std::invalid_argument& e) { return mentions(e, "safetyMargin"); });
  BOOST_CHECK_EXCEPTION(dp::StateValidityChecker(si, nullptr), std::invalid_argument,
                        [](const std::invalid_argument& e) { return mentions(e, "world"); });
  auto wrong = std::make_shared<ob::SpaceInformation>(std::make_shared<ob::RealVectorStateSpace>(3));
  BOOST_CHECK_EXCEPTION(dp::StateValidityChecker(wrong, world), std::invalid_argument,
                        [](const std::invalid_argument& e) { return mentions(e, "dimension 3"); });
}

BOOST_AUTO_TEST_CASE(invalid_states_come_with_a_pushed_out_valid_state) {
  const auto world = bundledWorld("shelf");
  const auto si = spaceFor(*world);
  const dp::StateValidityChecker checker(si, world);
  ob::ScopedState<> state(si);
  ob::ScopedState<> pushed(si);

  dp::copyToState(configurationWithDistance(*world, -0.01, -0.002), state.get());
  double dist = 0.0;
  bool available = false;
  BOOST_TEST(!checker.isValid(state.get(), dist, pushed.get(), available));
  BOOST_TEST(dist < 0.0);
  BOOST_TEST(available);
  BOOST_TEST(checker.isValid(pushed.get()));
  BOOST_TEST(si->distance(state.get(), pushed.get()) < 0.5);

  dp::copyToState(dp::test::suggestedStart(), state.get());
  BOOST_TEST(checker.isValid(state.get(), dist, pushed.get(), available));
  BOOST_TEST(!available);
  BOOST_TEST(checker.clearance(state.get(), pushed.get(), available) == dist);
}

BOOST_AUTO_TEST_CASE(concurrent_queries_give_the_sequential_answers) {
  const auto world = bundledWorld("table");
  const auto si = spaceFor(*world);
  const dp::StateValidityChecker checker(si, world);
  const std::vector<Eigen::VectorXd> qs = randomConfigurations(world->robot(), 400, 11);
  std::vector<int> expectValid(qs.size());
  std::vector<double> expectClearance(qs.size());
  for (std::size_t i = 0; i < qs.size(); ++i) {
    expectValid[i] = checker.isValid(qs[i]);
    expectClearance[i] = checker.clearance(qs[i]);
  }
  std::vector<int> mismatches(2, 0);
  auto work = [&](int t) {
    ob::State* state = si->allocState();
    for (int pass = 0; pass < 3; ++pass) {
      for (std::size_t k = 0; k < qs.size(); ++k) {
        const std::size_t i = t == 0 ? k : qs.size() - 1 - k;  // opposite orders
        dp::copyToState(qs[i], state);
        // Distances of free states are GJK's and agree to round-off whatever the warm start; the
        // depth of a deep penetration may depend on where the DEEP walk was warm-started from
        // (another local minimum), so only its sign is compared.
        const double clearance = checker.clearance(state);
        const bool same = expectValid[i] ? std::abs(clearance - expectClearance[i]) <= kSameDistance : clearance <= 0.0;
        if (static_cast<int>(checker.isValid(state)) != expectValid[i] || !same) {
          ++mismatches[static_cast<std::size_t>(t)];
        }
      }
    }
    si->freeState(state);
  };
  std::thread a(work, 0);
  std::thread b(work, 1);
  a.join();
  b.join();
  BOOST_TEST(mismatches[0] == 0);
  BOOST_TEST(mismatches[1] == 0);
}

BOOST_AUTO_TEST_SUITE_END()
