#include "deepcheck/planners/valid_state_sampler.h"

#include "deepcheck/planners/state_space.h"

#include <ompl/base/SpaceInformation.h>

#include <stdexcept>
#include <string>

namespace deepcheck::planners {

PushOutValidStateSampler::PushOutValidStateSampler(const ompl::base::SpaceInformation* si,
                                                   std::shared_ptr<const StateValidityChecker> checker)
    : ompl::base::ValidStateSampler(si), checker_(std::move(checker)) {
  if (!checker_) throw std::invalid_argument("PushOutValidStateSampler: the validity checker is null");
  name_ = "push_out";
  sampler_ = si->allocStateSampler();
}

bool PushOutValidStateSampler::accept(ompl::base::State* state) {
  const Eigen::VectorXd q = checker_->mapping().configuration(state);
  if (checker_->isValid(q)) {
    ++uniformValid_;
    return true;
  }
  const PushOutResult pushed = checker_->pushOut().run(q);
  if (pushed.success()) {  // within the limits by construction
    checker_->mapping().toState(pushed.q, state);
    ++pushedOut_;
    return true;
  }
  ++rejected_;
  return false;
}

bool PushOutValidStateSampler::sample(ompl::base::State* state) {
  for (unsigned int attempt = 0; attempt < attempts_; ++attempt) {
    sampler_->sampleUniform(state);
    if (accept(state)) return true;
  }
  return false;
}

bool PushOutValidStateSampler::sampleNear(ompl::base::State* state, const ompl::base::State* near, double distance) {
  for (unsigned int attempt = 0; attempt < attempts_; ++attempt) {
    sampler_->sampleUniformNear(state, near, distance);
    if (accept(state)) return true;
  }
  return false;
}

ompl::base::ValidStateSamplerAllocator pushOutSamplerAllocator(std::shared_ptr<const StateValidityChecker> checker) {
  if (!checker) throw std::invalid_argument("pushOutSamplerAllocator: the validity checker is null");
  return [checker](const ompl::base::SpaceInformation* si) -> ompl::base::ValidStateSamplerPtr {
    return std::make_shared<PushOutValidStateSampler>(si, checker);
  };
}

}  // namespace deepcheck::planners
