#pragma once
// Push-out: from a slightly colliding configuration to a nearby valid one, by damped least squares
// on the signed-distance gradients of all the pairs in contact; and the random-jiggle baseline it
// is measured against.
//
// Push-out (the projection TrajOpt and CHOMP-style planners make, one pair at a time there).
// With threshold t (validity.h) and target t + c (c = PushOutOptions::targetClearance), each
// iteration at q:
//   1. the contact list of the world at q: every (robot link, other body) pair with signed
//      distance sd_i <= t + c + lookahead (tol::kPushOutLookahead), each with its gradient
//      g_i = d sd_i / dq (checker/world.h);
//   2. the step dq satisfies the linearized constraints g_i^T dq = t + c - sd_i of the pairs
//      inside the target, all at once, by damped least squares (Nakamura & Hanafusa 1986;
//      Wampler 1986):
//          dq = G^T (G G^T + lambda^2 I)^-1 e,   G = [g_i^T],   e_i = t + c - sd_i,
//      the smallest joint motion solving them when G is well conditioned, a bounded step when it
//      is not (two contacts pulling in opposite directions, a pair the joints barely move);
//   3. active set: a watched pair (inside the lookahead, outside the target) that the step would
//      bring inside the target joins the constraints, and the step is solved again, so pushing
//      one finger out of a wall does not push the other one in;
//   4. the step is scaled so that no joint moves more than maxJointStep (the linearization only
//      holds near q), then clipped to the joint limits: a joint that would leave its range is set
//      onto its limit and removed from the unknowns, the others are solved again with the
//      clipped joint's motion accounted for in e;
//   5. stop as soon as q is valid (the exact criterion of validity.h, not the linearization).
// Two safeguards, for where the signed distance is not smooth:
//   - bundle: a step that makes the minimum distance worse is not taken (twice at most in a row);
//     the gradients found at the rejected point are kept, re-linearized at the current iterate,
//     as extra constraints while they are within tol::kPushOutBundleRadius (a pair's gradient is
//     a one-sided derivative where its witness jumps, e.g. a flat face pressed onto an edge, and
//     flips sign from one side to the other; with both sides as constraints the step leaves
//     along a direction that helps on both);
//   - pattern search: when the minimum distance stalls (tol::kPushOutStallIterations iterations
//     without tol::kPushOutStallImprovement) or the gradients give no step, single joints are
//     tried at +-tol::kPushOutProbeSteps: the smallest move that makes q valid is taken, else the
//     most improving one. Penetration depth is the SHORTEST separating translation; where the
//     cheap way out in joint space goes another way (an arm poking sideways into a table edge,
//     which tilting lets slip under it) the gradient is flat there and only a probe sees the exit.
// Bodies. A contact is a (robot link, other body) pair; the world's signed distance gives it the
// deepest pair of pieces, whose direction is wrong where the link overlaps several pieces of one
// body (a box pressed into two touching boxes is pushed sideways out of one, into the other; a peg
// in a U of three boxes is pushed from each wall into the other, and the two cancel). With
// PushOutOptions::bodyDepth each overlapping contact whose A is a robot link (not an attached
// object) takes the body's distance, gradient and witnesses from checker::World::bodySignedDistance
// (the union's penetration depth; the pairwise answer where a piece is rounded), and so does the
// minimum distance that steps and probes are judged by. It converges in fewer iterations on the
// hard cases and on random starts of the bundled arm (docs/checker.md, "Body-level signed
// distance"). Its cost is bounded: a body query that would have to build more Minkowski
// differences than geometry::BodyDepthOptions::maxBuildCost pays for (deeply overlapping links of
// many pieces) answers BuildLimit, and that contact keeps its pairwise answer. Where the body
// search does not converge (on random starts of the bundled arm centimetres deep it fails a few
// more than the pairwise one), the pairwise search runs from the same start; maxDepth is judged
// by the deepest pair's depth either way.
// Departures from a textbook projection: the target is c above the threshold rather than on it,
// so that the last linearized step does not land exactly on the boundary. The minimum joint-space
// motion is not guaranteed (the problem is non-convex); the step is the locally smallest one.
//
// Joint limits: a start outside the limits is first clamped into them (that motion counts).
//
// Jiggle baseline (MoveIt's FixStartStateCollision adapter): up to `attempts` times, draw every
// joint uniformly within +-fraction * (its range) of the ORIGINAL configuration, clamped to the
// limits; return the first valid draw. MoveIt perturbs one joint group per attempt and keeps the
// previous perturbations; this version redraws every joint each attempt, which moves no farther.
//
// Thread safety: run() and jiggle() are const / free functions over a const World; run them from
// any number of threads.

#include "deepcheck/checker/world.h"
#include "deepcheck/planners/tolerances.h"
#include "deepcheck/planners/validity.h"

#include <Eigen/Core>

#include <cstdint>
#include <memory>
#include <random>

