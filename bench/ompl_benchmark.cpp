// SolveTimedBenchmark (ompl_benchmark.h): ompl::tools::Benchmark's experiment and run properties,
// with each run's time that of the planner's solve() alone.

#include "ompl_benchmark.h"

#include <ompl/base/PlannerData.h>
#include <ompl/tools/benchmark/MachineSpecs.h>
#include <ompl/util/RandomNumbers.h>
#include <ompl/util/String.h>
#include <ompl/util/Time.h>

#include <sstream>

namespace deepcheck::bench {

namespace ob = ompl::base;

void SolveTimedBenchmark::benchmark(const Request& req) {
  ompl::geometric::SimpleSetup& ss = *gsetup_;
  ss.setup();
  exp_.maxTime = req.maxTime;
  exp_.maxMem = req.maxMem;
  exp_.runCount = req.runCount;
  exp_.host = "-";  // the log describes no machine
  exp_.seed = ompl::RNG::getSeed();
  exp_.startTime = ompl::time::now();
  exp_.planners.assign(planners_.size(), PlannerExperiment{});
  std::ostringstream info;
  ss.print(info);
  info << "\nProperties of benchmarked planners:\n";
  for (std::size_t i = 0; i < planners_.size(); ++i) {
    planners_[i]->setProblemDefinition(ss.getProblemDefinition());
    if (!planners_[i]->isSetup()) planners_[i]->setup();
    planners_[i]->printProperties(info);
    exp_.planners[i].name = "geometric_" + planners_[i]->getName();
  }
  exp_.setupInfo = info.str();
  for (std::size_t i = 0; i < planners_.size(); ++i) runPlanner(i, req);
  exp_.totalDuration = ompl::time::seconds(ompl::time::now() - exp_.startTime);
}

void SolveTimedBenchmark::runPlanner(std::size_t i, const Request& req) {
  const ob::PlannerPtr& planner = planners_[i];
  PlannerExperiment& e = exp_.planners[i];
  if (plannerSwitch_) plannerSwitch_(planner);
  gsetup_->setup();
  planner->params().getParams(e.common);
  planner->getSpaceInformation()->params().getParams(e.common);
  for (unsigned run = 0; run < req.runCount; ++run) {
    planner->clear();
    gsetup_->getProblemDefinition()->clearSolutionPaths();
    gsetup_->getSpaceInformation()->getMotionValidator()->resetMotionCounter();
    if (preRun_) preRun_(planner);
    RunProperties props = timedRun(planner, req.maxTime);
    if (postRun_) postRun_(planner, props);
    e.runs.push_back(std::move(props));
  }
}

/// One run: solve() timed alone, then the properties Benchmark records for a geometric run.
SolveTimedBenchmark::RunProperties SolveTimedBenchmark::timedRun(const ob::PlannerPtr& planner, double maxTime) {
  const ompl::time::point start = ompl::time::now();
  const ob::PlannerStatus status = planner->solve(ob::timedPlannerTerminationCondition(maxTime));
  const double seconds = ompl::time::seconds(ompl::time::now() - start);
  ompl::geometric::SimpleSetup& ss = *gsetup_;
  RunProperties run;
  run["time REAL"] = ompl::toString(seconds);
  run["memory REAL"] = ompl::toString(static_cast<double>(ompl::machine::getProcessMemoryUsage()) / (1024.0 * 1024.0));
  run["status ENUM"] = std::to_string(static_cast<int>(static_cast<ob::PlannerStatus::StatusType>(status)));
  run["solved BOOLEAN"] = std::to_string(ss.haveExactSolutionPath());
  run["valid segment fraction REAL"] =
      ompl::toString(ss.getSpaceInformation()->getMotionValidator()->getValidMotionFraction());
  if (ss.haveSolutionPath()) {
    const ob::ProblemDefinitionPtr& pdef = ss.getProblemDefinition();
    run["approximate solution BOOLEAN"] = std::to_string(pdef->hasApproximateSolution());
    run["solution difference REAL"] = ompl::toString(pdef->getSolutionDifference());
    run["solution length REAL"] = ompl::toString(ss.getSolutionPath().length());
    run["solution segments INTEGER"] = std::to_string(ss.getSolutionPath().getStateCount() - 1);
  }
  ob::PlannerData data(ss.getSpaceInformation());
  planner->getPlannerData(data);
  run["graph states INTEGER"] = std::to_string(data.numVertices());
  run["graph motions INTEGER"] = std::to_string(data.numEdges());
  for (const auto& [name, value] : data.properties) run[name] = value;
  return run;
}

}  // namespace deepcheck::bench
