// Link speed bound and the clearance-stepping motion validator, against fine discrete checking and
// OMPL's DiscreteMotionValidator.

#include "bundled.h"

#include "deepcheck/planners/motion_bound.h"
#include "deepcheck/planners/motion_validator.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/planners/validity_checker.h"
#include "deepcheck/robots/collision_geometry.h"
#include "deepcheck/robots/kinematics.h"

#include <boost/test/unit_test.hpp>

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace dp = deepcheck::planners;
namespace ob = ompl::base;
using dp::test::bundledWorld;
using dp::test::randomConfiguration;
using dp::test::uniform01;

namespace {

/// Ground truth resolution of the motion checks: joint-space length between checked states (rad).
constexpr double kTruthResolution = 0.001;

Eigen::VectorXd randomDirection(int n, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::VectorXd d(n);
  for (int i = 0; i < n; ++i) d[i] = normal(rng);
  return d.normalized();
}

bool truthFree(const deepcheck::checker::World& world, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / kTruthResolution)));
  for (int k = 0; k <= steps; ++k) {
    if (!world.isFree(a + (static_cast<double>(k) / steps) * (b - a))) return false;
  }
  return true;
}

/// Some robot link is within `margin` of a scene body.
bool nearScene(const deepcheck::checker::World& world, const Eigen::VectorXd& q, double margin) {
  deepcheck::checker::DistanceOptions options;
  options.contactMargin = margin;
  options.maxDistance = margin;
  for (const auto& c : world.signedDistance(q, options).contacts) {
    if (c.bodyB.kind != deepcheck::checker::BodyRef::Kind::RobotLink) return true;
  }
  return false;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(planners_motion_validator)

BOOST_AUTO_TEST_CASE(link_speed_bound_contains_every_vertex_motion) {
  const auto world = bundledWorld("");
  const auto& model = world->robot();
  const dp::LinkSpeedBound bound = dp::LinkSpeedBound::forWorld(*world);
  const auto pieces = deepcheck::robots::collisionPieces(model);
  std::mt19937_64 rng(3);
  double tightest = 0.0;  // largest ratio of a real displacement to its bound
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::VectorXd q = randomConfiguration(model, rng);
    const Eigen::VectorXd dq = randomDirection(7, rng) * (0.05 + uniform01(rng));
    const auto X0 = deepcheck::robots::forwardKinematics(model, q);
    for (int s = 1; s <= 10; ++s) {
      const auto X = deepcheck::robots::forwardKinematics(model, q + (s / 10.0) * dq);
      for (int link = 0; link < model.numLinks(); ++link) {
        const double D = bound.linkDisplacement(link, (s / 10.0) * dq);
        for (const auto& piece : pieces[static_cast<std::size_t>(link)]) {
          for (const Eigen::Vector3d& v : piece.core->vertices()) {
            const Eigen::Vector3d p_L = piece.X_LP * v;
            const double moved =
                (X[static_cast<std::size_t>(link)] * p_L - X0[static_cast<std::size_t>(link)] * p_L).norm();
            BOOST_TEST_REQUIRE(moved <= D + 1e-12);
            if (D > 0.0) tightest = std::max(tightest, moved / D);
          }
        }
      }
    }
  }
  BOOST_TEST(tightest > 0.3);  // a bound, but not a uselessly loose one
}

BOOST_AUTO_TEST_CASE(pair_bound_contains_the_change_of_the_distance) {
  const auto world = bundledWorld("shelf");
  const dp::LinkSpeedBound bound = dp::LinkSpeedBound::forWorld(*world);
  std::mt19937_64 rng(4);
  int compared = 0;
  int pairsCompared = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::VectorXd q = randomConfiguration(world->robot(), rng);
    const Eigen::VectorXd dq = randomDirection(7, rng) * 0.2 * uniform01(rng);
    const double a = world->signedDistance(q).closest.distance;
    const double b = world->signedDistance(q + dq).closest.distance;
    if (a > 0.0 && b > 0.0) {  // GJK distances (exact); depths are DEEP's estimates
      ++compared;
      BOOST_TEST(std::abs(b - a) <= bound.pairDisplacement(dq) + 1e-12);
    }
    // Each body pair within 30 cm at both ends moves by at most its own bound.
    deepcheck::checker::DistanceOptions options;
    options.contactMargin = 0.3;
    const auto before = world->signedDistance(q, options).contacts;
    const auto after = world->signedDistance(q + dq, options).contacts;
    for (const auto& c : before) {
      for (const auto& d : after) {
        if (c.linkA != d.linkA || c.bodyB != d.bodyB || c.distance <= 0.0 || d.distance <= 0.0) continue;
        const int linkB = c.bodyB.kind == deepcheck::checker::BodyRef::Kind::RobotLink ? c.bodyB.index : -1;
        ++pairsCompared;
        BOOST_TEST(std::abs(d.distance - c.distance) <= bound.pairDisplacement(c.linkA, linkB, dq) + 1e-12);
        if (linkB >= 0) BOOST_TEST(bound.pairDisplacement(c.linkA, linkB, dq) <= bound.pairDisplacement(dq));
      }
    }
  }
  BOOST_TEST(compared > 50);
  BOOST_TEST(pairsCompared > 200);
}

