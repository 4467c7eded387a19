#include "deepcheck/fcl_reference/fcl_validity_checker.h"

#include "deepcheck/planners/state_space.h"

#include <stdexcept>
#include <string>

namespace deepcheck::fcl_reference {

FclStateValidityChecker::FclStateValidityChecker(ompl::base::SpaceInformation* si, const checker::World& world)
    : ompl::base::StateValidityChecker(si),
      n_(world.robot().numVariables()),
      lower_(world.robot().lowerLimits()),
      upper_(world.robot().upperLimits()),
      fcl_(std::make_unique<FclWorld>(world)) {
  if (si == nullptr) throw std::invalid_argument("FclStateValidityChecker: the space information is null");
  if (si->getStateDimension() != static_cast<unsigned int>(n_)) {
    throw std::invalid_argument("FclStateValidityChecker: the state space has dimension " +
                                std::to_string(si->getStateDimension()) + " but robot '" + world.robot().name() +
                                "' has " + std::to_string(n_) + " variables");
  }
  specs_.clearanceComputationType = ompl::base::StateValidityCheckerSpecs::APPROXIMATE;
}

FclStateValidityChecker::FclStateValidityChecker(const ompl::base::SpaceInformationPtr& si,
                                                 const checker::World& world)
    : FclStateValidityChecker(si.get(), world) {}

FclStateValidityChecker::~FclStateValidityChecker() = default;

bool FclStateValidityChecker::isFree(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return fcl_->isFree(q);
}

double FclStateValidityChecker::distance(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const FclDistanceResult r = fcl_->distance(q);
  return r.colliding ? 0.0 : r.distance;
}

bool FclStateValidityChecker::isValid(const ompl::base::State* state) const {
  const auto q = planners::mapState(state, n_);
  if (!((q.array() >= lower_.array()).all() && (q.array() <= upper_.array()).all())) return false;
  return isFree(q);
}

double FclStateValidityChecker::clearance(const ompl::base::State* state) const {
  return distance(planners::mapState(state, n_));
}

}  // namespace deepcheck::fcl_reference