namespace deepcheck::planners {

struct PushOutOptions {
  /// Aim this far above the validity threshold (metres, > 0).
  double targetClearance = tol::kPushOutTargetClearance;
  /// Damping lambda of the least-squares step (metres per radian, > 0).
  double damping = tol::kPushOutDamping;
  /// Largest joint change per iteration (rad or m, > 0).
  double maxJointStep = tol::kPushOutMaxJointStep;
  /// Iterations before NotConverged (>= 1).
  int maxIterations = tol::kPushOutMaxIterations;
  /// Configurations penetrating deeper than this are not attempted (metres, > 0; infinity for no
  /// limit).
  double maxDepth = tol::kPushOutMaxDepth;
  /// Body depth (header comment, "Bodies"): an overlapping contact of a robot link with a body
  /// measured as the union of the body's pieces (checker::World::bodySignedDistance) rather than as
  /// its deepest piece pair. False: always the deepest pair (cheaper, converges less often).
  bool bodyDepth = true;
  /// Cap on one body query's cost (geometry::BodyDepthOptions::maxBuildCost: estimated microseconds,
  /// >= 0; infinity for none): a contact whose body query would cost more keeps its pairwise answer.
  double bodyBuildCost = tol::kPushOutBodyBuildCost;
};

/// Throws std::invalid_argument naming the option and its value when one is out of its range.
void checkPushOutOptions(const PushOutOptions& options);

enum class PushOutStatus {
  AlreadyValid,  ///< the input was valid (and within the limits): returned unchanged
  Repaired,      ///< a valid configuration was found
  TooDeep,       ///< the input penetrates deeper than maxDepth: not attempted, q is the input
  NotConverged,  ///< no valid configuration within maxIterations (the jiggle: within attempts);
                 ///< q is the last iterate (not valid)
};
const char* toString(PushOutStatus status);

struct PushOutResult {
  PushOutStatus status = PushOutStatus::NotConverged;
  Eigen::VectorXd q;   ///< the result (valid when success())
  int iterations = 0;  ///< push-out iterations / jiggle attempts used
  /// sd of the input (metres), measured no farther than t + c + tol::kPushOutLookahead (that value
  /// when nothing is nearer); NaN when the push-out did not start (the input valid, or valid once
  /// clamped into the limits) and for the jiggle.
  double initialDistance = 0.0;
  /// sd of q (metres); NaN when the push-out did not start, and for a jiggle that did not repair.
  double finalDistance = 0.0;
  double jointMotion = 0.0;  ///< |q - input|, joint-space Euclidean norm
  /// Why it failed, when no configuration can succeed: a pair that no joint moves within the
  /// validity threshold (checker::World::fixedPairs), named with how to allow it. Else empty.
  std::string reason;
  bool success() const { return status == PushOutStatus::AlreadyValid || status == PushOutStatus::Repaired; }
};

class PushOut;
/// Shared pointer, named as OMPL names its own.
using PushOutPtr = std::shared_ptr<PushOut>;

class PushOut {
 public:
  /// Throws std::invalid_argument for bad options (naming them) or a null world.
  PushOut(std::shared_ptr<const checker::World> world, const ValidityOptions& validity = {},
          const PushOutOptions& options = {});

  /// Pushes q out (see the header comment); the values of wrapping variables (continuous joints,
  /// robots/joint_angles.h) are normalized to (-pi, pi] first, the others clamped into their
  /// limits. Throws std::invalid_argument for a q of the wrong size or with a non-finite value,
  /// naming the variable.
  PushOutResult run(const Eigen::Ref<const Eigen::VectorXd>& q) const;

  const checker::World& world() const { return *world_; }
  const ValidityOptions& validity() const { return validity_; }
  const PushOutOptions& options() const { return options_; }

 private:
  /// After a body-depth search that did not converge: the pairwise search from the same start.
  /// On success result.q is its answer; result.iterations counts both searches.
  bool retryPairwise(const Eigen::VectorXd& start, PushOutResult& result) const;

  std::shared_ptr<const checker::World> world_;
  ValidityOptions validity_;
  PushOutOptions options_;
};

/// A push-out whose configurations count as valid only `standOff` (metres, >= 0) above the
/// threshold of `validity`: it pushes slightly colliding configurations that far out of contact
/// (path repair, endpoint repair) instead of just past it. Throws like the PushOut constructor,
/// and std::invalid_argument for a negative or non-finite standOff.
PushOut standOffPushOut(std::shared_ptr<const checker::World> world, const ValidityOptions& validity,
                        const PushOutOptions& options, double standOff);

struct JiggleOptions {
  /// Each joint moves within +-fraction * (upper - lower) (> 0).
  double fraction = tol::kJiggleFraction;
  /// Random draws before NotConverged (>= 1).
  int attempts = tol::kJiggleAttempts;
};

/// The random-jiggle baseline (see the header comment). `rng` is the caller's, for pinned seeds.
/// Throws std::invalid_argument for bad options or a bad q.
PushOutResult jiggle(const checker::World& world, const ValidityOptions& validity,
                     const Eigen::Ref<const Eigen::VectorXd>& q, const JiggleOptions& options, std::mt19937_64& rng);

/// Largest displacement of a link frame origin between configurations a and b (metres): the
/// workspace motion of a repair, for reports.
double maxLinkDisplacement(const robots::RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& a,
                           const Eigen::Ref<const Eigen::VectorXd>& b);

}  // namespace deepcheck::planners
