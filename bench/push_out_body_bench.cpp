// push_out_body_bench: the push-out (planners/push_out.h) with the pairwise depth against the body
// depth (PushOutOptions::bodyDepth) with its default cap on a body query's cost and without a cap,
// on hard cases where the deepest pair points sideways and on random starts of the bundled arm.
//
// Hard cases (tests/common/body_cases.h): a gantry (x, y, z, then z and y rotations) carrying a box
// tool 0.06 x 0.1 x 0.1,
//   slab  pressed into a slab of two touching boxes (one scene link), its centre x in {0, 0.002,
//         0.005, 0.01, 0.015, 0.02} m off the seam, its bottom {0.01, 0.02, 0.03, 0.04, 0.045} m
//         deep, and the tool turned about z by {0, 0.3} rad;
//   U     lowered into a U of three boxes (one scene link) whose channel is 0.01 narrower than the
//         tool, centre x in {0, 0.001, 0.002, 0.004}, {0.01, 0.02, 0.03, 0.04} m below the walls'
//         top, turned by {0, 0.3} rad.
// Bundled: repair_bench's starts, 100 seeded random configurations of the bundled arm per bundled
// scene (table, shelf, narrow_passage) with signed distance in [-2 cm, 0); and 200 in the shelf
// as deep as the push-out starts from ([-5 cm, 0)), where body queries between links of many
// pieces are costly.
// Printed per family and option: starts, repaired, repaired in one iteration, mean iterations
// (over the repaired), mean joint motion (over the starts every option repaired), and the
// push-out's time per start (median, 99th percentile, largest); the same rows go to the CSV.
// Usage: push_out_body_bench [--each] [--csv FILE] (about half a minute; the CSV defaults to
// bench/results/push_out_body_bench.csv, run from the source tree); --each also prints every start
// of the hard cases with the iterations of the pairwise and the capped body push-out (0: not
// repaired).

#include "../tests/common/body_cases.h"
#include "csv_out.h"
#include "repair_starts.h"

#include "deepcheck/planners/push_out.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/validity.h"
#include "deepcheck/robots/random_configuration.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace dc = deepcheck::checker;
namespace dp = deepcheck::planners;
namespace dt = deepcheck::test;

namespace {

struct Tally {
  int starts = 0;
  int repaired = 0;
  int oneStep = 0;
  long iterations = 0;
  double motion = 0.0;          // over the starts every option repaired
  std::vector<double> seconds;  // per start
};

/// The compared push-outs: pairwise depth, body depth with the default cap on a body query's
/// cost, and body depth without a cap.
struct Variant {
  const char* name;
  dp::PushOutOptions options;
};

std::vector<Variant> variants() {
  Variant pairwise{"pairwise", {}};
  pairwise.options.bodyDepth = false;
  Variant body{"body", {}};
  Variant uncapped{"body-nocap", {}};
  uncapped.options.bodyBuildCost = std::numeric_limits<double>::infinity();
  return {pairwise, body, uncapped};
}

std::string format(const Eigen::VectorXd& q) {
  std::string out;
  char buf[32];
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%s%.3f", i ? " " : "", q[i]);
    out += buf;
  }
  return out;
}

double quantile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

void print(const std::string& family, const char* option, const Tally& t, int all, std::FILE* csv) {
  const double meanIterations = t.repaired ? static_cast<double>(t.iterations) / t.repaired : 0.0;
  const double motion = all ? t.motion / all : 0.0;
  const double median = 1e3 * quantile(t.seconds, 0.5), p99 = 1e3 * quantile(t.seconds, 0.99);
  const double worst = 1e3 * quantile(t.seconds, 1.0);
  std::printf("%-18s %-10s %6d %8d %8d %10.2f %12.4f %9.3f %9.2f %9.2f\n", family.c_str(), option, t.starts, t.repaired,
              t.oneStep, meanIterations, motion, median, p99, worst);
  if (csv) {
    std::fprintf(csv, "%s,%s,%d,%d,%d,%.4f,%.6f,%.4f,%.4f,%.4f\n", family.c_str(), option, t.starts, t.repaired,
                 t.oneStep, meanIterations, motion, median, p99, worst);
  }
}

