// mbm_bench: the Panda on MotionBenchMaker's scenes (Chamzas et al., RA-L 2022), our checker
// against the FCL mesh checker, through ompl::tools::Benchmark (logs in OMPL's format, readable by
// ompl_benchmark_statistics.py and Planner Arena), each run timed as the planner's solve() alone
// (SolveTimedBenchmark, ompl_benchmark.h).
//
// Scenes (mbm_problems.h): bookshelf_small, bookshelf_tall, bookshelf_thin, cage, box, table_pick,
// kitchen, table_bars, each with MotionBenchMaker's variation and query files for the Panda. Per
// scene, N problems are generated (deepcheck::problems::generateProblems, seeded: the same
// --seed and --problems give the same problems); a scene that cannot be loaded or whose problems
// cannot be generated is reported in the output and the table, and the run goes on.
// Checkers, on the same problems (the same state space and segment fraction):
//   deepcheck  makeSimpleSetup with default options: our validity checker on the convex pieces,
//              the certified motion validator (--motions discrete: OMPL's DiscreteMotionValidator
//              at the default resolution, for comparison), the push-out sampler;
//   fcl        FclStateValidityChecker (FCL on the original meshes), OMPL's DiscreteMotionValidator
//              and OMPL's default valid state sampler.
// OMPL's random numbers are reseeded before a problem's setups are made, before each planner is
// made, before each run and before its simplification, from --seed, the scene, the problem, the
// planner and the run only (runSeed): a run plans with the same numbers whichever scenes, planners
// and checkers run beside it, and both checkers' runs of a problem start from the same numbers.
// Planners (makePlanner, OMPL defaults): RRTConnect, BiEST, PRM. Every run ends at its first
// solution: the problem's objective is path length with an infinite cost threshold, which PRM (an
// optimizing planner in OMPL 1.5, otherwise growing its roadmap to the time limit) takes as met by
// any path. One run per problem, planner and checker (--runs R: R runs; the tables then count runs).
//
// After each solved run (timed apart from the plan): the path is simplified
// (simplifySolutionChecked, as it is returned) and checked by FCL at tol::kFineResolution
// (checkPathFine), then certified by certifyPath on our setup (the certified motion validator,
// repairing where it fails) and the certified path checked by FCL again. Checks are the state
// validity queries made while planning (the discrete motion checks' included).
//
// Outputs in OUT (default bench/results/mbm, a folder git ignores; bench/run_mbm_bench.sh keeps
// the summary of its runs as bench/results/mbm_bench.csv): mbm_<scene>.log (one OMPL experiment per scene, the
// problems as runs of the planners geometric_<planner>_<checker>; extra run properties: problem,
// checks, checks per second, simplified length, certified, certified exact, fcl fine verified), mbm_runs.csv,
// mbm_bench.csv, mbm_bench.md (also printed), mbm_bench.png (gnuplot, bench/mbm_plots.gp), and
// for a certified path FCL rejects, fcl_rejected_<scene>_<problem>_<planner>_<checker>.{txt,yaml}.
// Progress on stderr.
//
// Usage: mbm_bench [--problems N] [--runs R] [--time S] [--seed S] [--scenes a,b] [--planners a,b] [--checkers a,b]
//                  [--out DIR]
//
// Files: mbm_problems.* (scenes and problems), mbm_report.* (records and tables), this file (runs).

#include "mbm_problems.h"
#include "mbm_report.h"
#include "ompl_benchmark.h"
#include "options.h"
#include "plan_problems.h"
#include "plan_report.h"

#include "deepcheck/planners/path_tools.h"
#include "deepcheck/planners/planner_factory.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/planners/tolerances.h"
#include "deepcheck/robots/moveit_scene.h"

#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
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
  int problems = 100;
  int runs = 1;  ///< per problem, planner and checker
  double time = 10.0;
  unsigned seed = 1;
  std::vector<std::string> scenes;  ///< empty: all
  std::vector<std::string> planners{"RRTConnect", "BiEST", "PRM"};
  std::vector<std::string> checkers{"deepcheck", "fcl"};
  dp::MotionValidation motions = dp::MotionValidation::Certified;  ///< our setup's motion validator
  std::string out = std::string(DEEPCHECK_BENCH_RESULTS_DIR) + "/mbm";
};

