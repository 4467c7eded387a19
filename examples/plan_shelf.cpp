// Plan the bundled 7-DOF arm from in front of the shelf into one of its compartments.
//
//   example_plan_shelf [DATA_DIR] [OUT_FILE]
//
// DATA_DIR is the repository's robots/data (the default is compiled in), OUT_FILE the path file
// to write (default shelf_path.txt): one configuration per line.

#include "report.h"

#include <deepcheck/planners/setup.h>

#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  const std::string data = argc > 1 ? argv[1] : DEEPCHECK_DATA_DIR;
  const std::string out = argc > 2 ? argv[2] : "shelf_path.txt";
  ompl::RNG::setSeed(1);  // before any OMPL object: reproducible samples
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  try {
    // 1. One call: the arm (with its SRDF's disabled self pairs) in the shelf scene, as an OMPL
    //    SimpleSetup with deepcheck's validity checker (OMPL's discrete motion validator).
    deepcheck::planners::SetupOptions options;
    options.packageRoots = {data};  // resolves package://deepcheck_arm/...
    options.srdf = data + "/deepcheck_arm/srdf/deepcheck_arm.srdf";
    auto ss = deepcheck::planners::makeSimpleSetup(data + "/deepcheck_arm/urdf/deepcheck_arm.urdf",
                                                   {data + "/scenes/shelf.urdf"}, options);

    // 2. Start in front of the shelf, goal with the hand inside the middle-row compartment
    //    (robots/data/README.md); joint values in radians, joint1 ... joint7.
    Eigen::VectorXd start(7), goal(7);
    start << 0, -0.4, 0, -1.6, 0, 1.2, 0;
    goal << 1.05, 0.75, -1.17, -1.30, 0.05, -0.07, -2.79;
    deepcheck::planners::setStartAndGoal(*ss, start, goal);

    // 3. Any OMPL planner works; RRTConnect is the usual first choice.
    ss->setPlanner(std::make_shared<ompl::geometric::RRTConnect>(ss->getSpaceInformation()));
    const ompl::base::PlannerStatus status = ss->solve(10.0);
    if (status != ompl::base::PlannerStatus::EXACT_SOLUTION) {
      std::fprintf(stderr, "no exact solution: %s\n", status.asString().c_str());
      return 1;
    }

    // 4. Shortcut the path (every shortcut is checked by the same motion validator; should OMPL's
    //    simplifier still return a path its own checks reject, the planned one is kept), report.
    deepcheck::planners::simplifySolutionChecked(*ss);
    example::reportAndWrite(*ss, out);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
