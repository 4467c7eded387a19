// checker_bench: speed and agreement of the collision world (deepcheck::checker) against the FCL
// mesh backend (fcl_reference/fcl_backend.h) on the same worlds:
//   - Panda (../shared) in the bundled shelf scene (robots/data/scenes/shelf.urdf),
//   - Panda in the MotionBenchMaker kitchen (../shared/scenes),
//   - the bundled arm in the bundled shelf (runs without ../shared).
// Query sets: uniformly random configurations within the limits, and short motions (straight
// segments of 0.3 rad total length cut into steps of 0.01 rad, what a motion validator checks).
// Measured: isFree (ours, and FCL's boolean collide on the original meshes), signedDistance with
// gradient (ours) and FCL's mesh distance, per-query medians; throughput with 1 and 2 threads;
// the broad phases (static AABB tree, FCL's dynamic AABB tree, none); agreement with FCL on random
// configurations (FCL colliding but reported free must be 0; false alarms counted with their FCL
// distance against the pair tolerance, twice the world's geometry excess); forward kinematics
// alone (a floor under both backends: each poses every link); an empty call (the clock reads in
// every per-query time).
//
// Timing: per-query steady_clock times; each set is timed in 3 rounds and the round with the
// lowest median is kept (the machine is shared; other processes only add time).
// Output: a table on stdout and bench/results/checker_bench.csv.
// --batch: isFreeBatch (8 configurations per call; its AVX2 build where the processor has it, and
// its baseline build) against 8 isFree calls on the same states, per state: on the random set in
// batches of 8, and on 8 states spread along straight motions between two random free
// configurations (a planner's motion check); a table on stdout and
// bench/results/checker_bench_batch.csv.
// Usage: checker_bench [--quick] [--isfree | --batch] [--repeat N] [--world W]
//   --quick     1,000 random configurations and 30 motions instead of 10,000 and 300;
//   --isfree    only the empty call, forward kinematics and isFree (ours and FCL's); the CSV is
//               not written;
//   --repeat N  with --isfree: then run our isFree over both sets N more times, untimed (a
//               steady load for `perf record`);
//   --world W   only the world named W (panda-shelf, panda-kitchen, arm-shelf).

#include "format.h"

#include "batch_kinematics.h"
#include "world_internal.h"

#include "deepcheck/fcl_reference/fcl_backend.h"
#include "deepcheck/fcl_reference/fcl_broad_phase.h"
#include "deepcheck/checker/world.h"
#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/robot_model.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numeric>
#include <random>
#include <string>
#include <thread>
#include <vector>

using namespace deepcheck;
using Clock = std::chrono::steady_clock;

namespace {

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * (v.size() - 1))];
}

struct Row {
  std::string world, query, set, backend;
  double median = 0, p90 = 0, average = 0;
  std::size_t count = 0;
  std::string note;
};

std::vector<Row> rows;

void addTimes(const std::string& world, const std::string& query, const std::string& set, const std::string& backend,
              const std::vector<double>& us, const std::string& note = "") {
  rows.push_back(
      {world, query, set, backend, percentile(us, 0.5), percentile(us, 0.9), bench::mean(us), us.size(), note});
  std::printf("  %-10s %-8s %-22s median %8.2f us  p90 %8.2f us  mean %8.2f us  (%zu)%s%s\n", query.c_str(),
              set.c_str(), backend.c_str(), rows.back().median, rows.back().p90, rows.back().average, us.size(),
              note.empty() ? "" : "  ", note.c_str());
}

/// Rounds per timing: the machine is shared, so each set is timed this many times and the round
/// with the lowest median is kept (load from other processes only ever adds time).
constexpr int kRounds = 3;

/// Per-call times in microseconds, of the best of kRounds rounds over `qs`.
template <class F>
std::vector<double> timeEach(const std::vector<Eigen::VectorXd>& qs, F&& f) {
  std::vector<double> best;
  for (int round = 0; round < kRounds; ++round) {
    std::vector<double> us;
    us.reserve(qs.size());
    for (const Eigen::VectorXd& q : qs) {
      const auto t0 = Clock::now();
      f(q);
      us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
    }
    if (best.empty() || percentile(us, 0.5) < percentile(best, 0.5)) best = std::move(us);
  }
  return best;
}

