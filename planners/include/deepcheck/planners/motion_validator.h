#pragma once
// A motion validator that certifies motions by stepping by the clearance (conservative
// advancement), after the discrete checks OMPL's DiscreteMotionValidator makes.
//
// checkMotion(s1, s2):
//   1. s2 must be valid (isValid, as OMPL's DiscreteMotionValidator checks first);
//   2. discrete pass: the states of the motion at the state space's resolution, in bisection
//      order, through isValid, exactly as DiscreteMotionValidator. Most motions a planner asks
//      about collide, and this rejects them at the discrete validator's price (isFree queries,
//      cheaper than the distance queries of step 3);
//   3. certification of the motions that passed, by clearance steps. For the straight motion
//      q(s) = q1 + s (q2 - q1), s in [0, 1] (angular variables the short way round: the
//      checker's StateMapping, state_space.h), and each pair p of the World,
//      sd_p(q(s')) >= sd_p(q(s)) - B_p |s' - s| with B_p the pair's own displacement bound
//      (motion_bound.h), so with the validity threshold t the whole interval
//          |s' - s| < min over pairs p of (sd_p(q(s)) - t) / B_p
//      is valid. Each step asks one query: the contact list of every pair within
//      cap = t + B (the rest of the motion), B = max_p B_p; each listed pair limits the step by
//      its own clearance over its own bound, the pairs beyond the cap (never measured) certify
//      the rest of the motion. Per-pair bounds matter: the nearest pair of an arm is often its
//      wrist (link 5 against link 7, a few centimetres apart whatever the configuration), which
//      only joints 6 and 7 move, while the fast-moving hand is far from everything; a single
//      bound for all pairs makes nearly every step fall back to the discrete resolution.
//      Steps alternate from both ends (lo = 0 upwards, hi = 1 downwards) until lo >= hi. A state
//      found invalid rejects the motion (certificationRejections counts these: collisions the
//      discrete pass stepped over);
//   4. fallback: a certified step smaller than h is replaced by h, the smaller of
//      fallbackFraction x the longest valid segment (a quarter of the discrete pass's resolution
//      by default) and the step in which no point moves more than tol::kFallbackDisplacement
//      (0.5 mm) by the bound. Such a step is not certified: there the motion is only checked at
//      the states visited, as discrete checking does, but no point of the robot moves more than
//      0.5 mm unchecked, so only a collision shorter than 0.5 mm of motion can be stepped over.
//      This happens only where some pair's clearance is below its bound over h, i.e. within
//      about 0.5 mm of contact (sliding along a surface); fallbackSteps counts these steps.
//      With setRefuseFallback(true) such a step rejects the motion instead (nearContactRejections
//      counts these): every motion the validator then accepts is certified by clearance, and a
//      motion that passes within about 0.5 mm of contact is refused even when it does not touch.
// So the validator is never less careful than DiscreteMotionValidator, and exact wherever the
// clearance allows. It costs the discrete checks plus the certification of the accepted motions,
// and a contact list up to the cap measures every pair within it: a certification query costs
// more than an isFree query. CertifiedMotionValidator (certified_motion_validator.h) certifies
// every motion without fallback steps and at about the discrete validator's price, and is the
// default; this validator serves where that one cannot: a validity criterion with a penetration
// tolerance (a negative threshold), which makeSimpleSetup and certifyPath then use it for.
// tests/planners/test_motion_validator.cpp counts the checks and distance queries per motion of
// both validators; no benchmark here times them or plans with this validator (bench/plan_bench.cpp
// plans with the discrete one).
//
// The lastValid overload runs the discrete pass forwards (as OMPL does), then certifies from q1
// forwards, and reports the last state visited before the first invalid one (OMPL's convention:
// lastValid.second is its fraction of the motion).
//
// Assumes q1 valid, as every OMPL motion validator does. Thread safe (counters are atomics).

#include "deepcheck/planners/motion_bound.h"
#include "deepcheck/planners/tolerances.h"
#include "deepcheck/planners/validity_checker.h"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>

#include <atomic>
#include <cstdint>
#include <memory>