[[noreturn]] void usage(const std::string& error) {
  if (!error.empty()) std::fprintf(stderr, "mbm_bench: %s\n", error.c_str());
  std::fprintf(
      stderr,
      "usage: mbm_bench [--problems N] [--runs R] [--time SECONDS] [--seed S] [--scenes a,b] [--planners a,b]\n"
      "                 [--checkers a,b] [--motions certified|discrete] [--out DIR]\n"
      "  --problems N   generated problems per scene (default 100)\n"
      "  --time S       time limit per planning run, seconds (default 10)\n"
      "  --seed S       seed of problem generation and of every run's random numbers (default 1)\n"
      "  --scenes       bookshelf_small, bookshelf_tall, bookshelf_thin, cage, box, table_pick, kitchen,\n"
      "                 table_bars (default all)\n"
      "  --planners     names deepcheck::planners::makePlanner knows (default RRTConnect,BiEST,PRM)\n"
      "  --motions M    our motion validator: certified (default) or discrete (OMPL's, for comparison)\n"
      "  --out DIR      output folder (default bench/results/mbm)\n");
  std::exit(2);
}

Options parseOptions(int argc, char** argv) {
  Options opt;
  readOptions(argc, argv, usage, [&](const std::string& arg, auto value) {
    if (arg == "--problems") {
      opt.problems = positiveCount(value(), arg, usage);
    } else if (arg == "--runs") {
      opt.runs = positiveCount(value(), arg, usage);
    } else if (arg == "--time") {
      opt.time = positiveValue(value(), arg, usage);
    } else if (arg == "--seed") {
      opt.seed = static_cast<unsigned>(std::stoul(value()));
    } else if (arg == "--scenes") {
      opt.scenes = splitList(value());
    } else if (arg == "--planners") {
      opt.planners.clear();
      for (const std::string& name : splitList(value())) opt.planners.push_back(dp::plannerName(name));
    } else if (arg == "--checkers") {
      opt.checkers = splitList(value());
      for (const std::string& c : opt.checkers) {
        if (c != "deepcheck" && c != "fcl") usage("unknown checker '" + c + "' (known: deepcheck, fcl)");
      }
      if (opt.checkers.empty()) usage("--checkers needs at least one checker");
    } else if (arg == "--motions") {
      const std::string m = value();
      if (m != "certified" && m != "discrete") usage("unknown --motions '" + m + "' (known: certified, discrete)");
      opt.motions = m == "certified" ? dp::MotionValidation::Certified : dp::MotionValidation::Discrete;
    } else if (arg == "--out") {
      opt.out = value();
    } else {
      return false;
    }
    return true;
  });
  return opt;
}

/// Counts the validity queries of the FCL checker (ours counts its own).
class CountingChecker : public ob::StateValidityChecker {
 public:
  CountingChecker(const ob::SpaceInformationPtr& si, ob::StateValidityCheckerPtr inner)
      : ob::StateValidityChecker(si), inner_(std::move(inner)) {}
  bool isValid(const ob::State* state) const override {
    count_.fetch_add(1, std::memory_order_relaxed);
    return inner_->isValid(state);
  }
  double clearance(const ob::State* state) const override { return inner_->clearance(state); }
  std::uint64_t count() const { return count_.load(std::memory_order_relaxed); }
  void reset() { count_.store(0, std::memory_order_relaxed); }

 private:
  ob::StateValidityCheckerPtr inner_;
  mutable std::atomic<std::uint64_t> count_{0};
};

/// One problem's two setups.
struct ProblemSetups {
  const deepcheck::problems::Problem* problem = nullptr;
  std::shared_ptr<og::SimpleSetup> ours, fcl;
  std::shared_ptr<const dp::StateValidityChecker> ourChecker;
  std::shared_ptr<deepcheck::fcl_reference::FclStateValidityChecker> fclChecker;
  std::shared_ptr<CountingChecker> fclCounter;
};

/// Every run ends at its first solution (see the header comment).
void stopAtFirstSolution(og::SimpleSetup& ss) {
  auto objective = std::make_shared<ob::PathLengthOptimizationObjective>(ss.getSpaceInformation());
  objective->setCostThreshold(objective->infiniteCost());
  ss.setOptimizationObjective(objective);
}

