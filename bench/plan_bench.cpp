// plan_bench: OMPL planners on our collision checker against the same planners on the FCL mesh
// checker (issue 6, item 8), through ompl::tools::Benchmark, so that the logs load into OMPL's
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
// (also printed), plan_bench_time.png (gnuplot, bench/plan_plots.gp; skipped when gnuplot is
// missing). Progress on stderr.
//
// Usage: plan_bench [--runs N] [--time S] [--problems a,b] [--planners a,b] [--quick] [--out DIR]
//                   [--seed S] [--pick-panda-endpoints] [--certify DIR]
//   --certify DIR  for each rejected path in DIR: certifyPath (setup.h) on our setup, then the
//                  fine FCL check again; writes DIR/plan_bench_certify.md.

#include "deepcheck/fcl_reference/fcl_validity_checker.h"
#include "deepcheck/planners/path_tools.h"
#include "deepcheck/planners/planner_factory.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/planners/tolerances.h"
#include "deepcheck/robots/kinematics.h"

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

// The Panda's start and goal (see problems(); printed by --pick-panda-endpoints, rounded to 1e-4).
#define PANDA_KITCHEN_START 2.3235, -0.7332, -0.7202, -1.0283, -1.0430, 1.9942, 0.8179, 0.0350
#define PANDA_KITCHEN_GOAL 0.6441, -1.7750, -1.3077, -2.4067, -0.8443, 3.7595, -0.7133, 0.0350
#define PANDA_TABLE_BARS_START 1.1207, 0.3870, -1.5234, -1.4975, -0.8731, 2.3007, 0.2042, 0.0350
#define PANDA_TABLE_BARS_GOAL 0.6831, 0.5868, -0.9187, -2.1369, -2.5455, 2.2887, -2.3964, 0.0350

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace ot = ompl::tools;
namespace dp = deepcheck::planners;
using deepcheck::fcl_reference::FclStateValidityChecker;

