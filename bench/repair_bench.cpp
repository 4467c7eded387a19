// repair_bench: push-out against the random-jiggle baseline (planners/push_out.h) on slightly
// colliding starts of the bundled arm.
//
// For each bundled scene (table, shelf, narrow_passage): 100 seeded random configurations whose
// signed distance lies in [-2 cm, 0) (with the scene or the robot itself), each repaired by the
// push-out and by the jiggle (default options of both). Printed per scene and in total: how many
// each repaired, and over the starts both repaired, the mean joint motion (joint-space Euclidean
// norm, rad) and the mean largest link displacement (m). The planners suite asserts the same
// trials' claims (>= 99 % repaired by the push-out, less motion than the jiggle); this prints the
// figures; the same rows go to a CSV. Usage: repair_bench [--csv FILE] (about half a minute; the
// CSV defaults to bench/results/repair_bench.csv, run from the source tree).

#include "csv_out.h"
#include "repair_starts.h"

#include "deepcheck/planners/push_out.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/validity.h"
#include "deepcheck/robots/random_configuration.h"

#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace dp = deepcheck::planners;

namespace {

constexpr int kTrialsPerScene = 100;
constexpr double kMaxDepth = 0.02;

struct Totals {
  int trials = 0;
  int pushRepaired = 0;
  int jiggleRepaired = 0;
  int both = 0;
  double pushMotion = 0.0;
  double jiggleMotion = 0.0;
  double pushWorkspace = 0.0;
  double jiggleWorkspace = 0.0;

  void add(const Totals& o) {
    trials += o.trials;
    pushRepaired += o.pushRepaired;
    jiggleRepaired += o.jiggleRepaired;
    both += o.both;
    pushMotion += o.pushMotion;
    jiggleMotion += o.jiggleMotion;
    pushWorkspace += o.pushWorkspace;
    jiggleWorkspace += o.jiggleWorkspace;
  }
  void print(const std::string& name, std::FILE* csv) const {
    std::printf("%-16s %6d %10d %10d %6d %15.3f %15.3f %13.3f %13.3f\n", name.c_str(), trials, pushRepaired,
                jiggleRepaired, both, pushMotion / both, jiggleMotion / both, pushWorkspace / both,
                jiggleWorkspace / both);
    std::fprintf(csv, "%s,%d,%d,%d,%d,%.5f,%.5f,%.5f,%.5f\n", name.c_str(), trials, pushRepaired, jiggleRepaired, both,
                 pushMotion / both, jiggleMotion / both, pushWorkspace / both, jiggleWorkspace / both);
  }
};

Totals runScene(const std::string& scene) {
  const auto world = deepcheck::bench::bundledArmWorld(scene);
  std::mt19937_64 rng(1234);
  const std::vector<Eigen::VectorXd> starts =
      deepcheck::bench::penetratingStarts(*world, kTrialsPerScene, kMaxDepth, rng);
  const dp::PushOut pushOut(world);
  Totals t;
  for (const Eigen::VectorXd& q : starts) {
    ++t.trials;
    const dp::PushOutResult p = pushOut.run(q);
    const dp::PushOutResult j = dp::jiggle(*world, {}, q, {}, rng);
    t.pushRepaired += p.success();
    t.jiggleRepaired += j.success();
    if (!p.success() || !j.success()) continue;
    ++t.both;
    t.pushMotion += p.jointMotion;
    t.jiggleMotion += j.jointMotion;
    t.pushWorkspace += dp::maxLinkDisplacement(world->robot(), q, p.q);
    t.jiggleWorkspace += dp::maxLinkDisplacement(world->robot(), q, j.q);
  }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  std::string csvPath = "bench/results/repair_bench.csv";
  if (argc == 3 && std::string(argv[1]) == "--csv") {
    csvPath = argv[2];
  } else if (argc != 1) {
    std::fprintf(stderr, "usage: repair_bench [--csv FILE]\n");
    return 2;
  }
  std::FILE* csv = deepcheck::bench::openCsv("repair_bench", csvPath,
                                             "scene,starts,push_out_repaired,jiggle_repaired,both,push_out_motion_rad,"
                                             "jiggle_motion_rad,push_out_link_m,jiggle_link_m");
  std::printf("repair_bench: %d starts per scene penetrating up to %.0f cm; means over the starts both repaired\n",
              kTrialsPerScene, 100 * kMaxDepth);
  std::printf("%-16s %6s %10s %10s %6s %15s %15s %13s %13s\n", "scene", "starts", "push-out", "jiggle", "both",
              "push motion rad", "jiggle mot. rad", "push link m", "jiggle link m");
  Totals all;
  for (const std::string scene : {"table", "shelf", "narrow_passage"}) {
    const Totals t = runScene(scene);
    t.print(scene, csv);
    all.add(t);
  }
  all.print("all", csv);
  std::fclose(csv);
  return 0;
}
