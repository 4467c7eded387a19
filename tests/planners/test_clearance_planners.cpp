// MEASUREMENT (temporary)
#include "deepcheck/planners/objectives.h"
#include "deepcheck/planners/planner_factory.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/state_space.h"
#include "../common/test_paths.h"

#include <boost/test/unit_test.hpp>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/RandomNumbers.h>

#include <chrono>
#include <cstdio>
#include <cmath>
#include <string>

namespace dp = deepcheck::planners;
namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {
std::shared_ptr<deepcheck::checker::World> ur5World() {
  const std::string dir = deepcheck::test::sharedDir() + "/robots/ur5";
  const std::string ur = dir + "/example-robot-data/robots/ur_description";
  dp::SetupOptions options;
  options.packageRoots = {dir};
  options.useRosPackagePath = false;
  options.srdf = ur + "/srdf/ur5.srdf";
  auto world = dp::loadWorld(ur + "/urdf/ur5_robot.urdf", {}, options);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  const double top = std::getenv("TOP") ? std::atof(std::getenv("TOP")) : 0.4;
  pose.translation() = Eigen::Vector3d(0.55, 0.0, top / 2);
  world->addObstacle(deepcheck::checker::Obstacle::cylinder("pole", 0.04, top, pose));
  return world;
}
}  // namespace

BOOST_AUTO_TEST_SUITE(planners_clearance_measure)
BOOST_AUTO_TEST_CASE(measure) {
  if (!deepcheck::test::haveShared("measure")) return;
  const auto world = ur5World();
  const char* which = std::getenv("MEASURE");
  const std::string planner = which ? which : "RRT*";
  for (int clearance = 0; clearance < 2; ++clearance) {
    for (unsigned seed = 1; seed <= 3; ++seed) {
      auto ss = dp::makeSimpleSetup(world);
      const auto checker = dp::validityCheckerOf(*ss);
      Eigen::VectorXd s(6), g(6);
      const char* ends = std::getenv("ENDS");
      if (ends && std::string(ends) == "free") {
        s << 0, -1.57, 1.57, 0, 0, 0;
        g << 2.5, -1.0, 1.0, 0.5, 0.5, 0;
      } else {
        const double pan = std::getenv("PAN") ? std::atof(std::getenv("PAN")) : 0.8;
        const double lift = std::getenv("LIFT") ? std::atof(std::getenv("LIFT")) : -0.2;
        s << -pan, lift, 0, -1.4, -1.57, 0;
        g << pan, lift, 0, -1.4, -1.57, 0;
      }
      dp::setStartAndGoal(*ss, s, g);
      if (seed == 1 && clearance == 0) std::printf("start valid %d %.4f goal valid %d %.4f\n", checker->isValid(s), checker->clearance(s), checker->isValid(g), checker->clearance(g));
      auto p = dp::makePlanner(planner, ss->getSpaceInformation());
      if (clearance) {
        ss->setOptimizationObjective(dp::makeLengthClearanceObjective(ss->getSpaceInformation(), checker,
            dp::tol::kDefaultSafeDistance, dp::tol::kDefaultHingeWeight, dp::linkSpeedBoundOf(*ss)));
        dp::prepareForCostlyObjective(*p);
      } else {
        ss->setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(ss->getSpaceInformation()));
      }
      if (std::getenv("RANGE")) p->params().setParam("range", std::getenv("RANGE"));
      if (std::getenv("REWIRE")) p->params().setParam("rewire_factor", std::getenv("REWIRE"));
      ss->setPlanner(p);
      ss->setup();
      std::const_pointer_cast<dp::StateValidityChecker>(checker)->resetCounters();
      const auto t0 = std::chrono::steady_clock::now();
      auto props0 = p->getPlannerProgressProperties();
      auto best = props0.count("best cost REAL") ? props0["best cost REAL"] : props0.count("best cost DOUBLE") ? props0["best cost DOUBLE"] : ob::Planner::PlannerProgressProperty();
      auto pdef = ss->getProblemDefinition();
      const auto ptc = ob::plannerOrTerminationCondition(ob::timedPlannerTerminationCondition(std::getenv("TIME") ? std::atof(std::getenv("TIME")) : 8.0),
          ob::PlannerTerminationCondition([best, pdef] {
            if (std::getenv("FULL")) return false;
            if (pdef->hasExactSolution()) return true;
            if (!best) return false;
            const double c = std::stod(best());
            return std::isfinite(c);
          }));
      const auto status = ss->solve(ptc);
      const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      ob::PlannerData data(ss->getSpaceInformation());
      ss->getPlannerData(data);
      std::string iters = "?";
      auto props = p->getPlannerProgressProperties();
      if (props.count("iterations INTEGER")) iters = props["iterations INTEGER"]();
      std::printf("%s %s seed %u: %s in %.2f s, iterations %s, vertices %u, validity %llu distance %llu\n", planner.c_str(),
                  clearance ? "clearance" : "length", seed, status.asString().c_str(), t, iters.c_str(),
                  data.numVertices(), (unsigned long long)checker->validityQueries(),
                  (unsigned long long)checker->distanceQueries());
    }
  }
}
BOOST_AUTO_TEST_SUITE_END()
