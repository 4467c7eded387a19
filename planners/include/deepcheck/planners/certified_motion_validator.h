#pragma once
// The default motion validator: a motion is accepted only when every configuration on it is
// proven valid, continuously, not sampled (adaptive dynamic collision checking: Schwarzer, Saha,
// Latombe, IEEE T-RO 21(3), 2005).
//
// For the straight motion q(t) = q1 + t dq, t in [0, 1] (angular variables the short way round:
// StateMapping::displacement), link i moves by at most D_i(dq) over the whole motion and a self
// pair (a, b) relatively by at most B_ab(dq) (motion_bound.h), so over a sub-motion of half
// length h around q(tm) by h D_i and h B_ab. World::certifyMotion (checker/world.h) takes these
// bounds and proves the motion pair by pair: a pair farther apart at q(tm) than threshold + h
// times its bound is clear over the sub-motion (one isClear test of that pair: isFree with the
// piece grown), otherwise its distance d at q(tm) (a GJK lower bound) proves it clear over the
// part around tm that it cannot cross, (d - threshold) over its bound, and the two ends left are
// examined next. Pairs that stay apart over the whole motion never reach a narrow phase; near
// pairs are refined only where they are near. Sub-motions are visited level by level, so the
// configurations tested are spread along the motion first and a collision is met early.
// checkMotion(s1, s2): s2 must lie within the joint limits, then the motion must be Certified
// (the certification covers s2's collisions: OMPL's contract, s2 valid, holds). A motion neither
// certified nor found colliding down to checker::tol::kCertifiedResolution (it passes within
// about 10 micrometres of the threshold without reaching it) is refused and counted
// (stats().unproven): a motion is accepted only when proven.
// The resolution is the robot's geometry moving (metres), not a fraction of the state space's
// extent: continuous joints and wide joint ranges are no special case, and far from obstacles a
// long motion is certified by a few tests.
//
// The lastValid overload, for a motion it rejects, finds the longest certified prefix by
// bisection on its length (to the same resolution) and reports its end (OMPL's convention:
// lastValid.second is its fraction of the motion; that configuration is proven valid).
//
// An accepted motion is remembered in the checker's memo (certified_motion_memo.h) and answered
// from it when asked again in the same world; a motion checkMotion(s1, s2) refused after testing
// it is remembered by the validator (refused_motion_memo.h) and refused again likewise.
//
// The bound is made from the world's pieces (LinkSpeedBound::forWorld) and made again when the
// world changes in a way that moves them (an object attached or detached: World::version and
// World::linkExtents), so attached objects are always covered.
//
// The validity threshold of the checker must be >= 0 (a safety margin, no penetration
// tolerance): a penetration tolerance cannot be a clearance demand; makeSimpleSetup then uses
// ClearanceMotionValidator (motion_validator.h). Thread safe.

#include "deepcheck/planners/motion_bound.h"
#include "deepcheck/planners/refused_motion_memo.h"
#include "deepcheck/planners/validity_checker.h"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace deepcheck::planners {

struct CertifiedMotionStats {
  std::uint64_t motions = 0;         ///< checkMotion calls
  std::uint64_t configurations = 0;  ///< configurations the certifications tested
  std::uint64_t unproven = 0;        ///< certifications that ended neither certified nor colliding
  std::uint64_t refusedAgain = 0;    ///< motions refused from the memo of refused motions, untested
};

class CertifiedMotionValidator;
/// Shared pointer, as OMPL names its own (ompl::base::MotionValidatorPtr).
using CertifiedMotionValidatorPtr = std::shared_ptr<CertifiedMotionValidator>;

class CertifiedMotionValidator : public ompl::base::MotionValidator {
 public:
  /// Throws std::invalid_argument for a null space information or checker, or a checker whose
  /// validity threshold is negative (naming the penetration tolerance).
  CertifiedMotionValidator(ompl::base::SpaceInformation* si, std::shared_ptr<const StateValidityChecker> checker);
  CertifiedMotionValidator(const ompl::base::SpaceInformationPtr& si,
                           std::shared_ptr<const StateValidityChecker> checker);

  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

  CertifiedMotionStats stats() const;
  void resetStats();
  /// Empties the memo of refused motions, so that each is tested again (a benchmark replaying
  /// motions, say); the world's changes need no call, the memo answers in one world version only.
  void forgetRefusedMotions() { refused_.clear(); }

  /// The bound in use (made again when the world's pieces change).
  std::shared_ptr<const LinkSpeedBound> bound() const;

 private:
  struct Motion;
  /// Reads the states and the displacement of one motion.
  void prepare(const ompl::base::State* s1, const ompl::base::State* s2, Motion& m) const;
  /// Computes the motion's bounds (once).
  void bind(Motion& m) const;
  /// Certifies the first `fraction` of the motion, counting.
  checker::MotionCertificate certify(const Motion& m, double fraction) const;
  checker::MotionCertificate prefix(const Motion& m, double fraction) const;
  /// The whole motion is valid: in the checker's memo of certified motions, or s2 within the
  /// limits and the motion certified now (then remembered).
  bool accepted(Motion& m) const;

  std::shared_ptr<const StateValidityChecker> checker_;
  mutable std::mutex boundMutex_;
  mutable std::shared_ptr<const LinkSpeedBound> bound_;
  mutable std::uint64_t boundVersion_ = 0;
  mutable std::atomic<std::uint64_t> motions_{0};
  mutable std::atomic<std::uint64_t> configurations_{0};
  mutable std::atomic<std::uint64_t> unproven_{0};
  mutable std::atomic<std::uint64_t> refusedAgain_{0};
  /// The motions checkMotion(s1, s2) refused by a certification (refused_motion_memo.h).
  mutable RefusedMotionMemo refused_;
};

}  // namespace deepcheck::planners
