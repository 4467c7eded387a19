#include "deepcheck/fcl_reference/fcl_validity_checker.h"

#include "deepcheck/planners/state_space.h"

#include <stdexcept>
#include <string>

namespace deepcheck::fcl_reference {

namespace {

ompl::base::SpaceInformation* nonNull(ompl::base::SpaceInformation* si) {
  if (si == nullptr) throw std::invalid_argument("FclStateValidityChecker: the space information is null");
  return si;
}

}  // namespace

FclStateValidityChecker::FclStateValidityChecker(ompl::base::SpaceInformation* si, const checker::World& world)
    : ompl::base::StateValidityChecker(nonNull(si)),
      mapping_(planners::makeStateMapping(*si->getStateSpace(), world.robot())),
      lower_(world.robot().lowerLimits()),
      upper_(world.robot().upperLimits()),
      fcl_(std::make_unique<FclWorld>(world)) {
  specs_.clearanceComputationType = ompl::base::StateValidityCheckerSpecs::APPROXIMATE;
}

FclStateValidityChecker::FclStateValidityChecker(const ompl::base::SpaceInformationPtr& si, const checker::World& world)
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
  const Eigen::VectorXd q = mapping_.configuration(state);
  if (!((q.array() >= lower_.array()).all() && (q.array() <= upper_.array()).all())) return false;
  return isFree(q);
}

double FclStateValidityChecker::clearance(const ompl::base::State* state) const {
  return distance(mapping_.configuration(state));
}

}  // namespace deepcheck::fcl_reference
