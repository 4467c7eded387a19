// `deepcheck plan`: plan a robot from a start configuration to a goal configuration, or to a pose
// of one of its links, among its scenes with OMPL and deepcheck's checker, and write the path.
//
//   deepcheck plan --robot R.urdf [--scene S.urdf [--scene-pose x y z roll pitch yaw]]...
//                  [--scene S.yaml]... [--frame-alias NAME=LINK]...
//                  [--srdf FILE]... [--group NAME] [--lock JOINT=VALUE]... [--package-path DIR]... --start q1 ... qn
//                  (--goal q1 ... qn | --goal-pose LINK x y z qx qy qz qw
//                                      [--position-tol M | --position-box X Y Z] [--orientation-tol RAD])
//                  [--planner NAME] [--time SECONDS] [--objective length|clearance]
//                  [--repair-start [--repair-margin METRES]] [--clamp-to-limits] [--seed N] --out path.txt
//
// A pose goal (planners/pose_goal.h) is reached by inverse kinematics: one collision-free
// solution is found before planning (none: exit status 1 with the best attempt's error), then
// more are sampled while the planner runs. The quaternion is in MoveIt's order (x y z w) and is
// normalized; the pose is of the link's frame in the world frame.
//
// The path written is the planner's solution, shortcut by OMPL's simplifier where that does not make
// the objective's cost worse (planners/setup.h: simplifySolutionChecked). The planner and the
// simplifier accept only motions the certified motion validator proves free
// (planners/certified_motion_validator.h), so the path is certified as planned; certifyPath checks
// it once more (and would repair what fails, planners/path_tools.h), and the report says how long
// that took. Exit status 0 only for an exact solution
// whose every waypoint and motion passed that check (and, for a pose goal, whose last
// configuration reaches the pose within the tolerances); 1 otherwise (no solution, approximate
// solution, a start or goal outside the joint limits (naming the joint, its value and limit) or in
// collision without --repair-start (naming the pair), no collision-free IK solution, a failed
// certification), with one line on stderr saying which; 2 for a bad command line. The report on
// stderr gives the path's scene clearance and self clearance separately, each with its pair, and
// for a pose goal the reached pose's position and orientation errors.

#include "common.h"
#include "goal_pose.h"
#include "load_world.h"
#include "subcommands.h"

