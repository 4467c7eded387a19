#pragma once
// An informed sampler that is not informed: every sample is drawn uniformly from the whole state
// space, whatever the cost bound. For the state spaces OMPL's direct path-length sampler refuses
// (compounds with SO2 components: continuous joints, state_space.h), in place of OMPL's default
// rejection sampler: the whole space contains every informed set, so nothing better is left out
// (the planners prune by their own heuristics), and a sample never costs more than one draw. The
// rejection sampler draws up to its call limit per sample and, on an arm's large joint space
// once a solution is known, accepts almost none: BIT* then draws for seconds without checking its
// termination condition (objectives.h).

#include <ompl/base/samplers/InformedStateSampler.h>

namespace deepcheck::planners {

class UniformInformedSampler : public ompl::base::InformedSampler {
 public:
  UniformInformedSampler(const ompl::base::ProblemDefinitionPtr& problem, unsigned int maxCalls)
      : ompl::base::InformedSampler(problem, maxCalls), sampler_(space_->allocDefaultStateSampler()) {}

  bool sampleUniform(ompl::base::State* state, const ompl::base::Cost& /*maxCost*/) override {
    sampler_->sampleUniform(state);
    return true;
  }
  bool sampleUniform(ompl::base::State* state, const ompl::base::Cost& /*minCost*/,
                     const ompl::base::Cost& /*maxCost*/) override {
    sampler_->sampleUniform(state);
    return true;
  }
  bool hasInformedMeasure() const override { return false; }
  double getInformedMeasure(const ompl::base::Cost& /*currentCost*/) const override { return space_->getMeasure(); }

 private:
  ompl::base::StateSamplerPtr sampler_;
};

}  // namespace deepcheck::planners
