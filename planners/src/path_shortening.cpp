// Path shortening for simplifySolutionChecked (see path_shortening.h).

#include "path_shortening.h"

#include "deepcheck/planners/certified_motion_validator.h"
#include "deepcheck/planners/tolerances.h"

#include <memory>
#include <vector>

namespace deepcheck::planners {
namespace {

/// Rounds of B-spline smoothing in one pass.
constexpr unsigned kSmoothingRounds = 2;

/// Corner cutting by subdivision (a quadratic B-spline's refinement): each round halves every
/// motion, then moves each original vertex v (neighbours a, b, now the halves' midpoints) to
/// (a + 2 v + b) / 4 when both new motions pass the motion validator. Stops after a round that
/// moved nothing. The path's vertices must be valid (a checked path's are).
void smoothCorners(ompl::geometric::PathGeometric& path, unsigned rounds) {
  const ompl::base::SpaceInformationPtr& si = path.getSpaceInformation();
  const ompl::base::StateSpacePtr& space = si->getStateSpace();
  std::vector<ompl::base::State*>& s = path.getStates();
  ompl::base::State* corner = si->allocState();
  ompl::base::State* half = si->allocState();
  for (unsigned round = 0; round < rounds; ++round) {
    path.subdivide();
    // A midpoint across a wrapping joint's bound can round onto it (SO2's pi, outside its
    // half-open interval): the same angle inside.
    for (std::size_t i = 1; i < s.size(); i += 2) si->enforceBounds(s[i]);
    bool moved = false;
    for (std::size_t i = 2; i + 1 < s.size(); i += 2) {
      space->interpolate(s[i - 1], s[i], 0.5, corner);
      space->interpolate(s[i], s[i + 1], 0.5, half);
      space->interpolate(corner, half, 0.5, corner);
      if (si->distance(s[i], corner) > tol::kSmoothingMinMove && si->checkMotion(s[i - 1], corner) &&
          si->checkMotion(corner, s[i + 1])) {
        si->copyState(s[i], corner);
        moved = true;
      }
    }
    if (!moved) break;
  }
  si->freeState(half);
  si->freeState(corner);
}

}  // namespace

void shortenPath(ompl::geometric::PathSimplifier& simplifier, ompl::geometric::PathGeometric& path) {
  const bool certified = std::dynamic_pointer_cast<const CertifiedMotionValidator>(
                             path.getSpaceInformation()->getMotionValidator()) != nullptr;
  simplifier.reduceVertices(path);
  simplifier.shortcutPath(path);
  simplifier.reduceVertices(path);
  if (certified) {
    smoothCorners(path, kSmoothingRounds);
  } else {
    simplifier.smoothBSpline(path, kSmoothingRounds);
  }
}

}  // namespace deepcheck::planners