ProblemSetups makeSetups(const std::shared_ptr<deepcheck::checker::World>& world,
                         const deepcheck::problems::Problem& problem, dp::MotionValidation motions) {
  ProblemSetups s;
  s.problem = &problem;
  dp::SetupOptions options = pandaArmOptions();
  options.motionValidation = motions;
  s.ours = dp::makeSimpleSetup(world, options);
  dp::setStartAndGoal(*s.ours, problem.start, problem.goal);
  s.ourChecker = dp::validityCheckerOf(*s.ours);
  s.fcl = makeFclSetup(*s.ours, *world, &s.fclChecker);
  s.fclCounter = std::make_shared<CountingChecker>(s.fcl->getSpaceInformation(), s.fclChecker);
  s.fcl->setStateValidityChecker(s.fclCounter);
  setEndpoints(*s.fcl, problem.start, problem.goal);
  for (og::SimpleSetup* ss : {s.ours.get(), s.fcl.get()}) {
    stopAtFirstSolution(*ss);
    ss->setup();
  }
  return s;
}

/// `path` (of any state space with the robot's layout) as a path of `si`.
og::PathGeometric pathIn(const og::PathGeometric& path, const ob::SpaceInformationPtr& si) {
  og::PathGeometric out(si);
  ob::State* state = si->allocState();
  for (const Eigen::VectorXd& q : dp::pathConfigurations(path)) {
    dp::copyToState(q, state);
    out.append(state);
  }
  si->freeState(state);
  return out;
}

/// What the runs of one scene read and add to.
struct SceneRun {
  const Options& opt;
  const MbmScene& scene;
  std::vector<MbmRecord>& records;
};

/// Writes a certified path that FCL's fine check rejects, for a look at it: FILE.yaml, the problem's
/// scene, and FILE.txt, the path as `deepcheck plan --out` writes it (so that `deepcheck view`
/// shows it), after comment lines naming the first motion FCL rejects and the scene file.
void saveRejectedPath(const std::string& file, const deepcheck::problems::Problem& problem,
                      const og::PathGeometric& path, const dp::PathCheck& fclCheck) {
  std::ofstream(file + ".yaml") << deepcheck::robots::writePlanningScene(problem.scene);
  std::ofstream out(file + ".txt");
  out << "# certified, rejected by FCL at " << fmt(dp::tol::kFineResolution, "%.17g") << " rad (first rejected motion "
      << fclCheck.firstInvalidMotion << ", " << fclCheck.invalidMotions << " motion(s))\n# scene "
      << std::filesystem::path(file).filename().string() << ".yaml\n";
  dp::writePath(path, out);
  std::fprintf(stderr, "wrote %s.txt and %s.yaml\n", file.c_str(), file.c_str());
}