void run(const std::string& family, const std::shared_ptr<const dc::World>& world,
         const std::vector<Eigen::VectorXd>& starts, bool each, std::FILE* csv) {
  const std::vector<Variant> vs = variants();
  std::vector<dp::PushOut> pushOuts;
  for (const Variant& v : vs) pushOuts.emplace_back(world, dp::ValidityOptions{}, v.options);
  std::vector<Tally> tallies(vs.size());
  int all = 0;
  for (const Eigen::VectorXd& q : starts) {
    std::vector<dp::PushOutResult> results;
    for (std::size_t k = 0; k < vs.size(); ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      results.push_back(pushOuts[k].run(q));
      tallies[k].seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      const dp::PushOutResult& r = results.back();
      ++tallies[k].starts;
      if (!r.success()) continue;
      ++tallies[k].repaired;
      tallies[k].oneStep += r.iterations <= 1;
      tallies[k].iterations += r.iterations;
    }
    if (each) {
      std::printf("  %s q = %s: pairwise %d, body %d\n", family.c_str(), format(q).c_str(),
                  results[0].success() ? results[0].iterations : 0, results[1].success() ? results[1].iterations : 0);
    }
    if (std::all_of(results.begin(), results.end(), [](const dp::PushOutResult& r) { return r.success(); })) {
      ++all;
      for (std::size_t k = 0; k < vs.size(); ++k) tallies[k].motion += results[k].jointMotion;
    }
  }
  for (std::size_t k = 0; k < vs.size(); ++k) print(family, vs[k].name, tallies[k], all, csv);
}

std::shared_ptr<dc::World> gantryWorld(const std::string& link, const std::string& collisions) {
  auto world = std::make_shared<dc::World>(dt::gantryRobot(dt::toolBox()));
  world->addScene(dt::sceneOf(link, collisions), Eigen::Isometry3d::Identity());
  return world;
}

}  // namespace

int main(int argc, char** argv) {
  bool each = false;
  std::string csvPath = "bench/results/push_out_body_bench.csv";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--each") {
      each = true;
    } else if (arg == "--csv" && i + 1 < argc) {
      csvPath = argv[++i];
    } else {
      std::fprintf(stderr, "usage: push_out_body_bench [--each] [--csv FILE]\n");
      return 2;
    }
  }
  std::FILE* csv = deepcheck::bench::openCsv(
      "push_out_body_bench", csvPath,
      "family,option,starts,repaired,one_step,mean_iterations,motion,median_ms,p99_ms,max_ms");
  std::printf("push_out_body_bench: push-out with the pairwise depth against the body depth\n");
  std::printf("%-18s %-10s %6s %8s %8s %10s %12s %9s %9s %9s\n", "family", "depth", "starts", "repaired", "one step",
              "mean iter.", "motion (all)", "med. ms", "p99 ms", "max ms");
  {
    std::vector<Eigen::VectorXd> starts;
    for (double x : {0.0, 0.002, 0.005, 0.01, 0.015, 0.02}) {
      for (double depth : {0.01, 0.02, 0.03, 0.04, 0.045}) {
        for (double turn : {0.0, 0.3}) starts.push_back(dt::gantryQ(x, 0, 0.05 - depth, turn));
      }
    }
    run("slab", gantryWorld("slab", dt::slabCollisions()), starts, each, csv);
  }
  {
    std::vector<Eigen::VectorXd> starts;
    for (double x : {0.0, 0.001, 0.002, 0.004}) {
      for (double depth : {0.01, 0.02, 0.03, 0.04}) {
        for (double turn : {0.0, 0.3}) starts.push_back(dt::gantryQ(x, 0, 0.15 - depth, turn));
      }
    }
    run("U", gantryWorld("u", dt::uCollisions()), starts, each, csv);
  }
  for (const std::string scene : {"table", "shelf", "narrow_passage"}) {
    const auto world = deepcheck::bench::bundledArmWorld(scene);
    std::mt19937_64 rng(1234);
    const std::vector<Eigen::VectorXd> starts = deepcheck::bench::penetratingStarts(*world, 100, 0.02, rng);
    run("arm/" + scene, world, starts, false, csv);
  }
  {
    // As deep as the push-out goes (PushOutOptions::maxDepth): links and objects of many pieces
    // overlapping by centimetres, where a body query can need many Minkowski differences.
    const auto world = deepcheck::bench::bundledArmWorld("shelf");
    std::mt19937_64 rng(99);
    const dp::PushOutOptions defaults;
    const auto starts = deepcheck::bench::penetratingStarts(*world, 200, defaults.maxDepth, rng);
    run("arm/shelf deep", world, starts, false, csv);
  }
  std::fclose(csv);
  return 0;
}
