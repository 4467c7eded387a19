#include "deepcheck/planners/state_space.h"

#include "deepcheck/planners/tolerances.h"
#include "deepcheck/robots/format_number.h"
#include "deepcheck/robots/joint_angles.h"

#include <ompl/base/spaces/SO2StateSpace.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace deepcheck::planners {

namespace {

void checkLimits(const robots::RobotModel& model, int v) {
  const double lo = model.lowerLimits()[v];
  const double hi = model.upperLimits()[v];
  if (std::isfinite(lo) && std::isfinite(hi) && lo < hi) return;
  throw std::invalid_argument(
      "makeStateSpace: robot '" + model.name() + "', variable '" + model.variableNames()[static_cast<std::size_t>(v)] +
      "' has limits [" + robots::formatNumber(lo) + ", " + robots::formatNumber(hi) + "] (need finite lower < upper)");
}

/// A RealVectorStateSpace of the variables first .. last - 1 (none of them wrapping), each
/// dimension bounded by its limits and named after it.
std::shared_ptr<ompl::base::RealVectorStateSpace> boundedSpace(const robots::RobotModel& model, int first, int last) {
  const auto n = static_cast<unsigned int>(last - first);
  auto space = std::make_shared<ompl::base::RealVectorStateSpace>(n);
  ompl::base::RealVectorBounds bounds(n);
  for (int v = first; v < last; ++v) {
    checkLimits(model, v);
    const auto d = static_cast<unsigned int>(v - first);
    bounds.setLow(d, model.lowerLimits()[v]);
    bounds.setHigh(d, model.upperLimits()[v]);
    space->setDimensionName(d, model.variableNames()[static_cast<std::size_t>(v)]);
  }
  space->setBounds(bounds);
  return space;
}

/// The compound of makeStateSpace for a model with wrapping variables: in variable order, an SO2
/// space per wrapping variable (named after it) and a RealVector space per run of the others.
std::shared_ptr<ompl::base::CompoundStateSpace> compoundSpace(const robots::RobotModel& model,
                                                              const std::vector<bool>& wraps) {
  auto space = std::make_shared<ompl::base::CompoundStateSpace>();
  const int n = model.numVariables();
  int v = 0;
  while (v < n) {
    if (wraps[static_cast<std::size_t>(v)]) {
      auto so2 = std::make_shared<ompl::base::SO2StateSpace>();
      so2->setName(model.variableNames()[static_cast<std::size_t>(v)]);
      space->addSubspace(so2, 1.0);
      ++v;
      continue;
    }
    int last = v;
    while (last < n && !wraps[static_cast<std::size_t>(last)]) ++last;
    auto block = boundedSpace(model, v, last);
    block->setName(model.name() + "_bounded_" + std::to_string(space->getSubspaceCount()));
    space->addSubspace(block, 1.0);
    v = last;
  }
  space->lock();
  return space;
}

}  // namespace

ompl::base::StateSpacePtr makeStateSpace(const robots::RobotModel& model) {
  const int n = model.numVariables();
  if (n == 0) {
    throw std::invalid_argument("makeStateSpace: robot '" + model.name() + "' (" + model.source() +
                                ") has no moving joint");
  }
  const std::vector<bool> wraps = robots::wrappingVariables(model);
  ompl::base::StateSpacePtr space;
  if (std::find(wraps.begin(), wraps.end(), true) == wraps.end()) {
    space = boundedSpace(model, 0, n);
  } else {
    space = compoundSpace(model, wraps);
  }
  space->setName(model.name() + "_joint_space");
  space->setLongestValidSegmentFraction(tol::kDefaultSegmentFraction);
  return space;
}

void copyToState(const Eigen::Ref<const Eigen::VectorXd>& q, ompl::base::State* state) {
  mapState(state, static_cast<int>(q.size())) = q;
}

}  // namespace deepcheck::planners