Eigen::VectorXd randomConfiguration(const robots::RobotModel& m, std::mt19937& rng) {
  Eigen::VectorXd q(m.numVariables());
  for (int v = 0; v < q.size(); ++v) {
    q[v] = std::uniform_real_distribution<double>(m.lowerLimits()[v], m.upperLimits()[v])(rng);
  }
  return q;
}

/// Short motions: from a random start, a random direction, 30 steps of 0.01 rad (0.3 rad).
std::vector<Eigen::VectorXd> shortMotions(const robots::RobotModel& m, int motions, std::mt19937& rng) {
  std::vector<Eigen::VectorXd> out;
  std::normal_distribution<double> n(0.0, 1.0);
  for (int k = 0; k < motions; ++k) {
    Eigen::VectorXd q = randomConfiguration(m, rng);
    Eigen::VectorXd d(q.size());
    for (int v = 0; v < d.size(); ++v) d[v] = n(rng);
    d /= d.norm();
    for (int s = 0; s <= 30; ++s) {
      Eigen::VectorXd x = q + 0.01 * s * d;
      x = x.cwiseMax(m.lowerLimits()).cwiseMin(m.upperLimits());
      out.push_back(x);
    }
  }
  return out;
}

struct WorldSpec {
  std::string name;
  std::string robot;
  std::vector<std::string> packageRoots;
  std::string srdf;
  std::string scene;
};

double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

struct Throughput {
  double wall = 0.0;  ///< queries per second of wall-clock time
  double cpu = 0.0;   ///< queries per second of CPU time, summed over the threads
};

/// Throughput of `perQuery` over `qs` split between `threads` threads, each with its own context.
/// On a loaded machine the wall-clock rate cannot scale (the threads get no extra core); the rate
/// per CPU-second shows whether the threads slow each other down (contention, false sharing).
/// The set is run `repeat` times so that a run lasts long enough (about a second) for the
/// scheduler to give each thread a core.
Throughput throughput(
    const checker::World& world, const std::vector<Eigen::VectorXd>& qs, int threads, int repeat,
    const std::function<void(const checker::World&, checker::World::Context&, const Eigen::VectorXd&)>& perQuery) {
  std::vector<std::thread> pool;
  std::vector<double> cpu(threads, 0.0);
  const auto t0 = Clock::now();
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      auto context = world.makeContext();
      const double c0 = threadCpuSeconds();
      for (int r = 0; r < repeat; ++r) {
        for (std::size_t i = t; i < qs.size(); i += threads) perQuery(world, context, qs[i]);
      }
      cpu[t] = threadCpuSeconds() - c0;
    });
  }
  for (std::thread& th : pool) th.join();
  const double total = static_cast<double>(qs.size()) * repeat;
  Throughput r;
  r.wall = total / std::chrono::duration<double>(Clock::now() - t0).count();
  r.cpu = total / std::accumulate(cpu.begin(), cpu.end(), 0.0);
  return r;
}

struct RunOptions {
  int samples = 10000;
  int motions = 300;
  bool isFreeOnly = false;
  bool batch = false;
  int repeat = 0;
  std::string world;  ///< only this world when not empty
};

/// One world of the benchmark, with the FCL backend on the same robot and scene, and its query
/// sets.
struct BenchWorld {
  const WorldSpec& spec;
  robots::LoadOptions load;
  robots::RobotModel robot;
  checker::WorldOptions options;
  checker::World world;
  fcl_reference::FclWorld fcl;
  std::vector<Eigen::VectorXd> random;
  std::vector<Eigen::VectorXd> motion;

  /// The two query sets, named.
  std::vector<std::pair<std::string, const std::vector<Eigen::VectorXd>*>> sets() const {
    return {{"random", &random}, {"motions", &motion}};
  }
};

robots::LoadOptions loadOptions(const WorldSpec& spec) {
  robots::LoadOptions load;
  load.packageRoots = spec.packageRoots;
  load.useRosPackagePath = false;
  return load;
}

