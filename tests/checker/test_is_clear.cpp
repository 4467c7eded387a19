// World::isClear against the pairs' signed distances, World::certifyMotion's verdicts, and the
// link extents and version a motion bound is made from.

#include "checker_test_util.h"
#include "world_test_access.h"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <random>

namespace dc = deepcheck::checker;
using namespace deepcheck::checker::test;

namespace {

/// A random demand for `world`'s robot: per-link and symmetric self clearances in [0, top).
dc::ClearanceDemand randomDemand(const dc::World& world, double base, double top, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, top);
  const int n = world.robot().numLinks();
  dc::ClearanceDemand d;
  d.base = base;
  d.scale = 0.5 + u(rng) / top;
  d.link.resize(n);
  d.self.resize(n, n);
  for (int i = 0; i < n; ++i) {
    d.link[i] = u(rng);
    for (int j = 0; j <= i; ++j) d.self(i, j) = d.self(j, i) = u(rng);
  }
  return d;
}

/// What isClear must answer, from the contact list of every body pair: every pair farther apart
/// than its demand. `ambiguous` is set when some pair is within 1e-7 m of its demand.
bool clearByContacts(const dc::World& world, const Eigen::VectorXd& q, const dc::ClearanceDemand& d, bool& ambiguous) {
  dc::DistanceOptions options;
  options.contactMargin = 2.0;
  bool clear = true;
  ambiguous = false;
  for (const dc::Contact& c : world.signedDistance(q, options).contacts) {
    const bool self = c.bodyB.kind == dc::BodyRef::Kind::RobotLink;
    const double demand = d.base + d.scale * (self ? d.self(c.linkA, c.bodyB.index) : d.link[c.linkA]);
    if (std::abs(c.distance - demand) < 1e-7) ambiguous = true;
    if (!(c.distance > demand)) clear = false;
  }
  return clear;
}

std::shared_ptr<dc::World> armWithObstacles() {
  auto world = std::make_shared<dc::World>(armRobot(), testWorldOptions());
  addCrateBallPost(*world);
  return world;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_is_clear)

BOOST_AUTO_TEST_CASE(is_clear_agrees_with_every_pair_distance) {
  const auto world = armWithObstacles();
  std::mt19937 rng(21);
  int clear = 0;
  int notClear = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const Eigen::VectorXd q = randomConfiguration(world->robot(), rng);
    const dc::ClearanceDemand d = randomDemand(*world, trial % 3 == 0 ? 0.01 : 0.0, 0.15, rng);
    bool ambiguous = false;
    const bool expected = clearByContacts(*world, q, d, ambiguous);
    if (ambiguous) continue;
    BOOST_TEST_CONTEXT("q = " << q.transpose()) { BOOST_TEST(world->isClear(q, d) == expected); }
    (expected ? clear : notClear) += 1;
  }
  BOOST_TEST(clear > 50);
  BOOST_TEST(notClear > 50);
}

BOOST_AUTO_TEST_CASE(a_zero_demand_is_is_free) {
  const auto world = armWithObstacles();
  std::mt19937 rng(22);
  dc::ClearanceDemand zero;
  zero.link = Eigen::VectorXd::Zero(world->robot().numLinks());
  zero.self = Eigen::MatrixXd::Zero(world->robot().numLinks(), world->robot().numLinks());
  int colliding = 0;
  for (const Eigen::VectorXd& q : randomConfigurations(world->robot(), 500, rng)) {
    const bool free = world->isFree(q);
    BOOST_TEST(world->isClear(q, zero) == free);
    colliding += !free;
  }
  BOOST_TEST(colliding > 20);
}

BOOST_AUTO_TEST_CASE(bad_demands_are_named) {
  const auto world = armWithObstacles();
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(world->robot().numVariables());
  dc::ClearanceDemand d;
  d.link = Eigen::VectorXd::Zero(2);
  d.self = Eigen::MatrixXd::Zero(2, 2);
  checkThrowsWith([&] { world->isClear(q, d); }, "2 link entries");
  const int n = world->robot().numLinks();
  d.link = Eigen::VectorXd::Zero(n);
  d.self = Eigen::MatrixXd::Zero(n, n);
  d.link[n - 1] = -0.1;
  checkThrowsWith([&] { world->isClear(q, d); }, "-0.1");
  d.link[n - 1] = std::nan("");
  checkThrowsWith([&] { world->isClear(q, d); }, "nan");
  d.link[n - 1] = 0.0;
  d.base = -1.0;
  checkThrowsWith([&] { world->isClear(q, d); }, "-1");
}

// A motion of the first joint through the post collides, one far from everything is certified,
// and bounds of zero (a motion nothing moves in) certify exactly when the middle is free.
BOOST_AUTO_TEST_CASE(certify_motion_finds_collisions_and_certifies_clear_motions) {
  const auto world = armWithObstacles();
  const int n = world->robot().numLinks();
  dc::ClearanceDemand bounds;
  bounds.link = Eigen::VectorXd::Constant(n, 1.0);  // generous: 1 m for the whole motion
  bounds.self = Eigen::MatrixXd::Constant(n, n, 2.0);
  std::mt19937 rng(23);
  int certified = 0;
  int collides = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::VectorXd a = randomConfiguration(world->robot(), rng);
    const Eigen::VectorXd b = a + 0.3 * (randomConfiguration(world->robot(), rng) - a);
    if (!world->isFree(a)) continue;
    const dc::MotionCertificate c = world->certifyMotion(a, b - a, bounds);
    bool denselyFree = true;
    for (int k = 0; k <= 3000 && denselyFree; ++k) denselyFree = world->isFree(a + (k / 3000.0) * (b - a));
    if (c.verdict == dc::MotionCertificate::Verdict::Certified) {
      ++certified;
      BOOST_TEST(denselyFree);
    } else if (c.verdict == dc::MotionCertificate::Verdict::Collides) {
      ++collides;
      BOOST_TEST(!denselyFree);
    }
  }
  BOOST_TEST(certified > 20);
  BOOST_TEST(collides > 20);
  checkThrowsWith([&] { world->certifyMotion(Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2), bounds); },
                  "2 values");
}

