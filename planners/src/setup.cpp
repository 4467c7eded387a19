#include "deepcheck/planners/setup.h"

#include "deepcheck/planners/certified_motion_validator.h"
#include "deepcheck/planners/motion_validator.h"
#include "deepcheck/planners/planner_factory.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/planners/valid_state_sampler.h"
#include "deepcheck/robots/format_number.h"
#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/planning_group.h"

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/geometric/PathSimplifier.h>

#include <limits>
#include <stdexcept>
#include <string>

namespace deepcheck::planners {

namespace {

robots::LoadOptions loadOptions(const SetupOptions& options) {
  robots::LoadOptions load;
  load.packageRoots = options.packageRoots;
  load.useRosPackagePath = options.useRosPackagePath;
  return load;
}

void checkConfigurationNamed(const robots::RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                             const char* what) {
  try {
    robots::checkConfiguration(model, q);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(what) + " configuration: " + e.what());
  }
}

}  // namespace

std::shared_ptr<checker::World> loadWorld(const std::string& robotUrdf, const std::vector<SceneSpec>& scenes,
                                          const SetupOptions& options) {
  const robots::LoadOptions load = loadOptions(options);
  robots::RobotModel robot = robots::planningGroupModel(robots::RobotModel::fromUrdfFile(robotUrdf, load), options.srdf,
                                                        options.group, options.lockedVariables);
  checker::WorldOptions worldOptions = options.world;
  if (!options.srdf.empty()) {
    const std::vector<robots::DisabledPair> pairs = robots::readSrdfDisabledPairs(options.srdf);
    robots::checkDisabledPairs(robot, pairs, options.srdf);
    worldOptions.disabledPairs.insert(worldOptions.disabledPairs.end(), pairs.begin(), pairs.end());
  }
  auto world = std::make_shared<checker::World>(std::move(robot), worldOptions);
  for (const SceneSpec& spec : scenes) {
    robots::RobotModel scene = robots::RobotModel::fromUrdfFile(spec.urdf, load);
    world->addScene(std::move(scene), spec);
  }
  return world;
}

namespace {

/// Throws std::invalid_argument when the world's robot is not the one `options` describes: a
/// variable of lockedVariables that it does not hold at that value, or a variable outside
/// `options.group` that it still moves (a world built without the options).
void checkGroupOfWorld(const robots::RobotModel& robot, const SetupOptions& options) {
  const std::string hint =
      " (build the world with loadWorld(urdf, scenes, options), or leave the group and the "
      "locked variables out of the options)";
  for (const auto& [name, value] : options.lockedVariables) {
    const int j = robot.jointIndex(name);
    if (j < 0 || !robot.joint(j).locked || robot.joint(j).lockedValue != value) {
      throw std::invalid_argument("makeSimpleSetup: the options hold '" + name + "' at " + robots::formatNumber(value) +
                                  ", the world's robot '" + robot.name() + "' does not" + hint);
    }
  }
  if (options.group.empty()) return;
  const robots::RobotModel check = robots::planningGroupModel(robot, options.srdf, options.group, {});
  if (check.numVariables() != robot.numVariables()) {
    throw std::invalid_argument("makeSimpleSetup: the world's robot '" + robot.name() + "' moves " +
                                std::to_string(robot.numVariables()) + " variables, group '" + options.group +
                                "' only " + std::to_string(check.numVariables()) + hint);
  }
}

}  // namespace

namespace {

/// The validator that certifies motions under the checker's criterion (setup.h: Certified).
ompl::base::MotionValidatorPtr certifyingValidator(ompl::base::SpaceInformation* si,
                                                   const std::shared_ptr<const StateValidityChecker>& checker) {
  if (checker->validityOptions().threshold() >= 0.0) return std::make_shared<CertifiedMotionValidator>(si, checker);
  return std::make_shared<ClearanceMotionValidator>(si, checker);
}

}  // namespace

