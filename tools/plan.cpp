// `deepcheck plan`: plan a robot from a start to a goal configuration among its scenes with OMPL
// and deepcheck's checker, and write the path.
//
//   deepcheck plan --robot R.urdf [--scene S.urdf [--scene-pose x y z roll pitch yaw]]...
//                  [--srdf FILE] [--package-path DIR]... --start q1 ... qn --goal q1 ... qn
//                  [--planner NAME] [--time SECONDS] [--objective length|clearance]
//                  [--repair-start [--repair-margin METRES]] [--seed N] --out path.txt
//
// The path written is the planner's solution, shortcut by OMPL's simplifier where that does not make
// the objective's cost worse (planners/setup.h: simplifySolutionChecked), then certified by the
// clearance motion validator (planners/motion_validator.h: every waypoint and every motion is
// proved free by conservative advancement, with discrete checks where that cannot conclude) and
// repaired where that fails (planners/path_tools.h). Exit status 0 only for an exact solution
// whose every waypoint and motion passed that check; 1 otherwise (no solution, approximate
// solution, a start or goal outside the joint limits (naming the joint, its value and limit) or in
// collision without --repair-start (naming the pair), a failed certification), with one line on
// stderr saying which; 2 for a bad command line. The report on stderr gives the path's scene
// clearance and self clearance separately, each with its pair.

#include "common.h"
#include "subcommands.h"

#include "deepcheck/planners/objectives.h"
#include "deepcheck/planners/path_tools.h"
#include "deepcheck/planners/planner_factory.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/checker/world.h"
#include "deepcheck/robots/robot_model.h"

