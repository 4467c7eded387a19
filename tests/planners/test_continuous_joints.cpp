// Continuous joints (robots/joint_angles.h, state_space.h): an SO2 component per wrapping
// variable, motions the short way round through +-pi, values normalized to (-pi, pi] wherever they
// enter (setStartAndGoal, the validity checker, the push-out, the problem files), and a motion
// validator that stays sound across the wrap.

#include "bundled.h"

#include "deepcheck/planners/motion_validator.h"
#include "deepcheck/planners/objectives.h"
#include "deepcheck/planners/planner_factory.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/problems/problem_generation.h"
#include "deepcheck/robots/joint_angles.h"

#include <boost/test/unit_test.hpp>

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SO2StateSpace.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

namespace dp = deepcheck::planners;
namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

constexpr double kPi = M_PI;
/// The short way from 3.0 to -3.0 rad, through pi (rad).
const double kShortTurn = 2.0 * kPi - 6.0;

/// A rod turning about z on a continuous joint 'spin' (1 mm thick, 0.1 to 0.5 m from the axis),
/// and an elbow-less second variable: a revolute 'tilt' of a small box at the base, so that the
/// compound has a RealVector run too.
deepcheck::robots::RobotModel wheel() {
  const std::string xml = R"(<robot name='wheel'>
  <link name='base'/>
  <link name='rod'><collision><origin xyz='0.3 0 0'/><geometry><box size='0.4 0.001 0.04'/></geometry></collision></link>
  <joint name='spin' type='continuous'><parent link='base'/><child link='rod'/><axis xyz='0 0 1'/></joint>
  <link name='nub'><collision><origin xyz='0 0 -0.2'/><geometry><box size='0.02 0.02 0.02'/></geometry></collision></link>
  <joint name='tilt' type='revolute'><parent link='base'/><child link='nub'/><axis xyz='1 0 0'/>
    <limit lower='-1' upper='1' effort='1' velocity='1'/></joint>
</robot>)";
  return deepcheck::robots::RobotModel::fromUrdfString(xml, ".", {}, "wheel.urdf");
}

/// The wheel, and a plate 1 mm thick (in y) at angle pi, 0.35 to 0.45 m from the axis, when
/// `plate`: the rod passes through it only within about (1 + 1) mm / 0.4 m = 0.005 rad of pi.
std::shared_ptr<deepcheck::checker::World> wheelWorld(bool plate) {
  auto world = std::make_shared<deepcheck::checker::World>(wheel());
  if (plate) {
    Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
    X_WO.translation() = Eigen::Vector3d(-0.4, 0.0, 0.0);
    world->addObstacle(deepcheck::checker::Obstacle::box("plate", Eigen::Vector3d(0.1, 0.001, 0.1), X_WO));
  }
  return world;
}

Eigen::VectorXd config(double spin, double tilt) {
  Eigen::VectorXd q(2);
  q << spin, tilt;
  return q;
}

/// The spin of each waypoint of a path.
double spinTravel(const og::PathGeometric& path, const dp::StateMapping& mapping) {
  double travel = 0.0;
  for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i) {
    const Eigen::VectorXd dq =
        mapping.displacement(mapping.configuration(path.getState(i)), mapping.configuration(path.getState(i + 1)));
    travel += std::abs(dq[0]);
  }
  return travel;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(planners_continuous_joints)

