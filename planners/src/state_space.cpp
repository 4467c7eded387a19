#include "deepcheck/planners/state_space.h"

#include "deepcheck/planners/tolerances.h"
#include "deepcheck/robots/format_number.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace deepcheck::planners {

std::shared_ptr<ompl::base::RealVectorStateSpace> makeStateSpace(const robots::RobotModel& model) {
  const int n = model.numVariables();
  if (n == 0) {
    throw std::invalid_argument("makeStateSpace: robot '" + model.name() + "' (" + model.source() +
                                ") has no moving joint");
  }
  auto space = std::make_shared<ompl::base::RealVectorStateSpace>(static_cast<unsigned int>(n));
  ompl::base::RealVectorBounds bounds(static_cast<unsigned int>(n));
  for (int v = 0; v < n; ++v) {
    const double lo = model.lowerLimits()[v];
    const double hi = model.upperLimits()[v];
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
      throw std::invalid_argument("makeStateSpace: robot '" + model.name() + "', variable '" +
                                  model.variableNames()[static_cast<std::size_t>(v)] + "' has limits [" +
                                  robots::formatNumber(lo) + ", " + robots::formatNumber(hi) + "] (need finite lower < upper)");
    }
    bounds.setLow(static_cast<unsigned int>(v), lo);
    bounds.setHigh(static_cast<unsigned int>(v), hi);
    space->setDimensionName(static_cast<unsigned int>(v), model.variableNames()[static_cast<std::size_t>(v)]);
  }
  space->setBounds(bounds);
  space->setName(model.name() + "_joint_space");
  space->setLongestValidSegmentFraction(tol::kDefaultSegmentFraction);
  return space;
}

void copyToState(const Eigen::Ref<const Eigen::VectorXd>& q, ompl::base::State* state) {
  mapState(state, static_cast<int>(q.size())) = q;
}

}  // namespace deepcheck::planners
