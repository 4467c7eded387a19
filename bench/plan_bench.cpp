// plan_bench: OMPL planners on our collision checker against the same planners on the FCL mesh
// checker through ompl::tools::Benchmark, so that the logs load into OMPL's
// ompl_benchmark_statistics.py and Planner Arena.
//
// Problems (start and goal configurations are fixed; see problems() below):
//   table, shelf, narrow_passage  the bundled arm (robots/data/deepcheck_arm, with its SRDF) in
//                                 the bundled scenes, the start/goal pairs of robots/data/README.md
//                                 "Suggested planning problems";
//   panda_kitchen, panda_table_bars
//                                 the Panda of ../shared/robots/panda (its MoveIt SRDF) in the
//                                 MotionBenchMaker kitchen and table_bars URDF scenes of
//                                 ../shared/scenes; skipped with a message when ../shared is absent.
// Checkers:
//   deepcheck  deepcheck::planners::makeSimpleSetup with default options (our validity checker,
//              OMPL's DiscreteMotionValidator at the default longest valid segment fraction, the
//              push-out valid state sampler);
//   fcl        the same state space and segment fraction, FclStateValidityChecker (FCL on the
//              original meshes, the same disabled pairs), OMPL's DiscreteMotionValidator and
//              OMPL's default valid state sampler.
// Planners (deepcheck::planners::makePlanner, OMPL defaults): RRTConnect, RRT*, BIT*, PRM.
//
// Per run, besides OMPL's own properties (time, solved, lengths, graph states, ...), run
// properties added by the post-run event, on the path as OMPL's benchmark leaves it (simplified):
//   "min clearance REAL"        minimum of OUR signed distance along the path (minClearanceAlong,
//                               tol::kFineResolution), the same measure for both checkers;
//   "fcl verified BOOLEAN"      the path passes checkPathFine with the FCL checker at
//                               tol::kFineResolution (every state at most 0.002 rad apart);
//   "fcl invalid motions INTEGER", "fcl invalid waypoints INTEGER";
//   "first solution time REAL"  seconds to the first exact solution: the first intermediate
//                               solution reported by RRT* and BIT* (they use the whole time
//                               limit), the run's time for planners that stop at their first
//                               solution (RRTConnect); absent for PRM, which in OMPL 1.5 grows its
//                               roadmap until the time limit and reports no intermediate solution.
// BIT*'s progress properties are removed (ProgressPropertyStripper: reading them while it runs
// crashes OMPL 1.5.2); the other planners keep theirs (Planner Arena's progress plots).
// A path the FCL check rejects is written to OUT/rejected_<problem>_<checker>_<planner>_<run>.txt
// (one configuration per line, the `deepcheck plan` format).
//
// Outputs in OUT (default bench/results): plan_bench_<problem>.log (one OMPL experiment per
// problem, 8 planner entries named geometric_<planner>_<checker>), plan_bench.csv, plan_bench.md
// (also printed), plan_bench.png (gnuplot, bench/plan_plots.gp; skipped when gnuplot is
// missing). Progress on stderr.
//
// Usage: plan_bench [--runs N] [--time S] [--problems a,b] [--planners a,b] [--quick] [--out DIR]
//                   [--seed S] [--pick-panda-endpoints]
// What certification makes of the rejected paths: plan_certify DIR (plan_certify.cpp).
//
// Files: plan_problems.* (the problems and the FCL setup), plan_report.* (records, medians,
// tables and plot), this file (the runs).

#include "ompl_benchmark.h"
#include "options.h"
#include "plan_problems.h"
#include "plan_report.h"

#include "deepcheck/planners/path_tools.h"
#include "deepcheck/planners/planner_factory.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/planners/tolerances.h"

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace ot = ompl::tools;
namespace dp = deepcheck::planners;
using namespace deepcheck::bench;

namespace {

struct Options {
  int runs = 10;
  double time = 5.0;
  std::vector<std::string> problems;
  std::vector<std::string> planners{"RRTConnect", "RRT*", "BIT*", "PRM"};
  std::string out = DEEPCHECK_BENCH_RESULTS_DIR;
  std::uint32_t seed = 1;
  bool quick = false;
  std::vector<std::string> wantedPlanners;
  std::vector<std::string> wantedProblems;
};

[[noreturn]] void usage(const std::string& error) {
  if (!error.empty()) std::fprintf(stderr, "plan_bench: %s\n", error.c_str());
  std::fprintf(stderr,
               "usage: plan_bench [--runs N] [--time SECONDS] [--problems a,b] [--planners a,b] [--quick]\n"
               "                  [--out DIR] [--seed S] [--pick-panda-endpoints]\n"
               "  --runs N       runs per planner, checker and problem (default 10)\n"
               "  --time S       time limit per run, seconds (default 5)\n"
               "  --problems     table, shelf, narrow_passage, panda_kitchen, panda_table_bars (default all)\n"
               "  --planners     any name deepcheck::planners::makePlanner knows (default RRTConnect,RRT*,BIT*,PRM)\n"
               "  --quick        2 runs of 1 s (overrides --runs and --time)\n"
               "  --out DIR      output folder (default bench/results)\n"
               "  --seed S       OMPL's random seed (default 1)\n"
               "  --pick-panda-endpoints  print how the Panda's start and goal were found, and exit\n"
               "(certifyPath and the fine FCL check of the rejected paths: plan_certify DIR)\n");
  std::exit(2);
}

}  // namespace

