#pragma once
// Optimization objectives for OMPL's optimizing planners (RRT*, BIT*, PRM*, ...) on our clearance.
//
// ClearanceHingeObjective: the penetration and clearance cost of TrajOpt (Schulman et al., IJRR
// 2014, the hinge penalty on signed distances), as a state cost integrated along motions:
//     stateCost(q)       = max(0, d_safe - sd_world(q), d_self - sd_self(q))   metres
//     motionCost(q1, q2) = integral over the joint-space arc length of stateCost     metres x rad
// evaluated by the trapezoid rule on segments no longer than `resolution` (default: the state
// space's longest valid segment). sd_world is the signed distance to the scenes and obstacles,
// sd_self the robot's self distance (validity.h, SplitDistance); d_self defaults to 0 (self pairs
// pay only for penetration, tolerances.h explains why). Zero terms are skipped exactly: with B the
// pair displacement bound of motion_bound.h, each of sd_world and sd_self between two evaluated
// states is at least (sd_a + sd_b - B) / 2, so where that is >= its safe distance the hinge is
// zero in between; otherwise the middle state is evaluated (bisection). Far from obstacles a motion
// costs two distance queries. Penetrating states pay d_safe plus their depth, so optimizing
// planners drive paths out of slight penetration (a penetration tolerance, validity.h, lets them
// through it) and away from obstacles. Cost 0 means "never nearer than d_safe"; the objective
// alone is satisfied by any such path, which is why it is meant to be combined with path length.
//
// Invalid motions: every state the integration evaluates is first checked by the validity
// checker (isFree's early exit by default), and a motion with an invalid evaluated state costs
// infinity. Optimizing planners ask the cost of many motions they then reject (RRT* asks it for
// every neighbour before checking any); this spares their penetration depths. A motion that the
// motion validator accepts at the same resolution has only valid states on the integration grid,
// so its cost is the trapezoid sum above. When d_self <= the validity threshold (both 0 by
// default) the self term is zero on every valid state and the self pairs are not measured.
// stateCost is the hinge for any state, valid or not.
//
// Planner settings: with OMPL's k-nearest RRT* (its default) every new node asks the cost to a
// number of neighbours that exceeds the whole tree on a 7-joint arm; and its radius neighbours
// stay within min(range, r(n)), where OMPL's range is 0.2 of the extent (5.76 rad on a UR5) and
// r(n) stays above it for the first ~10^4 nodes. Call prepareForCostlyObjective
// (planner_factory.h): radius neighbours and a range of tol::kCostlyObjectiveRangeFraction of the
// extent (measured on a UR5: 3,300 RRT* iterations in 8 s with OMPL's range, 134 distance queries
// each; 25,000 to 30,000 with the shorter one).
//
// makeLengthClearanceObjective: the objective `deepcheck plan --objective clearance` optimizes,
//     cost(path) = length(path) + w * integral over the path of stateCost
// OMPL's MultiOptimizationObjective of PathLengthOptimizationObjective (weight 1, the state
// space's distance: radians, or the compound distance of state_space.h) and the hinge (weight w,
// 1 / metre; tolerances.h says why 100 by default). The hinge alone is degenerate (every path that
// keeps d_safe away costs 0, however long), hence the length term. Heuristics: the cost-to-go is
// the distance to the goal region and the motion heuristic the distance, both admissible since
// the hinge is >= 0. Its informed sampler (BIT*, InformedRRT*) samples the informed set of PATH
// LENGTH for the same cost bound directly (a path costing c is at most c long, so nothing better
// is left out); OMPL's default for a MultiOptimizationObjective is rejection sampling of the whole
// space, which on a UR5 accepts almost nothing once a solution is known (measured: BIT* grew 252
// to 533 vertices in 8 s instead of about 5,000 in 3 s, and overran its time budget by 0.6 s).
// On a space with SO2 components (continuous joints) it samples the whole space uniformly
// (uniform_informed_sampler.h: never stalls, leaves nothing out), as OMPL's direct
// sampler takes RealVector spaces only.
//
// makeMaxMinClearanceObjective: OMPL's MaximizeMinClearanceObjective, unchanged: it reads the
// state validity checker's clearance(), which ours makes the signed distance. It interpolates
// motions at the state space's valid segment count.

