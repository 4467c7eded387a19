// Repair a colliding start state, then plan from it: the bundled 7-DOF arm with its hand pushed
// into the side wall of a shelf compartment (a start a perception or teleoperation step could
// leave behind) goes back to the front of the shelf.
//
//   example_repair_start [DATA_DIR] [OUT_FILE]
//
// DATA_DIR is the repository's robots/data (the default is compiled in), OUT_FILE the path file
// to write (default repaired_path.txt): one configuration per line, the repaired start first.

#include "report.h"

#include <deepcheck/planners/push_out.h>
#include <deepcheck/planners/setup.h>

#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <cstdio>
#include <exception>
#include <random>
#include <string>

int main(int argc, char** argv) {
  const std::string data = argc > 1 ? argv[1] : DEEPCHECK_DATA_DIR;
  const std::string out = argc > 2 ? argv[2] : "repaired_path.txt";
  ompl::RNG::setSeed(1);  // before any OMPL object: reproducible samples
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  try {
    auto ss = example::bundledArm(data, "shelf");  // as in example_plan_shelf
    const auto checker = deepcheck::planners::validityCheckerOf(*ss);

    // 1. The hand in the middle-row compartment (robots/data/README.md), turned about joint 1 by
    //    0.18 rad: the hand is then 1 cm deep in the compartment's side wall.
    Eigen::VectorXd start(7), goal(7);
    start << 1.05 + 0.18, 0.75, -1.17, -1.30, 0.05, -0.07, -2.79;
    goal << 0, -0.4, 0, -1.6, 0, 1.2, 0;
    std::printf("start            signed distance %.4f m (in collision: %s)\n", checker->clearance(start),
                checker->isValid(start) ? "no" : "yes");

    // 2. The baseline, for comparison: MoveIt's random jiggle (every joint moved at random within
    //    5 % of its range, up to 100 tries). It repairs too, but moves the arm farther.
    std::mt19937_64 rng(1);
    const deepcheck::planners::PushOutResult jiggled =
        deepcheck::planners::jiggle(checker->world(), checker->validityOptions(), start, {}, rng);
    std::printf(
        "random jiggle    %s after %d tries, joint motion %.3f rad, farthest link moved %.3f m\n",
        deepcheck::planners::toString(jiggled.status), jiggled.iterations, jiggled.jointMotion,
        jiggled.success() ? deepcheck::planners::maxLinkDisplacement(checker->world().robot(), start, jiggled.q) : 0.0);

    // 3. Push-out: damped least squares on the signed-distance gradients of every pair in
    //    contact, joint limits respected. repairStartAndGoal() replaces the start in the
    //    SimpleSetup's problem by the repaired one (the goal is valid and left as it is).
    deepcheck::planners::setStartAndGoal(*ss, start, goal);
    const deepcheck::planners::EndpointRepair repair = deepcheck::planners::repairStartAndGoal(*ss);
    const deepcheck::planners::PushOutResult& pushed = repair.starts.front();
    std::printf(
        "push-out         %s in %d iterations, joint motion %.3f rad, farthest link moved %.3f m, "
        "signed distance %.4f m\n",
        deepcheck::planners::toString(pushed.status), pushed.iterations, pushed.jointMotion,
        pushed.success() ? deepcheck::planners::maxLinkDisplacement(checker->world().robot(), start, pushed.q) : 0.0,
        pushed.finalDistance);
    if (!repair.ok()) {
      std::fprintf(stderr, "the start could not be repaired\n");
      return 1;
    }

    // 4. Plan from the repaired start as usual, shortcut, certify, report. The repaired start is
    //    only 1 mm from the wall: the discrete motion checks may let a motion graze it, so the
    //    path is certified by the clearance motion validator (and repaired where needed).
    std::printf("\n");
    return example::planCertifyAndWrite(*ss, 10.0, out) ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
