// Conservative advancement along straight joint-space motions (see motion_validator.h).

#include "deepcheck/planners/motion_validator.h"

#include "deepcheck/planners/state_space.h"
#include "deepcheck/planners/tolerances.h"
#include "deepcheck/robots/format_number.h"

#include <algorithm>
#include <queue>
#include <stdexcept>
#include <string>

namespace deepcheck::planners {

ClearanceMotionValidator::ClearanceMotionValidator(ompl::base::SpaceInformation* si,
                                                   std::shared_ptr<const StateValidityChecker> checker,
                                                   std::shared_ptr<const LinkSpeedBound> bound, double fallbackFraction)
    : ompl::base::MotionValidator(si),
      checker_(std::move(checker)),
      bound_(std::move(bound)),
      fallbackFraction_(fallbackFraction) {
  if (!(fallbackFraction > 0.0 && fallbackFraction <= 1.0)) {
    throw std::invalid_argument("ClearanceMotionValidator: fallbackFraction must be in (0, 1], got " +
                                robots::formatNumber(fallbackFraction));
  }
  if (si == nullptr) throw std::invalid_argument("ClearanceMotionValidator: the space information is null");
  if (!checker_) throw std::invalid_argument("ClearanceMotionValidator: the validity checker is null");
  if (!bound_) throw std::invalid_argument("ClearanceMotionValidator: the link speed bound is null");
  n_ = checker_->dimension();
  if (bound_->speeds().cols() != n_) {
    throw std::invalid_argument("ClearanceMotionValidator: checker of dimension " + std::to_string(n_) +
                                ", bound of dimension " + std::to_string(bound_->speeds().cols()) + " do not match");
  }
}

ClearanceMotionValidator::ClearanceMotionValidator(const ompl::base::SpaceInformationPtr& si,
                                                   std::shared_ptr<const StateValidityChecker> checker,
                                                   std::shared_ptr<const LinkSpeedBound> bound, double fallbackFraction)
    : ClearanceMotionValidator(si.get(), std::move(checker), std::move(bound), fallbackFraction) {}

namespace {

std::shared_ptr<const LinkSpeedBound> boundOfWorld(const std::shared_ptr<const StateValidityChecker>& checker) {
  if (!checker) throw std::invalid_argument("ClearanceMotionValidator: the validity checker is null");
  return std::make_shared<const LinkSpeedBound>(LinkSpeedBound::forWorld(checker->world()));
}

}  // namespace

ClearanceMotionValidator::ClearanceMotionValidator(ompl::base::SpaceInformation* si,
                                                   std::shared_ptr<const StateValidityChecker> checker,
                                                   double fallbackFraction)
    : ClearanceMotionValidator(si, checker, boundOfWorld(checker), fallbackFraction) {}

ClearanceMotionValidator::ClearanceMotionValidator(const ompl::base::SpaceInformationPtr& si,
                                                   std::shared_ptr<const StateValidityChecker> checker,
                                                   double fallbackFraction)
    : ClearanceMotionValidator(si.get(), checker, boundOfWorld(checker), fallbackFraction) {}

double ClearanceMotionValidator::minStep(double length, double B) const {
  double h = fallbackFraction_ * si_->getStateSpace()->getLongestValidSegmentLength();
  // No point may move more than kFallbackDisplacement between two checked states.
  if (B > 0.0) h = std::min(h, tol::kFallbackDisplacement / B * length);
  return length > h ? h / length : 1.0;
}

double ClearanceMotionValidator::certifiedStep(const Eigen::VectorXd& q, const Eigen::VectorXd& dq, double B,
                                               double remaining) const {
  const double threshold = checker_->validityOptions().threshold();
  // Every pair within the cap, each with its own clearance and bound; the pairs beyond the cap
  // certify the whole remaining motion.
  const double cap = std::max(threshold + B * remaining, 0.0) + tol::kDistanceCapMargin;
  checker::DistanceOptions options;
  options.maxDistance = cap;
  options.contactMargin = cap;
  distanceQueries_.fetch_add(1, std::memory_order_relaxed);
  const checker::DistanceResult d = checker_->world().signedDistance(q, options);
  if (d.found && !(d.closest.distance > threshold)) return -1.0;
  double step = (cap - threshold) / B;
  for (const checker::Contact& c : d.contacts) {
    const int linkB = c.bodyB.kind == checker::BodyRef::Kind::RobotLink ? c.bodyB.index : -1;
    const double pairBound = bound_->pairDisplacement(c.linkA, linkB, dq);
    if (pairBound > 0.0) step = std::min(step, (c.distance - threshold) / pairBound);
  }
  return step;
}

bool ClearanceMotionValidator::discretePass(const Eigen::Ref<const Eigen::VectorXd>& q1, const Eigen::VectorXd& dq,
                                            int segments) const {
  // The states j / segments, j = 1 .. segments - 1, in bisection order (OMPL's
  // DiscreteMotionValidator's order: a collision in the middle is found first).
  const StateMapping& mapping = checker_->mapping();
  std::queue<std::pair<int, int>> ranges;
  if (segments > 1) ranges.emplace(1, segments - 1);
  Eigen::VectorXd q(n_);
  while (!ranges.empty()) {
    const auto [a, b] = ranges.front();
    ranges.pop();
    const int mid = (a + b) / 2;
    q = mapping.along(q1, dq, static_cast<double>(mid) / segments);
    validityQueries_.fetch_add(1, std::memory_order_relaxed);
    if (!checker_->isValid(q)) return false;
    if (a < mid) ranges.emplace(a, mid - 1);
    if (mid < b) ranges.emplace(mid + 1, b);
  }
  return true;
}

bool ClearanceMotionValidator::checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const {
  motions_.fetch_add(1, std::memory_order_relaxed);
  const StateMapping& mapping = checker_->mapping();
  const Eigen::VectorXd q1 = mapping.configuration(s1);
  const Eigen::VectorXd q2 = mapping.configuration(s2);
  validityQueries_.fetch_add(1, std::memory_order_relaxed);
  if (!checker_->isValid(q2)) {
    ++invalid_;
    return false;
  }
  const Eigen::VectorXd dq = mapping.displacement(q1, q2);
  // 1. The discrete pass: colliding motions (most of those a planner asks about) are rejected at
  //    the price of OMPL's DiscreteMotionValidator.
  if (!discretePass(q1, dq, static_cast<int>(si_->getStateSpace()->validSegmentCount(s1, s2)))) {
    ++invalid_;
    return false;
  }
  // 2. Certification by clearance steps from both ends.
  const double B = bound_->pairDisplacement(dq);
  if (!(B > 0.0)) {  // no link with geometry moves
    ++valid_;
    return true;
  }
  const double h = minStep(si_->distance(s1, s2), B);
  double lo = 0.0;
  double hi = 1.0;
  bool fromLo = true;
  Eigen::VectorXd q(n_);
  while (true) {
    q = mapping.along(q1, dq, fromLo ? lo : hi);
    double step = certifiedStep(q, dq, B, hi - lo);
    if (step < 0.0) {
      certificationRejections_.fetch_add(1, std::memory_order_relaxed);
      ++invalid_;
      return false;
    }
    if (step < h) {
      if (refuseFallback_) {
        nearContactRejections_.fetch_add(1, std::memory_order_relaxed);
        ++invalid_;
        return false;
      }
      step = h;
      fallbackSteps_.fetch_add(1, std::memory_order_relaxed);
    }
    if (fromLo) {
      lo += step;
    } else {
      hi -= step;
    }
    if (lo >= hi) break;
    fromLo = !fromLo;
  }
  ++valid_;
  return true;
}

bool ClearanceMotionValidator::checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                                           std::pair<ompl::base::State*, double>& lastValid) const {
  motions_.fetch_add(1, std::memory_order_relaxed);
  const StateMapping& mapping = checker_->mapping();
  const Eigen::VectorXd q1 = mapping.configuration(s1);
  const Eigen::VectorXd q2 = mapping.configuration(s2);
  const Eigen::VectorXd dq = mapping.displacement(q1, q2);
  auto fail = [&](double last) {
    lastValid.second = last;
    if (lastValid.first != nullptr) mapping.toState(mapping.along(q1, dq, last), lastValid.first);
    ++invalid_;
    return false;
  };
  // 1. The discrete pass, forwards (as OMPL's DiscreteMotionValidator does for this overload).
  const int segments = static_cast<int>(si_->getStateSpace()->validSegmentCount(s1, s2));
  Eigen::VectorXd q(n_);
  for (int j = 1; j < segments; ++j) {
    q = mapping.along(q1, dq, static_cast<double>(j) / segments);
    validityQueries_.fetch_add(1, std::memory_order_relaxed);
    if (!checker_->isValid(q)) return fail(static_cast<double>(j - 1) / segments);
  }
  validityQueries_.fetch_add(1, std::memory_order_relaxed);
  if (!checker_->isValid(q2)) return fail(static_cast<double>(segments - 1) / segments);
  // 2. Certification forwards from s1.
  const double B = bound_->pairDisplacement(dq);
  const double h = minStep(si_->distance(s1, s2), B);
  double previous = 0.0;
  double s = 0.0;
  if (B > 0.0) {
    while (s < 1.0) {
      q = mapping.along(q1, dq, s);
      double step = certifiedStep(q, dq, B, 1.0 - s);
      if (step < 0.0) {
        certificationRejections_.fetch_add(1, std::memory_order_relaxed);
        return fail(previous);
      }
      previous = s;
      if (step < h) {
        if (refuseFallback_) {
          nearContactRejections_.fetch_add(1, std::memory_order_relaxed);
          return fail(previous);
        }
        step = h;
        fallbackSteps_.fetch_add(1, std::memory_order_relaxed);
      }
      s += step;
    }
  }
  ++valid_;
  return true;
}

MotionValidatorStats ClearanceMotionValidator::stats() const {
  MotionValidatorStats s;
  s.motions = motions_.load(std::memory_order_relaxed);
  s.distanceQueries = distanceQueries_.load(std::memory_order_relaxed);
  s.validityQueries = validityQueries_.load(std::memory_order_relaxed);
  s.fallbackSteps = fallbackSteps_.load(std::memory_order_relaxed);
  s.nearContactRejections = nearContactRejections_.load(std::memory_order_relaxed);
  s.certificationRejections = certificationRejections_.load(std::memory_order_relaxed);
  return s;
}

void ClearanceMotionValidator::resetStats() {
  motions_.store(0, std::memory_order_relaxed);
  distanceQueries_.store(0, std::memory_order_relaxed);
  validityQueries_.store(0, std::memory_order_relaxed);
  fallbackSteps_.store(0, std::memory_order_relaxed);
  nearContactRejections_.store(0, std::memory_order_relaxed);
  certificationRejections_.store(0, std::memory_order_relaxed);
  resetMotionCounter();
}

}  // namespace deepcheck::planners
