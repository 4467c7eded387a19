#pragma once
// Checking, measuring, repairing and writing joint-space paths (ompl::geometric::PathGeometric of
// a state space made by state_space.h).
//
// Two checks of a path:
//   checkPathWithPlanner  every waypoint passes si.isValid and every motion si.checkMotion: with
//                         the clearance motion validator, a certificate (the `deepcheck plan`
//                         exit status);
//   checkPathFine         every state along the path at most `resolution` apart in joint space
//                         passes an independent predicate (the FCL reference backend in tests):
//                         a ground truth that does not trust the planner's motion validator.
//
// Repair (repairPath): after a planner ran with a penetration tolerance, or after smoothing
// (shortcutting moves waypoints onto obstacle boundaries), some waypoints may penetrate slightly.
// Every invalid waypoint, and every interior waypoint nearer than tol::kRepairClearance (above
// the threshold) to an obstacle, is pushed out to that stand-off (push_out.h, with the checker of
// `si`); then every motion that fails si.checkMotion is split at its midpoint, the midpoint
// pushed out to the stand-off when nearer, and both halves checked again, down to `maxDepth`
// splits. The stand-off matters: the chord between two states pushed just onto the two faces of
// an edge cuts through the edge. Best effort: a motion that still fails at the deepest split stays
// (PathRepair::valid is then false), e.g. when its ends were pushed out on two sides of a wall.
// A valid start or goal never moves; an invalid one is pushed out like the other waypoints
// (repair them before planning to keep them fixed: setup.h, repairStartAndGoal).
// Repair the path against a SpaceInformation with the clearance motion validator
// (setup.h: certifyingSpaceInformation), whose accepted motions are certified.

#include "deepcheck/planners/tolerances.h"

#include <Eigen/Core>

#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/PathGeometric.h>

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace deepcheck::planners {

struct PathCheck {
  bool valid = true;
  int statesChecked = 0;
  int invalidWaypoints = 0;
  int invalidMotions = 0;         ///< motions with an invalid state (or rejected by checkMotion)
  int firstInvalidWaypoint = -1;  ///< index into the path's states
  int firstInvalidMotion = -1;    ///< motion i goes from state i to state i + 1
};

/// Waypoints through si.isValid, motions through si.checkMotion (the path's own si if null).
PathCheck checkPathWithPlanner(const ompl::geometric::PathGeometric& path,
                               const ompl::base::SpaceInformation* si = nullptr);

/// Every waypoint and every state along each motion, at most `resolution` apart (joint-space
/// length, > 0), through `isFree`. Throws std::invalid_argument for a resolution <= 0.
PathCheck checkPathFine(const ompl::geometric::PathGeometric& path,
                        const std::function<bool(const Eigen::VectorXd&)>& isFree,
                        double resolution = tol::kFineResolution);

/// The minimum of `clearance` over the same states as checkPathFine.
double minClearanceAlong(const ompl::geometric::PathGeometric& path,
                         const std::function<double(const Eigen::VectorXd&)>& clearance,
                         double resolution = tol::kFineResolution);

struct PathRepair {
  bool valid = false;       ///< the repaired path passes checkPathWithPlanner with si
  int waypointsPushed = 0;  ///< waypoints moved by the push-out
  int statesInserted = 0;   ///< midpoints added
  int pushOutFailures = 0;  ///< states the push-out could not repair
};

/// Repairs `path` in place against `si` (see the header comment); si's validity checker must be a
/// deepcheck::planners::StateValidityChecker (std::invalid_argument otherwise).
PathRepair repairPath(ompl::geometric::PathGeometric& path, const ompl::base::SpaceInformationPtr& si,
                      int maxDepth = 10);

/// The path's states as configurations.
std::vector<Eigen::VectorXd> pathConfigurations(const ompl::geometric::PathGeometric& path);

/// One configuration per line, values separated by spaces (%.17g): the `deepcheck plan` format.
void writePath(const ompl::geometric::PathGeometric& path, std::ostream& out);
/// Same, to a file; throws std::invalid_argument naming the file when it cannot be written.
void writePath(const ompl::geometric::PathGeometric& path, const std::string& file);

}  // namespace deepcheck::planners