#include "deepcheck/planners/objectives.h"
#include "deepcheck/planners/path_tools.h"
#include "deepcheck/planners/planner_factory.h"
#include "deepcheck/planners/pose_goal.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/checker/world.h"
#include "deepcheck/robots/format_number.h"
#include "deepcheck/robots/inverse_kinematics.h"
#include "deepcheck/robots/joint_angles.h"
#include "deepcheck/robots/robot_model.h"

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::tools {
namespace {

constexpr const char* kPlanUsage =
    "usage: deepcheck plan --robot R.urdf [--scene S.urdf [--scene-pose x y z roll pitch yaw]]...\n"
    "                      [--scene S.yaml]... [--frame-alias NAME=LINK]...\n"
    "                      [--srdf FILE]... [--group NAME] [--lock JOINT=VALUE]... [--package-path DIR]... --start q1 "
    "... qn\n"
    "                      (--goal q1 ... qn | --goal-pose LINK x y z qx qy qz qw\n"
    "                                          [--position-tol M | --position-box X Y Z] [--orientation-tol RAD])\n"
    "                      [--planner NAME] [--time SECONDS] [--objective length|clearance]\n"
    "                      [--repair-start [--repair-margin METRES]] [--clamp-to-limits] [--seed N]\n"
    "                      --out path.txt\n"
    "\n"
    "Plans with OMPL and deepcheck's checker and writes the path, one configuration per line\n"
    "(joint values in the order `deepcheck info` prints). Every motion the planner and the\n"
    "shortcutting accept is proven collision free (certified, not sampled); the path is checked\n"
    "once more (and repaired where that fails). Exit status 0 only for an exact, certified solution. A start or goal "
    "value outside\n"
    "its joint's limits is an error naming the joint, the value and the limits (see\n"
    "--clamp-to-limits); a continuous joint's value is taken as the same angle in (-pi, pi].\n"
    "\n"
    "options:\n" DEEPCHECK_WORLD_OPTIONS_HELP
    "  --start q1 ... qn   the start configuration (required; n = the robot's variables)\n"
    "  --goal q1 ... qn    the goal configuration (this or --goal-pose is required)\n"
    "  --goal-pose LINK x y z qx qy qz qw\n"
    "                      the goal is a pose of the robot's link LINK: its frame's origin at\n"
    "                      (x, y, z) in the world frame (metres), its orientation the quaternion\n"
    "                      qx qy qz qw (MoveIt's order, normalized; not zero). Reached by inverse\n"
    "                      kinematics; no collision-free solution is exit status 1\n"
    "  --position-tol M    how far the link's origin may be from the goal, metres (default 1e-4)\n"
    "  --position-box X Y Z  instead, a box of those edge lengths (metres) centred on the goal\n"
    "                      along the goal frame's x, y and z (MoveIt's box region)\n"
    "  --orientation-tol RAD  the largest rotation between the link's orientation and the goal's,\n"
    "                      radians (default 1e-3)\n"
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
    "  --repair-margin M   the clearance a repaired start or goal gets, metres (default 0.001)\n" DEEPCHECK_CLAMP_HELP
    "  --seed N            OMPL's random seed, 0 to 4294967295 (default: OMPL's own, different\n"
    "                      each run), and the first seed of a pose goal's IK (default 0)\n"
    "  --out FILE          where to write the path (required)\n";

Eigen::VectorXd toVector(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

/// Throws InputError naming `what` for a q of the wrong size.
void checkSize(const robots::RobotModel& model, const std::vector<double>& q, const std::string& what) {
  if (static_cast<int>(q.size()) == model.numVariables()) return;
  throw InputError("the " + what + " configuration has " + std::to_string(q.size()) + " values, robot '" +
                   model.name() + "' has " + std::to_string(model.numVariables()) + " variables");
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

/// The command line of `deepcheck plan`.
struct PlanArgs {
  WorldArgs world;
  std::vector<double> start;
  std::vector<double> goal;
  std::optional<GoalPoseArg> goalPose;
  JointLimitPolicy limits;  ///< --clamp-to-limits
  std::string plannerName;
  double seconds = 0.0;
  std::string objectiveName;
  bool repair = false;
  double margin = planners::tol::kEndpointRepairMargin;
  std::uint64_t seed = 0;  ///< of the IK samples of a pose goal (and OMPL's, when seeded)
  bool seeded = false;
  std::string out;
};

/// --repair-start [--repair-margin M].
void takeRepairOptions(std::vector<std::string>& args, PlanArgs& a) {
  a.repair = takeFlag(args, "--repair-start");
  const std::string marginText = takeSingleOption(args, "--repair-margin");
  if (marginText.empty()) return;
  if (!a.repair) throw UsageError("--repair-margin needs --repair-start");
  a.margin = parseValue(marginText, "--repair-margin");
  if (a.margin < 0.0) throw UsageError("--repair-margin must be >= 0 metres, got " + marginText);
}

PlanArgs takePlanArgs(std::vector<std::string>& args) {
  PlanArgs a;
  a.world = takeWorldArgs(args);
  a.limits.clamp = takeFlag(args, "--clamp-to-limits");
  a.start = takeVector(args, "--start");
  a.goalPose = takeGoalPose(args);
  a.goal = takeVector(args, "--goal");
  a.plannerName = takeSingleOption(args, "--planner", "RRTConnect");
  a.seconds = parseValue(takeSingleOption(args, "--time", "5"), "--time");
  a.objectiveName = takeSingleOption(args, "--objective", "length");
  takeRepairOptions(args, a);
  if (const std::string seed = takeSingleOption(args, "--seed"); !seed.empty()) {
    // OMPL seeds a 32-bit generator (and takes 0 as 1).
    a.seed = parseCount(seed, "--seed", 0, std::numeric_limits<std::uint32_t>::max());
    a.seeded = true;
  }
  a.out = takeSingleOption(args, "--out");
  rejectUnknownOptions(args);
  if (!args.empty()) throw UsageError("unexpected argument '" + args.front() + "'");
  if (a.start.empty()) throw UsageError("option --start is required");
  if (a.goalPose && !a.goal.empty()) throw UsageError("--goal and --goal-pose exclude each other");
  if (!a.goalPose && a.goal.empty()) throw UsageError("option --goal (or --goal-pose) is required");
  if (a.out.empty()) throw UsageError("option --out is required");
  if (!(a.seconds > 0.0)) throw UsageError("--time must be > 0 seconds, got " + std::to_string(a.seconds));
  if (a.objectiveName != "length" && a.objectiveName != "clearance") {
    throw UsageError("--objective must be 'length' or 'clearance', got '" + a.objectiveName + "'");
  }
  return a;
}

/// The PoseGoal options of the command line: its tolerances, and the seed of its IK samples.
planners::PoseGoalOptions poseGoalOptions(const PlanArgs& a, const Eigen::VectorXd& start) {
  planners::PoseGoalOptions options;
  options.ik.positionTolerance = a.goalPose->positionTolerance;
  options.ik.orientationTolerance = a.goalPose->orientationTolerance;
  if (a.goalPose->positionBox) options.ik.positionBox = *a.goalPose->positionBox;
  options.ik.seed = a.seed;
  options.ik.initial = start;  // the first solution near the start
  return options;
}

/// Sets the pose goal: one collision-free IK solution first (none: InputError with the best
/// attempt's error), handed to the goal as its first state, then PoseGoal samples more while the
/// planner runs. Call after the start state is set.
std::shared_ptr<planners::PoseGoal> setPoseGoal(ompl::geometric::SimpleSetup& ss, const PlanArgs& a,
                                                const Eigen::VectorXd& start) {
  const auto checker = planners::validityCheckerOf(ss);
  const GoalPoseArg& pose = *a.goalPose;
  const planners::PoseGoalOptions options = poseGoalOptions(a, start);
  const robots::IkResult first = planners::solveCollisionFree(*checker, pose.link, pose.X_WT, options.ik);
  std::fprintf(stderr, "goal pose of %s: IK %s after %d attempt(s), %d solution(s) in collision rejected\n",
               pose.link.c_str(), robots::toString(first.status), first.attempts, first.rejected);
  if (first.status == robots::IkStatus::Rejected) {
    throw InputError("no collision-free inverse kinematics solution for link '" + pose.link +
                     "' at the goal pose: the " + std::to_string(first.rejected) +
                     " solution(s) found all fail the planner's validity check (a collision, or a joint outside "
                     "its bounds)");
  }
  if (!first.converged()) {
    char position[96];
    if (pose.positionBox) {
      const Eigen::Vector3d& h = *pose.positionBox;
      std::snprintf(position, sizeof position, "box %.4g %.4g %.4g m", h.x(), h.y(), h.z());
    } else {
      std::snprintf(position, sizeof position, "%.4g m", pose.positionTolerance);
    }
    char text[240];
    std::snprintf(text, sizeof text, ": the best attempt is %.4g m and %.4g rad from it (tolerances %s, %.4g rad)",
                  first.error.position, first.error.orientation, position, pose.orientationTolerance);
    throw InputError("no inverse kinematics solution for link '" + pose.link + "' reaches the goal pose" + text);
  }
  // The first solution is already a goal state: the sampling thread goes on from the next seed.
  planners::PoseGoalOptions sampling = options;
  sampling.ik.initial.resize(0);
  sampling.ik.seed += 1;
  auto goal = std::make_shared<planners::PoseGoal>(ss.getSpaceInformation(), pose.link, pose.X_WT, sampling);
  ompl::base::ScopedState<> state(ss.getStateSpace());
  checker->mapping().toState(first.q, state.get());
  goal->addState(state.get());
  ss.setGoal(goal);
  return goal;
}

/// The start and a goal configuration taken within the joint limits (a.limits: refused or clamped,
/// one warning line naming the clamped joints). A continuous joint's value becomes the same angle
/// in (-pi, pi], the range of its SO2 component (robots/joint_angles.h).
void takeEndpointsWithinLimits(const robots::RobotModel& model, PlanArgs& a) {
  std::vector<std::pair<const char*, std::vector<double>*>> endpoints = {{"start", &a.start}};
  if (!a.goalPose) endpoints.emplace_back("goal", &a.goal);
  for (const auto& [what, values] : endpoints) {
    checkSize(model, *values, what);
    Eigen::VectorXd q = toVector(*values);
    applyJointLimits(model, q, std::string("the ") + what + " configuration", a.limits);
    robots::normalizeWrappingVariables(model, q);
    values->assign(q.data(), q.data() + q.size());
  }
  warnClamped("plan", a.limits);
}

/// The start state and a goal configuration (a pose goal is set after the endpoints are checked).
void setStartAndGoal(ompl::geometric::SimpleSetup& ss, const PlanArgs& a) {
  const auto checker = planners::validityCheckerOf(ss);
  const Eigen::VectorXd start = toVector(a.start);
  if (!a.goalPose) {
    planners::setStartAndGoal(ss, start, toVector(a.goal));
    return;
  }
  ompl::base::ScopedState<> state(ss.getStateSpace());
  checker->mapping().toState(start, state.get());
  ss.setStartState(state);
}
/// The world of the command line and a SimpleSetup on it.
std::shared_ptr<ompl::geometric::SimpleSetup> makeSetup(const PlanArgs& a) {
  auto world = std::make_shared<checker::World>(loadWorld(a.world));
  planners::SetupOptions options;
  options.packageRoots = a.world.packages.commandLine;
  return planners::makeSimpleSetup(world, options);
}

/// With --repair-start: pushes a start (and goal state) in slight collision out, reporting each.
/// Without: InputError naming the pair of a start or goal configuration in collision.
void checkOrRepairEndpoints(ompl::geometric::SimpleSetup& ss, const PlanArgs& a) {
  const auto checker = planners::validityCheckerOf(ss);
  if (a.repair) {
    const planners::EndpointRepair r = planners::repairStartAndGoal(ss, a.margin);
    const auto report = [&](const char* what, const planners::PushOutResult& p) {
      // finalDistance is NaN when the push-out did not start (push_out.h): measure it then.
      const double sd = std::isnan(p.finalDistance) ? checker->clearance(p.q) : p.finalDistance;
      std::fprintf(stderr, "repair %s: %s, moved %.4g rad, signed distance now %.4g m (margin %.4g m)\n", what,
                   planners::toString(p.status), p.jointMotion, sd, a.margin);
      if (!p.reason.empty()) std::fprintf(stderr, "repair %s: %s\n", what, p.reason.c_str());
    };
    report("start", r.starts.front());
    if (r.goalIsState) report("goal", r.goal);
    if (!r.ok()) throw InputError("the start or goal could not be pushed out of collision (see above)");
    return;
  }
  std::vector<std::pair<const char*, const std::vector<double>*>> endpoints = {{"start", &a.start}};
  if (!a.goalPose) endpoints.emplace_back("goal", &a.goal);
  for (const auto& [what, q] : endpoints) {
    if (checker->isValid(toVector(*q))) continue;
    const checker::DistanceResult d = checker->world().signedDistance(toVector(*q));
    char distance[48];
    std::snprintf(distance, sizeof distance, "%.4g m", d.closest.distance);
    throw InputError(std::string("the ") + what + " configuration is in collision: signed distance " + distance +
                     " between " + d.closest.nameA + " and " + d.closest.nameB +
                     "; --repair-start pushes a slightly colliding one out");
  }
}

void setObjective(ompl::geometric::SimpleSetup& ss, ompl::base::Planner& planner, const std::string& name) {
  const auto si = ss.getSpaceInformation();
  if (name == "clearance") {
    ss.setOptimizationObjective(
        planners::makeLengthClearanceObjective(si, planners::validityCheckerOf(ss), planners::tol::kDefaultSafeDistance,
                                               planners::tol::kDefaultHingeWeight, planners::linkSpeedBoundOf(ss)));
    planners::prepareForCostlyObjective(planner);  // RRT*: radius neighbours (planner_factory.h)
  } else {
    ss.setOptimizationObjective(planners::makePathLengthObjective(si));
  }
}

/// Solves; InputError unless the solution is exact (an approximate path is written first).
void solve(ompl::geometric::SimpleSetup& ss, const PlanArgs& a) {
  // A condition the planner checks itself: ss.solve(seconds) would start OMPL's polling thread,
  // whose join adds up to a millisecond to plans that take a few (docs/planners.md).
  const ompl::base::PlannerStatus status = ss.solve(ompl::base::timedPlannerTerminationCondition(a.seconds));
  std::fprintf(stderr, "planner %s: %s after %s\n", ss.getPlanner()->getName().c_str(), status.asString().c_str(),
               formatDuration(ss.getLastPlanComputationTime()).c_str());
  if (status == ompl::base::PlannerStatus::EXACT_SOLUTION) return;
  if (ss.haveSolutionPath()) planners::writePath(ss.getSolutionPath(), a.out);
  throw InputError(std::string("no exact solution (") + status.asString() + ")" +
                   (ss.haveSolutionPath() ? "; the approximate path was written to " + a.out : std::string()));
}

/// The reached pose's error at the path's end; InputError when it is outside the tolerances.
void reportPoseError(const planners::PoseGoal& goal, const ompl::geometric::PathGeometric& path) {
  const robots::PoseError e = goal.poseError(path.getState(path.getStateCount() - 1));
  std::fprintf(stderr, "goal pose of %s: reached within %.3g m and %.3g rad\n", goal.linkName().c_str(), e.position,
               e.orientation);
  if (!e.within()) throw InputError("the path's last configuration does not reach the goal pose within the tolerances");
}

/// Simplifies, certifies (repairing where needed) and writes the solution, with its report.
void finishPath(ompl::geometric::SimpleSetup& ss, const PlanArgs& a, const planners::PoseGoal* goal) {
  if (!planners::simplifySolutionChecked(ss)) {
    std::fprintf(stderr,
                 "path simplification: no simplified path passed the planner's checks without a worse "
                 "objective cost; the path as planned is kept\n");
  }
  ompl::geometric::PathGeometric& path = ss.getSolutionPath();
  const auto t0 = std::chrono::steady_clock::now();
  const planners::PathCertificate certificate = planners::certifyPath(ss, path);
  const double certifyMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  planners::writePath(path, a.out);
  const auto [scene, self] = pathClearances(path, planners::validityCheckerOf(ss)->world());
  const std::string uncertified =
      certificate.valid && certificate.fallbackSteps > 0
          ? ", except " + std::to_string(certificate.fallbackSteps) + " step(s) within about " +
                robots::formatNumber(planners::tol::kFallbackDisplacement * 1e3) + " mm of contact, checked discretely"
          : "";
  std::fprintf(stderr,
               "path: %zu waypoints, length %.4f rad, scene clearance %s, self clearance %s, %s%s%s (checked in "
               "%.1f ms), written to %s\n",
               path.getStateCount(), path.length(), scene.describe().c_str(), self.describe().c_str(),
               certificate.valid ? "certified" : "NOT certified", certificate.repaired ? " (after repair)" : "",
               uncertified.c_str(), certifyMs, a.out.c_str());
  if (goal != nullptr) reportPoseError(*goal, path);
  if (!certificate.valid) throw InputError("the path could not be certified collision free");
}

int runPlan(std::vector<std::string> args) {
  PlanArgs a = takePlanArgs(args);
  if (a.seeded) ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(a.seed));  // before any OMPL object
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const auto ss = makeSetup(a);
  // The planner first: an unknown name is reported before any work.
  const auto planner = planners::makePlanner(a.plannerName, ss->getSpaceInformation());
  std::fprintf(stderr, "%s", planners::validityCheckerOf(*ss)->world().summary().c_str());
  warnVisualOnlyLinks("plan", planners::validityCheckerOf(*ss)->world().robot());
  takeEndpointsWithinLimits(planners::validityCheckerOf(*ss)->world().robot(), a);
  setStartAndGoal(*ss, a);
  checkOrRepairEndpoints(*ss, a);
  const std::shared_ptr<planners::PoseGoal> goal = a.goalPose ? setPoseGoal(*ss, a, toVector(a.start)) : nullptr;
  setObjective(*ss, *planner, a.objectiveName);
  ss->setPlanner(planner);
  solve(*ss, a);
  finishPath(*ss, a, goal.get());
  return 0;
}

}  // namespace

const Subcommand kPlanCommand = {"plan", "plan a path between two configurations with OMPL", kPlanUsage, runPlan};

}  // namespace deepcheck::tools
