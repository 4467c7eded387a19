#pragma once
// ompl::tools::Benchmark pieces shared by the planning benchmarks: access to the recorded
// experiment (to merge several runs' experiments into one log, in OMPL's format that
// ompl_benchmark_statistics.py reads), runs timed as the planner alone takes them, and the removal
// of progress properties that crash.

#include <ompl/base/Planner.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/tools/benchmark/Benchmark.h>

#include <string>

namespace deepcheck::bench {

/// Benchmark with access to its recorded data, to merge experiments into one log.
class Bench : public ompl::tools::Benchmark {
 public:
  Bench(ompl::geometric::SimpleSetup& ss, const std::string& name) : ompl::tools::Benchmark(ss, name) {}
  CompleteExperiment& data() { return exp_; }
};

/// A Benchmark whose runs are timed as a planner runs when its termination condition is checked in
/// its own thread (ompl::base::timedPlannerTerminationCondition(seconds)): the time of solve()
/// alone. ompl::tools::Benchmark's own runs start two threads per run inside the timed span (one
/// polling the termination condition every millisecond, one collecting progress properties), and
/// the join waits for the poller's sleep, which adds up to a millisecond to a run's reported time
/// on one core (harness_overhead measures it: bench/README.md, "What is timed").
/// SimpleSetup::solve(seconds) with a limit of a second or more polls the same way;
/// `solve(timedPlannerTerminationCondition(seconds))` does not.
/// The log, the run properties and the pre- and post-run events are Benchmark's; no progress
/// properties are collected.
class SolveTimedBenchmark : public Bench {
 public:
  using Bench::Bench;
  void benchmark(const Request& req) override;

 private:
  void runPlanner(std::size_t i, const Request& req);
  RunProperties timedRun(const ompl::base::PlannerPtr& planner, double maxTime);
};

/// Removes a planner's progress properties (the values Benchmark's collector thread reads every
/// 50 ms while the planner runs). BIT*'s read its search queue unsynchronized, which can crash a
/// benchmark run inside libompl (OMPL 1.5; ompl/ompl#779, "BIT* is failing when added to a
/// benchmark", traced there to currentVertexProgressProperty). The member is protected; a pointer
/// to it named through a derived class is the standard way to reach it.
struct ProgressPropertyStripper : ompl::base::Planner {
  static void strip(ompl::base::Planner& planner) {
    (planner.*(&ProgressPropertyStripper::plannerProgressProperties_)).clear();
  }
};

}  // namespace deepcheck::bench