namespace {

// ---- problems ---------------------------------------------------------------------------------

struct Problem {
  std::string name;
  std::string robotUrdf;
  dp::SetupOptions options;  // package paths and SRDF
  std::vector<dp::SceneSpec> scenes;
  Eigen::VectorXd start;
  Eigen::VectorXd goal;
  bool needsShared = false;
  std::string note;  // where start and goal come from
};

Eigen::VectorXd vec(std::initializer_list<double> values) {
  Eigen::VectorXd q(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double v : values) q[i++] = v;
  return q;
}

std::string sourceDir() { return DEEPCHECK_SOURCE_DIR; }
std::string sharedDir() { return DEEPCHECK_SHARED_DIR; }
bool haveShared() { return std::filesystem::is_directory(sharedDir() + "/robots/panda"); }

/// The table_bars scene is placed 0.3 m in front of the Panda (+x): the shelves' front edge
/// (the bars) is at x = -0.06 in the scene's frame, so at the identity the robot's base would be
/// inside them. MotionBenchMaker's own robot placement for this scene is in its problem files,
/// which ../shared does not include.
Eigen::Isometry3d tableBarsPose() {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(0.3, 0.0, 0.0);
  return X;
}

std::string pandaUrdf() {
  return sharedDir() + "/robots/panda/moveit_resources_panda_description/urdf/panda.urdf";
}
std::string mbmScene(const std::string& name) {
  return sharedDir() + "/scenes/motion_bench_maker/configs/scenes/" + name + "/" + name + ".urdf";
}

dp::SetupOptions pandaOptions() {
  dp::SetupOptions o;
  o.packagePaths = {sharedDir() + "/robots/panda", sharedDir() + "/scenes"};
  o.useRosPackagePath = false;
  o.srdf = sharedDir() + "/robots/panda/moveit_resources_panda_moveit_config/config/panda.srdf";
  return o;
}

std::vector<Problem> problems() {
  std::vector<Problem> list;
  const std::string data = sourceDir() + "/robots/data";
  dp::SetupOptions arm;
  arm.packagePaths = {data};
  arm.useRosPackagePath = false;
  arm.srdf = data + "/deepcheck_arm/srdf/deepcheck_arm.srdf";
  const Eigen::VectorXd armStart = vec({0, -0.4, 0, -1.6, 0, 1.2, 0});
  const std::string readme = "robots/data/README.md, Suggested planning problems";
  list.push_back({"table", data + "/deepcheck_arm/urdf/deepcheck_arm.urdf", arm, {data + "/scenes/table.urdf"},
                  armStart, vec({-0.14, 0.61, 0.24, -0.77, -0.14, 1.77, -2.23}), false, readme});
  list.push_back({"shelf", data + "/deepcheck_arm/urdf/deepcheck_arm.urdf", arm, {data + "/scenes/shelf.urdf"},
                  armStart, vec({1.05, 0.75, -1.17, -1.30, 0.05, -0.07, -2.79}), false, readme});
  list.push_back({"narrow_passage", data + "/deepcheck_arm/urdf/deepcheck_arm.urdf", arm,
                  {data + "/scenes/narrow_passage.urdf"}, armStart,
                  vec({-0.40, 1.72, -0.40, 1.79, 0.31, 1.50, 0.59}), false, readme});
  // Panda: 8 variables (panda_joint1..7, panda_finger_joint1; finger 2 mimics finger 1). The
  // MotionBenchMaker configs give end-effector poses relative to scene objects, not joint
  // values; the configurations below were found by `plan_bench --pick-panda-endpoints`
  // (pickEndpoints(): damped least squares on the fingertip position from seeded random
  // configurations, std::mt19937 seed 1, first solution within 1 cm that is at least 2 cm from
  // everything by our signed distance and free for FCL). Targets, world frame (Panda at the
  // origin):
  //   kitchen (URDF pose, as the checker tests): start (0.45, 0.2, 1.0), above the counter under
  //     the cupboard; goal (0.2, -0.5, 0.6), in front of the dishwasher (MotionBenchMaker's
  //     "FrontEasy" goal offset; its start, in the cupboard at z 1.5, is out of the Panda's reach
  //     from the origin);
  //   table_bars (at tableBarsPose()): MotionBenchMaker's queries.yaml "ArmAboveShelfR" ->
  //     "ArmBelowShelfR": shelves + (0.35, -0.2, 0.7) -> shelves + (0.35, -0.2, 0.25), above and
  //     below the middle shelf.
  list.push_back({"panda_kitchen", pandaUrdf(), pandaOptions(), {mbmScene("kitchen")},
                  vec({PANDA_KITCHEN_START}), vec({PANDA_KITCHEN_GOAL}), true,
                  "picked by --pick-panda-endpoints (seed 1)"});
  list.push_back({"panda_table_bars", pandaUrdf(), pandaOptions(), {dp::SceneSpec(mbmScene("table_bars"), tableBarsPose())},
                  vec({PANDA_TABLE_BARS_START}), vec({PANDA_TABLE_BARS_GOAL}), true,
                  "picked by --pick-panda-endpoints (seed 1)"});
  return list;
}

// ---- helpers ----------------------------------------------------------------------------------

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

std::string uptimeLine() {
  std::string out;
  if (FILE* p = popen("uptime 2>/dev/null", "r")) {
    char buf[256];
    while (std::fgets(buf, sizeof buf, p) != nullptr) out += buf;
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  return out.empty() ? "load average: " + loadAverage() : out;
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string fmt(double v, const char* f = "%.3g") {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

/// Benchmark with access to its recorded data, to merge the two checkers' experiments of a
/// problem into one log (one experiment, planners named by checker).
class Bench : public ot::Benchmark {
 public:
  Bench(og::SimpleSetup& ss, const std::string& name) : ot::Benchmark(ss, name) {}
  CompleteExperiment& data() { return exp_; }
};

/// Removes a planner's progress properties (the values Benchmark's collector thread reads every
/// 50 ms while the planner runs). BIT*'s read its search queue unsynchronized: in this benchmark
/// OMPL 1.5.2 crashed with a segfault inside libompl during a BIT* run (shelf, run 9 of 10), as in
/// ompl/ompl#779 ("BIT* is failing when added to a benchmark", traced there to
/// currentVertexProgressProperty). The member is protected; a pointer to it named through a
/// derived class is the standard way to reach it.
struct ProgressPropertyStripper : ob::Planner {
  static void strip(ob::Planner& planner) { (planner.*(&ProgressPropertyStripper::plannerProgressProperties_)).clear(); }
};

/// An OMPL SimpleSetup with the FCL checker on the same state space (bounds, names, segment
/// fraction) as `ours`.
std::shared_ptr<og::SimpleSetup> makeFclSetup(const og::SimpleSetup& ours, const deepcheck::checker::World& world,
                                              std::shared_ptr<FclStateValidityChecker>* checkerOut) {
  auto space = dp::makeStateSpace(world.robot());
  space->setLongestValidSegmentFraction(ours.getStateSpace()->getLongestValidSegmentFraction());
  auto ss = std::make_shared<og::SimpleSetup>(space);
  auto checker = std::make_shared<FclStateValidityChecker>(ss->getSpaceInformation(), world);
  ss->setStateValidityChecker(checker);
  if (checkerOut != nullptr) *checkerOut = checker;
  return ss;
}

void setEndpoints(og::SimpleSetup& ss, const Eigen::VectorXd& start, const Eigen::VectorXd& goal) {
  ob::ScopedState<> s(ss.getStateSpace());
  ob::ScopedState<> g(ss.getStateSpace());
  dp::copyToState(start, s.get());
  dp::copyToState(goal, g.get());
  ss.setStartAndGoalStates(s, g);
}

// ---- one run's record and the summary ---------------------------------------------------------

struct Record {
  std::string problem, checker, planner;
  bool solved = false;  // exact
  double time = 0.0, firstSolution = std::nan(""), length = std::nan(""), minClearance = std::nan("");
  bool fclVerified = false;
  double graphStates = std::nan("");
};

struct Row {
  std::string problem, checker, planner;
  int runs = 0, solved = 0, verified = 0;
  double tMed = 0, firstMed = 0, lengthMed = 0, clearanceMed = 0, statesMed = 0;
  double successPct() const { return runs > 0 ? 100.0 * solved / runs : 0.0; }
  double verifiedPct() const { return solved > 0 ? 100.0 * verified / solved : std::nan(""); }
};

Row summarize(const std::vector<Record>& all, const std::string& problem, const std::string& checker,
              const std::string& planner) {
  Row row{problem, checker, planner};
  std::vector<double> t, first, length, clearance, states;
  for (const Record& r : all) {
    if (r.problem != problem || r.checker != checker || r.planner != planner) continue;
    ++row.runs;
    t.push_back(r.time);
    if (!std::isnan(r.graphStates)) states.push_back(r.graphStates);
    if (!r.solved) continue;
    ++row.solved;
    if (r.fclVerified) ++row.verified;
    if (!std::isnan(r.firstSolution)) first.push_back(r.firstSolution);
    length.push_back(r.length);
    clearance.push_back(r.minClearance);
  }
  row.tMed = median(t);
  row.firstMed = median(first);
  row.lengthMed = median(length);
  row.clearanceMed = median(clearance);
  row.statesMed = median(states);
  return row;
}

// ---- the Panda's start and goal (--pick-panda-endpoints) --------------------------------------

/// The first configuration found, from seeded random starts refined by damped least squares on
/// the fingertip position (panda_hand origin + 0.1034 m along its z), within 1 cm of `target`, at
/// least 2 cm from everything by our signed distance, and free for FCL. Finger at 0.035 m.
Eigen::VectorXd pickEndpoint(const deepcheck::checker::World& world, FclStateValidityChecker& fcl,
                             const Eigen::Vector3d& target, std::mt19937& rng, int* attemptsOut) {
  const auto& model = world.robot();
  const int n = model.numVariables();
  const int hand = model.linkIndex("panda_hand");
  const int finger = model.variableIndex("panda_finger_joint1");
  const Eigen::Vector3d tip(0.0, 0.0, 0.1034);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int attempt = 1; attempt <= 5000; ++attempt) {
    Eigen::VectorXd q(n);
    for (int i = 0; i < n; ++i) {
      q[i] = model.lowerLimits()[i] + unit(rng) * (model.upperLimits()[i] - model.lowerLimits()[i]);
    }
    q[finger] = 0.035;
    double err = 1e9;
    for (int it = 0; it < 200 && err > 0.002; ++it) {
      const auto X = deepcheck::robots::forwardKinematics(model, q);
      const Eigen::Vector3d e = target - X[hand] * tip;
      err = e.norm();
      Eigen::Matrix3Xd J = deepcheck::robots::pointJacobian(model, X, hand, tip);
      J.col(finger).setZero();
      const double lambda = 0.05;
      const Eigen::Matrix3d A = J * J.transpose() + lambda * lambda * Eigen::Matrix3d::Identity();
      Eigen::VectorXd dq = J.transpose() * A.ldlt().solve(e);
      const double m = dq.cwiseAbs().maxCoeff();
      if (m > 0.2) dq *= 0.2 / m;
      q = (q + dq).cwiseMax(model.lowerLimits()).cwiseMin(model.upperLimits());
    }
    const Eigen::Vector3d reached = deepcheck::robots::forwardKinematics(model, q)[hand] * tip;
    if ((reached - target).norm() > 0.01) continue;
    const auto d = world.signedDistance(q);
    if (!d.found || d.closest.distance < 0.02) continue;
    if (!fcl.isFree(q)) continue;
    *attemptsOut = attempt;
    return q;
  }
  throw std::runtime_error("no endpoint found near the target");
}

int pickPandaEndpoints() {
  if (!haveShared()) {
    std::fprintf(stderr, "plan_bench: ../shared is absent (%s): nothing to pick\n", sharedDir().c_str());
    return 1;
  }
  struct Target {
    std::string name;
    std::vector<dp::SceneSpec> scenes;
    Eigen::Vector3d start, goal;
  };
  const Eigen::Vector3d shelves = tableBarsPose().translation();
  const std::vector<Target> targets{
      {"panda_kitchen", {mbmScene("kitchen")}, {0.45, 0.2, 1.0}, {0.2, -0.5, 0.6}},
      {"panda_table_bars",
       {dp::SceneSpec(mbmScene("table_bars"), tableBarsPose())},
       shelves + Eigen::Vector3d(0.35, -0.2, 0.7),
       shelves + Eigen::Vector3d(0.35, -0.2, 0.25)}};
  for (const Target& t : targets) {
    auto world = dp::loadWorld(pandaUrdf(), t.scenes, pandaOptions());
    auto ss = dp::makeSimpleSetup(world);
    std::shared_ptr<FclStateValidityChecker> fcl;
    auto fss = makeFclSetup(*ss, *world, &fcl);
    std::mt19937 rng(1);
    int a1 = 0, a2 = 0;
    const Eigen::VectorXd qs = pickEndpoint(*world, *fcl, t.start, rng, &a1);
    const Eigen::VectorXd qg = pickEndpoint(*world, *fcl, t.goal, rng, &a2);
    // Is the straight motion free? (Then the problem would be trivial.)
    og::PathGeometric straight(fss->getSpaceInformation());
    ob::ScopedState<> s(fss->getStateSpace()), g(fss->getStateSpace());
    dp::copyToState(qs, s.get());
    dp::copyToState(qg, g.get());
    straight.append(s.get());
    straight.append(g.get());
    const dp::PathCheck check = dp::checkPathFine(straight, [&](const Eigen::VectorXd& q) { return fcl->isFree(q); });
    auto print = [](const Eigen::VectorXd& q) {
      std::string out;
      for (int i = 0; i < q.size(); ++i) out += (i ? ", " : "") + fmt(q[i], "%.4f");
      return out;
    };
    std::printf("%s: start %s (attempt %d, clearance %.4f m)\n", t.name.c_str(), print(qs).c_str(), a1,
                world->signedDistance(qs).closest.distance);
    std::printf("%s: goal  %s (attempt %d, clearance %.4f m)\n", t.name.c_str(), print(qg).c_str(), a2,
                world->signedDistance(qg).closest.distance);
    std::printf("%s: straight-line motion %s\n", t.name.c_str(),
                check.valid ? "FREE (trivial problem)" : "in collision (good)");
  }
  return 0;
}

// ---- what certification makes of the rejected paths (--certify DIR) ---------------------------

/// For every rejected_<problem>_<checker>_<planner>_<run>.txt in `dir`: the path through
/// certifyPath (setup.h: the clearance motion validator, repairing where it fails) on our setup of
/// that problem, then the same fine FCL check. Writes DIR/plan_bench_certify.md (also printed).
int certifyRejected(const std::string& dir) {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("rejected_", 0) == 0 && entry.path().extension() == ".txt") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  const std::vector<Problem> all = problems();
  std::ostringstream md;
  md << "| rejected path | waypoints | certified as planned | repaired | certified after repair | FCL ok after |\n";
  md << "|---|--:|--:|--:|--:|--:|\n";
  for (const std::string& file : files) {
    const std::string name = std::filesystem::path(file).filename().string();
    const Problem* problem = nullptr;
    for (const Problem& p : all) {
      if (name.rfind("rejected_" + p.name + "_", 0) == 0 && (problem == nullptr || p.name.size() > problem->name.size())) {
        problem = &p;
      }
    }
    if (problem == nullptr || (problem->needsShared && !haveShared())) {
      std::fprintf(stderr, "plan_bench: %s: no such problem here, skipped\n", name.c_str());
      continue;
    }
    auto world = dp::loadWorld(problem->robotUrdf, problem->scenes, problem->options);
    auto ss = dp::makeSimpleSetup(world, problem->options);
    dp::setStartAndGoal(*ss, problem->start, problem->goal);
    ss->setup();
    std::shared_ptr<FclStateValidityChecker> fcl;
    auto fss = makeFclSetup(*ss, *world, &fcl);
    og::PathGeometric path(ss->getSpaceInformation());
    std::ifstream in(file);
    std::string line;
    ob::ScopedState<> state(ss->getStateSpace());
    while (std::getline(in, line)) {
      std::istringstream values(line);
      std::vector<double> q{std::istream_iterator<double>(values), std::istream_iterator<double>()};
      if (q.empty()) continue;
      dp::copyToState(Eigen::Map<const Eigen::VectorXd>(q.data(), static_cast<Eigen::Index>(q.size())), state.get());
      path.append(state.get());
    }
    const std::size_t waypoints = path.getStateCount();
    const dp::PathCertificate cert = dp::certifyPath(*ss, path);
    const dp::PathCheck after = dp::checkPathFine(path, [&](const Eigen::VectorXd& q) { return fcl->isFree(q); });
    md << "| `" << name << "` | " << waypoints << " | " << (cert.initial.valid ? "yes" : "no") << " | "
       << (cert.repaired ? "yes (" + std::to_string(cert.repair.waypointsPushed) + " pushed, " +
                               std::to_string(cert.repair.statesInserted) + " inserted)"
                         : std::string("no"))
       << " | " << (cert.valid ? "yes" : "no") << " | " << (after.valid ? "yes" : "NO") << " |\n";
  }
  std::cout << md.str();
  std::ofstream(dir + "/plan_bench_certify.md") << md.str();
  return 0;
}

// ---- main -------------------------------------------------------------------------------------

struct Options {
  int runs = 10;
  double time = 5.0;
  std::vector<std::string> problems;
  std::vector<std::string> planners{"RRTConnect", "RRT*", "BIT*", "PRM"};
  std::string out = DEEPCHECK_BENCH_RESULTS_DIR;
  std::uint32_t seed = 1;
};

[[noreturn]] void usage(const std::string& error) {
  if (!error.empty()) std::fprintf(stderr, "plan_bench: %s\n", error.c_str());
  std::fprintf(stderr,
               "usage: plan_bench [--runs N] [--time SECONDS] [--problems a,b] [--planners a,b] [--quick]\n"
               "                  [--out DIR] [--seed S] [--pick-panda-endpoints] [--certify DIR]\n"
               "  --runs N       runs per planner, checker and problem (default 10)\n"
               "  --time S       time limit per run, seconds (default 5)\n"
               "  --problems     table, shelf, narrow_passage, panda_kitchen, panda_table_bars (default all)\n"
               "  --planners     any name deepcheck::planners::makePlanner knows (default RRTConnect,RRT*,BIT*,PRM)\n"
               "  --quick        2 runs of 1 s (overrides --runs and --time)\n"
               "  --out DIR      output folder (default bench/results)\n"
               "  --seed S       OMPL's random seed (default 1)\n"
               "  --pick-panda-endpoints  print how the Panda's start and goal were found, and exit\n"
               "  --certify DIR  certifyPath + fine FCL check of the rejected_*.txt paths in DIR, and exit\n");
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  bool quick = false;
  std::vector<std::string> wantedPlanners;
  std::vector<std::string> wantedProblems;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(arg + " needs a value");
      return argv[++i];
    };
    try {
      if (arg == "--runs") {
        opt.runs = std::stoi(value());
        if (opt.runs < 1) usage("--runs must be at least 1");
      } else if (arg == "--time") {
        opt.time = std::stod(value());
        if (!(opt.time > 0.0)) usage("--time must be positive");
      } else if (arg == "--problems") {
        wantedProblems = splitList(value());
      } else if (arg == "--planners") {
        wantedPlanners = splitList(value());
      } else if (arg == "--quick") {
        quick = true;
      } else if (arg == "--out") {
        opt.out = value();
      } else if (arg == "--seed") {
        opt.seed = static_cast<std::uint32_t>(std::stoul(value()));
      } else if (arg == "--pick-panda-endpoints") {
        return pickPandaEndpoints();
      } else if (arg == "--certify") {
        return certifyRejected(value());
      } else if (arg == "--help" || arg == "-h") {
        usage("");
      } else {
        usage("unknown option '" + arg + "'");
      }
    } catch (const std::logic_error&) {  // stoi / stod
      usage("bad value for " + arg);
    }
  }
  if (quick) {
    opt.runs = 2;
    opt.time = 1.0;
  }

