// harness_overhead: what ompl::tools::Benchmark adds to the time of a run, measured on a planner
// that works for a known time (bench/README.md, "What is timed").
//
// A run of ompl::tools::Benchmark starts a thread that evaluates the termination condition every
// millisecond (and sleeps in between) and, for planners with progress properties, a second one;
// their start and join lie inside the time it reports. SimpleSetup::solve(seconds) with a limit of
// a second or more polls the same way. The planner here does nothing but read the clock and the
// termination condition until its work time has passed, so every microsecond beyond the work time
// is the harness's. Each work time is run --runs times through ompl::tools::Benchmark, through
// SolveTimedBenchmark (ompl_benchmark.h: the termination condition checked in the planner's
// thread, as mbm_bench times its runs) and through SimpleSetup::solve(10 s); the medians and
// 90th percentiles are printed (markdown) and written to --out (CSV). Pin it to one core to see
// what a single-core run of a benchmark sees: `taskset -c 0 build/bench/harness_overhead`.
//
// Usage: harness_overhead [--runs N] [--out FILE]

#include "format.h"
#include "ompl_benchmark.h"
#include "options.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/util/Console.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace deepcheck::bench;
namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace ot = ompl::tools;
using Clock = std::chrono::steady_clock;

namespace {

/// Works (reads the clock and the termination condition) for a fixed time, then gives up.
class WorkingPlanner : public ob::Planner {
 public:
  WorkingPlanner(const ob::SpaceInformationPtr& si, double seconds) : ob::Planner(si, "Working"), seconds_(seconds) {}
  ob::PlannerStatus solve(const ob::PlannerTerminationCondition& ptc) override {
    const auto start = Clock::now();
    while (std::chrono::duration<double>(Clock::now() - start).count() < seconds_) {
      if (ptc()) return ob::PlannerStatus::TIMEOUT;
    }
    return ob::PlannerStatus::TIMEOUT;
  }

 private:
  double seconds_;
};

struct Options {
  int runs = 100;
  std::string out = std::string(DEEPCHECK_BENCH_RESULTS_DIR) + "/harness_overhead.csv";
};

[[noreturn]] void usage(const std::string& error) {
  if (!error.empty()) std::fprintf(stderr, "harness_overhead: %s\n", error.c_str());
  std::fprintf(stderr,
               "usage: harness_overhead [--runs N] [--out FILE]\n"
               "  --runs N    runs per work time and harness (default 100)\n"
               "  --out FILE  CSV (default bench/results/harness_overhead.csv)\n");
  std::exit(2);
}

/// The times (seconds) a harness reports for `runs` runs of a planner working `seconds`.
std::vector<double> benchmarkTimes(og::SimpleSetup& ss, ot::Benchmark& bench, double seconds, int runs) {
  bench.addPlanner(std::make_shared<WorkingPlanner>(ss.getSpaceInformation(), seconds));
  std::vector<double> times;
  bench.setPostRunEvent(
      [&](const ob::PlannerPtr&, ot::Benchmark::RunProperties& run) { times.push_back(std::stod(run["time REAL"])); });
  ot::Benchmark::Request req(10.0, 4096.0, static_cast<unsigned>(runs));
  req.displayProgress = false;
  req.saveConsoleOutput = false;
  req.simplify = false;
  bench.benchmark(req);
  return times;
}

/// The wall times of SimpleSetup::solve(10 s) around the same planner.
std::vector<double> simpleSetupTimes(og::SimpleSetup& ss, double seconds, int runs) {
  ss.setPlanner(std::make_shared<WorkingPlanner>(ss.getSpaceInformation(), seconds));
  std::vector<double> times;
  for (int r = 0; r < runs; ++r) {
    ss.clear();
    const auto start = Clock::now();
    ss.solve(10.0);
    times.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }
  return times;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  readOptions(argc, argv, usage, [&](const std::string& arg, auto value) {
    if (arg == "--runs") {
      opt.runs = positiveCount(value(), arg, usage);
    } else if (arg == "--out") {
      opt.out = value();
    } else {
      return false;
    }
    return true;
  });
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  auto space = std::make_shared<ob::RealVectorStateSpace>(2);
  space->setBounds(0.0, 1.0);
  og::SimpleSetup ss(space);
  ss.setStateValidityChecker([](const ob::State*) { return true; });
  ob::ScopedState<> start(space), goal(space);
  start[0] = start[1] = 0.0;
  goal[0] = goal[1] = 1.0;
  ss.setStartAndGoalStates(start, goal);
  std::filesystem::create_directories(std::filesystem::path(opt.out).parent_path());
  std::ofstream csv(opt.out);
  csv << "work_ms,harness,median_ms,p90_ms\n";
  std::printf(
      "| work (ms) | ompl::tools::Benchmark: median / p90 (ms) | SolveTimedBenchmark | SimpleSetup::solve(10 s) |\n"
      "|--:|--:|--:|--:|\n");
  for (double ms : {0.1, 0.3, 1.0, 2.0, 3.0, 5.0, 10.0}) {
    ot::Benchmark plain(ss, "plain");
    SolveTimedBenchmark timed(ss, "timed");
    const std::vector<std::vector<double>> times = {benchmarkTimes(ss, plain, ms * 1e-3, opt.runs),
                                                    benchmarkTimes(ss, timed, ms * 1e-3, opt.runs),
                                                    simpleSetupTimes(ss, ms * 1e-3, opt.runs)};
    const char* names[] = {"ompl::tools::Benchmark", "SolveTimedBenchmark", "SimpleSetup::solve"};
    std::printf("| %s |", fmt(ms).c_str());
    for (int h = 0; h < 3; ++h) {
      const double med = median(times[h]) * 1e3;
      const double p90 = quantile(times[h], 0.9) * 1e3;
      std::printf(" %s / %s |", fmt(med).c_str(), fmt(p90).c_str());
      csv << ms << ',' << names[h] << ',' << med << ',' << p90 << '\n';
    }
    std::printf("\n");
  }
  std::fprintf(stderr, "wrote %s\n", opt.out.c_str());
  return 0;
}