checker::WorldOptions worldOptions(const WorldSpec& spec) {
  checker::WorldOptions options;
  if (!spec.srdf.empty()) options.disabledPairs = robots::readSrdfDisabledPairs(spec.srdf);
  return options;
}

/// Empty call, forward kinematics, and isFree of both backends over both sets.
void timeIsFree(BenchWorld& b) {
  // An empty call: what the two clock reads add to every per-query time below.
  addTimes(b.spec.name, "clock", "random", "empty call", timeEach(b.random, [](const Eigen::VectorXd&) {}));
  // Forward kinematics alone: a floor under both backends' isFree (both pose every link).
  {
    std::vector<Eigen::Isometry3d> X_WL;
    addTimes(
        b.spec.name, "kinematics", "random", "robots::forwardKinematics",
        timeEach(b.random, [&](const Eigen::VectorXd& q) { robots::forwardKinematics(b.world.robot(), q, X_WL); }));
  }
  // isFree: ours (one context, warm starts across the set, as a planner thread has) and FCL's.
  for (const auto& [setName, qs] : b.sets()) {
    auto context = b.world.makeContext();
    int freeCount = 0;
    const std::vector<double> ours =
        timeEach(*qs, [&](const Eigen::VectorXd& q) { freeCount += b.world.isFree(q, context); });
    freeCount /= kRounds;
    const std::vector<double> theirs = timeEach(*qs, [&](const Eigen::VectorXd& q) { b.fcl.isFree(q); });
    const double ratio = percentile(theirs, 0.5) / percentile(ours, 0.5);
    char note[128];
    std::snprintf(note, sizeof note, "free %.1f %%, FCL/ours %.1fx", 100.0 * freeCount / qs->size(), ratio);
    addTimes(b.spec.name, "isFree", setName, "deepcheck", ours, note);
    addTimes(b.spec.name, "isFree", setName, "fcl-mesh", theirs);
  }
}

/// --isfree: `repeat` untimed rounds of isFree, then what one query does on average.
void isFreeWork(const BenchWorld& b, int repeat) {
  auto context = b.world.makeContext();
  std::size_t freeCount = 0;
  for (int r = 0; r < repeat; ++r) {
    for (const Eigen::VectorXd& q : b.random) freeCount += b.world.isFree(q, context);
    for (const Eigen::VectorXd& q : b.motion) freeCount += b.world.isFree(q, context);
  }
  if (repeat > 0) std::printf("  (%d more untimed rounds of isFree, %zu free)\n", repeat, freeCount);
  for (const auto& [setName, qs] : b.sets()) {
    auto counted = b.world.makeContext();
    for (const Eigen::VectorXd& q : *qs) b.world.isFree(q, counted);
    const checker::QueryStats& st = counted.stats();
    const double n = static_cast<double>(st.queries);
    std::printf(
        "  isFree %-8s per query: %.2f link candidates, %.2f piece tests, %.2f narrow phase (%.2f self), "
        "%.2f self pairs in a certified-free cell, %.2f overlaps decided by a centroid inside a world piece\n",
        setName.c_str(), st.linkCandidates / n, st.pieceTests / n, st.narrowPhase / n, st.selfNarrowPhase / n,
        st.certifiedSelf / n, st.centroidInside / n);
  }
}

/// signedDistance with gradient (ours), FCL distance (boolean, then distance when free).
void timeDistance(BenchWorld& b, const checker::DistanceOptions& withGradient) {
  for (const auto& [setName, qs] : b.sets()) {
    auto context = b.world.makeContext();
    const std::vector<double> ours =
        timeEach(*qs, [&](const Eigen::VectorXd& q) { b.world.signedDistance(q, context, withGradient); });
    addTimes(b.spec.name, "sd+grad", setName, "deepcheck", ours);
    std::vector<Eigen::VectorXd> subset(qs->begin(), qs->begin() + std::min<std::size_t>(qs->size(), 2000));
    std::vector<double> theirs;  // one round: milliseconds per call
    for (const Eigen::VectorXd& q : subset) {
      const auto t0 = Clock::now();
      b.fcl.distance(q);
      theirs.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
    }
    addTimes(b.spec.name, "distance", setName, "fcl-mesh (no depth)", theirs);
  }
}

