#include "deepcheck/planners/objectives.h"

#include "deepcheck/planners/state_space.h"
#include "uniform_informed_sampler.h"
#include "deepcheck/robots/format_number.h"

#include <ompl/base/goals/GoalRegion.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/samplers/informed/PathLengthDirectInfSampler.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace deepcheck::planners {

namespace {

/// OMPL's direct path-length sampler can be made: a RealVector space (it refuses others), a start,
/// and a goal it can sample now (it throws otherwise; a pose goal's IK solutions come lazily).
bool directSamplerApplies(const ompl::base::StateSpace& space, const ompl::base::ProblemDefinition& problem) {
  if (space.getType() != ompl::base::STATE_SPACE_REAL_VECTOR || problem.getStartStateCount() < 1) return false;
  const ompl::base::GoalPtr& goal = problem.getGoal();
  return goal && goal->hasType(ompl::base::GOAL_SAMPLEABLE_REGION) &&
         goal->as<ompl::base::GoalSampleableRegion>()->maxSampleCount() >= 1;
}

/// Path length + weight * hinge, keeping the path length's heuristics (admissible: hinge >= 0).
class LengthClearanceObjective : public ompl::base::MultiOptimizationObjective {
 public:
  explicit LengthClearanceObjective(const ompl::base::SpaceInformationPtr& si)
      : ompl::base::MultiOptimizationObjective(si) {
    setCostToGoHeuristic(&ompl::base::goalRegionCostToGo);
    description_ = "Path length + clearance hinge";
  }
  ompl::base::Cost motionCostHeuristic(const ompl::base::State* s1, const ompl::base::State* s2) const override {
    return ompl::base::Cost(si_->distance(s1, s2));
  }
  /// The informed set of path length: every path costing at most c is at most c long (the hinge is
  /// >= 0), so sampling the states of paths at most c long (the prolate hyperspheroid, sampled
  /// directly) never leaves out a better path. OMPL's default for other objectives is rejection
  /// sampling of the whole space, whose acceptance rate on an arm (a UR5: 28.8 rad across) is
  /// nearly 0 once a solution is known: BIT* then draws for seconds without checking its
  /// termination condition. Where the direct sampler cannot be made (directSamplerApplies) the
  /// whole space is sampled uniformly (uniform_informed_sampler.h).
  ompl::base::InformedSamplerPtr allocInformedStateSampler(const ompl::base::ProblemDefinitionPtr& problem,
                                                           unsigned int maxCalls) const override {
    if (!directSamplerApplies(*si_->getStateSpace(), *problem)) {
      return std::make_shared<UniformInformedSampler>(problem, maxCalls);
    }
    return std::make_shared<ompl::base::PathLengthDirectInfSampler>(problem, maxCalls);
  }
};

/// OMPL's path length, with uniform sampling of the whole space where OMPL's direct informed
/// sampler refuses the space (state_space.h: compounds with SO2 components).
class PathLengthObjective : public ompl::base::PathLengthOptimizationObjective {
 public:
  using ompl::base::PathLengthOptimizationObjective::PathLengthOptimizationObjective;
  ompl::base::InformedSamplerPtr allocInformedStateSampler(const ompl::base::ProblemDefinitionPtr& problem,
                                                           unsigned int maxCalls) const override {
    if (si_->getStateSpace()->getType() == ompl::base::STATE_SPACE_REAL_VECTOR) {
      return ompl::base::PathLengthOptimizationObjective::allocInformedStateSampler(problem, maxCalls);
    }
    return std::make_shared<UniformInformedSampler>(problem, maxCalls);
  }
};

}  // namespace

ompl::base::OptimizationObjectivePtr makePathLengthObjective(const ompl::base::SpaceInformationPtr& si) {
  if (!si) throw std::invalid_argument("makePathLengthObjective: the space information is null");
  return std::make_shared<PathLengthObjective>(si);
}

