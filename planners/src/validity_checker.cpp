#include "deepcheck/planners/validity_checker.h"

#include "deepcheck/planners/state_space.h"
#include "deepcheck/robots/joint_angles.h"
#include "deepcheck/robots/kinematics.h"

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace deepcheck::planners {

namespace {

const std::shared_ptr<const checker::World>& nonNull(const std::shared_ptr<const checker::World>& world) {
  if (!world) throw std::invalid_argument("StateValidityChecker: the world is null");
  return world;
}

ompl::base::SpaceInformation* nonNull(ompl::base::SpaceInformation* si) {
  if (si == nullptr) throw std::invalid_argument("StateValidityChecker: the space information is null");
  return si;
}

}  // namespace

StateValidityChecker::StateValidityChecker(ompl::base::SpaceInformation* si,
                                           std::shared_ptr<const checker::World> world, const ValidityOptions& validity,
                                           const PushOutOptions& pushOut)
    : StateValidityChecker(si, world, makeStateMapping(*nonNull(si)->getStateSpace(), nonNull(world)->robot()),
                           validity, pushOut) {}

StateValidityChecker::StateValidityChecker(const ompl::base::SpaceInformationPtr& si,
                                           std::shared_ptr<const checker::World> world, const ValidityOptions& validity,
                                           const PushOutOptions& pushOut)
    : StateValidityChecker(si.get(), std::move(world), validity, pushOut) {}

StateValidityChecker::StateValidityChecker(ompl::base::SpaceInformation* si,
                                           std::shared_ptr<const checker::World> world, StateMapping mapping,
                                           const ValidityOptions& validity, const PushOutOptions& pushOut)
    : ompl::base::StateValidityChecker(nonNull(si)),
      world_(nonNull(world)),
      mapping_(std::move(mapping)),
      validity_(validity),
      pushOut_(world_, validity, pushOut),
      n_(world_->robot().numVariables()) {
  if (mapping_.numVariables() != n_) {
    throw std::invalid_argument("StateValidityChecker: the state mapping (" + mapping_.description() + ") has " +
                                std::to_string(mapping_.numVariables()) + " variables but robot '" +
                                world_->robot().name() + "' has " + std::to_string(n_));
  }
  lower_ = world_->robot().lowerLimits();
  upper_ = world_->robot().upperLimits();
  const std::vector<bool> wraps = robots::wrappingVariables(world_->robot());
  for (int v = 0; v < n_; ++v) {
    if (!wraps[static_cast<std::size_t>(v)]) continue;
    lower_[v] = -std::numeric_limits<double>::infinity();
    upper_[v] = std::numeric_limits<double>::infinity();
  }
  specs_.clearanceComputationType = ompl::base::StateValidityCheckerSpecs::APPROXIMATE;
  specs_.hasValidDirectionComputation = true;
  certifiedMotions_ = std::make_unique<CertifiedMotionMemo>(n_);
}

StateValidityChecker::StateValidityChecker(const ompl::base::SpaceInformationPtr& si,
                                           std::shared_ptr<const checker::World> world, StateMapping mapping,
                                           const ValidityOptions& validity, const PushOutOptions& pushOut)
    : StateValidityChecker(si.get(), std::move(world), std::move(mapping), validity, pushOut) {}

bool StateValidityChecker::withinBounds(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  const robots::RobotModel& model = world_->robot();
  if (q.size() != n_) robots::checkConfiguration(model, q);  // throws, naming the sizes
  return (q.array() >= lower_.array()).all() && (q.array() <= upper_.array()).all();
}

bool StateValidityChecker::isValid(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  validityQueries_.fetch_add(1, std::memory_order_relaxed);
  if (!withinBounds(q)) return false;
  return isConfigurationValid(*world_, q, validity_);
}

double StateValidityChecker::clearance(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  return clearanceUpTo(q, std::numeric_limits<double>::infinity());
}

bool StateValidityChecker::finite(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  if (q.size() != n_) robots::checkConfiguration(world_->robot(), q);  // throws, naming the sizes
  return q.allFinite();
}

double StateValidityChecker::clearanceUpTo(const Eigen::Ref<const Eigen::VectorXd>& q, double cap) const {
  distanceQueries_.fetch_add(1, std::memory_order_relaxed);
  if (!finite(q)) return -std::numeric_limits<double>::infinity();
  return signedDistanceUpTo(*world_, q, cap);
}

SplitDistance StateValidityChecker::splitClearanceUpTo(const Eigen::Ref<const Eigen::VectorXd>& q, double cap,
                                                       bool selfPairs) const {
  distanceQueries_.fetch_add(1, std::memory_order_relaxed);
  if (!finite(q)) {
    constexpr double worst = -std::numeric_limits<double>::infinity();
    return SplitDistance{worst, selfPairs ? worst : std::numeric_limits<double>::infinity()};
  }
  return splitSignedDistanceUpTo(*world_, q, cap, selfPairs);
}

bool StateValidityChecker::isValid(const ompl::base::State* state) const {
  return isValid(mapping_.configuration(state));
}

bool StateValidityChecker::isValid(const ompl::base::State* state, double& dist) const {
  const Eigen::VectorXd q = mapping_.configuration(state);
  dist = clearance(q);
  validityQueries_.fetch_add(1, std::memory_order_relaxed);
  if (!withinBounds(q)) return false;
  // Same criterion as isValid(q), decided from the distance already computed; the threshold-0
  // case keeps isFree's answer so that both overloads always agree at contact.
  const double threshold = validity_.threshold();
  return threshold == 0.0 ? isConfigurationValid(*world_, q, validity_) : dist > threshold;
}

bool StateValidityChecker::isValid(const ompl::base::State* state, double& dist, ompl::base::State* validState,
                                   bool& validStateAvailable) const {
  const bool valid = isValid(state, dist);
  validStateAvailable = false;
  if (valid) return true;
  const Eigen::VectorXd q = mapping_.configuration(state);
  if (!q.allFinite()) return false;  // no configuration to push out from
  const PushOutResult pushed = pushOut_.run(q);
  if (pushed.success()) {
    mapping_.toState(pushed.q, validState);
    validStateAvailable = true;
  }
  return false;
}

double StateValidityChecker::clearance(const ompl::base::State* state) const {
  return clearance(mapping_.configuration(state));
}

double StateValidityChecker::clearance(const ompl::base::State* state, ompl::base::State* validState,
                                       bool& validStateAvailable) const {
  double dist = 0.0;
  isValid(state, dist, validState, validStateAvailable);
  return dist;
}

void StateValidityChecker::resetCounters() {
  validityQueries_.store(0, std::memory_order_relaxed);
  distanceQueries_.store(0, std::memory_order_relaxed);
}

}  // namespace deepcheck::planners