#include "deepcheck/planners/motion_bound.h"
#include "deepcheck/planners/tolerances.h"
#include "deepcheck/planners/validity_checker.h"

#include <ompl/base/OptimizationObjective.h>
#include <ompl/base/SpaceInformation.h>

#include <memory>

namespace deepcheck::planners {

class ClearanceHingeObjective;
/// Shared pointer, as OMPL names its own (ompl::base::OptimizationObjectivePtr).
using ClearanceHingeObjectivePtr = std::shared_ptr<ClearanceHingeObjective>;

class ClearanceHingeObjective : public ompl::base::OptimizationObjective {
 public:
  /// `bound` may be null (no skipping). `resolution` <= 0 means the longest valid segment.
  /// Throws std::invalid_argument for a null checker, a negative or non-finite d_safe.
  ClearanceHingeObjective(const ompl::base::SpaceInformationPtr& si,
                          std::shared_ptr<const StateValidityChecker> checker,
                          double safeDistance = tol::kDefaultSafeDistance,
                          std::shared_ptr<const LinkSpeedBound> bound = nullptr, double resolution = 0.0);

  ompl::base::Cost stateCost(const ompl::base::State* s) const override;
  ompl::base::Cost motionCost(const ompl::base::State* s1, const ompl::base::State* s2) const override;

  double safeDistance() const { return safeDistance_; }
  double selfSafeDistance() const { return selfSafeDistance_; }
  /// d_self (metres, finite, >= 0); throws std::invalid_argument otherwise.
  void setSelfSafeDistance(double d);

 private:
  /// One motion's integral (objectives.cpp).
  struct Motion;
  /// The hinge of a split distance.
  double hinge(const SplitDistance& d) const;
  /// The hinge at q, asking the distances only up to the safe distances.
  double hinge(const Eigen::Ref<const Eigen::VectorXd>& q) const;

  std::shared_ptr<const StateValidityChecker> checker_;
  std::shared_ptr<const LinkSpeedBound> bound_;
  double safeDistance_ = 0.0;
  double selfSafeDistance_ = tol::kDefaultSelfSafeDistance;
  double resolution_ = 0.0;
};

/// Path length + weight * hinge (see the header comment); `resolution` as for the hinge (a coarser
/// one makes optimizing planners cheaper near obstacles: each motion cost evaluates the states
/// within d_safe + B of an obstacle). Throws std::invalid_argument for a
/// negative or non-finite weight.
ompl::base::OptimizationObjectivePtr makeLengthClearanceObjective(const ompl::base::SpaceInformationPtr& si,
                                                                  std::shared_ptr<const StateValidityChecker> checker,
                                                                  double safeDistance = tol::kDefaultSafeDistance,
                                                                  double weight = tol::kDefaultHingeWeight,
                                                                  std::shared_ptr<const LinkSpeedBound> bound = nullptr,
                                                                  double resolution = 0.0);

/// OMPL's PathLengthOptimizationObjective, except that the informed planners (BIT*,
/// InformedRRT*) sample a state space with SO2 components (continuous joints, state_space.h)
/// uniformly, without information (uniform_informed_sampler.h), instead of throwing "PathLengthDirectInfSampler only
/// supports RealVector, SE2 and SE3 statespaces". Identical on a RealVectorStateSpace. Throws std::invalid_argument for
/// a null space information.
ompl::base::OptimizationObjectivePtr makePathLengthObjective(const ompl::base::SpaceInformationPtr& si);

/// OMPL's MaximizeMinClearanceObjective on `si` (whose checker must compute clearance).
ompl::base::OptimizationObjectivePtr makeMaxMinClearanceObjective(const ompl::base::SpaceInformationPtr& si);

}  // namespace deepcheck::planners
