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
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
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

/// The minimum robot-scene signed distance along a path (self pairs left out), every 0.002 rad.
double minSceneClearance(const og::PathGeometric& path, const dp::StateValidityChecker& checker) {
  return dp::minClearanceAlong(path, [&](const Eigen::VectorXd& q) {
    return checker.splitClearanceUpTo(q, std::numeric_limits<double>::infinity(), false).world;
  });
}

/// A planar arm (two 4 cm thick links of 0.5 m and 0.4 m turning about z) and a pole (radius 5 cm)
/// at 0.75 m from the shoulder. From q = (-0.6, 0) to (0.9, 0) the stretched arm sweeps through
/// the pole: every path folds the elbow to pass it, and the shortest ones graze it.
std::shared_ptr<const deepcheck::checker::World> planarArmAndPole() {
  const std::string xml = R"(
<robot name='planar'>
  <link name='base'/>
  <link name='upper'><collision><origin xyz='0.25 0 0'/><geometry><box size='0.5 0.04 0.04'/></geometry></collision></link>
  <joint name='shoulder' type='revolute'><parent link='base'/><child link='upper'/>
    <axis xyz='0 0 1'/><limit lower='-3.14159' upper='3.14159' effort='1' velocity='1'/></joint>
  <link name='fore'><collision><origin xyz='0.23 0 0'/><geometry><box size='0.4 0.04 0.04'/></geometry></collision></link>
  <joint name='elbow' type='revolute'><parent link='upper'/><child link='fore'/><origin xyz='0.5 0 0'/>
    <axis xyz='0 0 1'/><limit lower='-2.8' upper='2.8' effort='1' velocity='1'/></joint>
</robot>)";
  auto world = std::make_shared<deepcheck::checker::World>(
      deepcheck::robots::RobotModel::fromUrdfString(xml, ".", {}, "planar.urdf"));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0.75 * std::cos(0.15), 0.75 * std::sin(0.15), 0.0);
  world->addObstacle(deepcheck::checker::Obstacle::cylinder("pole", 0.05, 0.5, pose));
  return world;
}

/// OMPL's RRT* drawing from its own pinned seed (with dp::test::SeededSampler, two runs on the same
/// seed differ only by their objective).
class SeededRRTstar : public og::RRTstar {
 public:
  SeededRRTstar(const ob::SpaceInformationPtr& si, std::uint_fast32_t seed) : og::RRTstar(si) {
    rng_.setLocalSeed(seed);
  }
};

}  // namespace

BOOST_AUTO_TEST_SUITE(planners_objectives)

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
  int positive = 0;
  int throughInvalid = 0;
  // The integration evaluates valid states only (sd > 0 here): GJK distances, no penetration
  // depths, so the costs agree to rounding.
  const auto same = [](double x, double y) { return std::abs(x - y) <= 1e-9 * std::max(1.0, std::abs(x)); };
  // Motions from valid configurations, every other one within d_safe of the shelf, 0.3 of the
  // way to a random configuration: some stay far from the shelf, some pass near it, some through.
  for (int found = 0; found < 60;) {
    const Eigen::VectorXd qa = randomConfiguration(world->robot(), rng);
    const Eigen::VectorXd qb = qa + 0.3 * (randomConfiguration(world->robot(), rng) - qa);
    if (!checker->isValid(qa)) continue;
    if (found % 2 == 0 && checker->splitClearanceUpTo(qa, 0.1, false).world >= 0.05) continue;
    ++found;
    dp::copyToState(qa, a.get());
    dp::copyToState(qb, b.get());
    const double withoutBound = plain.motionCost(a.get(), b.get()).value();
    const double withBound = bounded.motionCost(a.get(), b.get()).value();
    // The trapezoid rule on the same states by hand; a motion with an invalid state costs infinity.
    const int segments = std::max(1, static_cast<int>(std::ceil((qb - qa).norm() / resolution)));
    double sum = 0.0;
    bool valid = true;
    for (int k = 0; k <= segments; ++k) {
      const Eigen::VectorXd q = qa + (double(k) / segments) * (qb - qa);
      valid = valid && checker->isValid(q);
      const dp::SplitDistance d = checker->splitClearanceUpTo(q, std::numeric_limits<double>::infinity());
      const double h = std::max({0.0, 0.05 - d.world, -d.self});
      sum += (k == 0 || k == segments) ? 0.5 * h : h;
    }
    if (!valid) {
      ++throughInvalid;
      BOOST_TEST(std::isinf(withoutBound));
      // The bisection meets the invalid states unless they lie where the bound proves
      // sd_world >= d_safe (then only self pairs, which it does not measure, can collide).
      BOOST_TEST((std::isinf(withBound) || withBound >= 0.0));
      continue;
    }
    BOOST_TEST(same(withoutBound, withBound), withoutBound << " vs " << withBound);  // skips only zero costs
    BOOST_TEST(same(withoutBound, sum * (qb - qa).norm() / segments));
    skipped += withBound == 0.0;
    positive += withBound > 0.0;
  }
  BOOST_TEST(skipped > 5);
  BOOST_TEST(positive > 5);
  BOOST_TEST(throughInvalid > 5);
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
  BOOST_TEST(combined->motionCost(a.get(), b.get()).value() == length + weight * h, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(combined->stateCost(b.get()).value() == weight * hinge.stateCost(b.get()).value(),
             boost::test_tools::tolerance(1e-9));
  // The path length's heuristic, admissible since the hinge is >= 0.
  BOOST_TEST(combined->motionCostHeuristic(a.get(), b.get()).value() == length);
}