/// isFree and signedDistance over the random set with each broad phase.
void timeBroadPhases(const BenchWorld& b, const checker::DistanceOptions& withGradient) {
  for (int phase = 0; phase < 3; ++phase) {
    checker::WorldOptions o = b.options;
    if (phase == 1) o.externalBroadPhase = fcl_reference::fclBroadPhase();
    if (phase == 2) o.broadPhase = checker::BroadPhase::None;
    const std::string name = phase == 1 ? o.externalBroadPhase->name() : checker::toString(o.broadPhase);
    checker::World w(b.robot, o);
    w.addScene(robots::RobotModel::fromUrdfFile(b.spec.scene, b.load));
    auto context = w.makeContext();
    addTimes(b.spec.name, "isFree", "random", "broad phase " + name,
             timeEach(b.random, [&](const Eigen::VectorXd& q) { w.isFree(q, context); }));
    auto sdContext = w.makeContext();
    addTimes(b.spec.name, "sd+grad", "random", "broad phase " + name,
             timeEach(b.random, [&](const Eigen::VectorXd& q) { w.signedDistance(q, sdContext, withGradient); }));
  }
}

/// Throughput of isFree and signedDistance with 1 and 2 threads.
void timeThroughput(const BenchWorld& b, const checker::DistanceOptions& withGradient) {
  for (int threads : {1, 2}) {
    const Throughput isFreeRate = throughput(
        b.world, b.random, threads, 40,
        [](const checker::World& w, checker::World::Context& c, const Eigen::VectorXd& q) { w.isFree(q, c); });
    const Throughput sdRate = throughput(b.world, b.random, threads, 6,
                                         [&](const checker::World& w, checker::World::Context& c,
                                             const Eigen::VectorXd& q) { w.signedDistance(q, c, withGradient); });
    std::printf(
        "  throughput %d thread%s: isFree %.0f /s (%.0f per CPU-second), sd+grad %.0f /s (%.0f per CPU-second)\n",
        threads, threads > 1 ? "s" : " ", isFreeRate.wall, isFreeRate.cpu, sdRate.wall, sdRate.cpu);
    for (const auto& [query, rate] : {std::pair<std::string, Throughput>{"isFree", isFreeRate}, {"sd+grad", sdRate}}) {
      rows.push_back({b.spec.name, query, "random", "throughput " + std::to_string(threads) + " thread(s)", 0, 0, 0,
                      b.random.size(),
                      std::to_string(static_cast<long long>(rate.wall)) + " /s wall, " +
                          std::to_string(static_cast<long long>(rate.cpu)) + " /s per CPU-second"});
    }
  }
}

/// Agreement with FCL on the random set.
void agreement(BenchWorld& b) {
  const double tolerance = 2 * b.world.summaryCounts().geometryExcess;
  auto context = b.world.makeContext();
  int fclColliding = 0, missed = 0, falseAlarms = 0, beyond = 0;
  double worst = 0.0;
  for (const Eigen::VectorXd& q : b.random) {
    const bool ours = b.world.isFree(q, context);
    const bool theirs = b.fcl.isFree(q);
    fclColliding += !theirs;
    missed += !theirs && ours;
    if (theirs && !ours) {
      ++falseAlarms;
      const double d = b.fcl.distance(q).distance;
      worst = std::max(worst, d);
      beyond += d > tolerance;
    }
  }
  char note[256];
  std::snprintf(note, sizeof note,
                "FCL colliding %d; missed (FCL colliding, ours free) %d; false alarms %d (largest FCL distance "
                "%.4g m, tolerance 2 x excess = %.4g m, beyond it %d)",
                fclColliding, missed, falseAlarms, worst, tolerance, beyond);
  std::printf("  agreement on %zu random configurations: %s\n", b.random.size(), note);
  rows.push_back({b.spec.name, "agreement", "random", "deepcheck vs fcl-mesh", 0, 0, 0, b.random.size(), note});
}

// --- --batch --------------------------------------------------------------------------------

