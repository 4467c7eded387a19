#pragma once
// What every example prints after planning: planner, time, path length, minimum clearance along
// the path (signed distance, metres, checked every 0.002 rad of joint motion; overall and to the
// scene alone), and where the path went. Shared by the examples so that each of them stays about planning.

#include <deepcheck/planners/path_tools.h>
#include <deepcheck/planners/setup.h>

#include <ompl/geometric/SimpleSetup.h>

#include <cstdio>
#include <limits>
#include <string>

namespace example {

/// Prints the report for the solution of `ss` and writes its path to `file`.
inline void reportAndWrite(const ompl::geometric::SimpleSetup& ss, const std::string& file) {
  const auto checker = deepcheck::planners::validityCheckerOf(ss);
  const ompl::geometric::PathGeometric& path = ss.getSolutionPath();
  const double clearance = deepcheck::planners::minClearanceAlong(
      path, [&](const Eigen::VectorXd& q) { return checker->clearance(q); });
  // The robot's own links sit a few centimetres apart in every configuration (an arm's wrist):
  // the clearance to the scene alone is what a clearance objective can change.
  const double sceneClearance = deepcheck::planners::minClearanceAlong(path, [&](const Eigen::VectorXd& q) {
    return checker->splitClearanceUpTo(q, std::numeric_limits<double>::infinity(), false).world;
  });
  deepcheck::planners::writePath(path, file);
  std::printf("planner          %s\n", ss.getPlanner()->getName().c_str());
  std::printf("time             %.3f s\n", ss.getLastPlanComputationTime());
  std::printf("waypoints        %zu\n", path.getStateCount());
  std::printf("path length      %.3f rad\n", path.length());
  std::printf("min clearance    %.4f m (to the scene %.4f m)\n", clearance, sceneClearance);
  std::printf("path written to  %s\n", file.c_str());
}

}  // namespace example