BOOST_AUTO_TEST_CASE(a_continuous_joint_is_an_so2_component_in_variable_order) {
  const auto space = dp::makeStateSpace(wheel());
  const auto* compound = dynamic_cast<const ob::CompoundStateSpace*>(space.get());
  BOOST_TEST_REQUIRE(compound != nullptr);
  BOOST_TEST_REQUIRE(compound->getSubspaceCount() == 2u);
  BOOST_TEST(compound->getSubspace(0)->getType() == ob::STATE_SPACE_SO2);
  BOOST_TEST(compound->getSubspace(0)->getName() == "spin");
  BOOST_TEST(compound->getSubspace(1)->getType() == ob::STATE_SPACE_REAL_VECTOR);
  BOOST_TEST(space->getLongestValidSegmentFraction() == dp::tol::kDefaultSegmentFraction);
  // ScopedState's values are the variables in order; the distance goes the short way.
  ob::ScopedState<> a(space), b(space);
  a = std::vector<double>{3.0, 0.5};
  b = std::vector<double>{-3.0, 0.5};
  BOOST_TEST(a[0] == 3.0);
  BOOST_TEST(a[1] == 0.5);
  BOOST_TEST(space->distance(a.get(), b.get()) == kShortTurn, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(a_start_of_4_rad_is_the_angle_4_minus_2_pi) {
  auto ss = dp::makeSimpleSetup(wheelWorld(false));
  const auto checker = dp::validityCheckerOf(*ss);
  BOOST_TEST(checker->isValid(config(4.0, 0.0)));   // not refused as above pi
  BOOST_TEST(!checker->isValid(config(0.0, 1.5)));  // the revolute joint keeps its limits
  dp::setStartAndGoal(*ss, config(4.0, 0.0), config(-7.0, 0.0));
  const Eigen::VectorXd start = checker->mapping().configuration(ss->getProblemDefinition()->getStartState(0));
  BOOST_TEST(start[0] == 4.0 - 2.0 * kPi);
  const dp::PushOutResult pushed = checker->pushOut().run(config(4.0, 0.0));
  BOOST_TEST(pushed.status == dp::PushOutStatus::AlreadyValid);
  BOOST_TEST(pushed.q[0] == 4.0 - 2.0 * kPi);  // not clamped to pi
}

BOOST_AUTO_TEST_CASE(start_3_goal_minus_3_plans_the_short_way_through_pi) {
  auto ss = dp::makeSimpleSetup(wheelWorld(false));
  dp::setStartAndGoal(*ss, config(3.0, 0.0), config(-3.0, 0.0));
  ss->setPlanner(std::make_shared<og::RRTConnect>(ss->getSpaceInformation()));
  BOOST_TEST_REQUIRE(ss->solve(5.0) == ob::PlannerStatus::EXACT_SOLUTION);
  dp::simplifySolutionChecked(*ss);
  const auto checker = dp::validityCheckerOf(*ss);
  const double travel = spinTravel(ss->getSolutionPath(), checker->mapping());
  BOOST_TEST(travel == kShortTurn, boost::test_tools::tolerance(1e-6));
  BOOST_TEST(ss->getSolutionPath().length() == kShortTurn, boost::test_tools::tolerance(1e-6));
}

BOOST_AUTO_TEST_CASE(a_start_at_pi_is_inside_ompls_interval_and_plans) {
  // The project's angles are (-pi, pi], OMPL's SO2 values [-pi, pi): pi and -pi are one angle, which
  // must enter OMPL as -pi (or OMPL skips the start as out of bounds) and come back as pi.
  for (const double spin : {kPi, -kPi, 3.0 * kPi}) {
    auto ss = dp::makeSimpleSetup(wheelWorld(false));
    const auto checker = dp::validityCheckerOf(*ss);
    dp::setStartAndGoal(*ss, config(spin, 0.0), config(-2.0, 0.0));
    const ob::State* start = ss->getProblemDefinition()->getStartState(0);
    BOOST_TEST(ss->getStateSpace()->satisfiesBounds(start), spin);
    BOOST_TEST(checker->mapping().configuration(start)[0] == kPi, spin);
    ss->setPlanner(std::make_shared<og::RRTConnect>(ss->getSpaceInformation()));
    BOOST_TEST_REQUIRE(ss->solve(5.0) == ob::PlannerStatus::EXACT_SOLUTION);
    dp::simplifySolutionChecked(*ss);
    const og::PathGeometric& path = ss->getSolutionPath();
    for (std::size_t i = 0; i < path.getStateCount(); ++i) {
      BOOST_TEST(ss->getStateSpace()->satisfiesBounds(path.getState(i)), spin << " state " << i);
      const double value = checker->mapping().configuration(path.getState(i))[0];
      BOOST_TEST((value > -kPi && value <= kPi), spin << " state " << i << ": " << value);
    }
    BOOST_TEST(spinTravel(path, checker->mapping()) == kPi - 2.0, boost::test_tools::tolerance(1e-6));
  }
}

BOOST_AUTO_TEST_CASE(informed_planners_plan_on_so2_components_with_the_library_objectives) {
  // OMPL's PathLengthDirectInfSampler refuses a compound with SO2 components; makePathLengthObjective
  // and the clearance objective sample it by rejection.
  for (const char* name : {"BIT*", "InformedRRT*"}) {
    for (const bool clearance : {false, true}) {
      auto ss = dp::makeSimpleSetup(wheelWorld(false));
      dp::setStartAndGoal(*ss, config(3.0, 0.0), config(-3.0, 0.0));
      const ob::SpaceInformationPtr& si = ss->getSpaceInformation();
      ss->setOptimizationObjective(clearance ? dp::makeLengthClearanceObjective(si, dp::validityCheckerOf(*ss))
                                             : dp::makePathLengthObjective(si));
      const ob::PlannerPtr planner = dp::makePlanner(name, si);
      dp::prepareForCostlyObjective(*planner);
      ss->setPlanner(planner);
      BOOST_TEST_REQUIRE(ss->solve(0.5) == ob::PlannerStatus::EXACT_SOLUTION, name);
      BOOST_TEST(spinTravel(ss->getSolutionPath(), dp::validityCheckerOf(*ss)->mapping()) < 0.3, name);
    }
  }
}

BOOST_AUTO_TEST_CASE(with_a_plate_at_pi_the_plan_goes_the_long_way_and_is_certified) {
  // The plate is thinner than the discrete validator's step: plan with the clearance validator.
  dp::SetupOptions options;
  options.motionValidation = dp::MotionValidation::Clearance;
  auto ss = dp::makeSimpleSetup(wheelWorld(true), options);
  dp::setStartAndGoal(*ss, config(3.0, 0.0), config(-3.0, 0.0));
  ss->setPlanner(std::make_shared<og::RRTConnect>(ss->getSpaceInformation()));
  BOOST_TEST_REQUIRE(ss->solve(5.0) == ob::PlannerStatus::EXACT_SOLUTION);
  dp::simplifySolutionChecked(*ss);
  og::PathGeometric& path = ss->getSolutionPath();
  const dp::PathCertificate certificate = dp::certifyPath(*ss, path);
  BOOST_TEST(certificate.valid);
  BOOST_TEST(spinTravel(path, dp::validityCheckerOf(*ss)->mapping()) > 6.0 - 1e-6);
}

BOOST_AUTO_TEST_CASE(the_clearance_validator_finds_a_thin_plate_on_the_short_way_across_the_wrap) {
  const auto world = wheelWorld(true);
  auto ss = dp::makeSimpleSetup(world);
  const auto si = ss->getSpaceInformation();
  const auto checker = dp::validityCheckerOf(*ss);
  // The premise: the short way from 3.0 to -3.0 hits the plate (a fine sweep through pi finds an
  // invalid state), the long way does not, and both ends are free.
  BOOST_TEST_REQUIRE(checker->isValid(config(3.0, 0.0)));
  BOOST_TEST_REQUIRE(checker->isValid(config(-3.0, 0.0)));
  int invalid = 0;
  for (int k = 0; k <= 10000; ++k) invalid += checker->isValid(config(3.0 + kShortTurn * k / 10000.0, 0.0)) ? 0 : 1;
  BOOST_TEST_REQUIRE(invalid > 0);
  const auto bound = std::make_shared<const dp::LinkSpeedBound>(dp::LinkSpeedBound::forWorld(*world));
  dp::ClearanceMotionValidator validator(si, checker, bound);
  ob::ScopedState<> a(si), b(si), zero(si);
  checker->mapping().toState(config(3.0, 0.0), a.get());
  checker->mapping().toState(config(-3.0, 0.0), b.get());
  checker->mapping().toState(config(0.0, 0.0), zero.get());
  BOOST_TEST(!validator.checkMotion(a.get(), b.get()));
  BOOST_TEST(!validator.checkMotion(b.get(), a.get()));
  // The discrete pass (about 0.015 rad steps) steps over the 0.005 rad the rod spends in the
  // plate: the certification is what rejects it.
  BOOST_TEST(validator.stats().certificationRejections == 2u);
  BOOST_TEST(validator.checkMotion(a.get(), zero.get()));
  BOOST_TEST(validator.checkMotion(zero.get(), b.get()));
  std::pair<ob::State*, double> last(nullptr, 0.0);
  BOOST_TEST(!validator.checkMotion(a.get(), b.get(), last));
  BOOST_TEST(last.second < 0.5);  // before pi, the middle of the motion
}

BOOST_AUTO_TEST_CASE(the_link_speed_bound_measures_the_wrapped_motion) {
  // Across the wrap the validator's displacement is the short turn: its bound is that of 0.28 rad,
  // and a point 0.5 m out moves at most 0.5 m/rad times it (the rod's far corner is a bit farther).
  const auto world = wheelWorld(false);
  auto ss = dp::makeSimpleSetup(world);
  const auto& mapping = dp::validityCheckerOf(*ss)->mapping();
  const Eigen::VectorXd dq = mapping.displacement(config(3.0, 0.0), config(-3.0, 0.0));
  BOOST_TEST(dq[0] == kShortTurn, boost::test_tools::tolerance(1e-12));
  const dp::LinkSpeedBound bound = dp::LinkSpeedBound::forWorld(*world);
  BOOST_TEST(bound.pairDisplacement(dq) < 0.6 * kShortTurn);
  BOOST_TEST(bound.pairDisplacement(dq) >= 0.5 * kShortTurn);
}

BOOST_AUTO_TEST_CASE(problem_files_read_a_continuous_joint_as_the_same_angle) {
  const auto robot = wheel();
  const auto readBack = [&](double spin, std::vector<std::string>* notes) {
    char yaml[200];
    std::snprintf(yaml, sizeof yaml,
                  "robot_state:\n  joint_state:\n    name: [spin, tilt]\n    position: [%.17g, 0.5]\n", spin);
    return deepcheck::problems::configurationOf(robot, deepcheck::problems::parseRobotConfig(yaml, "wheel.yaml"),
                                                notes);
  };
  std::vector<std::string> notes;
  const Eigen::VectorXd q = readBack(4.0, &notes);
  BOOST_TEST(q[0] == 4.0 - 2.0 * kPi);
  BOOST_TEST(q[1] == 0.5);
  BOOST_TEST(notes.empty());  // not "outside its limits; clamped"
  // Round trip: a normalized value written with 17 digits reads back exactly, -pi as pi.
  BOOST_TEST(readBack(q[0], &notes)[0] == q[0]);
  BOOST_TEST(readBack(-kPi, &notes)[0] == kPi);
  BOOST_TEST(readBack(kPi, &notes)[0] == kPi);
  BOOST_TEST(notes.empty());
}

BOOST_AUTO_TEST_SUITE_END()