struct BatchRow {
  std::string world, set, method;
  double median = 0, p90 = 0, mean = 0;  ///< ns per state (a batch's time / 8)
  std::size_t batches = 0;
  double certifiedPercent = 0;  ///< isFreeBatch: states its bound stage certified free
  double freePercent = 0;
};

std::vector<BatchRow> batchRows;

/// `motions` straight motions between two random free configurations, 8 states spread along
/// each ((k + 0.5) / 8 of the way, k = 0..7), one matrix per motion.
std::vector<Eigen::MatrixXd> motionBatches(const checker::World& world, int motions, std::mt19937& rng) {
  const robots::RobotModel& m = world.robot();
  auto freeConfiguration = [&] {
    for (;;) {
      Eigen::VectorXd q = randomConfiguration(m, rng);
      if (world.isFree(q)) return q;
    }
  };
  std::vector<Eigen::MatrixXd> out;
  for (int k = 0; k < motions; ++k) {
    const Eigen::VectorXd a = freeConfiguration();
    const Eigen::VectorXd b = freeConfiguration();
    Eigen::MatrixXd qs(m.numVariables(), 8);
    for (int s = 0; s < 8; ++s) qs.col(s) = a + (s + 0.5) / 8.0 * (b - a);
    out.push_back(std::move(qs));
  }
  return out;
}

/// The random set in matrices of 8 columns.
std::vector<Eigen::MatrixXd> randomBatches(const std::vector<Eigen::VectorXd>& qs) {
  std::vector<Eigen::MatrixXd> out;
  for (std::size_t first = 0; first + 8 <= qs.size(); first += 8) {
    Eigen::MatrixXd m(qs[first].size(), 8);
    for (int l = 0; l < 8; ++l) m.col(l) = qs[first + l];
    out.push_back(std::move(m));
  }
  return out;
}

/// Nanoseconds per state of `check` (one batch of 8 per call, writing 8 answers), best of kRounds
/// rounds by median; the answers of the last round in `answers`.
template <class F>
std::vector<double> timeBatches(const std::vector<Eigen::MatrixXd>& batches, std::vector<char>& answers, F&& check) {
  std::vector<double> best;
  answers.assign(batches.size() * 8, 0);
  for (int round = 0; round < kRounds; ++round) {
    std::vector<double> ns;
    ns.reserve(batches.size());
    for (std::size_t i = 0; i < batches.size(); ++i) {
      bool free[8];
      const auto t0 = Clock::now();
      check(batches[i], free);
      ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / 8.0);
      for (int l = 0; l < 8; ++l) answers[i * 8 + l] = free[l];
    }
    if (best.empty() || percentile(ns, 0.5) < percentile(best, 0.5)) best = std::move(ns);
  }
  return best;
}

void addBatchRow(const BenchWorld& b, const std::string& set, const std::string& method, const std::vector<double>& ns,
                 const std::vector<char>& answers, double certifiedPercent) {
  const double freePercent = 100.0 * std::count(answers.begin(), answers.end(), 1) / answers.size();
  batchRows.push_back({b.spec.name, set, method, percentile(ns, 0.5), percentile(ns, 0.9), bench::mean(ns), ns.size(),
                       certifiedPercent, freePercent});
  const BatchRow& r = batchRows.back();
  std::printf("  %-8s %-26s per state: median %7.1f ns  p90 %7.1f ns  mean %7.1f ns  free %5.1f %%", set.c_str(),
              method.c_str(), r.median, r.p90, r.mean, r.freePercent);
  if (certifiedPercent >= 0) std::printf("  certified by the bound stage %5.1f %%", certifiedPercent);
  std::printf("\n");
}

