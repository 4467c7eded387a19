// `deepcheck plan`: plan a robot from a start to a goal configuration among its scenes with OMPL
// and deepcheck's checker, and write the path.
//
//   deepcheck plan --robot R.urdf [--scene S.urdf [--scene-pose x y z roll pitch yaw]]...
//                  [--srdf FILE] [--package-path DIR]... --start q1 ... qn --goal q1 ... qn
//                  [--planner NAME] [--time SECONDS] [--objective length|clearance]
//                  [--repair-start] [--seed N] --out path.txt
//
// The path written is the planner's solution, shortcut by OMPL's simplifier where that does not make
// the objective's cost worse (planners/setup.h: simplifySolutionChecked), then certified by the
// clearance motion validator (planners/motion_validator.h: every waypoint and every motion is
// proved free by conservative advancement, with discrete checks where that cannot conclude) and
// repaired where that fails (planners/path_tools.h). Exit status 0 only for an exact solution
// whose every waypoint and motion passed that check; 1 otherwise (no solution, approximate
// solution, a start or goal in collision without --repair-start, a failed certification), with
// one line on stderr saying which; 2 for a bad command line.

#include "common.h"
#include "subcommands.h"

#include "deepcheck/planners/objectives.h"
#include "deepcheck/planners/path_tools.h"
#include "deepcheck/planners/planner_factory.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/robots/robot_model.h"