std::shared_ptr<ompl::geometric::SimpleSetup> makeSimpleSetup(std::shared_ptr<const checker::World> world,
                                                              const SetupOptions& options) {
  if (!world) throw std::invalid_argument("makeSimpleSetup: the world is null");
  checkGroupOfWorld(world->robot(), options);
  if (!(options.segmentFraction > 0.0 && options.segmentFraction <= 1.0)) {
    throw std::invalid_argument("makeSimpleSetup: segmentFraction must be in (0, 1], got " +
                                robots::formatNumber(options.segmentFraction));
  }
  auto space = makeStateSpace(world->robot());
  space->setLongestValidSegmentFraction(options.segmentFraction);
  auto ss = std::make_shared<ompl::geometric::SimpleSetup>(space);
  const ompl::base::SpaceInformationPtr& si = ss->getSpaceInformation();
  auto checker = std::make_shared<StateValidityChecker>(si.get(), world, options.validity, options.pushOut);
  ss->setStateValidityChecker(checker);
  switch (options.motionValidation) {
    case MotionValidation::Certified:
      si->setMotionValidator(certifyingValidator(si.get(), checker));
      break;
    case MotionValidation::Clearance: {
      auto bound = std::make_shared<const LinkSpeedBound>(LinkSpeedBound::forWorld(*world));
      si->setMotionValidator(std::make_shared<ClearanceMotionValidator>(si.get(), checker, bound));
      break;
    }
    case MotionValidation::Discrete:
      si->setMotionValidator(std::make_shared<ompl::base::DiscreteMotionValidator>(si.get()));
      break;
  }
  if (options.pushOutSampler) si->setValidStateSamplerAllocator(pushOutSamplerAllocator(checker));
  // Without a planner of the caller's, solve() makes this one (OMPL's choice would be RRTConnect
  // at its own range).
  ss->setPlannerAllocator([](const ompl::base::SpaceInformationPtr& s) { return makePlanner("RRTConnect", s); });
  si->setup();
  return ss;
}

std::shared_ptr<ompl::geometric::SimpleSetup> makeSimpleSetup(const std::string& robotUrdf,
                                                              const std::vector<SceneSpec>& scenes,
                                                              const SetupOptions& options) {
  return makeSimpleSetup(loadWorld(robotUrdf, scenes, options), options);
}

std::shared_ptr<const StateValidityChecker> validityCheckerOf(const ompl::geometric::SimpleSetup& ss) {
  auto checker = std::dynamic_pointer_cast<const StateValidityChecker>(ss.getStateValidityChecker());
  if (!checker) {
    throw std::invalid_argument(
        "validityCheckerOf: the SimpleSetup's validity checker is not a "
        "deepcheck::planners::StateValidityChecker");
  }
  return checker;
}

std::shared_ptr<const LinkSpeedBound> linkSpeedBoundOf(const ompl::geometric::SimpleSetup& ss) {
  const ompl::base::MotionValidatorPtr& v = ss.getSpaceInformation()->getMotionValidator();
  if (auto certified = std::dynamic_pointer_cast<const CertifiedMotionValidator>(v)) return certified->bound();
  // The validator owns its bound for as long as it lives; share its ownership.
  if (auto clearance = std::dynamic_pointer_cast<const ClearanceMotionValidator>(v)) {
    return std::shared_ptr<const LinkSpeedBound>(clearance, &clearance->bound());
  }
  return std::make_shared<const LinkSpeedBound>(LinkSpeedBound::forWorld(validityCheckerOf(ss)->world()));
}

ompl::base::SpaceInformationPtr certifyingSpaceInformation(const ompl::geometric::SimpleSetup& ss) {
  const auto checker = validityCheckerOf(ss);
  auto si = std::make_shared<ompl::base::SpaceInformation>(ss.getStateSpace());
  si->setStateValidityChecker(std::const_pointer_cast<StateValidityChecker>(checker));
  si->setMotionValidator(certifyingValidator(si.get(), checker));
  si->setup();
  return si;
}