// Degenerate motions: one of length zero is certified exactly when its configuration is free;
// bounds of a kilometre (a robot that could move anywhere) or of 300 m (a first level of 1024
// sub-motions, all the tests allowed, after a rake) leave every motion uncertified, after at most
// kCertifiedMaxTests tests.
BOOST_AUTO_TEST_CASE(certify_motion_of_nothing_and_with_huge_bounds) {
  const auto world = armWithObstacles();
  const int n = world->robot().numLinks();
  dc::ClearanceDemand bounds;
  bounds.link = Eigen::VectorXd::Constant(n, 0.5);
  bounds.self = Eigen::MatrixXd::Constant(n, n, 1.0);
  dc::ClearanceDemand huge;
  huge.link = Eigen::VectorXd::Constant(n, 1e3);
  huge.self = Eigen::MatrixXd::Constant(n, n, 1e3);
  dc::ClearanceDemand large;
  large.link = Eigen::VectorXd::Constant(n, 300.0);
  large.self = Eigen::MatrixXd::Constant(n, n, 300.0);
  const Eigen::VectorXd none = Eigen::VectorXd::Zero(world->robot().numVariables());
  std::mt19937 rng(24);
  int free = 0;
  int colliding = 0;
  for (const Eigen::VectorXd& q : randomConfigurations(world->robot(), 100, rng)) {
    const bool isFree = world->isFree(q);
    const dc::MotionCertificate still = world->certifyMotion(q, none, bounds);
    BOOST_TEST(still.certified() == isFree);
    const Eigen::VectorXd dq = 0.2 * (randomConfiguration(world->robot(), rng) - q);
    for (const dc::ClearanceDemand* demand : {&huge, &large}) {
      const dc::MotionCertificate h = world->certifyMotion(q, dq, *demand);
      BOOST_TEST(!h.certified(), "a motion certified with bounds of " << demand->link[0] << " m");
      BOOST_TEST(h.configurations <= dc::tol::kCertifiedMaxTests + 1);
    }
    (isFree ? free : colliding) += 1;
  }
  BOOST_TEST(free > 10);
  BOOST_TEST(colliding > 10);
}

BOOST_AUTO_TEST_CASE(link_extents_hold_attached_objects_and_the_version_moves) {
  auto world = armWithObstacles();
  const int tool = world->robot().linkIndex("link3");
  const std::vector<double> before = world->linkExtents();
  BOOST_TEST(before[static_cast<std::size_t>(world->robot().linkIndex("elbow"))] < 0.0);  // no geometry
  BOOST_TEST(before[static_cast<std::size_t>(tool)] > 0.25);                              // the cylinder's far end
  const std::uint64_t version = world->version();
  world->attach("link3", dc::Obstacle::sphere("probe", 0.05, translation(0.0, 0.0, 0.9)));
  BOOST_TEST(world->version() != version);
  BOOST_TEST(world->linkExtents()[static_cast<std::size_t>(tool)] >= 0.95);
  world->detach("probe", false);
  BOOST_TEST(world->linkExtents() == before, boost::test_tools::per_element());
}

// Long motions start with the rake: the middles of the levels too long for a clearance test,
// tested eight at a time by isFreeBatch's bound stage. Its AVX2 and baseline builds reach the
// same verdicts after the same number of tests, and every certified motion is densely free.
BOOST_AUTO_TEST_CASE(certify_motion_rakes_alike_in_both_batch_builds) {
  const auto world = armWithObstacles();
  const int n = world->robot().numLinks();
  dc::ClearanceDemand bounds;
  bounds.link = Eigen::VectorXd::Constant(n, 3.0);  // 15 rake configurations: two batches
  bounds.self = Eigen::MatrixXd::Constant(n, n, 6.0);
  std::mt19937 rng(25);
  int certified = 0;
  int collides = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const Eigen::VectorXd a = randomConfiguration(world->robot(), rng);
    const Eigen::VectorXd b = a + 0.5 * (randomConfiguration(world->robot(), rng) - a);
    if (!world->isFree(a)) continue;
    forceBatchBaseline(*world, false);
    const dc::MotionCertificate fast = world->certifyMotion(a, b - a, bounds);
    forceBatchBaseline(*world, true);
    const dc::MotionCertificate baseline = world->certifyMotion(a, b - a, bounds);
    BOOST_TEST(static_cast<int>(fast.verdict) == static_cast<int>(baseline.verdict));
    BOOST_TEST(fast.configurations == baseline.configurations);
    if (fast.verdict == dc::MotionCertificate::Verdict::Certified) {
      ++certified;
      bool denselyFree = true;
      for (int k = 0; k <= 2000 && denselyFree; ++k) denselyFree = world->isFree(a + (k / 2000.0) * (b - a));
      BOOST_TEST(denselyFree);
    } else if (fast.verdict == dc::MotionCertificate::Verdict::Collides) {
      ++collides;
    }
  }
  forceBatchBaseline(*world, false);
  BOOST_TEST(certified > 10);
  BOOST_TEST(collides > 10);
}

BOOST_AUTO_TEST_SUITE_END()