BOOST_AUTO_TEST_CASE(bad_bounds_are_rejected) {
  const auto world = bundledWorld("");
  const auto& model = world->robot();
  BOOST_CHECK_THROW(dp::LinkSpeedBound(model, {1.0, 2.0}, {}), std::invalid_argument);
  std::vector<double> extents(static_cast<std::size_t>(model.numLinks()), 0.1);
  BOOST_CHECK_THROW(dp::LinkSpeedBound(model, extents, {{0, 99}}), std::invalid_argument);
  const dp::LinkSpeedBound bound(model, extents, {});
  BOOST_CHECK_THROW(bound.pairDisplacement(Eigen::VectorXd::Zero(3)), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(the_validator_builds_the_bound_of_its_world_by_default) {
  const auto world = bundledWorld("shelf");
  auto si = std::make_shared<ob::SpaceInformation>(dp::makeStateSpace(world->robot()));
  const dp::StateValidityCheckerPtr checker = std::make_shared<dp::StateValidityChecker>(si, world);
  si->setStateValidityChecker(checker);
  si->setup();
  const dp::ClearanceMotionValidatorPtr validator = std::make_shared<dp::ClearanceMotionValidator>(si, checker);
  const dp::LinkSpeedBound expected = dp::LinkSpeedBound::forWorld(*world);
  BOOST_CHECK(validator->bound().speeds() == expected.speeds());
  BOOST_TEST(validator->bound().linkExtents() == expected.linkExtents(), boost::test_tools::per_element());
  BOOST_CHECK_THROW(dp::ClearanceMotionValidator(si, nullptr), std::invalid_argument);
  // The same motion gets the same answer as with the bound given explicitly.
  const dp::ClearanceMotionValidator explicitBound(si, checker, std::make_shared<const dp::LinkSpeedBound>(expected));
  ob::ScopedState<> s1(si), s2(si);
  dp::copyToState(dp::test::suggestedStart(), s1.get());
  dp::copyToState(dp::test::suggestedGoal("shelf"), s2.get());
  BOOST_TEST(validator->checkMotion(s1.get(), s2.get()) == explicitBound.checkMotion(s1.get(), s2.get()));
  BOOST_TEST(validator->stats().distanceQueries == explicitBound.stats().distanceQueries);
}

namespace {

struct Comparison {
  int motions = 0;
  int truthValid = 0;
  int clearanceWrong = 0;           ///< accepted, but collides at the truth resolution
  int clearanceWrongCertified = 0;  ///< ... without a single fallback step
  int clearanceMissesFree = 0;      ///< rejected, but free at the truth resolution
  int discreteWrong = 0;
  std::uint64_t clearanceChecks = 0;   ///< isValid queries of the clearance validator (discrete pass)
  std::uint64_t clearanceQueries = 0;  ///< distance queries of its certification
  std::uint64_t discreteChecks = 0;
  int certificationRejections = 0;  ///< collisions only the certification found
  int lastValidMismatches = 0;
};

/// Random motions between valid states of `scene`, of joint-space length in [0.1, maxLength],
/// starting within 5 cm of the scene when `nearScene`.
Comparison compareValidators(const std::string& scene, bool nearSceneOnly, double maxLength, int count) {
  const auto world = bundledWorld(scene);
  auto si = std::make_shared<ob::SpaceInformation>(dp::makeStateSpace(world->robot()));
  auto checker = std::make_shared<dp::StateValidityChecker>(si, world);
  si->setStateValidityChecker(checker);
  si->setup();
  auto bound = std::make_shared<const dp::LinkSpeedBound>(dp::LinkSpeedBound::forWorld(*world));
  const dp::ClearanceMotionValidator clearance(si, checker, bound);
  const ob::DiscreteMotionValidator discrete(si);

  std::mt19937_64 rng(8);
  Comparison r;
  ob::ScopedState<> s1(si), s2(si), last(si);
  while (r.motions < count) {
    const Eigen::VectorXd a = randomConfiguration(world->robot(), rng);
    if (!checker->isValid(a) || (nearSceneOnly && !nearScene(*world, a, 0.05))) continue;
    Eigen::VectorXd b = a + randomDirection(7, rng) * (0.1 + (maxLength - 0.1) * uniform01(rng));
    b = b.cwiseMax(world->robot().lowerLimits()).cwiseMin(world->robot().upperLimits());
    if (!checker->isValid(b)) continue;
    ++r.motions;
    dp::copyToState(a, s1.get());
    dp::copyToState(b, s2.get());
    const bool truth = truthFree(*world, a, b);
    r.truthValid += truth;

    const auto before = clearance.stats();
    const bool byClearance = clearance.checkMotion(s1.get(), s2.get());
    const auto after = clearance.stats();
    r.clearanceQueries += after.distanceQueries - before.distanceQueries;
    r.clearanceChecks += after.validityQueries - before.validityQueries;
    r.certificationRejections += static_cast<int>(after.certificationRejections - before.certificationRejections);
    if (byClearance && !truth) {
      ++r.clearanceWrong;
      if (after.fallbackSteps == before.fallbackSteps) ++r.clearanceWrongCertified;
    }
    if (!byClearance && truth) ++r.clearanceMissesFree;

    const std::uint64_t checksBefore = checker->validityQueries();
    const bool byDiscrete = discrete.checkMotion(s1.get(), s2.get());
    r.discreteChecks += checker->validityQueries() - checksBefore;
    if (byDiscrete && !truth) ++r.discreteWrong;

    // The lastValid overload walks from s1 only (its fallback states may differ); when it
    // rejects, it reports a valid state before the collision.
    std::pair<ob::State*, double> lastValid(last.get(), -1.0);
    const bool byLastValid = clearance.checkMotion(s1.get(), s2.get(), lastValid);
    if (byLastValid != byClearance) ++r.lastValidMismatches;
    if (!byLastValid) {
      BOOST_TEST(lastValid.second >= 0.0);
      BOOST_TEST(lastValid.second < 1.0);
      BOOST_TEST(checker->isValid(last.get()));
    }
  }
  return r;
}

}  // namespace

// Issue 6: compare checks per motion and correctness against OMPL's DiscreteMotionValidator.
// The clearance validator is certified except for its fallback steps (where the robot passes
// within about one discrete step's motion of an obstacle); the discrete one checks states
// 0.069 rad apart and can step over a thin obstacle or a corner.
BOOST_AUTO_TEST_CASE(certified_steps_never_accept_a_colliding_motion) {
  for (const std::string scene : {"shelf", "narrow_passage"}) {
    const Comparison r = compareValidators(scene, true, 1.5, 150);
    BOOST_TEST(r.clearanceWrongCertified == 0);
    BOOST_TEST(r.clearanceWrong <= r.discreteWrong);
    BOOST_TEST(r.clearanceMissesFree == 0);  // it only rejects motions with a colliding state
    BOOST_TEST(r.certificationRejections + r.clearanceWrong == r.discreteWrong);  // catches discrete's misses
    BOOST_TEST(r.truthValid > 10);                                                // both outcomes in the sample
    BOOST_TEST(r.truthValid < r.motions - 10);
    BOOST_TEST(r.lastValidMismatches <= 2);
  }
}

// The motions planners ask about (RRTConnect's range on this arm is 2.8 rad): the certification
// steps are larger than the discrete resolution where the clearance allows.
BOOST_AUTO_TEST_CASE(long_motions_take_fewer_certification_queries_than_discrete_checks) {
  for (const std::string scene : {"table", "shelf"}) {
    const Comparison r = compareValidators(scene, false, 2.8, 100);
    BOOST_TEST(r.clearanceWrongCertified == 0);
    BOOST_TEST(r.clearanceChecks == r.discreteChecks);  // the same discrete pass
    BOOST_TEST(r.clearanceQueries < r.discreteChecks);
  }
}

BOOST_AUTO_TEST_SUITE_END()