namespace {

/// The clearance validator of `si`, or null (the certified validator takes no fallback step).
ClearanceMotionValidator* clearanceValidatorOf(const ompl::base::SpaceInformationPtr& si) {
  return dynamic_cast<ClearanceMotionValidator*>(si->getMotionValidator().get());
}

/// The fallback steps of `path`'s motions, checked once more on their own (a repair's counts
/// include the motions it replaced); 0 when the path no longer passes.
std::uint64_t recheckFallbackSteps(const ompl::geometric::PathGeometric& path,
                                   const ompl::base::SpaceInformationPtr& si) {
  ClearanceMotionValidator* validator = clearanceValidatorOf(si);
  if (validator == nullptr) return 0;
  validator->resetStats();
  return checkPathWithPlanner(path, si.get()).valid ? validator->stats().fallbackSteps : 0;
}

/// A path that passes only with fallback steps: repaired against a validator that refuses them
/// (the grazing motions split and their midpoints pushed out), kept when that repair certifies
/// every motion by clearance. Start and goal stay; one of them within the fallback distance of
/// contact cannot be made exact, and the path stays as it was.
void repairFallbackSteps(const ompl::geometric::SimpleSetup& ss, ompl::geometric::PathGeometric& path,
                         PathCertificate& certificate) {
  const ompl::base::SpaceInformationPtr strict = certifyingSpaceInformation(ss);
  clearanceValidatorOf(strict)->setRefuseFallback(true);
  ompl::geometric::PathGeometric candidate = path;
  const PathRepair repair = repairPath(candidate, strict);
  if (!repair.valid) return;
  path = candidate;
  certificate.repaired = true;
  certificate.repair = repair;
  certificate.fallbackSteps = 0;
}

}  // namespace

PathCertificate certifyPath(const ompl::geometric::SimpleSetup& ss, ompl::geometric::PathGeometric& path) {
  const ompl::base::SpaceInformationPtr si = certifyingSpaceInformation(ss);
  PathCertificate certificate;
  certificate.initial = checkPathWithPlanner(path, si.get());
  certificate.valid = certificate.initial.valid;
  if (!certificate.valid) {
    certificate.repaired = true;
    certificate.repair = repairPath(path, si);
    certificate.valid = certificate.repair.valid;
    if (!certificate.valid) return certificate;
  }
  // Unrepaired, the initial check went through exactly the path's motions: its counts stand.
  const ClearanceMotionValidator* clearance = clearanceValidatorOf(si);
  certificate.fallbackSteps = clearance == nullptr   ? 0
                              : certificate.repaired ? recheckFallbackSteps(path, si)
                                                     : clearance->stats().fallbackSteps;
  if (certificate.fallbackSteps > 0) repairFallbackSteps(ss, path, certificate);
  return certificate;
}

namespace {

/// Rounds of B-spline smoothing in one shortening pass. A second round (RRTConnect on the Panda's
/// MotionBenchMaker problems, bench/mbm_bench, each run's simplification of the same planned path
/// compared) made the paths 1.6 % shorter at the median and the simplification 35 % slower.
constexpr unsigned kBSplineRounds = 1;

/// One pass of OMPL's path shortening: vertex reduction, shortcuts, vertex reduction again, a
/// round of B-spline smoothing. Every change goes through the motion validator. simplifyMax
/// repeats such passes until nothing improves: slightly shorter paths for several times the time,
/// so the single pass is the default.
void shortenPath(ompl::geometric::PathSimplifier& simplifier, ompl::geometric::PathGeometric& path) {
  simplifier.reduceVertices(path);
  simplifier.shortcutPath(path);
  simplifier.reduceVertices(path);
  simplifier.smoothBSpline(path, kBSplineRounds);
}

/// The objective's cost of `path` is no worse than `reference` (always true without an objective).
bool costNotWorse(const ompl::geometric::PathGeometric& path, const ompl::base::OptimizationObjectivePtr& objective,
                  const ompl::base::Cost& reference) {
  return !objective || !objective->isCostBetterThan(reference, path.cost(objective));
}

}  // namespace