namespace deepcheck::planners {

struct MotionValidatorStats {
  std::uint64_t motions = 0;                  ///< checkMotion calls
  std::uint64_t distanceQueries = 0;          ///< distance queries of the certification
  std::uint64_t validityQueries = 0;          ///< isValid queries (end state and discrete pass)
  std::uint64_t fallbackSteps = 0;            ///< uncertified steps (see the header comment)
  std::uint64_t certificationRejections = 0;  ///< motions the discrete pass accepted and the
                                              ///< certification found colliding
  std::uint64_t nearContactRejections = 0;    ///< motions refused instead of a fallback step
                                              ///< (setRefuseFallback)
};

class ClearanceMotionValidator;
/// Shared pointer, as OMPL names its own (ompl::base::MotionValidatorPtr).
using ClearanceMotionValidatorPtr = std::shared_ptr<ClearanceMotionValidator>;

class ClearanceMotionValidator : public ompl::base::MotionValidator {
 public:
  /// Throws std::invalid_argument for a null checker or bound, or a bound of another size. States
  /// of `si` are read through the checker's StateMapping.
  /// `fallbackFraction` in (0, 1]: the fallback step as a fraction of the longest valid segment.
  ClearanceMotionValidator(ompl::base::SpaceInformation* si, std::shared_ptr<const StateValidityChecker> checker,
                           std::shared_ptr<const LinkSpeedBound> bound,
                           double fallbackFraction = tol::kFallbackStepFraction);
  ClearanceMotionValidator(const ompl::base::SpaceInformationPtr& si,
                           std::shared_ptr<const StateValidityChecker> checker,
                           std::shared_ptr<const LinkSpeedBound> bound,
                           double fallbackFraction = tol::kFallbackStepFraction);
  /// The same with the bound of the checker's world, built here (LinkSpeedBound::forWorld, which
  /// loads the robot's meshes): what an OMPL user plugging in the validator wants.
  ClearanceMotionValidator(ompl::base::SpaceInformation* si, std::shared_ptr<const StateValidityChecker> checker,
                           double fallbackFraction = tol::kFallbackStepFraction);
  ClearanceMotionValidator(const ompl::base::SpaceInformationPtr& si,
                           std::shared_ptr<const StateValidityChecker> checker,
                           double fallbackFraction = tol::kFallbackStepFraction);

  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

  MotionValidatorStats stats() const;
  void resetStats();

  /// Refuse a motion where a fallback step would be needed (see the header comment); off by
  /// default.
  void setRefuseFallback(bool refuse) { refuseFallback_ = refuse; }
  bool refusesFallback() const { return refuseFallback_; }

  const LinkSpeedBound& bound() const { return *bound_; }

 private:
  /// The fallback step as a fraction of a motion of joint-space length `length` and bound B.
  double minStep(double length, double B) const;
  /// The fraction of the motion dq certified valid from q on (each pair's clearance above the
  /// threshold over its own bound), asking distances only up to what covers `remaining`; -1 when
  /// q itself is invalid.
  double certifiedStep(const Eigen::VectorXd& q, const Eigen::VectorXd& dq, double B, double remaining) const;
  /// The discrete pass: the states j / segments of the motion in bisection order.
  bool discretePass(const Eigen::Ref<const Eigen::VectorXd>& q1, const Eigen::VectorXd& dq, int segments) const;

  std::shared_ptr<const StateValidityChecker> checker_;
  std::shared_ptr<const LinkSpeedBound> bound_;
  double fallbackFraction_ = tol::kFallbackStepFraction;
  bool refuseFallback_ = false;
  int n_ = 0;
  mutable std::atomic<std::uint64_t> motions_{0};
  mutable std::atomic<std::uint64_t> distanceQueries_{0};
  mutable std::atomic<std::uint64_t> validityQueries_{0};
  mutable std::atomic<std::uint64_t> fallbackSteps_{0};
  mutable std::atomic<std::uint64_t> certificationRejections_{0};
  mutable std::atomic<std::uint64_t> nearContactRejections_{0};
};

}  // namespace deepcheck::planners
