// certify_bench: what certifyPath costs on a UR5 of ../shared in a small scene, for a path our
// pipeline returned and for the same path handed in from elsewhere.
//
// The UR5 (example-robot-data, its SRDF) bolted to the table of robots/data/scenes/ur5_table.yaml
// (a crate and a post on it). For N problems between random valid configurations (seeded), the
// default pipeline plans (makeSimpleSetup, RRTConnect at defaultRange, certified motions) and
// simplifies (simplifySolutionChecked); then certifyPath runs on the returned path twice:
//   returned   on the same setup: its motions were certified while planning and simplifying, and
//              the validity checker's memo answers them (certified_motion_memo.h);
//   elsewhere  on a new setup of the same world (a new checker, an empty memo): what a path planned
//              by another tool costs.
// Both must find the path valid, unrepaired; a run where either does not is counted and reported.
// Prints a table (medians and p90 in ms) and writes bench/results/certify_bench.csv.
//
// Usage: certify_bench [--problems N] [--seed S] [--csv FILE]   (about half a minute)

#include "csv_out.h"
#include "format.h"
#include "options.h"

#include "deepcheck/planners/path_tools.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/robots/moveit_scene.h"

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace dp = deepcheck::planners;
using Clock = std::chrono::steady_clock;

namespace {

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

/// A valid configuration within the joint limits (bounded to +-pi on wrapping joints).
Eigen::VectorXd randomValid(const dp::StateValidityChecker& checker, std::mt19937_64& rng) {
  const auto& model = checker.world().robot();
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::VectorXd q(model.numVariables());
  for (;;) {
    for (int v = 0; v < q.size(); ++v) {
      const double lo = std::max(model.lowerLimits()[v], -M_PI);
      const double hi = std::min(model.upperLimits()[v], M_PI);
      q[v] = lo + (hi - lo) * u(rng);
    }
    if (checker.isValid(q)) return q;
  }
}

struct Times {
  std::vector<double> plan, simplify, returned, elsewhere;
  int unsolved = 0, notCertified = 0;
};

void usage(const std::string& error) {
  if (!error.empty()) std::fprintf(stderr, "certify_bench: %s\n", error.c_str());
  std::fprintf(stderr, "usage: certify_bench [--problems N] [--seed S] [--csv FILE]\n");
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  int problems = 30;
  unsigned seed = 1;
  std::string csvPath = DEEPCHECK_BENCH_RESULTS_DIR "/certify_bench.csv";
  deepcheck::bench::readOptions(argc, argv, usage, [&](const std::string& arg, auto value) {
    if (arg == "--problems") problems = deepcheck::bench::positiveCount(value(), arg, usage);
    else if (arg == "--seed") seed = static_cast<unsigned>(std::stoul(value()));
    else if (arg == "--csv") csvPath = value();
    else return false;
    return true;
  });
  const std::string ur5 = DEEPCHECK_SHARED_DIR "/robots/ur5";
  const std::string urdf = ur5 + "/example-robot-data/robots/ur_description/urdf/ur5_robot.urdf";
  if (!std::filesystem::is_regular_file(urdf)) {
    std::fprintf(stderr, "certify_bench: no UR5 at %s\n", urdf.c_str());
    return 1;
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  ompl::RNG::setSeed(seed);
  dp::SetupOptions options;
  options.packageRoots = {ur5};
  options.srdf = ur5 + "/example-robot-data/robots/ur_description/srdf/ur5.srdf";
  const auto world = dp::loadWorld(urdf, {}, options);
  const bool reports = world->setFixedPairReports(false);
  world->addPlanningScene(
      deepcheck::robots::loadPlanningScene(DEEPCHECK_SOURCE_DIR "/robots/data/scenes/ur5_table.yaml"));
  world->setFixedPairReports(reports);

  std::mt19937_64 rng(seed);
  Times t;
  for (int p = 0; p < problems; ++p) {
    auto ss = dp::makeSimpleSetup(world, options);
    const auto checker = dp::validityCheckerOf(*ss);
    dp::setStartAndGoal(*ss, randomValid(*checker, rng), randomValid(*checker, rng));
    auto t0 = Clock::now();
    // The limit as a condition the planner checks: SimpleSetup::solve(10.0) would time OMPL's
    // polling thread's join too (up to 1 ms; bench/harness_overhead).
    const bool solved =
        static_cast<bool>(ss->solve(ompl::base::timedPlannerTerminationCondition(10.0))) && ss->haveExactSolutionPath();
    const double plan = msSince(t0);
    if (!solved) {
      ++t.unsolved;
      continue;
    }
    t0 = Clock::now();
    dp::simplifySolutionChecked(*ss);
    t.plan.push_back(plan);
    t.simplify.push_back(msSince(t0));
    ompl::geometric::PathGeometric path = ss->getSolutionPath();
    t0 = Clock::now();
    const dp::PathCertificate own = dp::certifyPath(*ss, path);
    t.returned.push_back(msSince(t0));
    auto fresh = dp::makeSimpleSetup(world, options);
    ompl::geometric::PathGeometric handedIn(fresh->getSpaceInformation());
    for (std::size_t i = 0; i < path.getStateCount(); ++i) handedIn.append(path.getState(i));
    t0 = Clock::now();
    const dp::PathCertificate other = dp::certifyPath(*fresh, handedIn);
    t.elsewhere.push_back(msSince(t0));
    if (!own.valid || own.repaired || !other.valid || other.repaired) ++t.notCertified;
    std::fprintf(stderr, "\rcertify_bench: %d/%d problems", p + 1, problems);
  }
  std::fprintf(stderr, "\n");

  std::printf("# certifyPath on the UR5 in ur5_table (certify_bench)\n\n");
  std::printf("%d problems (seed %u), %zu solved; %d paths not certified as returned\n\n", problems, seed,
              t.plan.size(), t.notCertified);
  std::printf("| step | median (ms) | p90 (ms) |\n|---|--:|--:|\n");
  std::FILE* csv = deepcheck::bench::openCsv("certify_bench", csvPath, "step,median_ms,p90_ms,runs");
  const std::pair<const char*, const std::vector<double>*> rows[] = {
      {"plan", &t.plan},
      {"simplify", &t.simplify},
      {"certifyPath, returned path", &t.returned},
      {"certifyPath, path from elsewhere", &t.elsewhere}};
  for (const auto& [name, v] : rows) {
    const double median = deepcheck::bench::quantile(*v, 0.5);
    const double p90 = deepcheck::bench::quantile(*v, 0.9);
    std::printf("| %s | %.3g | %.3g |\n", name, median, p90);
    std::fprintf(csv, "%s,%.6g,%.6g,%zu\n", name, median, p90, v->size());
  }
  std::fclose(csv);
  return t.notCertified == 0 ? 0 : 1;
}