ClearanceHingeObjective::ClearanceHingeObjective(const ompl::base::SpaceInformationPtr& si,
                                                 std::shared_ptr<const StateValidityChecker> checker,
                                                 double safeDistance, std::shared_ptr<const LinkSpeedBound> bound,
                                                 double resolution)
    : ompl::base::OptimizationObjective(si),
      checker_(std::move(checker)),
      bound_(std::move(bound)),
      safeDistance_(safeDistance),
      resolution_(resolution) {
  if (!checker_) throw std::invalid_argument("ClearanceHingeObjective: the validity checker is null");
  if (!std::isfinite(safeDistance) || safeDistance < 0.0) {
    throw std::invalid_argument("ClearanceHingeObjective: safe distance must be finite and >= 0, got " +
                                robots::formatNumber(safeDistance));
  }
  if (std::isnan(resolution) || std::isinf(resolution)) {
    throw std::invalid_argument("ClearanceHingeObjective: resolution must be finite, got " +
                                robots::formatNumber(resolution));
  }
  description_ = "Clearance hinge (d_safe " + robots::formatNumber(safeDistance) + " m)";
}

void ClearanceHingeObjective::setSelfSafeDistance(double d) {
  if (!std::isfinite(d) || d < 0.0) {
    throw std::invalid_argument("ClearanceHingeObjective: self safe distance must be finite and >= 0, got " +
                                robots::formatNumber(d));
  }
  selfSafeDistance_ = d;
}

double ClearanceHingeObjective::hinge(const SplitDistance& d) const {
  return std::max({0.0, safeDistance_ - d.world, selfSafeDistance_ - d.self});
}

double ClearanceHingeObjective::hinge(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  const double cap = std::max(safeDistance_, selfSafeDistance_) + tol::kDistanceCapMargin;
  return hinge(checker_->splitClearanceUpTo(q, cap));
}

ompl::base::Cost ClearanceHingeObjective::stateCost(const ompl::base::State* s) const {
  return ompl::base::Cost(hinge(checker_->mapping().configuration(s)));
}

/// One motion's integral of the hinge: the states it evaluates and the two ways of summing them.
struct ClearanceHingeObjective::Motion {
  const ClearanceHingeObjective& objective;
  const StateMapping& mapping;
  Eigen::VectorXd q1;
  Eigen::VectorXd dq;
  int segments;
  bool selfTerm;  ///< the self distances are measured
  double safe;    ///< the larger safe distance measured

  /// The split distance at state k, asked up to the safe distance + B (all the tests of the spans
  /// that state ends need); `valid` false (and no distance) for an invalid state.
  SplitDistance evaluate(int k, double B, bool& valid) const {
    const Eigen::VectorXd q = mapping.along(q1, dq, static_cast<double>(k) / segments);
    valid = objective.checker_->isValid(q);
    return valid ? objective.checker_->splitClearanceUpTo(q, safe + B + tol::kDistanceCapMargin, selfTerm)
                 : SplitDistance{};
  }

  /// Trapezoid rule on the states k = 0..segments: the sum of h_k with weight 1/2 at the ends
  /// (times length / segments, the caller's). False when a state is invalid.
  bool trapezoidSum(double* sum) const {
    bool valid = false;
    *sum = 0.0;
    for (int k = 0; k <= segments; ++k) {
      const SplitDistance d = evaluate(k, 0.0, valid);
      if (!valid) return false;
      *sum += (k == 0 || k == segments ? 0.5 : 1.0) * objective.hinge(d);
    }
    return true;
  }

