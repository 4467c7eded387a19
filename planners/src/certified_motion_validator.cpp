// Certified motions through World::certifyMotion (see certified_motion_validator.h).

#include "deepcheck/planners/certified_motion_validator.h"

#include "deepcheck/planners/state_space.h"
#include "deepcheck/robots/format_number.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace deepcheck::planners {

/// One motion being checked: the calling thread's scratch, reused from motion to motion.
struct CertifiedMotionValidator::Motion {
  std::shared_ptr<const LinkSpeedBound> bound;
  const ompl::base::State* s2 = nullptr;
  Eigen::VectorXd q1, q2, dq;
  checker::ClearanceDemand demand;  ///< the bounds over the whole motion
  bool bounded = false;             ///< demand holds this motion's bounds (bind)
};

namespace {

std::shared_ptr<const StateValidityChecker> checkedChecker(std::shared_ptr<const StateValidityChecker> checker) {
  if (!checker) throw std::invalid_argument("CertifiedMotionValidator: the validity checker is null");
  const ValidityOptions& v = checker->validityOptions();
  if (v.threshold() < 0.0) {
    throw std::invalid_argument("CertifiedMotionValidator: a penetration tolerance of " +
                                robots::formatNumber(v.penetrationTolerance) + " m above the safety margin of " +
                                robots::formatNumber(v.safetyMargin) +
                                " m cannot be certified; use ClearanceMotionValidator");
  }
  return checker;
}

}  // namespace

CertifiedMotionValidator::CertifiedMotionValidator(ompl::base::SpaceInformation* si,
                                                   std::shared_ptr<const StateValidityChecker> checker)
    : ompl::base::MotionValidator(si),
      checker_(checkedChecker(std::move(checker))),
      refused_(checker_->world().robot().numVariables()) {
  if (si == nullptr) throw std::invalid_argument("CertifiedMotionValidator: the space information is null");
  boundVersion_ = checker_->world().version();
  bound_ = std::make_shared<const LinkSpeedBound>(LinkSpeedBound::forWorld(checker_->world()));
}

CertifiedMotionValidator::CertifiedMotionValidator(const ompl::base::SpaceInformationPtr& si,
                                                   std::shared_ptr<const StateValidityChecker> checker)
    : CertifiedMotionValidator(si.get(), std::move(checker)) {}

std::shared_ptr<const LinkSpeedBound> CertifiedMotionValidator::bound() const {
  const checker::World& world = checker_->world();
  const std::uint64_t version = world.version();
  std::lock_guard<std::mutex> lock(boundMutex_);
  if (version != boundVersion_) {
    // Obstacles and allowed pairs change the version too; only the pieces' extents and the
    // checked self pairs matter to the bound.
    if (world.linkExtents() != bound_->linkExtents() || world.allowedSelfPairs() != bound_->selfPairs()) {
      bound_ = std::make_shared<const LinkSpeedBound>(LinkSpeedBound::forWorld(world));
    }
    boundVersion_ = version;
  }
  return bound_;
}

void CertifiedMotionValidator::prepare(const ompl::base::State* s1, const ompl::base::State* s2, Motion& m) const {
  const StateMapping& mapping = checker_->mapping();
  m.bound = bound();
  m.s2 = s2;
  m.q1 = mapping.configuration(s1);
  m.q2 = mapping.configuration(s2);
  m.dq = mapping.displacement(m.q1, m.q2);
  m.bounded = false;
}

void CertifiedMotionValidator::bind(Motion& m) const {
  if (m.bounded) return;
  m.bound->displacements(m.dq, m.demand.link, m.demand.self);
  m.demand.base = checker_->validityOptions().threshold();
  m.bounded = true;
}