/// The record of a finished run: simplified, certified and checked by FCL when solved. A certified
/// path FCL rejects is saved as rejectFile.{txt,yaml}.
MbmRecord measureRun(og::SimpleSetup& ss, const ProblemSetups& setups, const std::string& checker,
                     ot::Benchmark::RunProperties& run, double checks, const std::string& rejectFile) {
  MbmRecord r;
  r.checker = checker;
  r.time = std::stod(run["time REAL"]);
  r.solved = run["solved BOOLEAN"] == "1" && ss.haveExactSolutionPath();
  r.checks = checks;
  if (r.solved) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    dp::simplifySolutionChecked(ss);
    r.simplifyTime = std::chrono::duration<double>(Clock::now() - t0).count();
    og::PathGeometric path = pathIn(ss.getSolutionPath(), setups.ours->getSpaceInformation());
    r.length = path.length();
    const auto* fcl = setups.fclChecker.get();
    const auto fclFree = [fcl](const Eigen::VectorXd& q) { return fcl->isFree(q); };
    r.fclReturned = dp::checkPathFine(path, fclFree).valid;
    const auto t1 = Clock::now();
    const dp::PathCertificate cert = dp::certifyPath(*setups.ours, path);
    r.certifyTime = std::chrono::duration<double>(Clock::now() - t1).count();
    r.certifiedAsPlanned = cert.initial.valid;
    r.certified = cert.valid;
    r.certifiedExact = cert.exact();
    const dp::PathCheck fine = dp::checkPathFine(path, fclFree);
    r.fclFine = fine.valid;
    if (r.certified && !r.fclFine) {
      try {
        saveRejectedPath(rejectFile, *setups.problem, path, fine);
      } catch (const std::exception& e) {  // a scene without a file form: the run goes on
        std::fprintf(stderr, "mbm_bench: %s not saved: %s\n", rejectFile.c_str(), e.what());
      }
    }
  }
  run["checks INTEGER"] = fmt(checks, "%.0f");
  run["checks per second REAL"] = fmt(r.time > 0.0 ? checks / r.time : 0.0, "%.17g");
  if (r.solved) {
    run["simplified length REAL"] = fmt(r.length, "%.17g");
    run["certified as planned BOOLEAN"] = r.certifiedAsPlanned ? "1" : "0";
    run["certified BOOLEAN"] = r.certified ? "1" : "0";
    run["certified exact BOOLEAN"] = r.certifiedExact ? "1" : "0";
    run["fcl fine verified BOOLEAN"] = r.fclFine ? "1" : "0";
    run["fcl fine as returned BOOLEAN"] = r.fclReturned ? "1" : "0";
    run["simplify time REAL"] = fmt(r.simplifyTime, "%.17g");
    run["certify time REAL"] = fmt(r.certifyTime, "%.17g");
  }
  return r;
}

/// What the random numbers are drawn for: a problem's setups (their path simplifiers keep the
/// generator they are made with), the planner's own generator (made with the planner), the
/// planning (samplers made in solve()) and the simplification and certification after it.
enum class RunStage : std::uint64_t { Setups = 0, MakePlanner = 1, Solve = 2, Simplify = 3 };

/// The seed of OMPL's random numbers at one stage of one run: a function of --seed, the scene, the
/// problem, the planner, the run and the stage only. A run then draws the same numbers whichever
/// scenes, planners and checkers run beside it, and both checkers' runs of a problem draw alike:
/// while their answers agree they grow the same trees, and two versions of the checker pair run
/// for run.
std::uint_fast32_t runSeed(unsigned seed, const std::string& scene, int problem, const std::string& planner, int run,
                           RunStage stage) {
  std::uint64_t h = 1469598103934665603ULL;  // FNV-1a over the names
  for (const char ch : scene + '/' + planner) h = (h ^ static_cast<unsigned char>(ch)) * 1099511628211ULL;
  for (const std::uint64_t v : {std::uint64_t{seed}, static_cast<std::uint64_t>(problem),
                                static_cast<std::uint64_t>(run), static_cast<std::uint64_t>(stage)}) {
    h ^= v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  }
  h ^= h >> 31;
  h *= 0xbf58476d1ce4e5b9ULL;
  h ^= h >> 29;
  return static_cast<std::uint_fast32_t>(h % 4294967295ULL) + 1;  // OMPL takes seed 0 as "pick one"
}

/// Reseeds OMPL's generator of seeds: every ompl::RNG made from now on draws from `seed`. OMPL
/// reports an error when numbers were drawn already (reseeding is the intent here), so its log is
/// silenced for the call.
void reseedOmpl(std::uint_fast32_t seed) {
  const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  ompl::RNG::setSeed(seed);
  ompl::msg::setLogLevel(level);
}