/// Forward kinematics alone: 8 robots::forwardKinematics calls against the batch's (its floor).
void timeBatchKinematics(const BenchWorld& b, const std::vector<Eigen::MatrixXd>& batches) {
  std::vector<char> unused;
  std::vector<Eigen::Isometry3d> X_WL;
  addBatchRow(b, "random", "8 x forwardKinematics",
              timeBatches(batches, unused,
                          [&](const Eigen::MatrixXd& qs, bool* free) {
                            for (int l = 0; l < 8; ++l) robots::forwardKinematics(b.world.robot(), qs.col(l), X_WL);
                            std::fill(free, free + 8, false);
                          }),
              unused, -1);
  const checker::detail::RobotData& robot = *b.world.internalState()->robot;
  if (checker::detail::batchAvx2Available()) {
    checker::detail::BatchPosesT<checker::detail::Avx2Lanes> poses;
    addBatchRow(b, "random", "batch kinematics (AVX2)",
                timeBatches(batches, unused,
                            [&](const Eigen::MatrixXd& qs, bool* free) {
                              checker::detail::batchForwardKinematics(robot, qs, poses);
                              std::fill(free, free + 8, false);
                            }),
                unused, -1);
  }
  checker::detail::BatchPosesT<checker::detail::BaselineLanes> poses;
  addBatchRow(b, "random", "batch kinematics (baseline)",
              timeBatches(batches, unused,
                          [&](const Eigen::MatrixXd& qs, bool* free) {
                            checker::detail::batchForwardKinematics(robot, qs, poses);
                            std::fill(free, free + 8, false);
                          }),
              unused, -1);
}

/// isFreeBatch (AVX2 and baseline builds) against 8 isFree calls, on the random set and on
/// `motions` motions of 8 states; every answer compared.
void timeBatch(BenchWorld& b, int motions, std::mt19937& rng) {
  const std::vector<std::pair<std::string, std::vector<Eigen::MatrixXd>>> sets = {
      {"random", randomBatches(b.random)}, {"motion8", motionBatches(b.world, motions, rng)}};
  std::atomic<bool>& baseline = b.world.internalState()->batchBaseline;
  timeBatchKinematics(b, sets.front().second);
  for (const auto& [setName, batches] : sets) {
    std::vector<char> reference, answers;
    auto scalarContext = b.world.makeContext();
    const std::vector<double> scalar = timeBatches(batches, reference, [&](const Eigen::MatrixXd& qs, bool* free) {
      for (int l = 0; l < 8; ++l) free[l] = b.world.isFree(qs.col(l), scalarContext);
    });
    addBatchRow(b, setName, "8 x isFree", scalar, reference, -1);
    for (bool useBaseline : {false, true}) {
      if (!useBaseline && !checker::detail::batchAvx2Available()) continue;
      baseline = useBaseline;
      auto context = b.world.makeContext();
      const std::vector<double> ns = timeBatches(
          batches, answers, [&](const Eigen::MatrixXd& qs, bool* free) { b.world.isFreeBatch(qs, free, context); });
      const checker::QueryStats& st = context.stats();
      const double certified = 100.0 * st.batchCertified / (kRounds * batches.size() * 8.0);
      addBatchRow(b, setName, useBaseline ? "isFreeBatch (baseline)" : "isFreeBatch (AVX2)", ns, answers, certified);
      if (answers != reference) std::printf("  ERROR: isFreeBatch and isFree disagree\n");
    }
    baseline = false;
  }
}

void writeBatchCsv() {
  const std::string dir = DEEPCHECK_BENCH_RESULTS_DIR;
  std::filesystem::create_directories(dir);
  std::ofstream csv(dir + "/checker_bench_batch.csv");
  csv << "world,set,method,median_ns_per_state,p90_ns_per_state,mean_ns_per_state,batches,certified_percent,"
         "free_percent\n";
  for (const BatchRow& r : batchRows) {
    csv << r.world << ',' << r.set << ',' << r.method << ',' << r.median << ',' << r.p90 << ',' << r.mean << ','
        << r.batches << ',' << (r.certifiedPercent >= 0 ? std::to_string(r.certifiedPercent) : "") << ','
        << r.freePercent << '\n';
  }
  std::printf("wrote %s/checker_bench_batch.csv\n", dir.c_str());
}

