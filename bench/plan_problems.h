#pragma once
// The planning problems of plan_bench and plan_certify (bench/README.md, "Planning benchmark"):
// the bundled arm in the bundled scenes, and the Panda in two MotionBenchMaker scenes of
// ../shared (skipped when it is absent); and the FCL setup they are compared against.

#include "deepcheck/fcl_reference/fcl_validity_checker.h"
#include "deepcheck/planners/setup.h"

#include <ompl/geometric/SimpleSetup.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <memory>
#include <string>
#include <vector>

namespace deepcheck::bench {

struct Problem {
  std::string name;
  std::string robotUrdf;
  planners::SetupOptions options;  // package paths and SRDF
  std::vector<planners::SceneSpec> scenes;
  Eigen::VectorXd start;
  Eigen::VectorXd goal;
  bool needsShared = false;
  std::string note;  // where start and goal come from
};

/// ../shared (real robots and scenes), and whether it is there.
std::string sharedDir();
bool haveShared();

/// The Panda of ../shared (URDF) and its setup options (package roots, MoveIt SRDF).
std::string pandaUrdf();
planners::SetupOptions pandaOptions();
/// ../shared's MotionBenchMaker scene URDF `name` (kitchen, table_bars).
std::string mbmScene(const std::string& name);
/// Where the table_bars scene goes in the Panda's world (see plan_problems.cpp).
Eigen::Isometry3d tableBarsPose();

/// Every problem, in the order of the tables.
std::vector<Problem> problems();

/// An OMPL SimpleSetup with the FCL checker on the same state space (bounds, names, segment
/// fraction) as `ours`.
std::shared_ptr<ompl::geometric::SimpleSetup> makeFclSetup(
    const ompl::geometric::SimpleSetup& ours, const checker::World& world,
    std::shared_ptr<fcl_reference::FclStateValidityChecker>* checkerOut);

/// Sets the start and goal states of `ss`.
void setEndpoints(ompl::geometric::SimpleSetup& ss, const Eigen::VectorXd& start, const Eigen::VectorXd& goal);

/// Prints how the Panda's start and goal were found (plan_bench --pick-panda-endpoints); the exit
/// status.
int pickPandaEndpoints();

}  // namespace deepcheck::bench