#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::tools {
namespace {

constexpr const char* kUsage =
    "usage: deepcheck plan --robot R.urdf [--scene S.urdf [--scene-pose x y z roll pitch yaw]]...\n"
    "                      [--srdf FILE] [--package-path DIR]... --start q1 ... qn --goal q1 ... qn\n"
    "                      [--planner NAME] [--time SECONDS] [--objective length|clearance]\n"
    "                      [--repair-start [--repair-margin METRES]] [--seed N] --out path.txt\n"
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
    "  --repair-start      push a start (and goal) in slight collision out to the nearest\n"
    "                      configuration with --repair-margin of clearance first\n"
    "                      (planners/push_out.h)\n"
    "  --repair-margin M   the clearance a repaired start or goal gets, metres (default 0.001)\n"
    "  --seed N            OMPL's random seed, 0 to 4294967295 (default: OMPL's own, different\n"
    "                      each run)\n"
    "  --out FILE          where to write the path (required)\n";

Eigen::VectorXd toVector(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

/// Throws InputError naming the first joint of q outside its limits, its value and the limit.
void checkWithinLimits(const robots::RobotModel& model, const Eigen::VectorXd& q, const std::string& what) {
  for (int v = 0; v < model.numVariables(); ++v) {
    const double lower = model.lowerLimits()[v];
    const double upper = model.upperLimits()[v];
    if (q[v] >= lower && q[v] <= upper) continue;
    const char* unit = model.joint(model.variableJoint(v)).type == robots::JointType::Prismatic ? "m" : "rad";
    char text[160];
    std::snprintf(text, sizeof text, " = %.6g %s is %s its %s limit %.6g %s", q[v], unit,
                  q[v] < lower ? "below" : "above", q[v] < lower ? "lower" : "upper", q[v] < lower ? lower : upper,
                  unit);
    throw InputError("the " + what + " configuration is outside the joint limits: joint '" +
                     model.variableNames()[static_cast<std::size_t>(v)] + "'" + text);
  }
}

/// The nearest pair of one kind, for the report.
struct NearestPair {
  double distance = std::numeric_limits<double>::infinity();
  std::string a = "none";
  std::string b = "none";

  void update(const checker::DistanceResult& r) {
    if (!r.found || !(r.closest.distance < distance)) return;
    distance = r.closest.distance;
    a = r.closest.nameA;
    b = r.closest.nameB;
  }
  std::string describe() const {
    char text[64];
    std::snprintf(text, sizeof text, "%.4g m", distance);
    return std::string(text) + " (" + a + ", " + b + ")";
  }
};

/// The path's smallest scene clearance and self clearance (each with its pair), over the states
/// planners::minClearanceAlong visits.
std::pair<NearestPair, NearestPair> pathClearances(const ompl::geometric::PathGeometric& path,
                                                   const checker::World& world) {
  NearestPair scene;
  NearestPair self;
  checker::DistanceOptions sceneQuery;
  sceneQuery.selfPairs = false;
  checker::DistanceOptions selfQuery;
  selfQuery.worldPairs = false;
  planners::minClearanceAlong(path, [&](const Eigen::VectorXd& q) {
    scene.update(world.signedDistance(q, sceneQuery));
    self.update(world.signedDistance(q, selfQuery));
    return std::min(scene.distance, self.distance);
  });
  return {scene, self};
}

int run(std::vector<std::string> args) {
  std::string robotPath;
  std::vector<SceneArg> scenes;
  std::string srdf;
  takeWorldOptions(args, robotPath, scenes, srdf);
  const PackageRoots packages = takePackageRoots(args);
  const std::vector<double> start = takeVector(args, "--start");
  const std::vector<double> goal = takeVector(args, "--goal");
  const std::string plannerName = takeSingleOption(args, "--planner", "RRTConnect");
  const double seconds = parseValue(takeSingleOption(args, "--time", "5"), "--time");
  const std::string objectiveName = takeSingleOption(args, "--objective", "length");
  const bool repair = takeFlag(args, "--repair-start");
  const std::string marginText = takeSingleOption(args, "--repair-margin");
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
  double margin = planners::tol::kEndpointRepairMargin;
  if (!marginText.empty()) {
    if (!repair) throw UsageError("--repair-margin needs --repair-start");
    margin = parseValue(marginText, "--repair-margin");
    if (margin < 0.0) throw UsageError("--repair-margin must be >= 0 metres, got " + marginText);
  }
  if (!seed.empty()) {
    // OMPL seeds a 32-bit generator (and takes 0 as 1).
    const std::uint64_t value = parseCount(seed, "--seed", 0, std::numeric_limits<std::uint32_t>::max());
    ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(value));  // before any OMPL object
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

  planners::SetupOptions options;
  options.packageRoots = packages.commandLine;
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

  checkWithinLimits(checker->world().robot(), toVector(start), "start");
  checkWithinLimits(checker->world().robot(), toVector(goal), "goal");
  if (repair) {
    const planners::EndpointRepair r = planners::repairStartAndGoal(*ss, margin);
    const auto report = [&](const char* what, const planners::PushOutResult& p) {
      // finalDistance is NaN when the push-out did not start (push_out.h): measure it then.
      const double sd = std::isnan(p.finalDistance) ? checker->clearance(p.q) : p.finalDistance;
      std::fprintf(stderr, "repair %s: %s, moved %.4g rad, signed distance now %.4g m (margin %.4g m)\n", what,
                   planners::toString(p.status), p.jointMotion, sd, margin);
    };
    report("start", r.starts.front());
    if (r.goalIsState) report("goal", r.goal);
    if (!r.ok()) throw InputError("the start or goal could not be pushed out of collision (see above)");
  } else {
    for (const auto& [what, q] : {std::pair<const char*, const std::vector<double>*>{"start", &start}, {"goal", &goal}}) {
      if (checker->isValid(toVector(*q))) continue;
      const checker::DistanceResult d = checker->world().signedDistance(toVector(*q));
      char distance[48];
      std::snprintf(distance, sizeof distance, "%.4g m", d.closest.distance);
      throw InputError(std::string("the ") + what + " configuration is in collision: signed distance " + distance +
                       " between " + d.closest.nameA + " and " + d.closest.nameB +
                       "; --repair-start pushes a slightly colliding one out");
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
  std::fprintf(stderr, "planner %s: %s after %s\n", planner->getName().c_str(), status.asString().c_str(),
               formatDuration(ss->getLastPlanComputationTime()).c_str());
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
  const auto [scene, self] = pathClearances(path, checker->world());
  std::fprintf(stderr, "path: %zu waypoints, length %.4f rad, scene clearance %s, self clearance %s, %s%s, written to %s\n",
               path.getStateCount(), path.length(), scene.describe().c_str(), self.describe().c_str(),
               certificate.valid ? "certified" : "NOT certified",
               certificate.repaired ? " (after repair)" : "", out.c_str());
  if (!certificate.valid) throw InputError("the path could not be certified collision free");
  return 0;
}

}  // namespace

const Subcommand kPlanCommand = {"plan", "plan a path between two configurations with OMPL", kUsage, run};

}  // namespace deepcheck::tools
