#pragma once
// A valid state sampler that pushes colliding samples out instead of throwing them away.
//
// sample(): up to getNrAttempts() times, draw a uniform state; return it when valid; otherwise run
// the push-out (push_out.h) from it and return the pushed-out state when that succeeds. Samples
// penetrating deeper than PushOutOptions::maxDepth are drawn again, not pushed. The pushed-out
// states lie just outside obstacles (within about the push-out's target clearance of contact), so
// the sampler adds states near obstacle surfaces to the uniform ones, as OMPL's obstacle-based
// and Gaussian samplers do, which helps roadmap planners (PRM) through narrow passages.
// sampleNear() does the same with uniform draws within `distance` of `near`.
//
// Register it on a SpaceInformation with
//     si->setValidStateSamplerAllocator(pushOutSamplerAllocator(checker));
// (planners that ask for valid samples, PRM among them, then use it). One sampler per planner
// thread, as OMPL allocates them; the push-out itself is const and thread safe.

#include "deepcheck/planners/validity_checker.h"

#include <ompl/base/StateSampler.h>
#include <ompl/base/ValidStateSampler.h>

#include <cstdint>
#include <memory>

namespace deepcheck::planners {

class PushOutValidStateSampler;
/// Shared pointer, as OMPL names its own (ompl::base::ValidStateSamplerPtr).
using PushOutValidStateSamplerPtr = std::shared_ptr<PushOutValidStateSampler>;

class PushOutValidStateSampler : public ompl::base::ValidStateSampler {
 public:
  /// Throws std::invalid_argument for a null checker. States are read and written through the
  /// checker's StateMapping.
  PushOutValidStateSampler(const ompl::base::SpaceInformation* si, std::shared_ptr<const StateValidityChecker> checker);

  bool sample(ompl::base::State* state) override;
  bool sampleNear(ompl::base::State* state, const ompl::base::State* near, double distance) override;

  std::uint64_t uniformValid() const { return uniformValid_; }  ///< samples valid as drawn
  std::uint64_t pushedOut() const { return pushedOut_; }        ///< samples repaired by push-out
  std::uint64_t rejected() const { return rejected_; }          ///< draws thrown away

 private:
  /// The drawn state is valid or was pushed out into `state`.
  bool accept(ompl::base::State* state);

  std::shared_ptr<const StateValidityChecker> checker_;
  ompl::base::StateSamplerPtr sampler_;
  std::uint64_t uniformValid_ = 0;
  std::uint64_t pushedOut_ = 0;
  std::uint64_t rejected_ = 0;
};

/// An allocator for SpaceInformation::setValidStateSamplerAllocator.
ompl::base::ValidStateSamplerAllocator pushOutSamplerAllocator(std::shared_ptr<const StateValidityChecker> checker);

}  // namespace deepcheck::planners
