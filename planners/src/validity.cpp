#include "deepcheck/planners/validity.h"

#include "deepcheck/planners/tolerances.h"
#include "deepcheck/robots/format_number.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace deepcheck::planners {

namespace {

/// The minimum distance a query capped at `cap` found; `cap` when it found no pair below the cap
/// (then every pair is at least `cap` away).
double cappedMinimum(const checker::DistanceResult& result, double cap) {
  return result.found ? std::min(result.closest.distance, cap) : cap;
}

}  // namespace

void checkValidityOptions(const ValidityOptions& options) {
  if (!std::isfinite(options.penetrationTolerance) || options.penetrationTolerance < 0.0) {
    throw std::invalid_argument("ValidityOptions: penetrationTolerance must be finite and >= 0, got " +
                                robots::formatNumber(options.penetrationTolerance));
  }
  if (!std::isfinite(options.safetyMargin) || options.safetyMargin < 0.0) {
    throw std::invalid_argument("ValidityOptions: safetyMargin must be finite and >= 0, got " +
                                robots::formatNumber(options.safetyMargin));
  }
}

double signedDistanceUpTo(const checker::World& world, const Eigen::Ref<const Eigen::VectorXd>& q, double cap) {
  checker::DistanceOptions options;
  options.maxDistance = cap;
  return cappedMinimum(world.signedDistance(q, options), cap);
}

SplitDistance splitSignedDistanceUpTo(const checker::World& world, const Eigen::Ref<const Eigen::VectorXd>& q,
                                      double cap, bool selfPairs) {
  // Two pruned minimum searches, one per kind of pair: far cheaper than a contact list with a
  // margin of `cap`, which measures every body pair within it.
  checker::DistanceOptions options;
  options.maxDistance = cap;
  options.selfPairs = false;
  const double worldDistance = cappedMinimum(world.signedDistance(q, options), cap);
  if (!selfPairs) return SplitDistance{worldDistance, std::numeric_limits<double>::infinity()};
  options.selfPairs = true;
  options.worldPairs = false;
  return SplitDistance{worldDistance, cappedMinimum(world.signedDistance(q, options), cap)};
}

bool isConfigurationValid(const checker::World& world, const Eigen::Ref<const Eigen::VectorXd>& q,
                          const ValidityOptions& options) {
  const double threshold = options.threshold();
  if (threshold == 0.0) return world.isFree(q);
  const double cap = std::max(threshold, 0.0) + tol::kDistanceCapMargin;
  return signedDistanceUpTo(world, q, cap) > threshold;
}

}  // namespace deepcheck::planners