  /// The same sum, by bisection with the bound. On the states i..j the pair distances move by at
  /// most B_ij = B(dq (j - i) / segments), so each of sd_world and sd_self stays at least
  /// (sd_i + sd_j - B_ij) / 2 there; when that is >= its safe distance for both, every h_k in
  /// between is 0 and is not evaluated. Otherwise the middle state is evaluated and both halves
  /// looked at. The sum is the full trapezoid sum: only zero terms are skipped.
  bool bisectionSum(const LinkSpeedBound& bound, double* sum) const {
    const auto reach = [&](int i, int j) {
      return bound.pairDisplacement(dq * (static_cast<double>(j - i) / segments));
    };
    const auto zeroBetween = [&](const SplitDistance& a, const SplitDistance& b, double B) {
      return (a.world + b.world - B) / 2.0 >= objective.safeDistance_ &&
             (!selfTerm || (a.self + b.self - B) / 2.0 >= objective.selfSafeDistance_);
    };
    bool valid = false;
    const double Btotal = reach(0, segments);
    const SplitDistance first = evaluate(0, Btotal, valid);
    if (!valid) return false;
    const SplitDistance last = evaluate(segments, Btotal, valid);
    if (!valid) return false;
    *sum = 0.5 * (objective.hinge(first) + objective.hinge(last));
    struct Span {
      int i, j;
      SplitDistance a, b;
    };
    // Depth first: the stack holds at most one pending half per level of the bisection, and there
    // are at most 31 levels (segments is an int), so a fixed array does (no allocation per motion).
    std::array<Span, 64> stack;
    int size = 0;
    stack[size++] = {0, segments, first, last};
    while (size > 0) {
      const Span span = stack[--size];
      if (span.j - span.i <= 1) continue;
      const double B = reach(span.i, span.j);
      if (zeroBetween(span.a, span.b, B)) continue;
      const int m = (span.i + span.j) / 2;
      const SplitDistance mid = evaluate(m, B, valid);
      if (!valid) return false;
      *sum += objective.hinge(mid);
      stack[size++] = {span.i, m, span.a, mid};
      stack[size++] = {m, span.j, mid, span.b};
    }
    return true;
  }
};

ompl::base::Cost ClearanceHingeObjective::motionCost(const ompl::base::State* s1, const ompl::base::State* s2) const {
  const StateMapping& mapping = checker_->mapping();
  const Eigen::VectorXd q1 = mapping.configuration(s1);
  const Eigen::VectorXd dq = mapping.displacement(q1, mapping.configuration(s2));
  const double length = si_->distance(s1, s2);
  if (!(length > 0.0)) return ompl::base::Cost(0.0);
  const double resolution = resolution_ > 0.0 ? resolution_ : si_->getStateSpace()->getLongestValidSegmentLength();
  const int segments = std::max(1, static_cast<int>(std::ceil(length / resolution)));

  // Every state the integration evaluates is first checked for validity (validity.h; isFree's
  // early exit by default, no depth). A motion with an invalid evaluated state costs infinity: it
  // is never part of a valid path, and the early return spares the rest of the motion, penetration
  // depths included (optimizing planners ask the cost of many motions before checking them: RRT*
  // of every neighbour). On a valid state the self term is zero whenever d_self <= threshold
  // (sd_self > threshold >= d_self), so the self pairs are then not measured at all: adjacent
  // links a few millimetres apart would otherwise keep the bisection from skipping.
  const double threshold = checker_->validityOptions().threshold();
  const bool selfTerm = selfSafeDistance_ > threshold;
  const double safe = selfTerm ? std::max(safeDistance_, selfSafeDistance_) : safeDistance_;
  const Motion motion{*this, mapping, q1, dq, segments, selfTerm, safe};
  double sum = 0.0;
  const bool valid = bound_ ? motion.bisectionSum(*bound_, &sum) : motion.trapezoidSum(&sum);
  if (!valid) return infiniteCost();
  return ompl::base::Cost(sum * length / segments);
}

ompl::base::OptimizationObjectivePtr makeLengthClearanceObjective(const ompl::base::SpaceInformationPtr& si,
                                                                  std::shared_ptr<const StateValidityChecker> checker,
                                                                  double safeDistance, double weight,
                                                                  std::shared_ptr<const LinkSpeedBound> bound,
                                                                  double resolution) {
  if (!std::isfinite(weight) || weight < 0.0) {
    throw std::invalid_argument("makeLengthClearanceObjective: weight must be finite and >= 0, got " +
                                robots::formatNumber(weight));
  }
  auto objective = std::make_shared<LengthClearanceObjective>(si);
  objective->addObjective(std::make_shared<ompl::base::PathLengthOptimizationObjective>(si), 1.0);
  objective->addObjective(
      std::make_shared<ClearanceHingeObjective>(si, std::move(checker), safeDistance, std::move(bound), resolution),
      weight);
  objective->lock();
  return objective;
}

ompl::base::OptimizationObjectivePtr makeMaxMinClearanceObjective(const ompl::base::SpaceInformationPtr& si) {
  if (!si) throw std::invalid_argument("makeMaxMinClearanceObjective: the space information is null");
  return std::make_shared<ompl::base::MaximizeMinClearanceObjective>(si);
}

}  // namespace deepcheck::planners