#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace deepcheck::tools {
namespace {

constexpr const char* kUsage =
    "usage: deepcheck plan --robot R.urdf [--scene S.urdf [--scene-pose x y z roll pitch yaw]]...\n"
    "                      [--srdf FILE] [--package-path DIR]... --start q1 ... qn --goal q1 ... qn\n"
    "                      [--planner NAME] [--time SECONDS] [--objective length|clearance]\n"
    "                      [--repair-start] [--seed N] --out path.txt\n"
    "\n"
    "Plans with OMPL and deepcheck's checker and writes the path, one configuration per line\n"
    "(joint values in the order `deepcheck info` prints). The solution is shortcut, then every\n"
    "waypoint and motion is certified free by the clearance motion validator (and repaired where\n"
    "that fails). Exit status 0 only for an exact, certified solution.\n"
    "\n"
    "options:\n"
    "  --robot FILE        the robot's URDF (required)\n"
    "  --scene FILE        a scene URDF (repeatable), optionally followed by\n"
    "  --scene-pose x y z roll pitch yaw   its pose (metres, radians, URDF rpy)\n"
    "  --srdf FILE         disable the self-collision pairs of this SRDF\n"
    "  --package-path DIR  a root for package:// URIs (repeatable; ROS_PACKAGE_PATH is also read)\n"
    "  --start q1 ... qn   the start configuration (required; n = the robot's variables)\n"
    "  --goal q1 ... qn    the goal configuration (required)\n"
    "  --planner NAME      an OMPL planner (default RRTConnect): RRTConnect, RRT, RRT*,\n"
    "                      InformedRRT*, BIT*, PRM, PRM*, LazyPRM, LazyPRM*, KPIECE1, BKPIECE1,\n"
    "                      EST, BiEST, SBL, FMT, TRRT\n"
    "  --time SECONDS      planning time limit (default 5); optimizing planners use all of it\n"
    "  --objective O       length (default) or clearance: path length plus the clearance hinge\n"
    "                      max(0, 0.05 m - sd), weight 100 / m, integrated along the path\n"
    "                      (planners/objectives.h); RRT* then uses radius neighbours\n"
    "  --repair-start      push a start (and goal) in slight collision out to the nearest free\n"
    "                      configuration first (planners/push_out.h)\n"
    "  --seed N            OMPL's random seed, 0 to 4294967295 (default: OMPL's own, different\n"
    "                      each run)\n"
    "  --out FILE          where to write the path (required)\n";

Eigen::VectorXd toVector(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

int run(std::vector<std::string> args) {
  std::string robotPath;
  std::vector<SceneArg> scenes;
  std::string srdf;
  takeWorldOptions(args, robotPath, scenes, srdf);
  const PackagePaths packages = takePackagePaths(args);
  const std::vector<double> start = takeVector(args, "--start");
  const std::vector<double> goal = takeVector(args, "--goal");
  const std::string plannerName = takeSingleOption(args, "--planner", "RRTConnect");
  const double seconds = parseValue(takeSingleOption(args, "--time", "5"), "--time");
  const std::string objectiveName = takeSingleOption(args, "--objective", "length");
  const bool repair = takeFlag(args, "--repair-start");
  const std::string seed = takeSingleOption(args, "--seed");
  const std::string out = takeSingleOption(args, "--out");
  rejectUnknownOptions(args);
  if (!args.empty()) throw UsageError("unexpected argument '" + args.front() + "'");
  if (start.empty()) throw UsageError("option --start is required");
  if (goal.empty()) throw UsageError("option --goal is required");
  if (out.empty()) throw UsageError("option --out is required");
  if (!(seconds > 0.0)) throw UsageError("--time must be > 0 seconds, got " + std::to_string(seconds));
  if (objectiveName != "length" && objectiveName != "clearance") {
    throw UsageError("--objective must be 'length' or 'clearance', got '" + objectiveName + "'");
  }
  if (!seed.empty()) {
    // OMPL seeds a 32-bit generator (and takes 0 as 1).
    const std::uint64_t value = parseCount(seed, "--seed", 0, std::numeric_limits<std::uint32_t>::max());
    ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(value));  // before any OMPL object
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

  planners::SetupOptions options;
  options.packagePaths = packages.commandLine;
  options.srdf = srdf;
  std::vector<planners::SceneSpec> specs;
  for (const SceneArg& scene : scenes) {
    specs.push_back(scene.posed ? planners::SceneSpec(scene.path, scene.X_WS) : planners::SceneSpec(scene.path));
  }
  auto ss = planners::makeSimpleSetup(robotPath, specs, options);
  const auto checker = planners::validityCheckerOf(*ss);
  const auto si = ss->getSpaceInformation();
  planners::setStartAndGoal(*ss, toVector(start), toVector(goal));
  // The planner first: an unknown name is reported before any work.
  auto planner = planners::makePlanner(plannerName, si);
  std::fprintf(stderr, "%s", checker->world().summary().c_str());

  if (repair) {
    const planners::EndpointRepair r = planners::repairStartAndGoal(*ss);
    const auto report = [&](const char* what, const planners::PushOutResult& p) {
      // finalDistance is NaN when the push-out did not start (push_out.h): measure it then.
      const double sd = std::isnan(p.finalDistance) ? checker->clearance(p.q) : p.finalDistance;
      std::fprintf(stderr, "repair %s: %s, moved %.4g rad, signed distance now %.4g m\n", what, planners::toString(p.status),
                   p.jointMotion, sd);
    };
    report("start", r.starts.front());
    if (r.goalIsState) report("goal", r.goal);
    if (!r.ok()) throw InputError("the start or goal could not be pushed out of collision (see above)");
  } else {
    for (const auto& [what, q] : {std::pair<const char*, const std::vector<double>*>{"start", &start}, {"goal", &goal}}) {
      if (!checker->isValid(toVector(*q))) {
        throw InputError(std::string("the ") + what + " configuration is in collision or outside the limits (signed " +
                         "distance " + std::to_string(checker->clearance(toVector(*q))) +
                         " m); --repair-start pushes a slightly colliding one out");
      }
    }
  }

  if (objectiveName == "clearance") {
    ss->setOptimizationObjective(
        planners::makeLengthClearanceObjective(si, checker, planners::tol::kDefaultSafeDistance,
                                               planners::tol::kDefaultHingeWeight, planners::linkSpeedBoundOf(*ss)));
    planners::prepareForCostlyObjective(*planner);  // RRT*: radius neighbours (planner_factory.h)
  } else {
    ss->setOptimizationObjective(std::make_shared<ompl::base::PathLengthOptimizationObjective>(si));
  }
  ss->setPlanner(planner);
  const ompl::base::PlannerStatus status = ss->solve(seconds);
  std::fprintf(stderr, "planner %s: %s after %.3f s\n", planner->getName().c_str(), status.asString().c_str(),
               ss->getLastPlanComputationTime());
  if (status != ompl::base::PlannerStatus::EXACT_SOLUTION) {
    if (ss->haveSolutionPath()) planners::writePath(ss->getSolutionPath(), out);
    throw InputError(std::string("no exact solution (") + status.asString() + ")" +
                     (ss->haveSolutionPath() ? "; the approximate path was written to " + out : std::string()));
  }
  if (!planners::simplifySolutionChecked(*ss)) {
    std::fprintf(stderr, "path simplification: no simplified path passed the planner's checks without a worse "
                         "objective cost; the path as planned is kept\n");
  }
  ompl::geometric::PathGeometric& path = ss->getSolutionPath();
  const planners::PathCertificate certificate = planners::certifyPath(*ss, path);
  planners::writePath(path, out);
  const double clearance = planners::minClearanceAlong(
      path, [&](const Eigen::VectorXd& q) { return checker->clearance(q); });
  std::fprintf(stderr, "path: %zu waypoints, length %.4f rad, min clearance %.4f m, %s%s, written to %s\n",
               path.getStateCount(), path.length(), clearance,
               certificate.valid ? "certified" : "NOT certified",
               certificate.repaired ? " (after repair)" : "", out.c_str());
  if (!certificate.valid) throw InputError("the path could not be certified collision free");
  return 0;
}

}  // namespace

const Subcommand kPlanCommand = {"plan", "plan a path between two configurations with OMPL", kUsage, run};

}  // namespace deepcheck::tools
