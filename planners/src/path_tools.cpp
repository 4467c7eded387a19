#include "deepcheck/planners/path_tools.h"

#include "deepcheck/planners/state_space.h"
#include "deepcheck/planners/validity_checker.h"
#include "deepcheck/robots/format_number.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <ostream>
#include <stdexcept>

namespace deepcheck::planners {

namespace {

/// How the path's states are configurations: its validity checker's mapping when that is a
/// deepcheck checker, else the values of a RealVectorStateSpace.
StateMapping mappingOf(const ompl::geometric::PathGeometric& path) {
  const ompl::base::SpaceInformation& si = *path.getSpaceInformation();
  if (auto checker = std::dynamic_pointer_cast<const StateValidityChecker>(si.getStateValidityChecker())) {
    return checker->mapping();
  }
  const auto* real = dynamic_cast<const ompl::base::RealVectorStateSpace*>(si.getStateSpace().get());
  if (real == nullptr) {
    throw std::invalid_argument("path tools: the path's state space '" + si.getStateSpace()->getName() +
                                "' is not a RealVectorStateSpace and its validity checker is not a "
                                "deepcheck::planners::StateValidityChecker, whose StateMapping would say how to "
                                "read it");
  }
  return StateMapping::realVector(static_cast<int>(real->getDimension()), "RealVector '" + real->getName() + "'");
}

/// Calls visit(q) on every state of `path` at most `resolution` apart, waypoints included, with
/// the index of the motion the state belongs to (-1 for the first waypoint); stops when visit
/// returns false.
void forEachState(const ompl::geometric::PathGeometric& path, double resolution,
                  const std::function<bool(const Eigen::VectorXd&, int motion, bool waypoint)>& visit) {
  if (!(resolution > 0.0) || std::isinf(resolution)) {
    throw std::invalid_argument("path check: resolution must be finite and > 0, got " +
                                robots::formatNumber(resolution));
  }
  const std::size_t count = path.getStateCount();
  if (count == 0) return;
  const StateMapping mapping = mappingOf(path);
  Eigen::VectorXd q = mapping.configuration(path.getState(0));
  if (!visit(q, -1, true)) return;
  for (std::size_t i = 0; i + 1 < count; ++i) {
    const Eigen::VectorXd a = mapping.configuration(path.getState(i));
    const Eigen::VectorXd dq = mapping.displacement(a, mapping.configuration(path.getState(i + 1)));
    const int steps = std::max(1, static_cast<int>(std::ceil(dq.norm() / resolution)));
    for (int k = 1; k <= steps; ++k) {
      q = mapping.along(a, dq, static_cast<double>(k) / steps);
      if (!visit(q, static_cast<int>(i), k == steps)) return;
    }
  }
}

}  // namespace

PathCheck checkPathWithPlanner(const ompl::geometric::PathGeometric& path, const ompl::base::SpaceInformation* si) {
  if (si == nullptr) si = path.getSpaceInformation().get();
  PathCheck check;
  const std::size_t count = path.getStateCount();
  for (std::size_t i = 0; i < count; ++i) {
    ++check.statesChecked;
    if (!si->isValid(path.getState(i))) {
      check.valid = false;
      ++check.invalidWaypoints;
      if (check.firstInvalidWaypoint < 0) check.firstInvalidWaypoint = static_cast<int>(i);
    }
  }
  for (std::size_t i = 0; i + 1 < count; ++i) {
    if (!si->checkMotion(path.getState(i), path.getState(i + 1))) {
      check.valid = false;
      ++check.invalidMotions;
      if (check.firstInvalidMotion < 0) check.firstInvalidMotion = static_cast<int>(i);
    }
  }
  if (count == 0) check.valid = false;
  return check;
}

PathCheck checkPathFine(const ompl::geometric::PathGeometric& path,
                        const std::function<bool(const Eigen::VectorXd&)>& isFree, double resolution) {
  PathCheck check;
  check.valid = path.getStateCount() > 0;
  int lastBadMotion = -2;
  forEachState(path, resolution, [&](const Eigen::VectorXd& q, int motion, bool waypoint) {
    ++check.statesChecked;
    if (isFree(q)) return true;
    check.valid = false;
    if (waypoint) {
      ++check.invalidWaypoints;
      if (check.firstInvalidWaypoint < 0) check.firstInvalidWaypoint = motion + 1;
    }
    if (motion >= 0 && motion != lastBadMotion) {
      ++check.invalidMotions;
      lastBadMotion = motion;
      if (check.firstInvalidMotion < 0) check.firstInvalidMotion = motion;
    }
    return true;
  });
  return check;
}

double minClearanceAlong(const ompl::geometric::PathGeometric& path,
                         const std::function<double(const Eigen::VectorXd&)>& clearance, double resolution) {
  double smallest = std::numeric_limits<double>::infinity();
  forEachState(path, resolution, [&](const Eigen::VectorXd& q, int, bool) {
    smallest = std::min(smallest, clearance(q));
    return true;
  });
  return smallest;
}

PathRepair repairPath(ompl::geometric::PathGeometric& path, const ompl::base::SpaceInformationPtr& si, int maxDepth) {
  auto checker = std::dynamic_pointer_cast<const StateValidityChecker>(si->getStateValidityChecker());
  if (!checker) {
    throw std::invalid_argument(
        "repairPath: the validity checker of the space information is not a "
        "deepcheck::planners::StateValidityChecker");
  }
  if (maxDepth < 0) throw std::invalid_argument("repairPath: maxDepth must be >= 0, got " + std::to_string(maxDepth));
  const StateMapping& mapping = checker->mapping();
  const ompl::base::SpaceInformationPtr& owner = path.getSpaceInformation();
  PathRepair repair;
  // Repaired states stand a few millimetres off the surface, not one: the chord between two states
  // on the two faces of an edge cuts the edge unless they stand off it. So the push-out used here
  // treats everything nearer than kRepairClearance (above the threshold) as invalid.
  const PushOut pushOut = standOffPushOut(checker->worldPtr(), checker->validityOptions(), checker->pushOut().options(),
                                          tol::kRepairClearance);

  // Pushes `state` off when it is nearer than the stand-off; true when it is valid afterwards.
  auto standOffState = [&](ompl::base::State* state) {
    const bool valid = si->isValid(state);
    const PushOutResult pushed = pushOut.run(mapping.configuration(state));
    if (pushed.status == PushOutStatus::AlreadyValid) return valid;
    if (!pushed.success()) {
      if (!valid) ++repair.pushOutFailures;
      return valid;
    }
    mapping.toState(pushed.q, state);
    return true;
  };

  std::vector<ompl::base::State*>& states = path.getStates();
  for (std::size_t i = 0; i < states.size(); ++i) {
    const bool endpoint = i == 0 || i + 1 == states.size();
    if (si->isValid(states[i])) {
      if (endpoint) continue;  // a valid start or goal stays where it is
      const Eigen::VectorXd before = mapping.configuration(states[i]);
      standOffState(states[i]);
      if (mapping.configuration(states[i]) != before) ++repair.waypointsPushed;
    } else if (standOffState(states[i])) {
      ++repair.waypointsPushed;
    }
  }

  // Motions: split failing ones at their midpoints, depth first, into a new list of states.
  std::vector<ompl::base::State*> result;
  result.reserve(states.size());
  std::function<void(const ompl::base::State*, const ompl::base::State*, int)> fix =
      [&](const ompl::base::State* a, const ompl::base::State* b, int depth) {
        if (depth >= maxDepth || si->checkMotion(a, b)) return;
        ompl::base::State* mid = owner->allocState();
        const Eigen::VectorXd qa = mapping.configuration(a);
        mapping.toState(mapping.along(qa, mapping.displacement(qa, mapping.configuration(b)), 0.5), mid);
        standOffState(mid);
        ++repair.statesInserted;
        fix(a, mid, depth + 1);
        result.push_back(mid);
        fix(mid, b, depth + 1);
      };
  if (!states.empty()) result.push_back(states.front());
  for (std::size_t i = 0; i + 1 < states.size(); ++i) {
    fix(states[i], states[i + 1], 0);
    result.push_back(states[i + 1]);
  }
  states.swap(result);
  repair.valid = checkPathWithPlanner(path, si.get()).valid;
  return repair;
}

std::vector<Eigen::VectorXd> pathConfigurations(const ompl::geometric::PathGeometric& path) {
  const StateMapping mapping = mappingOf(path);
  std::vector<Eigen::VectorXd> qs;
  qs.reserve(path.getStateCount());
  for (std::size_t i = 0; i < path.getStateCount(); ++i) qs.push_back(mapping.configuration(path.getState(i)));
  return qs;
}

void writePath(const ompl::geometric::PathGeometric& path, std::ostream& out) {
  for (const Eigen::VectorXd& q : pathConfigurations(path)) {
    for (Eigen::Index j = 0; j < q.size(); ++j) out << (j > 0 ? " " : "") << robots::formatNumber(q[j]);
    out << '\n';
  }
}

void writePath(const ompl::geometric::PathGeometric& path, const std::string& file) {
  std::ofstream out(file);
  if (!out) throw std::invalid_argument("writePath: cannot write '" + file + "'");
  writePath(path, out);
  out.close();
  if (!out) throw std::invalid_argument("writePath: error while writing '" + file + "'");
}

}  // namespace deepcheck::planners
