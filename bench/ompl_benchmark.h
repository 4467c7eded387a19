#pragma once
// ompl::tools::Benchmark pieces shared by the planning benchmarks: access to the recorded
// experiment (to merge several runs' experiments into one log, in OMPL's format that
// ompl_benchmark_statistics.py reads), and the removal of progress properties that crash.

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

/// Removes a planner's progress properties (the values Benchmark's collector thread reads every
/// 50 ms while the planner runs). BIT*'s read its search queue unsynchronized: in plan_bench
/// OMPL 1.5.2 crashed with a segfault inside libompl during a BIT* run (shelf, run 9 of 10), as in
/// ompl/ompl#779 ("BIT* is failing when added to a benchmark", traced there to
/// currentVertexProgressProperty). The member is protected; a pointer to it named through a
/// derived class is the standard way to reach it.
struct ProgressPropertyStripper : ompl::base::Planner {
  static void strip(ompl::base::Planner& planner) {
    (planner.*(&ProgressPropertyStripper::plannerProgressProperties_)).clear();
  }
};

}  // namespace deepcheck::bench
