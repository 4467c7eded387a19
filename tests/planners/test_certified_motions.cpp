// The certified motion validator (certified_motion_validator.h) and World::certifyMotion: thin
// obstacles that discrete checks step over, dense sampling of every motion it accepts on random
// scenes, motions from a self-collision, lastValid, threads, attached objects and the bounds it
// is given.

#include "bundled.h"
#include "shared_robots.h"

#include "deepcheck/planners/certified_motion_validator.h"
#include "deepcheck/planners/motion_bound.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/robots/kinematics.h"

#include <boost/test/unit_test.hpp>

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace dp = deepcheck::planners;
namespace ob = ompl::base;
using deepcheck::checker::Obstacle;
using deepcheck::checker::World;
using dp::test::randomConfiguration;
using dp::test::uniform01;

namespace {

/// Joint-space step of the dense check of an accepted motion (rad).
constexpr double kDenseStep = 1e-4;

/// Every configuration of the motion a -> a + dq at kDenseStep is free.
bool denselyFree(const World& world, const Eigen::VectorXd& a, const Eigen::VectorXd& dq) {
  const int steps = std::max(1, static_cast<int>(std::ceil(dq.norm() / kDenseStep)));
  for (int k = 0; k <= steps; ++k) {
    if (!world.isFree(a + (static_cast<double>(k) / steps) * dq)) return false;
  }
  return true;
}

/// A setup on `world`, its validator and two scoped states.
struct Motions {
  explicit Motions(std::shared_ptr<const World> world, const dp::SetupOptions& options = dp::test::bundledOptions())
      : ss(dp::makeSimpleSetup(std::move(world), options)),
        si(ss->getSpaceInformation()),
        checker(dp::validityCheckerOf(*ss)),
        validator(si, checker),
        s1(si),
        s2(si) {}
  bool certified(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    checker->mapping().toState(a, s1.get());
    checker->mapping().toState(b, s2.get());
    return validator.checkMotion(s1.get(), s2.get());
  }
  bool discrete(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    checker->mapping().toState(a, s1.get());
    checker->mapping().toState(b, s2.get());
    return ob::DiscreteMotionValidator(si).checkMotion(s1.get(), s2.get());
  }
  std::shared_ptr<ompl::geometric::SimpleSetup> ss;
  ob::SpaceInformationPtr si;
  std::shared_ptr<const dp::StateValidityChecker> checker;
  dp::CertifiedMotionValidator validator;
  ob::ScopedState<> s1, s2;
};

/// Adds a post of 1 cm radius where the bundled arm's flange passes half-way from a to b; its id.
int addPostHalfWay(World& world, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const auto X = deepcheck::robots::forwardKinematics(world.robot(), a + 0.5 * (b - a));
  Eigen::Isometry3d X_WP = Eigen::Isometry3d::Identity();
  X_WP.translation() = X[static_cast<std::size_t>(world.robot().linkIndex("flange"))].translation();
  world.setFixedPairReports(false);
  return world.addObstacle(Obstacle::cylinder("post", 0.01, 2.0, X_WP));
}

/// The point of the robot's pieces farthest from the z axis at q (world frame).
Eigen::Vector3d farthestFromZ(const World& world, const Eigen::VectorXd& q) {
  const auto X = deepcheck::robots::forwardKinematics(world.robot(), q);
  Eigen::Vector3d best = Eigen::Vector3d::Zero();
  for (int link = 0; link < world.robot().numLinks(); ++link) {
    for (const auto& piece : world.linkPieces(link)) {
      for (const Eigen::Vector3d& v : piece.core->vertices()) {
        const Eigen::Vector3d p = X[static_cast<std::size_t>(link)] * (piece.X_LP * v);
        if (p.head<2>().norm() > best.head<2>().norm()) best = p;
      }
    }
  }
  return best;
}

/// Random valid motions of at most `longest` (joint-space length), within the limits, from a
/// valid configuration: for each, whether the validator accepts it; every accepted one must be
/// densely free. Returns {accepted, rejected}.
std::pair<int, int> checkRandomMotions(Motions& m, const World& world, int count, double longest,
                                       std::mt19937_64& rng) {
  const auto& model = world.robot();
  int accepted = 0;
  int rejected = 0;
  for (int tries = 0; accepted + rejected < count && tries < 200 * count; ++tries) {
    const Eigen::VectorXd a = randomConfiguration(model, rng);
    Eigen::VectorXd b = randomConfiguration(model, rng);
    const double length = (b - a).norm();
    if (length > longest) b = a + (b - a) * (longest * uniform01(rng) / length);
    if (!m.checker->isValid(a) || !m.checker->isValid(b)) continue;
    if (m.certified(a, b)) {
      ++accepted;
      BOOST_TEST_REQUIRE(denselyFree(world, a, m.checker->mapping().displacement(a, b)));
    } else {
      ++rejected;
    }
  }
  return {accepted, rejected};
}

/// Thin plates around an arm standing at the origin: 2 mm thick, 10 to 40 cm wide, at random
/// poses 0.2 to 0.8 m from its base axis; none within 5 cm of a link no joint moves.
void addThinPlates(World& world, int count, std::mt19937_64& rng) {
  world.setFixedPairReports(false);
  for (int k = 0; k < count; ++k) {
    const double angle = 2.0 * M_PI * uniform01(rng);
    const double radius = 0.2 + 0.6 * uniform01(rng);
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Eigen::Vector3d(radius * std::cos(angle), radius * std::sin(angle), 0.1 + uniform01(rng));
    X.linear() = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
    const double w = 0.1 + 0.3 * uniform01(rng);
    const std::string name = "plate" + std::to_string(k);
    const int id = world.addObstacle(Obstacle::box(name, Eigen::Vector3d(w, w, 0.002), X));
    for (const auto& c : world.fixedPairs(0.05)) {
      if (c.nameB == "obstacle/" + name) {
        world.removeObstacle(id);
        break;
      }
    }
  }
}
/// A robot of the shared data among thin plates: 80 random motions of at most `longest`.
void checkSharedRobot(const dp::test::SharedRobot& robot, double longest, unsigned seed) {
  auto world = dp::loadWorld(robot.urdf, {}, robot.options);
  std::mt19937_64 rng(seed);
  addThinPlates(*world, 25, rng);
  Motions m(world, robot.options);
  const auto [accepted, rejected] = checkRandomMotions(m, *world, 80, longest, rng);
  BOOST_TEST(accepted >= 5);
  BOOST_TEST(rejected >= 5);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(planners_certified_motions)

// A 2 mm plate and a 5 mm rod placed where the arm's flange passes between two states of the
// discrete check (0.069 rad apart on the bundled arm): the discrete check steps over them, the
// certified validator does not.
BOOST_AUTO_TEST_CASE(thin_obstacles_that_discrete_checks_step_over_are_caught) {
  for (const bool rod : {false, true}) {
    auto world = dp::loadWorld(dp::test::armUrdf(), {}, dp::test::bundledOptions());
    Motions m(world);
    Eigen::VectorXd a(7), b(7);
    bool placed = false;
    // Arm poses from folded to stretched out, turning about the first joint (about z) by 1 rad:
    // the states the discrete check visits are j / n of the motion. The obstacle goes half-way
    // between two of them, where the robot's outermost point passes, reaching 3 mm into its
    // sweep; the first place the discrete check steps over is kept.
    for (int pose = 0; pose < 4 && !placed; ++pose) {
      a << 0, -0.4 + 0.4 * pose, 0, -1.6 + 0.4 * pose, 0, 1.2, 0;
      b = a;
      b[0] += 1.0;
      m.checker->mapping().toState(a, m.s1.get());
      m.checker->mapping().toState(b, m.s2.get());
      const int n = static_cast<int>(m.si->getStateSpace()->validSegmentCount(m.s1.get(), m.s2.get()));
      for (int j = 0; j < n && !placed; ++j) {
        const double t = (j + 0.5) / n;
        const Eigen::Vector3d p = farthestFromZ(*world, a + t * (b - a));
        const Eigen::Vector3d radial = Eigen::Vector3d(p.x(), p.y(), 0.0).normalized();
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        // Plate: 2 mm thick across the motion (its normal tangent to the circle), 2 cm in z and
        // radially. Rod: 5 mm across, vertical, 2 cm long.
        const double reach = rod ? 0.0025 - 0.003 : 0.01 - 0.003;
        X.translation() = p + reach * radial;
        X.linear().col(0) = radial;
        X.linear().col(2) = Eigen::Vector3d::UnitZ().cross(radial);
        X.linear().col(1) = X.linear().col(2).cross(radial);
        if (rod) X.linear() = Eigen::Matrix3d::Identity();
        const int id = world->addObstacle(rod ? Obstacle::cylinder("rod", 0.0025, 0.02, X)
                                              : Obstacle::box("plate", Eigen::Vector3d(0.02, 0.02, 0.002), X));
        if (!world->isFree(a + t * (b - a)) && m.checker->isValid(a) && m.checker->isValid(b) && m.discrete(a, b)) {
          placed = true;
        } else {
          world->removeObstacle(id);
        }
      }
    }
    BOOST_TEST_REQUIRE(placed, (rod ? "rod" : "plate") << ": no place the discrete check steps over");
    BOOST_TEST(!m.certified(a, b));
    BOOST_TEST(!m.certified(b, a));
  }
}

BOOST_AUTO_TEST_CASE(every_accepted_motion_is_densely_free_on_the_bundled_arm) {
  auto world = dp::loadWorld(dp::test::armUrdf(), {dp::test::sceneUrdf("shelf")}, dp::test::bundledOptions());
  std::mt19937_64 rng(11);
  addThinPlates(*world, 25, rng);
  Motions m(world);
  const auto [accepted, rejected] = checkRandomMotions(m, *world, 60, 1.5, rng);
  BOOST_TEST(accepted >= 10);
  BOOST_TEST(rejected >= 5);
}

BOOST_AUTO_TEST_CASE(every_accepted_motion_is_densely_free_on_the_panda) {
  if (!deepcheck::test::haveShared("every_accepted_motion_is_densely_free_on_the_panda")) return;
  checkSharedRobot(dp::test::sharedPanda(), 1.5, 12);
}

// The UR5 of the shared data: joints of +-2 pi, where a discrete check at 0.5 % of the space's
// extent steps 0.144 rad.
BOOST_AUTO_TEST_CASE(every_accepted_motion_is_densely_free_on_a_wide_range_arm) {
  if (!deepcheck::test::haveShared("every_accepted_motion_is_densely_free_on_a_wide_range_arm")) return;
  checkSharedRobot(dp::test::sharedUr5(), 3.0, 13);
}

// A motion's end is proven with the motion, not tested apart: a motion that ends in a collision,
// however slightly, is never accepted, nor its reverse. Random valid starts on the shelf among
// thin plates, each moved along a random direction in kEndStep steps to its first colliding
// configuration.
BOOST_AUTO_TEST_CASE(a_motion_ending_in_a_collision_is_never_accepted) {
  constexpr double kEndStep = 0.002;  // rad
  auto world = dp::loadWorld(dp::test::armUrdf(), {dp::test::sceneUrdf("shelf")}, dp::test::bundledOptions());
  std::mt19937_64 rng(17);
  addThinPlates(*world, 25, rng);
  Motions m(world);
  int tested = 0;
  for (int tries = 0; tested < 200 && tries < 4000; ++tries) {
    const Eigen::VectorXd a = randomConfiguration(world->robot(), rng);
    if (!m.checker->isValid(a)) continue;
    const Eigen::VectorXd direction = (randomConfiguration(world->robot(), rng) - a).normalized();
    Eigen::VectorXd b = a;
    for (int k = 1; k <= 1000 && m.checker->isValid(b); ++k) b = a + (kEndStep * k) * direction;
    if (m.checker->isValid(b) || !m.checker->withinBounds(b)) continue;
    ++tested;
    BOOST_TEST_REQUIRE(!m.certified(a, b));
    BOOST_TEST_REQUIRE(!m.certified(b, a));
  }
  BOOST_TEST(tested == 200);
}

BOOST_AUTO_TEST_CASE(last_valid_is_a_certified_configuration_before_the_first_collision) {
  auto world = dp::loadWorld(dp::test::armUrdf(), {dp::test::sceneUrdf("shelf")}, dp::test::bundledOptions());
  std::mt19937_64 rng(14);
  addThinPlates(*world, 25, rng);
  Motions m(world);
  ob::ScopedState<> last(m.si);
  int rejected = 0;
  for (int trial = 0; trial < 400 && rejected < 20; ++trial) {
    const Eigen::VectorXd a = randomConfiguration(world->robot(), rng);
    const Eigen::VectorXd b = randomConfiguration(world->robot(), rng);
    if (!m.checker->isValid(a)) continue;
    m.checker->mapping().toState(a, m.s1.get());
    m.checker->mapping().toState(b, m.s2.get());
    std::pair<ob::State*, double> lastValid(last.get(), -1.0);
    if (m.validator.checkMotion(m.s1.get(), m.s2.get(), lastValid)) continue;
    ++rejected;
    BOOST_TEST_REQUIRE((lastValid.second >= 0.0 && lastValid.second < 1.0));
    const Eigen::VectorXd reached = m.checker->mapping().configuration(last.get());
    BOOST_TEST(m.checker->isValid(reached));
    const Eigen::VectorXd dq = m.checker->mapping().displacement(a, b);
    BOOST_TEST((reached - (a + lastValid.second * dq)).norm() < 1e-9);
    BOOST_TEST(denselyFree(*world, a, lastValid.second * dq));
  }
  BOOST_TEST(rejected >= 10);
}

BOOST_AUTO_TEST_CASE(two_threads_get_the_verdicts_of_one) {
  auto world = dp::loadWorld(dp::test::armUrdf(), {dp::test::sceneUrdf("shelf")}, dp::test::bundledOptions());
  Motions m(world);
  std::mt19937_64 rng(15);
  std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> motions;
  while (motions.size() < 150) {
    const Eigen::VectorXd a = randomConfiguration(world->robot(), rng);
    if (m.checker->isValid(a)) motions.emplace_back(a, randomConfiguration(world->robot(), rng));
  }
  std::vector<char> expected;
  for (const auto& [a, b] : motions) expected.push_back(m.certified(a, b) ? 1 : 0);
  std::vector<std::vector<char>> got(2);
  auto run = [&](int t) {
    ob::ScopedState<> s1(m.si), s2(m.si);
    for (const auto& [a, b] : motions) {
      m.checker->mapping().toState(a, s1.get());
      m.checker->mapping().toState(b, s2.get());
      got[static_cast<std::size_t>(t)].push_back(m.validator.checkMotion(s1.get(), s2.get()) ? 1 : 0);
    }
  };
  std::thread first(run, 0);
  std::thread second(run, 1);
  first.join();
  second.join();
  BOOST_TEST(got[0] == expected, boost::test_tools::per_element());
  BOOST_TEST(got[1] == expected, boost::test_tools::per_element());
  BOOST_TEST(std::count(expected.begin(), expected.end(), 1) > 0);
}

// A 40 cm rod attached to the flange after the validator was made: the validator's bound grows
// with it, and a motion that sweeps the rod through a post is refused.
BOOST_AUTO_TEST_CASE(an_object_attached_later_is_covered) {
  auto world = dp::loadWorld(dp::test::armUrdf(), {}, dp::test::bundledOptions());
  Motions m(world);
  const Eigen::VectorXd a = dp::test::suggestedStart();
  Eigen::VectorXd b = a;
  b[0] += 1.2;
  Eigen::Isometry3d X_LO = Eigen::Isometry3d::Identity();
  X_LO.translation() = Eigen::Vector3d(0.0, 0.0, 0.2);
  world->attach("flange", Obstacle::cylinder("rod", 0.01, 0.4, X_LO));
  // A post where the rod's far end passes half-way, out of reach of the bare arm.
  const auto X = deepcheck::robots::forwardKinematics(world->robot(), a + 0.5 * (b - a));
  Eigen::Isometry3d X_WP = Eigen::Isometry3d::Identity();
  X_WP.translation() = X[static_cast<std::size_t>(world->robot().linkIndex("flange"))] * Eigen::Vector3d(0, 0, 0.38);
  world->addObstacle(Obstacle::cylinder("post", 0.01, 2.0, X_WP));
  BOOST_TEST_REQUIRE(!denselyFree(*world, a, b - a));
  BOOST_TEST_REQUIRE(world->isFree(a));
  BOOST_TEST_REQUIRE(world->isFree(b));
  BOOST_TEST(!m.certified(a, b));
  world->detach("rod", false);
  BOOST_TEST(m.certified(a, b) == denselyFree(*world, a, b - a));
}

// The memo of certified motions: a motion asked again in the same world is answered from it
// without a certification, and so is the same motion reversed; an obstacle added across it makes
// it refused; the motion moved by a billionth of a radian is certified anew.
BOOST_AUTO_TEST_CASE(the_memo_answers_a_motion_again_only_in_the_same_world) {
  auto world = dp::loadWorld(dp::test::armUrdf(), {}, dp::test::bundledOptions());
  Motions m(world);
  const Eigen::VectorXd a = dp::test::suggestedStart();
  Eigen::VectorXd b = a;
  b[0] += 1.2;
  BOOST_TEST_REQUIRE(m.certified(a, b));
  const auto tested = m.validator.stats().configurations;
  const auto hits = m.checker->certifiedMotions().hits();
  BOOST_TEST(m.certified(a, b));
  BOOST_TEST(m.validator.stats().configurations == tested);
  BOOST_TEST(m.checker->certifiedMotions().hits() == hits + 1);
  BOOST_TEST(m.certified(b, a));
  BOOST_TEST(m.validator.stats().configurations == tested);
  BOOST_TEST(m.checker->certifiedMotions().hits() == hits + 2);
  Eigen::VectorXd nudged = b;
  nudged[1] += 1e-9;
  BOOST_TEST(m.certified(a, nudged));
  BOOST_TEST(m.checker->certifiedMotions().hits() == hits + 2);
  const int post = addPostHalfWay(*world, a, b);
  BOOST_TEST_REQUIRE(!denselyFree(*world, a, b - a));
  BOOST_TEST_REQUIRE(world->isFree(a));
  BOOST_TEST_REQUIRE(world->isFree(b));
  BOOST_TEST(!m.certified(a, b));
  world->removeObstacle(post);
  BOOST_TEST(m.certified(a, b));
}

// The memo of refused motions: a motion refused after its test is refused again without one, the
// same motion reversed too, until the world changes or the memo is emptied.
BOOST_AUTO_TEST_CASE(a_refused_motion_is_refused_again_only_in_the_same_world) {
  auto world = dp::loadWorld(dp::test::armUrdf(), {}, dp::test::bundledOptions());
  Motions m(world);
  const Eigen::VectorXd a = dp::test::suggestedStart();
  Eigen::VectorXd b = a;
  b[0] += 1.2;
  const int post = addPostHalfWay(*world, a, b);
  BOOST_TEST_REQUIRE(world->isFree(a));
  BOOST_TEST_REQUIRE(world->isFree(b));
  BOOST_TEST(!m.certified(a, b));
  const auto tested = m.validator.stats().configurations;
  BOOST_TEST(tested > 0u);
  BOOST_TEST(m.validator.stats().refusedAgain == 0u);
  BOOST_TEST(!m.certified(a, b));
  BOOST_TEST(!m.certified(b, a));
  BOOST_TEST(m.validator.stats().configurations == tested);
  BOOST_TEST(m.validator.stats().refusedAgain == 2u);
  m.validator.forgetRefusedMotions();
  BOOST_TEST(!m.certified(a, b));
  BOOST_TEST(m.validator.stats().configurations > tested);
  BOOST_TEST(m.validator.stats().refusedAgain == 2u);
  world->removeObstacle(post);
  BOOST_TEST(m.certified(a, b));
  BOOST_TEST(m.validator.stats().refusedAgain == 2u);
  m.validator.resetStats();
  BOOST_TEST(m.validator.stats().refusedAgain == 0u);
}

// A motion's end is not tested for validity apart from its motion: the certification proves its
// collisions, the joint limits are checked on their own. A motion's start is the caller's to check
// (OMPL's contract), so a motion from outside the limits is certified and remembered, and a motion
// ending at that same point must still be refused.
BOOST_AUTO_TEST_CASE(an_end_outside_the_limits_is_refused) {
  auto world = dp::loadWorld(dp::test::armUrdf(), {}, dp::test::bundledOptions());
  Motions m(world);
  const Eigen::VectorXd a = dp::test::suggestedStart();
  Eigen::VectorXd outside = a;
  outside[0] = world->robot().upperLimits()[0] + 0.05;
  BOOST_TEST_REQUIRE(!m.checker->isValid(outside));
  BOOST_TEST_REQUIRE(m.certified(outside, a));
  Eigen::VectorXd b = a;
  b[0] -= 0.3;
  BOOST_TEST_REQUIRE(m.certified(b, a));
  BOOST_TEST(!m.certified(b, outside));
  BOOST_TEST(m.certified(a, b));  // an end within the limits
}

// A path from solve and simplifySolutionChecked is certified again by certifyPath from the memo:
// no configuration is tested; so is the same path subdivided and interpolated (pieces of its
// certified motions).
BOOST_AUTO_TEST_CASE(certify_path_after_simplification_tests_nothing_new) {
  auto world = dp::test::bundledWorld("");
  auto ss = dp::makeSimpleSetup(world, dp::test::bundledOptions());
  const Eigen::VectorXd start = dp::test::suggestedStart();
  Eigen::VectorXd goal = start;
  goal[0] += 2.0;
  goal[1] -= 0.4;
  dp::setStartAndGoal(*ss, start, goal);
  BOOST_TEST_REQUIRE(static_cast<bool>(ss->solve(5.0)));
  BOOST_TEST_REQUIRE(dp::simplifySolutionChecked(*ss));
  auto validator =
      std::dynamic_pointer_cast<dp::CertifiedMotionValidator>(ss->getSpaceInformation()->getMotionValidator());
  BOOST_TEST_REQUIRE(validator != nullptr);
  const auto checker = dp::validityCheckerOf(*ss);
  const auto hits = checker->certifiedMotions().hits();
  ompl::geometric::PathGeometric path = ss->getSolutionPath();
  const dp::PathCertificate certificate = dp::certifyPath(*ss, path);
  BOOST_TEST(certificate.valid);
  BOOST_TEST(!certificate.repaired);
  BOOST_TEST(checker->certifiedMotions().hits() - hits == path.getStateCount() - 1);
  path.subdivide();
  path.interpolate(3 * path.getStateCount());
  const auto hitsBefore = checker->certifiedMotions().hits();
  BOOST_TEST(dp::certifyPath(*ss, path).valid);
  BOOST_TEST(checker->certifiedMotions().hits() - hitsBefore == path.getStateCount() - 1);
}

// A motion that starts in a self-collision is never certified: b collides with the Panda itself,
// a is free, 0.05 to 0.3 rad from b along a random direction of the last two arm joints (so that
// the pairs across them, whose grids decide them, are the ones that move), and the motion b -> a
// is asked with the validator's bounds (a motion's ends are not tested by themselves). The bound
// stage asks a grid once for all the sub-motions of a batch, over a box holding every one of
// them: a box short of the sub-motions' reach certified 19 of these 1000 motions.
BOOST_AUTO_TEST_CASE(a_motion_from_a_self_collision_is_never_certified) {
  if (!deepcheck::test::haveShared("a_motion_from_a_self_collision_is_never_certified")) return;
  const dp::test::SharedRobot panda = dp::test::sharedPanda();
  const auto world = dp::loadWorld(panda.urdf, {}, panda.options);
  const dp::LinkSpeedBound bound = dp::LinkSpeedBound::forWorld(*world);
  std::mt19937_64 rng(17);
  std::normal_distribution<double> g(0.0, 1.0);
  deepcheck::checker::ClearanceDemand demand;
  int motions = 0;
  while (motions < 1000) {
    const Eigen::VectorXd b = randomConfiguration(world->robot(), rng);
    if (world->isFree(b)) continue;
    Eigen::VectorXd direction(b.size());
    for (Eigen::Index v = 0; v < b.size(); ++v) direction[v] = v == 5 || v == 6 ? g(rng) : 0.0;
    const double length = 0.05 + 0.25 * uniform01(rng);
    const Eigen::VectorXd a = b + length / direction.cwiseAbs().maxCoeff() * direction;
    if (!world->isFree(a)) continue;
    ++motions;
    bound.displacements(a - b, demand.link, demand.self);
    BOOST_TEST(!world->certifyMotion(b, a - b, demand).certified(),
               "b = " << b.transpose() << ", a = " << a.transpose());
  }
}

// The bounds handed to World::certifyMotion: the self matrix holds each checked pair's own
// bound and the others' sum of link bounds.
BOOST_AUTO_TEST_CASE(displacements_hold_every_pair_bound) {
  const auto world = dp::test::bundledWorld("");
  const dp::LinkSpeedBound bound = dp::LinkSpeedBound::forWorld(*world);
  std::mt19937_64 rng(16);
  Eigen::VectorXd link;
  Eigen::MatrixXd self;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd dq(7);
    for (int v = 0; v < 7; ++v) dq[v] = uniform01(rng) - 0.5;
    bound.displacements(dq, link, self);
    const int n = world->robot().numLinks();
    BOOST_TEST_REQUIRE(link.size() == n);
    for (int i = 0; i < n; ++i) {
      BOOST_TEST(link[i] == bound.linkDisplacement(i, dq));
      for (int j = 0; j < n; ++j) {
        if (i == j) continue;
        BOOST_TEST(self(i, j) == self(j, i));
        BOOST_TEST(std::abs(self(i, j) - bound.pairDisplacement(i, j, dq)) <= 1e-12 * (1.0 + self(i, j)));
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(a_penetration_tolerance_is_refused_by_name) {
  dp::ValidityOptions lenient;
  lenient.penetrationTolerance = 0.002;
  const auto world = dp::test::bundledWorld("");
  auto ss = dp::makeSimpleSetup(world, dp::test::bundledOptions());
  auto checker = std::make_shared<dp::StateValidityChecker>(ss->getSpaceInformation(), world, lenient);
  BOOST_CHECK_EXCEPTION(dp::CertifiedMotionValidator(ss->getSpaceInformation(), checker), std::invalid_argument,
                        [](const std::invalid_argument& e) {
                          return std::string(e.what()).find("penetration tolerance") != std::string::npos;
                        });
}

BOOST_AUTO_TEST_SUITE_END()
