#pragma once
// One call from URDF files to a ready ompl::geometric::SimpleSetup.
//
//   auto ss = deepcheck::planners::makeSimpleSetup("arm.urdf", {"shelf.urdf"}, options);
//   deepcheck::planners::setStartAndGoal(*ss, start, goal);
//   ss->setPlanner(std::make_shared<ompl::geometric::RRTConnect>(ss->getSpaceInformation()));
//   ss->solve(1.0);
//
// What it holds:
//   state space      one bounded dimension per robot variable (state_space.h);
//   validity checker deepcheck::planners::StateValidityChecker on a checker::World made of the
//                    robot (its SRDF's disabled pairs when given) and the scenes;
//   motion validator CertifiedMotionValidator (certified_motion_validator.h): every motion a
//                    planner or the simplifier accepts is proven collision free, not sampled
//                    (SetupOptions::motionValidation; with a penetration tolerance the
//                    ClearanceMotionValidator instead);
//   valid sampler    PushOutValidStateSampler (valid_state_sampler.h) unless disabled;
//   resolution       the longest valid segment fraction SetupOptions::segmentFraction (OMPL's
//                    discrete checks and objective integration; the certified validator does not
//                    use it);
//   planner          none set; solve() without one makes RRTConnect at defaultRange()
//                    (planner_factory.h).
// No objective is set: OMPL's default applies until the caller sets one.
// validityCheckerOf() and linkSpeedBoundOf() give back the pieces for objectives and reports.
//
// So every path solve() and simplifySolutionChecked() return is certified: each of its motions
// was accepted by the certified validator. certifyPath() still checks (and repairs) paths from
// elsewhere, and costs little on such a path.

// Files: package:// URIs are resolved with SetupOptions::packageRoots first, then (unless
// useRosPackagePath is false) ROS_PACKAGE_PATH (robots/package_path.h). Errors are
// std::invalid_argument naming the file and the problem.

#include "deepcheck/checker/world.h"
#include "deepcheck/planners/motion_bound.h"
#include "deepcheck/planners/path_tools.h"
#include "deepcheck/planners/push_out.h"
#include "deepcheck/planners/tolerances.h"
#include "deepcheck/planners/validity.h"
#include "deepcheck/planners/validity_checker.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <ompl/geometric/SimpleSetup.h>

#include <cstdint>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace deepcheck::planners {

/// A scene URDF and where it goes (the checker's scene type).
using SceneSpec = checker::SceneSpec;

enum class MotionValidation {
  /// CertifiedMotionValidator (certified_motion_validator.h): every motion accepted is proven
  /// valid. With a penetration tolerance (a negative validity threshold), which it cannot
  /// certify, ClearanceMotionValidator instead: its distance queries make planning slow, and a
  /// tolerant plan is usually made with Discrete and repaired by certifyPath on a strict set-up.
  Certified,
  /// OMPL's DiscreteMotionValidator at the state space's resolution: samples motions, and steps
  /// over thin obstacles; for comparison.
  Discrete,
  /// ClearanceMotionValidator: discrete pass, then certification by clearance steps.
  Clearance,
};

struct SetupOptions {
  /// Package roots for package:// URIs, searched first.
  std::vector<std::string> packageRoots;
  bool useRosPackagePath = true;
  /// An SRDF whose <disable_collisions> pairs are not checked ("" for none).
  std::string srdf;
  /// Plan only the variables of this planning group of the SRDF (MoveIt's <group>; "" for all
  /// variables). Every other variable is held fixed (robots/robot_model.h, "Locked joints") at
  /// its lockedVariables value, else at its default; configurations are then vectors of the
  /// group's variables, in the robot's order.
  std::string group;
  /// Variables held fixed (name -> rad or m), with or without a group.
  std::map<std::string, double> lockedVariables;
  /// How the World is built (decomposition, broad phase, ...); its disabledPairs are extended by
  /// the SRDF's.
  checker::WorldOptions world;
  ValidityOptions validity;
  PushOutOptions pushOut;
  MotionValidation motionValidation = MotionValidation::Certified;
  /// Register the push-out valid state sampler.
  bool pushOutSampler = true;
  /// Longest valid segment as a fraction of the state space's extent (0, 1].
  double segmentFraction = tol::kDefaultSegmentFraction;
};

/// The World: the robot (its group's variables only when SetupOptions::group is set, its locked
/// variables held; the SRDF's pairs disabled) and the scenes. Throws std::invalid_argument naming
/// the SRDF, the group or the joint for an unknown group, a group without an SRDF, or a variable
/// that cannot be locked.
std::shared_ptr<checker::World> loadWorld(const std::string& robotUrdf, const std::vector<SceneSpec>& scenes,
                                          const SetupOptions& options = {});

/// A SimpleSetup on an existing world. With SetupOptions::group or lockedVariables set, the
/// world's robot must be the one they describe (as loadWorld builds it); otherwise
/// std::invalid_argument says what differs.
std::shared_ptr<ompl::geometric::SimpleSetup> makeSimpleSetup(std::shared_ptr<const checker::World> world,
                                                              const SetupOptions& options = {});
/// loadWorld + makeSimpleSetup.
std::shared_ptr<ompl::geometric::SimpleSetup> makeSimpleSetup(const std::string& robotUrdf,
                                                              const std::vector<SceneSpec>& scenes,
                                                              const SetupOptions& options = {});