checker::MotionCertificate CertifiedMotionValidator::certify(const Motion& m, double fraction) const {
  const checker::MotionCertificate c =
      fraction == 1.0 ? checker_->world().certifyMotion(m.q1, m.dq, m.demand) : prefix(m, fraction);
  configurations_.fetch_add(static_cast<std::uint64_t>(c.configurations), std::memory_order_relaxed);
  if (c.verdict == checker::MotionCertificate::Verdict::Unproven) {
    unproven_.fetch_add(1, std::memory_order_relaxed);
  }
  return c;
}

checker::MotionCertificate CertifiedMotionValidator::prefix(const Motion& m, double fraction) const {
  // The prefix moves every pair by `fraction` of the whole motion's bound.
  thread_local checker::ClearanceDemand demand;
  demand.base = m.demand.base;
  demand.link = fraction * m.demand.link;
  demand.self = fraction * m.demand.self;
  return checker_->world().certifyMotion(m.q1, fraction * m.dq, demand);
}

bool CertifiedMotionValidator::accepted(Motion& m) const {
  CertifiedMotionMemo& memo = checker_->certifiedMotions();
  // The version before the certification: a change of the world during it leaves an entry no
  // later lookup matches, never one that answers for a world it was not certified in.
  const std::uint64_t version = checker_->world().version();
  if (memo.contains(m.q1, m.q2, m.dq, version)) return true;
  // s2 within its joint limits (OMPL's contract; a value that is not a number is not): its
  // collisions are the certification's, which proves the whole motion, s2 included, clear at the
  // validity threshold. A validity test of s2 first would refuse some motions sooner, at the cost
  // of one configuration test on every motion accepted.
  if (!si_->satisfiesBounds(m.s2) || !checker_->withinBounds(m.q2)) return false;
  if (refused_.contains(m.q1, m.q2, m.dq, version)) {
    refusedAgain_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  bind(m);
  if (!certify(m, 1.0).certified()) {
    refused_.insert(m.q1, m.q2, m.dq, version);
    return false;
  }
  memo.insert(m.q1, m.q2, m.dq, version);
  return true;
}

bool CertifiedMotionValidator::checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const {
  thread_local Motion m;
  motions_.fetch_add(1, std::memory_order_relaxed);
  prepare(s1, s2, m);
  if (!accepted(m)) {
    ++invalid_;
    return false;
  }
  ++valid_;
  return true;
}

bool CertifiedMotionValidator::checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                                           std::pair<ompl::base::State*, double>& lastValid) const {
  thread_local Motion m;
  motions_.fetch_add(1, std::memory_order_relaxed);
  prepare(s1, s2, m);
  if (accepted(m)) {
    ++valid_;
    return true;
  }
  // The longest certified prefix, by bisection on its length: [0, lo] is certified, [0, hi] not.
  bind(m);
  const double maxMove = std::max(m.demand.link.maxCoeff(), m.demand.self.maxCoeff());
  double lo = 0.0;
  double hi = 1.0;
  while ((hi - lo) * maxMove > checker::tol::kCertifiedResolution) {
    const double mid = 0.5 * (lo + hi);
    (certify(m, mid).certified() ? lo : hi) = mid;
  }
  const StateMapping& mapping = checker_->mapping();
  lastValid.second = lo;
  if (lastValid.first != nullptr) mapping.toState(mapping.along(m.q1, m.dq, lo), lastValid.first);
  ++invalid_;
  return false;
}

CertifiedMotionStats CertifiedMotionValidator::stats() const {
  CertifiedMotionStats s;
  s.motions = motions_.load(std::memory_order_relaxed);
  s.configurations = configurations_.load(std::memory_order_relaxed);
  s.unproven = unproven_.load(std::memory_order_relaxed);
  s.refusedAgain = refusedAgain_.load(std::memory_order_relaxed);
  return s;
}

void CertifiedMotionValidator::resetStats() {
  motions_.store(0, std::memory_order_relaxed);
  configurations_.store(0, std::memory_order_relaxed);
  unproven_.store(0, std::memory_order_relaxed);
  refusedAgain_.store(0, std::memory_order_relaxed);
  resetMotionCounter();
}

}  // namespace deepcheck::planners
