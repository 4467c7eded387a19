#pragma once
// What the examples share, so that each of them stays about its own point: the report every one
// prints after planning (planner, time, path length, minimum clearance along the path — signed
// distance, metres, checked every 0.002 rad of joint motion; overall and to the scene alone — and
// where the path went, with a page next to it to look at it: viewer/html_view.h), the bundled
// arm's setup as example_plan_shelf makes it, and the plan-shortcut-certify sequence.

#include <deepcheck/planners/path_tools.h>
#include <deepcheck/planners/setup.h>
#include <deepcheck/viewer/html_view.h>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

namespace example {

/// `file` with its extension replaced by ".html" (shelf_path.txt -> shelf_path.html).
inline std::string viewFileOf(const std::string& file) {
  const std::size_t dot = file.find_last_of('.');
  const std::size_t slash = file.find_last_of('/');
  const bool hasExtension = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return (hasExtension ? file.substr(0, dot) : file) + ".html";
}

/// Prints the report for the solution of `ss`, writes its path to `file` and, next to it, the
/// page that shows it (the robot along the path, the closest pair and clearance per frame).
inline void reportAndWrite(const ompl::geometric::SimpleSetup& ss, const std::string& file) {
  const auto checker = deepcheck::planners::validityCheckerOf(ss);
  const ompl::geometric::PathGeometric& path = ss.getSolutionPath();
  // One pass over the path's states, split by kind of pair: the robot's own links sit a few
  // centimetres apart in every configuration (an arm's wrist), so the clearance to the scene
  // alone is what a clearance objective can change; the overall one is the smaller of the two.
  double sceneClearance = std::numeric_limits<double>::infinity();
  const double clearance = deepcheck::planners::minClearanceAlong(path, [&](const Eigen::VectorXd& q) {
    const deepcheck::planners::SplitDistance d =
        checker->splitClearanceUpTo(q, std::numeric_limits<double>::infinity());
    sceneClearance = std::min(sceneClearance, d.world);
    return std::min(d.world, d.self);
  });
  deepcheck::planners::writePath(path, file);
  deepcheck::viewer::WorldViewOptions view;
  view.title = "deepcheck example: " + file.substr(file.find_last_of('/') + 1);
  const std::string viewFile = viewFileOf(file);
  deepcheck::viewer::writeHtmlView(checker->world(), deepcheck::planners::pathConfigurations(path), viewFile, view);
  std::printf("planner          %s\n", ss.getPlanner()->getName().c_str());
  std::printf("time             %.3f s\n", ss.getLastPlanComputationTime());
  std::printf("waypoints        %zu\n", path.getStateCount());
  std::printf("path length      %.3f rad\n", path.length());
  std::printf("min clearance    %.4f m (to the scene %.4f m)\n", clearance, sceneClearance);
  std::printf("path written to  %s\n", file.c_str());
  std::printf("view written to  %s (open it in a browser)\n", viewFile.c_str());
}

/// The bundled arm (its SRDF's disabled self pairs) in robots/data/scenes/<scene>.urdf, as
/// example_plan_shelf sets it up; `data` is robots/data.
inline std::shared_ptr<ompl::geometric::SimpleSetup> bundledArm(const std::string& data, const std::string& scene) {
  deepcheck::planners::SetupOptions options;
  options.packageRoots = {data};
  options.srdf = data + "/deepcheck_arm/srdf/deepcheck_arm.srdf";
  return deepcheck::planners::makeSimpleSetup(data + "/deepcheck_arm/urdf/deepcheck_arm.urdf",
                                              {data + "/scenes/" + scene + ".urdf"}, options);
}

/// RRTConnect for up to `seconds`, shortcut, certifyPath (every waypoint and motion through the
/// clearance motion validator, the path repaired where it fails), then the report, and the path
/// written to `file`. False, with a message, when there is no exact solution or no certificate.
inline bool planCertifyAndWrite(ompl::geometric::SimpleSetup& ss, double seconds, const std::string& file) {
  ss.setPlanner(std::make_shared<ompl::geometric::RRTConnect>(ss.getSpaceInformation()));
  // The limit as a condition the planner checks: no polling thread to wait for at the end.
  const ompl::base::PlannerStatus status = ss.solve(ompl::base::timedPlannerTerminationCondition(seconds));
  if (status != ompl::base::PlannerStatus::EXACT_SOLUTION) {
    std::fprintf(stderr, "no exact solution: %s\n", status.asString().c_str());
    return false;
  }
  deepcheck::planners::simplifySolutionChecked(ss);  // shortcuts, each checked like the planner's motions
  const deepcheck::planners::PathCertificate certificate = deepcheck::planners::certifyPath(ss, ss.getSolutionPath());
  std::printf("certified        %s%s\n", certificate.valid ? "yes" : "NO",
              certificate.repaired ? " (after repairing the path)" : "");
  if (!certificate.valid) return false;
  reportAndWrite(ss, file);
  return true;
}

}  // namespace example