namespace {

/// The two setups of a problem: ours, and the same problem on the FCL checker.
struct Setups {
  std::shared_ptr<deepcheck::checker::World> world;
  std::shared_ptr<og::SimpleSetup> ours, fcl;
  std::shared_ptr<const dp::StateValidityChecker> ourChecker;
  std::shared_ptr<deepcheck::fcl_reference::FclStateValidityChecker> fclChecker;
};

/// What the runs of one problem read and add to.
struct RunContext {
  const Options& opt;
  const Problem& problem;
  const Setups& setups;
  std::size_t index, count;  ///< of the problem among the selected ones
  std::vector<Record>& records;
  std::vector<std::string>& rejected;
};

Options parseOptions(int argc, char** argv) {
  Options opt;
  readOptions(argc, argv, usage, [&](const std::string& arg, auto value) {
    if (arg == "--runs") {
      opt.runs = positiveCount(value(), arg, usage);
    } else if (arg == "--time") {
      opt.time = positiveValue(value(), arg, usage);
    } else if (arg == "--problems") {
      opt.wantedProblems = splitList(value());
    } else if (arg == "--planners") {
      opt.wantedPlanners = splitList(value());
    } else if (arg == "--quick") {
      opt.quick = true;
    } else if (arg == "--out") {
      opt.out = value();
    } else if (arg == "--seed") {
      opt.seed = static_cast<std::uint32_t>(std::stoul(value()));
    } else if (arg == "--pick-panda-endpoints") {
      std::exit(pickPandaEndpoints());
    } else {
      return false;
    }
    return true;
  });
  if (opt.quick) {
    opt.runs = 2;
    opt.time = 1.0;
  }

  // Planners: canonical names of makePlanner.
  if (!opt.wantedPlanners.empty()) {
    opt.planners.clear();
    for (const std::string& w : opt.wantedPlanners) {
      try {
        opt.planners.push_back(dp::plannerName(w));
      } catch (const std::invalid_argument& e) {  // names it and lists the known ones
        usage(e.what());
      }
    }
  }
  return opt;
}

/// The problems named on the command line (all when none), without those that need ../shared
/// when it is absent.
std::vector<Problem> selectProblems(const std::vector<std::string>& wanted) {
  std::vector<Problem> all = problems();
  std::vector<Problem> selected;
  if (wanted.empty()) {
    selected = all;
  } else {
    for (const std::string& w : wanted) {
      auto it = std::find_if(all.begin(), all.end(), [&](const Problem& p) { return p.name == w; });
      if (it == all.end()) {
        std::string list;
        for (const Problem& p : all) list += (list.empty() ? "" : ", ") + p.name;
        usage("unknown problem '" + w + "' (known: " + list + ")");
      }
      selected.push_back(*it);
    }
  }
  if (!haveShared()) {
    const auto before = selected.size();
    selected.erase(std::remove_if(selected.begin(), selected.end(), [](const Problem& p) { return p.needsShared; }),
                   selected.end());
    if (selected.size() != before) {
      std::fprintf(stderr, "plan_bench: ../shared is absent (%s): the Panda problems are skipped\n",
                   sharedDir().c_str());
    }
    if (selected.empty()) {
      std::fprintf(stderr, "plan_bench: no problem left to run\n");
      std::exit(1);
    }
  }

  return selected;
}

/// Our setup and the FCL one, with the problem's start and goal checked valid for both.
std::optional<Setups> prepareSetups(const Problem& problem) {
  Setups s;
  try {
    s.world = dp::loadWorld(problem.robotUrdf, problem.scenes, problem.options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "plan_bench: cannot load problem %s: %s\n", problem.name.c_str(), e.what());
    return std::nullopt;
  }
  auto& world = s.world;
  auto& ours = s.ours;
  auto& fcl = s.fcl;
  ours = dp::makeSimpleSetup(world, problem.options);
  dp::setStartAndGoal(*ours, problem.start, problem.goal);
  s.ourChecker = dp::validityCheckerOf(*ours);
  fcl = makeFclSetup(*ours, *world, &s.fclChecker);
  setEndpoints(*fcl, problem.start, problem.goal);
  if (!std::dynamic_pointer_cast<ob::DiscreteMotionValidator>(ours->getSpaceInformation()->getMotionValidator())) {
    std::fprintf(stderr, "plan_bench: our setup's motion validator is not OMPL's discrete one\n");
    return std::nullopt;
  }
  ours->setup();
  fcl->setup();
  // Sanity: the endpoints are valid for both checkers.
  for (const auto* ss : {ours.get(), fcl.get()}) {
    const auto si = ss->getSpaceInformation();
    const auto pdef = ss->getProblemDefinition();
    const auto goal = std::static_pointer_cast<ob::GoalState>(pdef->getGoal());
    if (!si->isValid(pdef->getStartState(0)) || !si->isValid(goal->getState())) {
      std::fprintf(stderr, "plan_bench: problem %s: start or goal is invalid for the %s checker\n",
                   problem.name.c_str(), ss == ours.get() ? "deepcheck" : "fcl");
      return std::nullopt;
    }
  }
  std::fprintf(stderr, "[%s] resolution %.4g rad (segment fraction %g of extent %.4g), clearance at start %.4f m\n",
               problem.name.c_str(), ours->getStateSpace()->getLongestValidSegmentLength(),
               ours->getStateSpace()->getLongestValidSegmentFraction(), ours->getStateSpace()->getMaximumExtent(),
               s.ourChecker->clearance(problem.start));

  return s;
}

/// The pre- and post-run events of one checker's benchmark: progress, the first solution time,
/// and the properties measured on each solved path (bench header comment).
void addRunEvents(Bench& b, og::SimpleSetup& ss, const std::string& checker, RunContext& ctx) {
  // The events run later, inside b.benchmark(): they hold pointers, not references to this call's
  // parameters.
  RunContext* context = &ctx;
  Bench* bench = &b;
  og::SimpleSetup* setup = &ss;
  // First exact solution time: RRT* and BIT* report intermediate solutions.
  auto runStart = std::make_shared<std::chrono::steady_clock::time_point>();
  auto firstSolution = std::make_shared<std::atomic<double>>(std::nan(""));
  setup->getProblemDefinition()->setIntermediateSolutionCallback(
      [runStart, firstSolution](const ob::Planner*, const std::vector<const ob::State*>&, const ob::Cost) {
        if (std::isnan(firstSolution->load())) {
          firstSolution->store(std::chrono::duration<double>(std::chrono::steady_clock::now() - *runStart).count());
        }
      });
  bench->setPreRunEvent([=](const ob::PlannerPtr& planner) {
    std::fprintf(stderr, "[%zu/%zu %s] %-9s %-10s run %u of %d\n", context->index + 1, context->count,
                 context->problem.name.c_str(), checker.c_str(), planner->getName().c_str(),
                 bench->getStatus().activeRun + 1, context->opt.runs);
    firstSolution->store(std::nan(""));
    *runStart = std::chrono::steady_clock::now();
  });
  bench->setPostRunEvent([=](const ob::PlannerPtr& planner, ot::Benchmark::RunProperties& run) {
    Record r;
    r.problem = context->problem.name;
    r.checker = checker;
    r.planner = planner->getName();
    r.time = std::stod(run["time REAL"]);
    r.solved = run["solved BOOLEAN"] == "1" && setup->haveExactSolutionPath();
    if (run.count("graph states INTEGER")) r.graphStates = std::stod(run["graph states INTEGER"]);
    if (r.solved) {
      og::PathGeometric& path = setup->getSolutionPath();
      r.length = path.length();
      r.minClearance = dp::minClearanceAlong(
          path, [context](const Eigen::VectorXd& q) { return context->setups.ourChecker->clearance(q); });
      const dp::PathCheck check = dp::checkPathFine(
          path, [context](const Eigen::VectorXd& q) { return context->setups.fclChecker->isFree(q); });
      r.fclVerified = check.valid;
      // The intermediate solution when one was reported (RRT*, BIT*); else the run's time when
      // the planner stopped before the limit (RRTConnect). PRM runs to the limit and reports
      // none: unknown.
      r.firstSolution = firstSolution->load();
      if (std::isnan(r.firstSolution) && !dp::isOptimizingPlanner(planner->getName()) &&
          r.time < 0.95 * context->opt.time) {
        r.firstSolution = r.time;
      }
      run["min clearance REAL"] = fmt(r.minClearance, "%.17g");
      run["fcl verified BOOLEAN"] = check.valid ? "1" : "0";
      run["fcl invalid motions INTEGER"] = std::to_string(check.invalidMotions);
      run["fcl invalid waypoints INTEGER"] = std::to_string(check.invalidWaypoints);
      if (!std::isnan(r.firstSolution)) run["first solution time REAL"] = fmt(r.firstSolution, "%.17g");
      if (!check.valid) {
        const std::string file = context->opt.out + "/rejected_" + context->problem.name + "_" + checker + "_" +
                                 r.planner + "_" + std::to_string(bench->getStatus().activeRun + 1) + ".txt";
        dp::writePath(path, file);
        context->rejected.push_back(file);
        std::fprintf(stderr, "  FCL rejects the path (%d invalid waypoints, %d invalid motions, first at %d): %s\n",
                     check.invalidWaypoints, check.invalidMotions, check.firstInvalidMotion, file.c_str());
      }
    }
    std::fprintf(stderr, "  %s in %.3f s%s\n", r.solved ? "solved" : "NOT solved", r.time,
                 r.solved ? (", length " + fmt(r.length) + ", min clearance " + fmt(r.minClearance) + " m" +
                             (r.fclVerified ? ", FCL ok" : ", FCL REJECTS"))
                                .c_str()
                          : "");
    context->records.push_back(r);
  });
}

/// Writes one log per problem: both checkers' planners in one experiment.
bool saveMergedLog(std::unique_ptr<Bench> (&benches)[2], const std::string& out, const Problem& problem) {
  auto& merged = benches[0]->data();
  const auto& other = benches[1]->data();
  for (auto& p : merged.planners) p.name += "_deepcheck";
  for (auto p : other.planners) {
    p.name += "_fcl";
    merged.planners.push_back(p);
  }
  merged.totalDuration += other.totalDuration;
  merged.setupInfo = "=== checker deepcheck (planner names ending in _deepcheck) ===\n" + merged.setupInfo +
                     "\n=== checker fcl (planner names ending in _fcl) ===\n" + other.setupInfo;
  const std::string log = out + "/plan_bench_" + problem.name + ".log";
  if (!benches[0]->saveResultsToFile(log.c_str())) {
    std::fprintf(stderr, "plan_bench: cannot write %s\n", log.c_str());
    return false;
  }
  std::fprintf(stderr, "wrote %s\n", log.c_str());
  return true;
}

/// Runs every planner on both checkers for one problem; false when it could not.
bool benchmarkProblem(RunContext ctx) {
  const Options& opt = ctx.opt;
  const Problem& problem = ctx.problem;
  const char* checkers[] = {"deepcheck", "fcl"};
  std::unique_ptr<Bench> benches[2];
  for (int c = 0; c < 2; ++c) {
    og::SimpleSetup& ss = c == 0 ? *ctx.setups.ours : *ctx.setups.fcl;
    const std::string checker = checkers[c];
    benches[c] = std::make_unique<Bench>(ss, "plan_bench_" + problem.name);
    Bench& b = *benches[c];
    b.addExperimentParameter("fine_resolution", "REAL", fmt(dp::tol::kFineResolution, "%.17g"));
    b.addExperimentParameter("longest_valid_segment_fraction", "REAL",
                             fmt(ss.getStateSpace()->getLongestValidSegmentFraction(), "%.17g"));
    b.addExperimentParameter("scenes", "INTEGER", std::to_string(problem.scenes.size()));
    for (const std::string& name : opt.planners) {
      ob::PlannerPtr planner = dp::makePlanner(name, ss.getSpaceInformation());
      if (planner->getName().find("BIT") != std::string::npos) ProgressPropertyStripper::strip(*planner);
      b.addPlanner(planner);
    }

    addRunEvents(b, ss, checker, ctx);
    ot::Benchmark::Request req(opt.time, 4096.0, static_cast<unsigned>(opt.runs));
    req.displayProgress = false;
    req.saveConsoleOutput = false;
    b.benchmark(req);
  }
  return saveMergedLog(benches, opt.out, problem);
}

}  // namespace

int main(int argc, char** argv) {
  const Options opt = parseOptions(argc, argv);
  const std::vector<Problem> selected = selectProblems(opt.wantedProblems);

  std::filesystem::create_directories(opt.out);
  ompl::RNG::setSeed(opt.seed);
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const auto wallStart = std::chrono::steady_clock::now();
  std::fprintf(stderr, "plan_bench: %zu problem(s) x 2 checkers x %zu planner(s) x %d run(s), %.3g s each\n",
               selected.size(), opt.planners.size(), opt.runs, opt.time);

  std::vector<Record> records;
  std::vector<std::string> rejected;
  for (std::size_t pi = 0; pi < selected.size(); ++pi) {
    const std::optional<Setups> setups = prepareSetups(selected[pi]);
    if (!setups || !benchmarkProblem({opt, selected[pi], *setups, pi, selected.size(), records, rejected})) return 1;
  }
  ReportSettings settings;
  settings.out = opt.out;
  settings.runs = opt.runs;
  settings.time = opt.time;
  settings.seed = opt.seed;
  settings.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
  settings.checkers = {"deepcheck", "fcl"};
  writeReport(settings, selected, records, rejected);
  plotReport(opt.out);
  return 0;
}
