#pragma once
// OMPL state validity checker on a deepcheck World.
//
// isValid(state)   the configuration is within the robot's URDF joint limits
//                  (RobotModel::lowerLimits / upperLimits; the state space's own bounds are not
//                  read: makeStateSpace sets them to the same limits, a user's space may differ;
//                  a wrapping variable, robots/joint_angles.h, has none: 4.0 rad is the angle
//                  4.0 - 2 pi, not a value above pi)
//                  AND valid by validity.h (sd > safetyMargin - penetrationTolerance; with both
//                  0, World::isFree's early exit). Thread safe and const: OMPL's parallel planners may call it from
//                  many threads (each uses its own warm-start context of the World).
// clearance(state) the signed distance sd(q) of the world, metres: positive the distance to the
//                  nearest obstacle (scene, obstacle or another link of the robot), NEGATIVE
//                  THE PENETRATION DEPTH when in collision, as OMPL documents. The raw distance:
//                  the safety margin and penetration tolerance are not subtracted.
// A state with a NaN or infinite value is invalid and its clearance is -infinity: OMPL may hand
// such a state to either call, and both then say "not a place to be" without throwing.
// isValid(state, dist)  isValid plus dist = clearance(state).
// isValid(state, dist, validState, validStateAvailable)
//                  as above; when the state is invalid, the push-out (push_out.h) is run from it
//                  and, when it succeeds, validState receives the pushed-out valid configuration
//                  and validStateAvailable is true. For a valid state validStateAvailable is false
//                  (nothing to move away from). clearance(state, validState, available) is the
//                  same with the clearance as result.
//
// States and configurations: the checker reads a state's configuration through its StateMapping
// (state_space.h), made from the space information's state space by makeStateMapping (a layout
// it does not understand is rejected, naming it) or given by the user. The motion validator,
// samplers, objectives, endpoint repair and path tools use the checker's mapping.
//
// Specs, set truthfully:
//   clearanceComputationType = APPROXIMATE. Distances are exact (GJK) for the convex pieces the
//   World checks, but the pieces contain the original meshes and stick out of them by up to the
//   decomposition tolerance (World::Summary::geometryExcess), so the clearance may be below the
//   true one by that much; penetration depths are DEEP's answers, always a valid separating
//   translation but possibly above the true depth when the walk ends in a local minimum. The
//   error is neither one-sided with respect to the original geometry in every case nor bounded
//   by a known constant, which is OMPL's definition of APPROXIMATE.
//   hasValidDirectionComputation = true (the push-out).
//
// Counters (relaxed atomics, for benchmarks): validity queries and distance queries made through
// this object.

#include "deepcheck/checker/world.h"
#include "deepcheck/planners/certified_motion_memo.h"
#include "deepcheck/planners/push_out.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/planners/validity.h"

#include <Eigen/Core>

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

#include <atomic>
#include <cstdint>
#include <memory>

namespace deepcheck::planners {

class StateValidityChecker;
/// Shared pointer, as OMPL names its own (ompl::base::StateValidityCheckerPtr).
using StateValidityCheckerPtr = std::shared_ptr<StateValidityChecker>;

class StateValidityChecker : public ompl::base::StateValidityChecker {
 public:
  /// States of si's state space map to configurations of world->robot() by
  /// makeStateMapping(space, robot) (state_space.h). Throws std::invalid_argument for a null
  /// world or space information, a state space whose layout is not understood (naming it) or
  /// bad options.
  StateValidityChecker(ompl::base::SpaceInformation* si, std::shared_ptr<const checker::World> world,
                       const ValidityOptions& validity = {}, const PushOutOptions& pushOut = {});
  StateValidityChecker(const ompl::base::SpaceInformationPtr& si, std::shared_ptr<const checker::World> world,
                       const ValidityOptions& validity = {}, const PushOutOptions& pushOut = {});
  /// The same with the user's mapping (e.g. StateMapping::custom); it must have the robot's
  /// number of variables (std::invalid_argument otherwise).
  StateValidityChecker(ompl::base::SpaceInformation* si, std::shared_ptr<const checker::World> world,
                       StateMapping mapping, const ValidityOptions& validity = {}, const PushOutOptions& pushOut = {});
  StateValidityChecker(const ompl::base::SpaceInformationPtr& si, std::shared_ptr<const checker::World> world,
                       StateMapping mapping, const ValidityOptions& validity = {}, const PushOutOptions& pushOut = {});

  bool isValid(const ompl::base::State* state) const override;
  bool isValid(const ompl::base::State* state, double& dist) const override;
  bool isValid(const ompl::base::State* state, double& dist, ompl::base::State* validState,
               bool& validStateAvailable) const override;
  double clearance(const ompl::base::State* state) const override;
  double clearance(const ompl::base::State* state, ompl::base::State* validState,
                   bool& validStateAvailable) const override;

  /// The same criteria on a configuration (numVariables() values; limits checked by isValid).
  bool isValid(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  double clearance(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  /// min(sd(q), cap), cheaper for a small cap (validity.h).
  double clearanceUpTo(const Eigen::Ref<const Eigen::VectorXd>& q, double cap) const;
  /// The same split into robot-world and self pairs (validity.h), each capped at `cap`; with
  /// `selfPairs` false the self pairs are not measured (`self` is +infinity).
  SplitDistance splitClearanceUpTo(const Eigen::Ref<const Eigen::VectorXd>& q, double cap, bool selfPairs = true) const;

  const checker::World& world() const { return *world_; }
  const std::shared_ptr<const checker::World>& worldPtr() const { return world_; }
  const ValidityOptions& validityOptions() const { return validity_; }
  const PushOut& pushOut() const { return pushOut_; }
  int dimension() const { return n_; }
  /// How states of the space are configurations (state_space.h).
  const StateMapping& mapping() const { return mapping_; }

  /// The motions certified motion validators on this checker have accepted
  /// (certified_motion_memo.h), shared by all of them.
  CertifiedMotionMemo& certifiedMotions() const { return *certifiedMotions_; }

  /// True when q lies within the joint limits isValid checks (false when a value is NaN; q of the
  /// wrong size throws, naming the sizes).
  bool withinBounds(const Eigen::Ref<const Eigen::VectorXd>& q) const;

  std::uint64_t validityQueries() const { return validityQueries_.load(std::memory_order_relaxed); }
  std::uint64_t distanceQueries() const { return distanceQueries_.load(std::memory_order_relaxed); }
  void resetCounters();

 private:
  /// False when a value of q is NaN or infinite (q of the wrong size throws, naming the sizes).
  bool finite(const Eigen::Ref<const Eigen::VectorXd>& q) const;

  std::shared_ptr<const checker::World> world_;
  StateMapping mapping_;
  ValidityOptions validity_;
  PushOut pushOut_;
  int n_ = 0;
  /// The joint limits isValid checks: the URDF's, none (+-infinity) for wrapping variables.
  Eigen::VectorXd lower_, upper_;
  std::unique_ptr<CertifiedMotionMemo> certifiedMotions_;
  mutable std::atomic<std::uint64_t> validityQueries_{0};
  mutable std::atomic<std::uint64_t> distanceQueries_{0};
};

}  // namespace deepcheck::planners