/// Runs every planner on one checker's setup of problem `k`; appends records and the experiment.
void benchmarkChecker(SceneRun& ctx, int k, int count, const ProblemSetups& setups, const std::string& checker,
                      Bench& carrier) {
  og::SimpleSetup& ss = checker == "deepcheck" ? *setups.ours : *setups.fcl;
  auto bench = std::make_unique<SolveTimedBenchmark>(ss, "mbm_" + ctx.scene.name);
  const auto seedOf = [&ctx, k](const std::string& planner, int run, RunStage stage) {
    return runSeed(ctx.opt.seed, ctx.scene.name, k, planner, run, stage);
  };
  for (const std::string& name : ctx.opt.planners) {
    reseedOmpl(seedOf(name, 0, RunStage::MakePlanner));
    bench->addPlanner(dp::makePlanner(name, ss.getSpaceInformation()));
  }
  bench->addExperimentParameter("problems", "INTEGER", std::to_string(ctx.opt.problems));
  bench->addExperimentParameter("problem_seed", "INTEGER", std::to_string(ctx.opt.seed));
  bench->addExperimentParameter("fine_resolution", "REAL", fmt(dp::tol::kFineResolution, "%.17g"));
  auto resetChecks = [&setups, checker]() {
    if (checker == "deepcheck") {
      std::const_pointer_cast<dp::StateValidityChecker>(setups.ourChecker)->resetCounters();
    } else {
      setups.fclCounter->reset();
    }
  };
  auto checks = [&setups, checker]() {
    return static_cast<double>(checker == "deepcheck" ? setups.ourChecker->validityQueries()
                                                      : setups.fclCounter->count());
  };
  SceneRun* c = &ctx;
  og::SimpleSetup* setup = &ss;
  // Runs of each planner so far (--runs R > 1 runs a planner R times on the problem).
  auto runsOf = std::make_shared<std::map<std::string, int>>();
  bench->setPreRunEvent([=](const ob::PlannerPtr& planner) {
    resetChecks();
    reseedOmpl(seedOf(planner->getName(), (*runsOf)[planner->getName()], RunStage::Solve));
  });
  bench->setPostRunEvent([=, &setups](const ob::PlannerPtr& planner, ot::Benchmark::RunProperties& run) {
    const double n = checks();  // before simplification and certification
    reseedOmpl(seedOf(planner->getName(), (*runsOf)[planner->getName()]++, RunStage::Simplify));
    const std::string reject = c->opt.out + "/fcl_rejected_" + c->scene.name + "_" + std::to_string(k) + "_" +
                               planner->getName() + "_" + checker;
    MbmRecord r = measureRun(*setup, setups, checker, run, n, reject);
    r.scene = c->scene.name;
    r.problem = k;
    r.planner = planner->getName();
    run["problem INTEGER"] = std::to_string(k);
    std::fprintf(
        stderr, "[%s %d/%d] %-9s %-10s %s %.4f s, %.0f checks%s\n", c->scene.name.c_str(), k + 1, count,
        checker.c_str(), r.planner.c_str(), r.solved ? "solved" : "NOT solved", r.time, r.checks,
        r.solved ? (r.certified ? (r.fclFine ? ", certified, FCL ok" : ", certified, FCL REJECTS") : ", NOT certified")
                 : "");
    c->records.push_back(r);
  });
  ot::Benchmark::Request req(ctx.opt.time, 4096.0, static_cast<unsigned>(ctx.opt.runs));
  req.displayProgress = false;
  req.saveConsoleOutput = false;
  req.simplify = false;  // done in the post-run event, after the checks are read
  bench->benchmark(req);
  // Merge: planners named by checker; the problems are the runs.
  auto& data = bench->data();
  for (auto& p : data.planners) p.name += "_" + checker;
  auto& merged = carrier.data();
  if (merged.planners.empty()) {
    merged = data;
    return;
  }
  for (const auto& p : data.planners) {
    auto it =
        std::find_if(merged.planners.begin(), merged.planners.end(), [&](const auto& m) { return m.name == p.name; });
    if (it == merged.planners.end()) {
      merged.planners.push_back(p);
    } else {
      it->runs.insert(it->runs.end(), p.runs.begin(), p.runs.end());
      it->runsProgressData.insert(it->runsProgressData.end(), p.runsProgressData.begin(), p.runsProgressData.end());
    }
  }
  merged.totalDuration += data.totalDuration;
}

}  // namespace

