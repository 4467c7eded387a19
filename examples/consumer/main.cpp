// deepcheck in an OMPL program: the program's own SimpleSetup, with deepcheck's state validity
// checker (signed-distance clearance) and clearance motion validator set on its
// SpaceInformation, planning the bundled 7-DOF arm into the shelf. Prints the path's minimum
// clearance (signed distance, metres) along the path.
//
//   deepcheck_consumer [DATA_DIR]   DATA_DIR: deepcheck's bundled robot and scenes
#include <deepcheck/planners/certified_motion_validator.h>
#include <deepcheck/planners/planner_factory.h>
#include <deepcheck/planners/path_tools.h>
#include <deepcheck/planners/setup.h>
#include <deepcheck/planners/state_space.h>
#include <deepcheck/planners/validity_checker.h>

#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <cstdio>
#include <exception>
#include <memory>
#include <string>

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace dp = deepcheck::planners;

int main(int argc, char** argv) {
  const std::string data = argc > 1 ? argv[1] : CONSUMER_DATA_DIR;
  ompl::RNG::setSeed(1);
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  try {
    // The world: the arm (its SRDF's disabled self pairs) in the shelf.
    dp::SetupOptions options;
    options.packageRoots = {data};  // resolves package://deepcheck_arm/...
    options.srdf = data + "/deepcheck_arm/srdf/deepcheck_arm.srdf";
    std::shared_ptr<const deepcheck::checker::World> world =
        dp::loadWorld(data + "/deepcheck_arm/urdf/deepcheck_arm.urdf", {data + "/scenes/shelf.urdf"}, options);

    // An OMPL setup on the arm's joint space, with deepcheck's checker and motion validator.
    auto space = dp::makeStateSpace(world->robot());
    og::SimpleSetup ss(space);
    const ob::SpaceInformationPtr& si = ss.getSpaceInformation();
    auto checker = std::make_shared<dp::StateValidityChecker>(si, world);
    ss.setStateValidityChecker(checker);
    // Every motion the planner accepts is proven collision free, not sampled.
    si->setMotionValidator(std::make_shared<dp::CertifiedMotionValidator>(si, checker));

    ob::ScopedState<> start(space), goal(space);
    const double from[] = {0, -0.4, 0, -1.6, 0, 1.2, 0};  // radians, joint1 ... joint7
    const double to[] = {1.05, 0.75, -1.17, -1.30, 0.05, -0.07, -2.79};
    for (int i = 0; i < 7; ++i) start[i] = from[i], goal[i] = to[i];
    ss.setStartAndGoalStates(start, goal);
    auto planner = std::make_shared<og::RRTConnect>(si);
    planner->setRange(dp::defaultRange(*si));
    ss.setPlanner(planner);
    if (ss.solve(20.0) != ob::PlannerStatus::EXACT_SOLUTION) {
      std::fprintf(stderr, "no exact solution\n");
      return 1;
    }
    const og::PathGeometric& path = ss.getSolutionPath();
    const double clearance =
        dp::minClearanceAlong(path, [&](const Eigen::VectorXd& q) { return checker->clearance(q); });
    std::printf("waypoints      %zu\n", path.getStateCount());
    std::printf("path length    %.3f rad\n", path.length());
    std::printf("min clearance  %.4f m\n", clearance);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