  // Planners: canonical names of makePlanner.
  if (!wantedPlanners.empty()) {
    opt.planners.clear();
    for (const std::string& w : wantedPlanners) {
      try {
        opt.planners.push_back(dp::plannerName(w));
      } catch (const std::invalid_argument& e) {  // names it and lists the known ones
        usage(e.what());
      }
    }
  }
  // Problems.
  std::vector<Problem> all = problems();
  std::vector<Problem> selected;
  if (wantedProblems.empty()) {
    selected = all;
  } else {
    for (const std::string& w : wantedProblems) {
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
      return 1;
    }
  }

  std::filesystem::create_directories(opt.out);
  ompl::RNG::setSeed(opt.seed);
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const std::string loadBefore = uptimeLine();
  const auto wallStart = std::chrono::steady_clock::now();
  std::fprintf(stderr, "plan_bench: %zu problem(s) x 2 checkers x %zu planner(s) x %d run(s), %.3g s each; %s\n",
               selected.size(), opt.planners.size(), opt.runs, opt.time, loadBefore.c_str());

  std::vector<Record> records;
  std::vector<std::string> rejected;
  const char* checkers[] = {"deepcheck", "fcl"};
  for (std::size_t pi = 0; pi < selected.size(); ++pi) {
    const Problem& problem = selected[pi];
    std::shared_ptr<deepcheck::checker::World> world;
    try {
      world = dp::loadWorld(problem.robotUrdf, problem.scenes, problem.options);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "plan_bench: cannot load problem %s: %s\n", problem.name.c_str(), e.what());
      return 1;
    }
    auto ours = dp::makeSimpleSetup(world, problem.options);
    dp::setStartAndGoal(*ours, problem.start, problem.goal);
    const auto ourChecker = dp::validityCheckerOf(*ours);
    std::shared_ptr<FclStateValidityChecker> fclChecker;
    auto fcl = makeFclSetup(*ours, *world, &fclChecker);
    setEndpoints(*fcl, problem.start, problem.goal);
    if (!std::dynamic_pointer_cast<ob::DiscreteMotionValidator>(ours->getSpaceInformation()->getMotionValidator())) {
      std::fprintf(stderr, "plan_bench: our setup's motion validator is not OMPL's discrete one\n");
      return 1;
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
        return 1;
      }
    }
    std::fprintf(stderr, "[%s] resolution %.4g rad (segment fraction %g of extent %.4g), clearance at start %.4f m\n",
                 problem.name.c_str(), ours->getStateSpace()->getLongestValidSegmentLength(),
                 ours->getStateSpace()->getLongestValidSegmentFraction(), ours->getStateSpace()->getMaximumExtent(),
                 ourChecker->clearance(problem.start));

    std::unique_ptr<Bench> benches[2];
    for (int c = 0; c < 2; ++c) {
      og::SimpleSetup& ss = c == 0 ? *ours : *fcl;
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

      // First exact solution time: RRT* and BIT* report intermediate solutions.
      auto runStart = std::make_shared<std::chrono::steady_clock::time_point>();
      auto firstSolution = std::make_shared<std::atomic<double>>(std::nan(""));
      ss.getProblemDefinition()->setIntermediateSolutionCallback(
          [runStart, firstSolution](const ob::Planner*, const std::vector<const ob::State*>&, const ob::Cost) {
            if (std::isnan(firstSolution->load())) {
              firstSolution->store(
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - *runStart).count());
            }
          });
      b.setPreRunEvent([&, runStart, firstSolution, checker, pi](const ob::PlannerPtr& planner) {
        std::fprintf(stderr, "[%zu/%zu %s] %-9s %-10s run %u of %d\n", pi + 1, selected.size(), problem.name.c_str(),
                     checker.c_str(), planner->getName().c_str(), b.getStatus().activeRun + 1, opt.runs);
        firstSolution->store(std::nan(""));
        *runStart = std::chrono::steady_clock::now();
      });
      b.setPostRunEvent([&, firstSolution, checker](const ob::PlannerPtr& planner, ot::Benchmark::RunProperties& run) {
        Record r;
        r.problem = problem.name;
        r.checker = checker;
        r.planner = planner->getName();
        r.time = std::stod(run["time REAL"]);
        r.solved = run["solved BOOLEAN"] == "1" && ss.haveExactSolutionPath();
        if (run.count("graph states INTEGER")) r.graphStates = std::stod(run["graph states INTEGER"]);
        if (r.solved) {
          og::PathGeometric& path = ss.getSolutionPath();
          r.length = path.length();
          r.minClearance = dp::minClearanceAlong(
              path, [&](const Eigen::VectorXd& q) { return ourChecker->clearance(q); });
          const dp::PathCheck check =
              dp::checkPathFine(path, [&](const Eigen::VectorXd& q) { return fclChecker->isFree(q); });
          r.fclVerified = check.valid;
          // The intermediate solution when one was reported (RRT*, BIT*); else the run's time when
          // the planner stopped before the limit (RRTConnect). PRM runs to the limit and reports
          // none: unknown.
          r.firstSolution = firstSolution->load();
          if (std::isnan(r.firstSolution) && !dp::isOptimizingPlanner(planner->getName()) && r.time < 0.95 * opt.time) {
            r.firstSolution = r.time;
          }
          run["min clearance REAL"] = fmt(r.minClearance, "%.17g");
          run["fcl verified BOOLEAN"] = check.valid ? "1" : "0";
          run["fcl invalid motions INTEGER"] = std::to_string(check.invalidMotions);
          run["fcl invalid waypoints INTEGER"] = std::to_string(check.invalidWaypoints);
          if (!std::isnan(r.firstSolution)) run["first solution time REAL"] = fmt(r.firstSolution, "%.17g");
          if (!check.valid) {
            const std::string file = opt.out + "/rejected_" + problem.name + "_" + checker + "_" + r.planner + "_" +
                                     std::to_string(b.getStatus().activeRun + 1) + ".txt";
            dp::writePath(path, file);
            rejected.push_back(file);
            std::fprintf(stderr, "  FCL rejects the path (%d invalid waypoints, %d invalid motions, first at %d): %s\n",
                         check.invalidWaypoints, check.invalidMotions, check.firstInvalidMotion, file.c_str());
          }
        }
        std::fprintf(stderr, "  %s in %.3f s%s\n", r.solved ? "solved" : "NOT solved", r.time,
                     r.solved ? (", length " + fmt(r.length) + ", min clearance " + fmt(r.minClearance) + " m" +
                                 (r.fclVerified ? ", FCL ok" : ", FCL REJECTS"))
                                    .c_str()
                              : "");
        records.push_back(r);
      });
      ot::Benchmark::Request req(opt.time, 4096.0, static_cast<unsigned>(opt.runs));
      req.displayProgress = false;
      req.saveConsoleOutput = false;
      b.benchmark(req);
    }
    // One log per problem: both checkers' planners in one experiment.
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
    const std::string log = opt.out + "/plan_bench_" + problem.name + ".log";
    if (!benches[0]->saveResultsToFile(log.c_str())) {
      std::fprintf(stderr, "plan_bench: cannot write %s\n", log.c_str());
      return 1;
    }
    std::fprintf(stderr, "wrote %s\n", log.c_str());
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
  const std::string loadAfter = uptimeLine();

  // ---- summary ----
  std::vector<Row> rows;
  for (const Problem& p : selected) {
    for (const char* c : checkers) {
      std::vector<std::string> names;
      for (const Record& r : records) {
        if (r.problem == p.name && r.checker == c && std::find(names.begin(), names.end(), r.planner) == names.end()) {
          names.push_back(r.planner);
        }
      }
      for (const std::string& n : names) rows.push_back(summarize(records, p.name, c, n));
    }
  }
  {
    std::ofstream csv(opt.out + "/plan_bench.csv");
    csv << "problem,checker,planner,runs,success_pct,median_time_s,median_first_solution_s,median_length,"
           "median_min_clearance_m,fcl_verified_pct,median_graph_states\n";
    for (const Row& r : rows) {
      csv << r.problem << ',' << r.checker << ',' << r.planner << ',' << r.runs << ',' << fmt(r.successPct(), "%.1f")
          << ',' << fmt(r.tMed, "%.4g") << ',' << fmt(r.firstMed, "%.4g") << ',' << fmt(r.lengthMed, "%.4g") << ','
          << fmt(r.clearanceMed, "%.4g") << ',' << fmt(r.verifiedPct(), "%.1f") << ',' << fmt(r.statesMed, "%.0f")
          << '\n';
    }
  }
  std::ostringstream md;
  md << "# Planning benchmark (plan_bench)\n\n";
  md << "Runs per planner, checker and problem: " << opt.runs << ", time limit " << opt.time << " s, OMPL seed "
     << opt.seed << ". Wall time " << fmt(wall / 60.0, "%.1f") << " min.\n\n";
  md << "Load before: `" << loadBefore << "`  \nLoad after: `" << loadAfter << "`\n\n";
  md << "success = exact solution within the time limit; medians over all runs (time) or the solved runs (the "
        "rest); first = time to the first exact solution; length = joint-space length of the simplified path "
        "(rad); clearance = minimum of our signed distance along the simplified path every "
     << dp::tol::kFineResolution
     << " rad (m); FCL ok = solved runs whose simplified path FCL finds free at that resolution; states = graph "
        "states.\n\n";
  md << "| problem | checker | planner | runs | success | time (s) | first (s) | length | clearance (m) | FCL ok | "
        "states |\n";
  md << "|---|---|---|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const Row& r : rows) {
    md << "| " << r.problem << " | " << r.checker << " | " << r.planner << " | " << r.runs << " | "
       << fmt(r.successPct(), "%.0f") << " % | " << fmt(r.tMed, "%.3g") << " | " << fmt(r.firstMed, "%.3g") << " | "
       << fmt(r.lengthMed, "%.3g") << " | " << fmt(r.clearanceMed, "%.3f") << " | "
       << (std::isnan(r.verifiedPct()) ? std::string("-") : fmt(r.verifiedPct(), "%.0f") + " %") << " | "
       << fmt(r.statesMed, "%.0f") << " |\n";
  }
  md << "\nStart and goal:\n\n";
  for (const Problem& p : selected) md << "- " << p.name << ": " << p.note << "\n";
  if (!rejected.empty()) {
    md << "\nPaths rejected by the FCL check (" << rejected.size() << "):\n\n";
    for (const std::string& f : rejected) md << "- `" << std::filesystem::path(f).filename().string() << "`\n";
  }
  std::cout << md.str();
  std::ofstream(opt.out + "/plan_bench.md") << md.str();
  std::fprintf(stderr, "wrote %s/plan_bench.csv and plan_bench.md\n", opt.out.c_str());

  // ---- plot ----
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    const std::string cmd = "gnuplot -e \"csv='" + opt.out + "/plan_bench.csv'; outdir='" + opt.out + "'\" '" +
                            std::string(DEEPCHECK_BENCH_DIR) + "/plan_plots.gp'";
    if (std::system(cmd.c_str()) == 0) {
      std::fprintf(stderr, "wrote %s/plan_bench_time.png\n", opt.out.c_str());
    } else {
      std::fprintf(stderr, "plan_bench: gnuplot failed (%s)\n", cmd.c_str());
    }
  } else {
    std::fprintf(stderr, "plan_bench: gnuplot not found, no plot\n");
  }
  return 0;
}