namespace {

std::string oneLine(std::string text) {
  for (char& ch : text) {
    if (ch == '\n' || ch == '|') ch = ' ';
  }
  return text;
}

/// Generates the scene's problems and runs them; the reason when the scene could not be run.
std::string benchmarkScene(const Options& opt, const MbmScene& scene,
                           const std::shared_ptr<deepcheck::checker::World>& world, std::vector<MbmRecord>& records) {
  auto base = dp::makeSimpleSetup(world, pandaArmOptions());
  std::vector<deepcheck::problems::Problem> problems;
  try {
    std::vector<std::string> notes;
    const deepcheck::problems::ProblemOptions options = pandaProblemOptions(scene, world->robot(), opt.seed, &notes);
    problems =
        generateMbmProblems(scene, *world, *dp::validityCheckerOf(*base), options, opt.problems,
                            [&](int k, const deepcheck::problems::Problem& p) {
                              std::fprintf(stderr, "[%s] problem %d/%d generated: goal %s%s%s, %d scene(s) drawn\n",
                                           scene.name.c_str(), k + 1, opt.problems, p.goalQuery.c_str(),
                                           p.startQuery.empty() ? "" : ", start ", p.startQuery.c_str(), p.attempts);
                            });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mbm_bench: scene %s is not run: %s\n", scene.name.c_str(), e.what());
    for (int id : world->obstacleIds()) world->removeObstacle(id);
    return oneLine(e.what());
  }
  Bench carrier(*base, "mbm_" + scene.name);
  SceneRun ctx{opt, scene, records};
  for (int k = 0; k < static_cast<int>(problems.size()); ++k) {
    placeScene(*world, problems[static_cast<std::size_t>(k)].scene);
    reseedOmpl(runSeed(opt.seed, scene.name, k, "", 0, RunStage::Setups));
    const ProblemSetups setups = makeSetups(world, problems[static_cast<std::size_t>(k)], opt.motions);
    for (const std::string& checker : opt.checkers) benchmarkChecker(ctx, k, opt.problems, setups, checker, carrier);
  }
  for (int id : world->obstacleIds()) world->removeObstacle(id);
  carrier.data().runCount = static_cast<unsigned>(problems.size()) * static_cast<unsigned>(opt.runs);
  // The log names the scene's files, not where they lie, and describes no machine.
  const auto fileName = [](const std::string& path) { return std::filesystem::path(path).filename().string(); };
  carrier.data().host = "-";
  carrier.data().cpuInfo.clear();
  carrier.data().setupInfo = "MotionBenchMaker " + scene.name + ": scene " + fileName(scene.scene) + ", variation " +
                             fileName(scene.variation) + ", queries " + fileName(scene.queries) +
                             "; planner names end in the checker (deepcheck, fcl); run k "
                             "of a planner is problem k / runs (see the problem property)\n" +
                             carrier.data().setupInfo;
  const std::string log = opt.out + "/mbm_" + scene.name + ".log";
  if (!carrier.saveResultsToFile(log.c_str())) return "cannot write " + log;
  std::fprintf(stderr, "wrote %s\n", log.c_str());
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  const Options opt = parseOptions(argc, argv);
  const std::vector<MbmScene> scenes = selectScenes(opt.scenes, usage);
  if (!haveShared()) {
    std::fprintf(stderr, "mbm_bench: ../shared is absent (%s): no Panda, no MotionBenchMaker scenes\n",
                 sharedDir().c_str());
    return 1;
  }
  std::filesystem::create_directories(opt.out);
  ompl::RNG::setSeed(opt.seed);
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  MbmSettings settings;
  settings.out = opt.out;
  settings.problems = opt.problems;
  settings.runs = opt.runs;
  settings.time = opt.time;
  settings.seed = opt.seed;
  settings.checkers = opt.checkers;
  settings.planners = opt.planners;
  const auto wallStart = std::chrono::steady_clock::now();
  std::fprintf(stderr, "mbm_bench: %zu scene(s) x %d problem(s) x %zu checker(s) x %zu planner(s), %.3g s limit\n",
               scenes.size(), opt.problems, opt.checkers.size(), opt.planners.size(), opt.time);
  const auto world = dp::loadWorld(pandaUrdf(), {}, pandaArmOptions());
  std::vector<MbmRecord> records;
  std::vector<SceneFailure> failures;
  for (const MbmScene& scene : scenes) {
    settings.scenes.push_back(scene.name);
    const std::string reason = benchmarkScene(opt, scene, world, records);
    if (!reason.empty()) failures.push_back({scene.name, reason});
    // The tables so far after every scene: a long run stopped early keeps its finished scenes.
    settings.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
    writeMbmReport(settings, records, failures, &scene != &scenes.back());
  }
  plotMbmReport(opt.out);
  return 0;
}