bool simplifySolutionChecked(ompl::geometric::SimpleSetup& ss, double seconds) {
  if (!ss.haveSolutionPath())
    throw std::invalid_argument("simplifySolutionChecked: the SimpleSetup has no solution path");
  const ompl::base::ProblemDefinitionPtr& pdef = ss.getProblemDefinition();
  const ompl::base::OptimizationObjectivePtr objective =
      pdef->hasOptimizationObjective() ? pdef->getOptimizationObjective() : nullptr;
  const bool lengthOnly =
      !objective || std::dynamic_pointer_cast<ompl::base::PathLengthOptimizationObjective>(objective) != nullptr;
  const ompl::geometric::PathGeometric planned = ss.getSolutionPath();
  const ompl::base::Cost plannedCost = objective ? planned.cost(objective) : ompl::base::Cost(0.0);
  // Another objective than length: shortcuts only, by a simplifier that knows the objective (the
  // vertex reduction and B-spline smoothing of simplifyMax ignore it and pull a clearance path
  // onto the obstacles).
  ompl::geometric::PathSimplifier costAware(ss.getSpaceInformation(), pdef->getGoal(), objective);
  ompl::geometric::PathSimplifier simplifier(ss.getSpaceInformation(), pdef->getGoal());
  // The simplifier is randomized: a failed attempt may succeed the next time.
  for (int attempt = 0; attempt < tol::kSimplifyAttempts; ++attempt) {
    ompl::geometric::PathGeometric& path = ss.getSolutionPath();
    if (lengthOnly && seconds == 0.0) {
      shortenPath(simplifier, path);
    } else if (lengthOnly) {
      ss.simplifySolution(seconds);
    } else {
      costAware.shortcutPath(path);
    }
    if (checkPathWithPlanner(path).valid && costNotWorse(path, objective, plannedCost)) return true;
    path = planned;
  }
  return false;
}

void setStartAndGoal(ompl::geometric::SimpleSetup& ss, const Eigen::Ref<const Eigen::VectorXd>& start,
                     const Eigen::Ref<const Eigen::VectorXd>& goal) {
  const auto checker = validityCheckerOf(ss);
  const robots::RobotModel& model = checker->world().robot();
  checkConfigurationNamed(model, start, "start");
  checkConfigurationNamed(model, goal, "goal");
  ompl::base::ScopedState<> s(ss.getStateSpace());
  ompl::base::ScopedState<> g(ss.getStateSpace());
  checker->mapping().toState(start, s.get());
  checker->mapping().toState(goal, g.get());
  ss.setStartAndGoalStates(s, g);
}

bool EndpointRepair::ok() const {
  for (const PushOutResult& r : starts) {
    if (!r.success()) return false;
  }
  return !goalIsState || goal.success();
}

EndpointRepair repairStartAndGoal(ompl::geometric::SimpleSetup& ss, double margin) {
  const auto checker = validityCheckerOf(ss);
  const StateMapping& mapping = checker->mapping();
  const PushOut pushOut =
      standOffPushOut(checker->worldPtr(), checker->validityOptions(), checker->pushOut().options(), margin);
  // An invalid state is pushed out to the margin, in place; a valid one stays.
  const auto repairState = [&](ompl::base::State* state) {
    const Eigen::VectorXd q = mapping.configuration(state);
    if (checker->isValid(q)) {
      PushOutResult unchanged;
      unchanged.status = PushOutStatus::AlreadyValid;
      unchanged.q = q;
      unchanged.initialDistance = unchanged.finalDistance = std::numeric_limits<double>::quiet_NaN();
      return unchanged;
    }
    PushOutResult pushed = pushOut.run(q);
    if (pushed.success()) mapping.toState(pushed.q, state);
    return pushed;
  };
  const ompl::base::ProblemDefinitionPtr& pdef = ss.getProblemDefinition();
  EndpointRepair repair;
  for (unsigned int i = 0; i < pdef->getStartStateCount(); ++i)
    repair.starts.push_back(repairState(pdef->getStartState(i)));
  if (auto goal = std::dynamic_pointer_cast<ompl::base::GoalState>(pdef->getGoal())) {
    repair.goalIsState = true;
    repair.goal = repairState(goal->getState());
  }
  return repair;
}

}  // namespace deepcheck::planners