// Plans: labelled integration (tests/CMakeLists.txt).
BOOST_AUTO_TEST_CASE(maximize_min_clearance_objective_reads_our_clearance, *boost::unit_test::label("integration")) {
  const auto world = bundledWorld("table");
  auto ss = dp::makeSimpleSetup(world, dp::test::bundledOptions());
  const auto objective = dp::makeMaxMinClearanceObjective(ss->getSpaceInformation());
  ob::ScopedState<> state(ss->getStateSpace());
  dp::copyToState(dp::test::suggestedStart(), state.get());
  BOOST_TEST(objective->stateCost(state.get()).value() ==
             dp::validityCheckerOf(*ss)->clearance(dp::test::suggestedStart()));
  // RRT* maximizing the minimum clearance returns a path whose cost is its smallest clearance.
  dp::setStartAndGoal(*ss, dp::test::suggestedStart(), dp::test::suggestedGoal("table"));
  ss->setOptimizationObjective(objective);
  ss->setPlanner(dp::makePlanner("RRT*", ss->getSpaceInformation()));
  BOOST_TEST_REQUIRE(ss->solve(iterationLimit(100)) == ob::PlannerStatus::EXACT_SOLUTION);
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

// Plans: labelled integration (tests/CMakeLists.txt).
BOOST_AUTO_TEST_CASE(clearance_objective_keeps_rrt_star_paths_farther_from_obstacles_than_length_alone,
                     *boost::unit_test::label("integration")) {
  // RRT* on the planar arm, 1,500 iterations, on the same five seeds with path length alone and
  // with path length + the clearance hinge (defaults: d_safe 5 cm, weight 100 / m). Length alone
  // grazes the pole (it even clips it between the discrete motion checks by up to ~1.5 mm); the
  // hinge keeps the fold about d_safe away from it, for a longer path.
  const auto world = planarArmAndPole();
  const auto bound = std::make_shared<const dp::LinkSpeedBound>(dp::LinkSpeedBound::forWorld(*world));
  Eigen::VectorXd start(2), goal(2);
  start << -0.6, 0.0;
  goal << 0.9, 0.0;
  // Returns the minimum clearance to the pole; `length` the path length.
  const auto plan = [&](bool clearance, std::uint_fast32_t seed, double& length) {
    auto space = dp::makeStateSpace(world->robot());
    space->setStateSamplerAllocator(
        [seed](const ob::StateSpace* s) { return std::make_shared<dp::test::SeededSampler>(s, seed); });
    auto si = std::make_shared<ob::SpaceInformation>(space);
    auto checker = std::make_shared<dp::StateValidityChecker>(si, world);
    si->setStateValidityChecker(checker);
    si->setStateValidityCheckingResolution(dp::tol::kDefaultSegmentFraction);
    si->setup();
    auto pdef = std::make_shared<ob::ProblemDefinition>(si);
    ob::ScopedState<> a(si), b(si);
    dp::copyToState(start, a.get());
    dp::copyToState(goal, b.get());
    pdef->setStartAndGoalStates(a, b);
    pdef->setOptimizationObjective(clearance
                                       ? dp::makeLengthClearanceObjective(si, checker, dp::tol::kDefaultSafeDistance,
                                                                          dp::tol::kDefaultHingeWeight, bound)
                                       : std::make_shared<ob::PathLengthOptimizationObjective>(si));
    auto planner = std::make_shared<SeededRRTstar>(si, seed);
    // The same neighbours for both objectives, and OMPL's default range (0.2 of the extent, which
    // prepareForCostlyObjective keeps when set): 1,500 iterations of the shorter range it picks
    // otherwise leave the length-only paths farther than 1 cm from the pole.
    planner->setRange(0.2 * si->getMaximumExtent());
    BOOST_TEST(dp::prepareForCostlyObjective(*planner));
    planner->setProblemDefinition(pdef);
    planner->setup();
    BOOST_TEST_REQUIRE(planner->solve(iterationLimit(1500)) == ob::PlannerStatus::EXACT_SOLUTION);
    const auto& path = *pdef->getSolutionPath()->as<og::PathGeometric>();
    length = path.length();
    return minSceneClearance(path, *checker);
  };
  for (std::uint_fast32_t seed = 1; seed <= 5; ++seed) {
    double lengthOnly = 0.0;
    double lengthWithHinge = 0.0;
    const double byLength = plan(false, seed, lengthOnly);
    const double byClearance = plan(true, seed, lengthWithHinge);
    BOOST_TEST(byLength < 0.01);
    BOOST_TEST(byClearance > byLength + 0.02);
    BOOST_TEST(byClearance > 0.6 * dp::tol::kDefaultSafeDistance);
    BOOST_TEST(lengthWithHinge > lengthOnly);  // the clearance is paid for with length
  }
}

BOOST_AUTO_TEST_CASE(motions_through_invalid_states_cost_infinity) {
  // The pole world: the straight motion from start to goal sweeps the arm through the pole.
  const auto world = planarArmAndPole();
  auto si = std::make_shared<ob::SpaceInformation>(dp::makeStateSpace(world->robot()));
  auto checker = std::make_shared<dp::StateValidityChecker>(si, world);
  si->setStateValidityChecker(checker);
  si->setup();
  const auto bound = std::make_shared<const dp::LinkSpeedBound>(dp::LinkSpeedBound::forWorld(*world));
  ob::ScopedState<> a(si), b(si), c(si);
  a[0] = -0.6;
  a[1] = 0.0;
  b[0] = 0.9;
  b[1] = 0.0;
  c[0] = -0.6;
  c[1] = 1.0;  // folding the elbow at the start: far from the pole
  BOOST_TEST_REQUIRE(!si->checkMotion(a.get(), b.get()));
  BOOST_TEST_REQUIRE(si->checkMotion(a.get(), c.get()));
  for (const auto& objective : {std::make_shared<dp::ClearanceHingeObjective>(si, checker, 0.05, nullptr),
                                std::make_shared<dp::ClearanceHingeObjective>(si, checker, 0.05, bound)}) {
    BOOST_TEST(std::isinf(objective->motionCost(a.get(), b.get()).value()));
    BOOST_TEST(std::isfinite(objective->motionCost(a.get(), c.get()).value()));
    // A state's own cost stays the hinge, depth included.
    ob::ScopedState<> inside(si);
    inside[0] = 0.15;
    inside[1] = 0.0;
    BOOST_TEST(objective->stateCost(inside.get()).value() == 0.05 - checker->clearance(inside.get()),
               boost::test_tools::tolerance(1e-9));
    BOOST_TEST(objective->stateCost(inside.get()).value() > 0.05);
  }
  // With a penetration tolerance, states penetrating less than it are valid and pay d_safe + depth.
  dp::ValidityOptions tolerant;
  tolerant.penetrationTolerance = 0.01;
  auto lenient = std::make_shared<dp::StateValidityChecker>(si, world, tolerant);
  const dp::ClearanceHingeObjective hinge(si, lenient, 0.05, bound, 0.01);
  ob::ScopedState<> grazing(si), before(si);
  // Along the elbow fold at shoulder 0.15 (the pole's angle), the fore link's tip enters the pole
  // as the elbow opens: find a state 0-10 mm inside and motion into it from a free one.
  grazing[0] = 0.15;
  before[0] = 0.15;
  before[1] = 2.0;
  double elbow = 2.0;
  while (elbow > 0.0) {
    grazing[1] = elbow;
    const double sd = checker->clearance(grazing.get());
    if (sd < -0.002 && sd > -0.008) break;
    elbow -= 0.001;
  }
  BOOST_TEST_REQUIRE(elbow > 0.0);
  BOOST_TEST_REQUIRE(lenient->isValid(grazing.get()));
  const double cost = hinge.motionCost(before.get(), grazing.get()).value();
  BOOST_TEST(std::isfinite(cost));
  BOOST_TEST(cost > 0.0);
}

BOOST_AUTO_TEST_CASE(simplification_never_makes_the_objective_cost_worse) {
  // The planar arm passes the pole with its elbow folded far (2.2 rad) from it: a valid path,
  // nearly all of it farther than d_safe from the pole. Shortening it brings the fold nearer the pole; with the
  // clearance objective the simplified path must cost no more than the planned one, while with path length alone it
  // gets shorter.
  const auto world = planarArmAndPole();
  const auto plannedPath = [&](const ompl::geometric::SimpleSetup& ss) {
    auto path = std::make_shared<og::PathGeometric>(ss.getSpaceInformation());
    ob::ScopedState<> state(ss.getStateSpace());
    for (const auto& [shoulder, elbow] : std::vector<std::pair<double, double>>{
             {-0.6, 0.0}, {-0.6, 1.1}, {-0.6, 2.2}, {0.15, 2.2}, {0.9, 2.2}, {0.9, 1.1}, {0.9, 0.0}}) {
      state[0] = shoulder;
      state[1] = elbow;
      path->append(state.get());
    }
    return path;
  };
  for (const bool clearance : {true, false}) {
    auto ss = dp::makeSimpleSetup(world);
    const auto si = ss->getSpaceInformation();
    const auto checker = dp::validityCheckerOf(*ss);
    Eigen::VectorXd start(2), goal(2);
    start << -0.6, 0.0;
    goal << 0.9, 0.0;
    dp::setStartAndGoal(*ss, start, goal);
    const ob::OptimizationObjectivePtr objective =
        clearance ? dp::makeLengthClearanceObjective(si, checker, dp::tol::kDefaultSafeDistance,
                                                     dp::tol::kDefaultHingeWeight, dp::linkSpeedBoundOf(*ss))
                  : ob::OptimizationObjectivePtr(std::make_shared<ob::PathLengthOptimizationObjective>(si));
    ss->setOptimizationObjective(objective);
    ss->setup();
    const auto path = plannedPath(*ss);
    const dp::PathCheck plannedCheck = dp::checkPathWithPlanner(*path);
    BOOST_TEST_REQUIRE(plannedCheck.valid, "waypoint " << plannedCheck.firstInvalidWaypoint << ", motion "
                                                       << plannedCheck.firstInvalidMotion);
    const double plannedCost = path->cost(objective).value();
    const double plannedLength = path->length();
    const double plannedClearance = minSceneClearance(*path, *checker);
    ss->getProblemDefinition()->addSolutionPath(path);
    for (int run = 0; run < 5; ++run) {
      ss->getSolutionPath() = *path;
      dp::simplifySolutionChecked(*ss);
      const og::PathGeometric& simplified = ss->getSolutionPath();
      BOOST_TEST(dp::checkPathWithPlanner(simplified).valid);
      const double cost = simplified.cost(objective).value();
      BOOST_TEST(cost <= plannedCost, (clearance ? "clearance" : "length")
                                          << " objective: cost " << cost << " after simplification, " << plannedCost
                                          << " as planned");
      if (clearance) {
        // The symptom the cost check prevents: shortcuts pulling the fold onto the pole (OMPL's
        // simplifyMax here leaves about 1 mm, or clips it between its discrete checks). Inside
        // d_safe the objective may trade some clearance for length (seen: 3.2 cm -> 1.5 cm), so
        // the bound is a quarter of the planned clearance, far above the collapse.
        BOOST_TEST(minSceneClearance(simplified, *checker) > 0.25 * plannedClearance);
      } else {
        BOOST_TEST(simplified.length() < plannedLength);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(prepare_for_costly_objective_switches_rrt_star_to_radius_neighbours) {
  const auto world = planarArmAndPole();
  auto si = std::make_shared<ob::SpaceInformation>(dp::makeStateSpace(world->robot()));
  si->setStateValidityChecker(std::make_shared<dp::StateValidityChecker>(si, world));
  si->setup();
  og::RRTstar rrtStar(si);
  og::InformedRRTstar informed(si);
  og::PRM prm(si);
  BOOST_TEST_REQUIRE(rrtStar.getKNearest());
  BOOST_TEST(dp::prepareForCostlyObjective(rrtStar));
  BOOST_TEST(!rrtStar.getKNearest());
  BOOST_TEST(!dp::prepareForCostlyObjective(rrtStar));  // already done
  BOOST_TEST(dp::prepareForCostlyObjective(informed));
  BOOST_TEST(!informed.getKNearest());
  BOOST_TEST(!dp::prepareForCostlyObjective(prm));
}

BOOST_AUTO_TEST_SUITE_END()