/// The deepcheck checker of a SimpleSetup; throws std::invalid_argument when it has another one.
std::shared_ptr<const StateValidityChecker> validityCheckerOf(const ompl::geometric::SimpleSetup& ss);
/// The link speed bound of its world (the ClearanceMotionValidator's when it has one; computed
/// otherwise, which loads the robot's meshes).
std::shared_ptr<const LinkSpeedBound> linkSpeedBoundOf(const ompl::geometric::SimpleSetup& ss);

/// A SpaceInformation with the state space and validity checker of `ss` and a certifying motion
/// validator (CertifiedMotionValidator; ClearanceMotionValidator with a penetration tolerance):
/// checkPathWithPlanner(path, si.get()) certifies a path, repairPath repairs it against it.
ompl::base::SpaceInformationPtr certifyingSpaceInformation(const ompl::geometric::SimpleSetup& ss);

/// The result of certifyPath.
struct PathCertificate {
  PathCheck initial;      ///< the path as given, through the certifying validator
  bool repaired = false;  ///< repairPath ran (the initial check failed)
  PathRepair repair;      ///< when repaired
  bool valid = false;     ///< every waypoint and motion (now) passes the certifying validator
  /// With a penetration tolerance only (the ClearanceMotionValidator certifies): the steps of the
  /// final path's motions it took without a certificate (its fallback within about 0.5 mm of
  /// contact, motion_validator.h). Always 0 with the certified validator.
  std::uint64_t fallbackSteps = 0;
  /// Valid with every motion certified: no fallback step.
  bool exact() const { return valid && fallbackSteps == 0; }
};
/// Certifies `path` (a path of `ss`'s space) with certifyingSpaceInformation's validator,
/// repairing it in place when that fails (repairPath: invalid waypoints pushed out, failing
/// motions split and their midpoints pushed out). With the certified validator a path that passes
/// is exact. With a penetration tolerance, a path that passes only with fallback steps is then
/// repaired against the clearance validator refusing them (setRefuseFallback), and that repair is
/// kept when it certifies every motion: exact() is true then; otherwise (a start or goal itself
/// that close to contact) the path stays, valid with its fallbackSteps.
PathCertificate certifyPath(const ompl::geometric::SimpleSetup& ss, ompl::geometric::PathGeometric& path);

/// Simplifies the solution of `ss` without ever making it worse: the simplified path is kept only
/// when it passes the planner's own checks (every waypoint isValid, every motion checkMotion) and
/// its cost under the problem's optimization objective (when one is set) is no worse than the
/// planned path's; otherwise the solution stays as planned. Up to tol::kSimplifyAttempts attempts,
/// each from the planned path (the simplifier is randomized).
///   - No objective, or path length: with `seconds` 0, one pass of OMPL's shortening (vertex
///     reduction, shortcuts, vertex reduction, one round of B-spline smoothing): OMPL's
///     simplifyMax, which repeats such passes until nothing improves, gives paths a few percent
///     shorter for several times the time. With `seconds` > 0, ss.simplifySolution(seconds).
///     OMPL 1.5's PathSimplifier can return a path that fails its own checks: when its shortcuts
///     and B-spline smoothing leave an invalid motion that checkAndRepair cannot mend, it warns
///     "Solution path may slightly touch on an invalid region of the state space" and returns it
///     (seen: a 4 rad motion through the bundled shelf).
///   - Any other objective (the clearance objectives of objectives.h): OMPL's shortcutting with
///     the objective (PathSimplifier::shortcutPath), not simplifyMax, whose vertex reduction and
///     B-spline smoothing ignore the objective and pull a path planned away from the obstacles
///     back onto them. `seconds` is not used.
/// Returns true when a simplified path was kept. Throws std::invalid_argument when `ss` has no
/// solution path.
bool simplifySolutionChecked(ompl::geometric::SimpleSetup& ss, double seconds = 0.0);

/// Sets one start and one goal state. Throws std::invalid_argument naming the configuration, the
/// variable and the value for a wrong size or a non-finite value (not for limits or collisions:
/// OMPL reports those when solving, repairStartAndGoal fixes them).
void setStartAndGoal(ompl::geometric::SimpleSetup& ss, const Eigen::Ref<const Eigen::VectorXd>& start,
                     const Eigen::Ref<const Eigen::VectorXd>& goal);

/// Push-out of the start states and of a single-state goal (ompl::base::GoalState) that are
/// invalid, in place, before planning: each is pushed out to at least `margin` (metres, >= 0)
/// above the validity threshold (standOffPushOut, push_out.h). Valid ones stay where they are
/// (status AlreadyValid). Throws std::invalid_argument for a negative or non-finite margin.
struct EndpointRepair {
  std::vector<PushOutResult> starts;  ///< one per start state
  bool goalIsState = false;           ///< the goal is a GoalState (others are left alone)
  PushOutResult goal;                 ///< when goalIsState
  /// Every start (and the goal state) is valid now.
  bool ok() const;
};
EndpointRepair repairStartAndGoal(ompl::geometric::SimpleSetup& ss, double margin = tol::kEndpointRepairMargin);

}  // namespace deepcheck::planners