void runWorld(const WorldSpec& spec, const RunOptions& run) {
  const robots::LoadOptions load = loadOptions(spec);
  robots::RobotModel robot = robots::RobotModel::fromUrdfFile(spec.robot, load);
  const checker::WorldOptions options = worldOptions(spec);
  const auto tLoad = Clock::now();
  checker::World world(robot, options);
  world.addScene(robots::RobotModel::fromUrdfFile(spec.scene, load));
  const double loadSeconds = std::chrono::duration<double>(Clock::now() - tLoad).count();
  fcl_reference::FclWorld fcl(world);
  std::printf("\n== %s  (world loaded in %.2f s, decomposition cache included)\n%s", spec.name.c_str(), loadSeconds,
              world.summary().c_str());
  BenchWorld b{spec, load, std::move(robot), options, std::move(world), std::move(fcl), {}, {}};

  std::mt19937 rng(2024);
  for (int i = 0; i < run.samples; ++i) b.random.push_back(randomConfiguration(b.world.robot(), rng));
  b.motion = shortMotions(b.world.robot(), run.motions, rng);

  if (run.batch) {
    timeBatch(b, run.samples / 8, rng);
    return;
  }
  timeIsFree(b);
  if (run.isFreeOnly) {
    isFreeWork(b, run.repeat);
    return;
  }
  checker::DistanceOptions withGradient;
  withGradient.gradient = true;
  timeDistance(b, withGradient);
  timeBroadPhases(b, withGradient);
  timeThroughput(b, withGradient);
  agreement(b);
}

}  // namespace

int main(int argc, char** argv) {
  RunOptions run;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      run.samples = 1000;
      run.motions = 30;
    } else if (arg == "--isfree") {
      run.isFreeOnly = true;
    } else if (arg == "--batch") {
      run.batch = true;
    } else if (arg == "--repeat" && i + 1 < argc) {
      run.repeat = std::stoi(argv[++i]);
    } else if (arg == "--world" && i + 1 < argc) {
      run.world = argv[++i];
    } else {
      std::fprintf(stderr, "usage: checker_bench [--quick] [--isfree | --batch] [--repeat N] [--world NAME]\n");
      return 2;
    }
  }
  const int samples = run.samples;
  const int motions = run.motions;
  const std::string shared = DEEPCHECK_SHARED_DIR;
  const std::string data = std::string(DEEPCHECK_SOURCE_DIR) + "/robots/data";
  std::printf("checker_bench: %d random configurations, %d short motions (31 states each)\n", samples, motions);
  std::vector<WorldSpec> worlds;
  const bool haveShared = std::filesystem::is_directory(shared + "/robots/panda");
  if (haveShared) {
    const std::string panda = shared + "/robots/panda/moveit_resources_panda_description/urdf/panda.urdf";
    const std::string srdf = shared + "/robots/panda/moveit_resources_panda_moveit_config/config/panda.srdf";
    worlds.push_back({"panda-shelf", panda, {shared + "/robots/panda"}, srdf, data + "/scenes/shelf.urdf"});
    worlds.push_back({"panda-kitchen",
                      panda,
                      {shared + "/robots/panda", shared + "/scenes"},
                      srdf,
                      shared + "/scenes/motion_bench_maker/configs/scenes/kitchen/kitchen.urdf"});
  } else {
    std::printf("(../shared absent: the Panda worlds are skipped)\n");
  }
  worlds.push_back({"arm-shelf",
                    data + "/deepcheck_arm/urdf/deepcheck_arm.urdf",
                    {data},
                    data + "/deepcheck_arm/srdf/deepcheck_arm.srdf",
                    data + "/scenes/shelf.urdf"});
  for (const WorldSpec& w : worlds) {
    if (run.world.empty() || run.world == w.name) runWorld(w, run);
  }
  if (run.isFreeOnly) return 0;
  if (run.batch) {
    writeBatchCsv();
    return 0;
  }

  const std::string dir = DEEPCHECK_BENCH_RESULTS_DIR;
  std::filesystem::create_directories(dir);
  std::ofstream csv(dir + "/checker_bench.csv");
  csv << "world,query,set,backend,median_us,p90_us,mean_us,count,note\n";
  for (const Row& r : rows) {
    csv << r.world << ',' << r.query << ',' << r.set << ',' << r.backend << ',' << r.median << ',' << r.p90 << ','
        << r.average << ',' << r.count << ",\"" << r.note << "\"\n";
  }
  std::printf("wrote %s/checker_bench.csv\n", dir.c_str());
  return 0;
}
