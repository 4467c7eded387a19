#include "deepcheck/planners/pose_goal.h"

#include "deepcheck/planners/state_space.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace deepcheck::planners {
namespace {

std::shared_ptr<const StateValidityChecker> deepcheckChecker(const ompl::base::SpaceInformationPtr& si) {
  auto checker = si ? std::dynamic_pointer_cast<const StateValidityChecker>(si->getStateValidityChecker()) : nullptr;
  if (!checker) {
    throw std::invalid_argument(
        "PoseGoal: the space information's validity checker is not a "
        "deepcheck::planners::StateValidityChecker");
  }
  return checker;
}

void checkGoalOptions(const PoseGoalOptions& options) {
  std::ostringstream msg;
  if (options.maxGoalStates < 1) {
    msg << "PoseGoal: option maxGoalStates is " << options.maxGoalStates << ", it must be at least 1";
  } else if (options.maxFailedSamples < 1) {
    msg << "PoseGoal: option maxFailedSamples is " << options.maxFailedSamples << ", it must be at least 1";
  } else if (!(std::isfinite(options.minSeparation) && options.minSeparation >= 0.0)) {
    msg << "PoseGoal: option minSeparation (rad) is " << options.minSeparation << ", it must be finite and >= 0";
  } else {
    return;
  }
  throw std::invalid_argument(msg.str());
}

}  // namespace

robots::IkResult solveCollisionFree(const StateValidityChecker& checker, const std::string& link,
                                    const Eigen::Isometry3d& X_WT, const robots::IkOptions& options) {
  return robots::solveInverseKinematics(checker.world().robot(), link, X_WT, options,
                                        [&checker](const Eigen::VectorXd& q) { return checker.isValid(q); });
}

PoseGoal::PoseGoal(const ompl::base::SpaceInformationPtr& si, const std::string& link, const Eigen::Isometry3d& X_WT,
                   const PoseGoalOptions& options)
    : ompl::base::GoalLazySamples(
          si, [this](const ompl::base::GoalLazySamples*, ompl::base::State* state) { return sample(state); },
          /*autoStart=*/false, options.minSeparation),
      checker_(deepcheckChecker(si)),
      linkName_(link),
      X_WT_(X_WT),
      options_(options) {
  link_ = robots::checkIkProblem(checker_->world().robot(), link, X_WT, options.ik);
  checkGoalOptions(options);
  setThreshold(1.0);  // distanceGoal is the normalized pose error
  startSampling();
}

PoseGoal::~PoseGoal() { stopSampling(); }

robots::PoseError PoseGoal::poseError(const ompl::base::State* state) const {
  return robots::poseError(checker_->world().robot(), link_, checker_->mapping().configuration(state), X_WT_,
                           options_.ik);
}

bool PoseGoal::isSatisfied(const ompl::base::State* state) const { return poseError(state).within(); }

bool PoseGoal::isSatisfied(const ompl::base::State* state, double* distance) const {
  const robots::PoseError error = poseError(state);
  if (distance != nullptr) *distance = error.normalized;
  return error.within();
}

double PoseGoal::distanceGoal(const ompl::base::State* state) const { return poseError(state).normalized; }

// Runs in the sampling thread: one valid IK solution per call, new seeds each time; false (no
// more calls) when enough goal states exist, too many IK calls in a row gave no new goal state
// (no valid solution, or one within minSeparation of a goal state: a robot with finitely many
// solutions runs out of new ones), or sampling stops.
bool PoseGoal::sample(ompl::base::State* state) {
  const int stateCount = static_cast<int>(getStateCount());
  if (stateCountAtLastSample_ >= 0) {
    // The last solution handed over was a duplicate (no new state), or a new goal state.
    failuresInRow_ = stateCount == stateCountAtLastSample_ ? failuresInRow_ + 1 : 0;
  }
  while (isSampling() && stateCount < options_.maxGoalStates && failuresInRow_ < options_.maxFailedSamples) {
    robots::IkOptions ik = options_.ik;
    ik.seed = options_.ik.seed + static_cast<std::uint64_t>(ikCalls_);
    if (ikCalls_++ > 0) ik.initial.resize(0);  // only the first call starts from the given configuration
    const robots::IkResult result = solveCollisionFree(*checker_, linkName_, X_WT_, ik);
    if (result.converged()) {
      checker_->mapping().toState(result.q, state);
      stateCountAtLastSample_ = stateCount;
      return true;
    }
    ++ikFailures_;
    ++failuresInRow_;
  }
  return false;
}

}  // namespace deepcheck::planners
