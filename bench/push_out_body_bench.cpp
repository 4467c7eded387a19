// push_out_body_bench: the push-out (planners/push_out.h) with the pairwise depth against the body
// depth (PushOutOptions::bodyDepth), on hard cases where the deepest pair points sideways and on
// random starts of the bundled arm.
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
// scene (table, shelf, narrow_passage) with signed distance in [-2 cm, 0).
// Printed per family and option: starts, repaired, repaired in one iteration, mean iterations
// (over the repaired), mean joint motion (over the starts both options repaired).
// Usage: push_out_body_bench [--each] (a second); --each also prints every start of the hard cases
// with the iterations of both options (0: not repaired).

#include "../tests/common/body_cases.h"
#include "repair_starts.h"

#include "deepcheck/planners/push_out.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/validity.h"
#include "deepcheck/robots/random_configuration.h"

#include <cstdio>
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
  double motion = 0.0;  // over the starts both options repaired
};

std::string format(const Eigen::VectorXd& q) {
  std::string out;
  char buf[32];
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%s%.3f", i ? " " : "", q[i]);
    out += buf;
  }
  return out;
}

void print(const std::string& family, const char* option, const Tally& t, int both) {
  std::printf("%-16s %-9s %6d %8d %8d %10.2f %12.4f\n", family.c_str(), option, t.starts, t.repaired, t.oneStep,
              t.repaired ? static_cast<double>(t.iterations) / t.repaired : 0.0, both ? t.motion / both : 0.0);
}

void run(const std::string& family, const std::shared_ptr<const dc::World>& world,
         const std::vector<Eigen::VectorXd>& starts, bool each) {
  dp::PushOutOptions pairOptions;
  pairOptions.bodyDepth = false;
  dp::PushOutOptions bodyOptions;
  bodyOptions.bodyDepth = true;
  const dp::PushOut pairwise(world, {}, pairOptions);
  const dp::PushOut body(world, {}, bodyOptions);
  Tally tp, tb;
  int both = 0;
  for (const Eigen::VectorXd& q : starts) {
    const dp::PushOutResult a = pairwise.run(q);
    const dp::PushOutResult b = body.run(q);
    for (auto [r, t] : {std::pair{&a, &tp}, std::pair{&b, &tb}}) {
      ++t->starts;
      if (!r->success()) continue;
      ++t->repaired;
      t->oneStep += r->iterations <= 1;
      t->iterations += r->iterations;
    }
    if (each) {
      std::printf("  %s q = %s: pairwise %d, body %d\n", family.c_str(), format(q).c_str(),
                  a.success() ? a.iterations : 0, b.success() ? b.iterations : 0);
    }
    if (a.success() && b.success()) {
      ++both;
      tp.motion += a.jointMotion;
      tb.motion += b.jointMotion;
    }
  }
  print(family, "pairwise", tp, both);
  print(family, "body", tb, both);
}

std::shared_ptr<dc::World> gantryWorld(const std::string& link, const std::string& collisions) {
  auto world = std::make_shared<dc::World>(dt::gantryRobot(dt::toolBox()));
  world->addScene(dt::sceneOf(link, collisions), Eigen::Isometry3d::Identity());
  return world;
}

}  // namespace

int main(int argc, char** argv) {
  const bool each = argc > 1 && std::string(argv[1]) == "--each";
  std::printf("push_out_body_bench: push-out with the pairwise depth against the body depth\n");
  std::printf("%-16s %-9s %6s %8s %8s %10s %12s\n", "family", "depth", "starts", "repaired", "one step",
              "mean iter.", "motion (both)");
  {
    std::vector<Eigen::VectorXd> starts;
    for (double x : {0.0, 0.002, 0.005, 0.01, 0.015, 0.02}) {
      for (double depth : {0.01, 0.02, 0.03, 0.04, 0.045}) {
        for (double turn : {0.0, 0.3}) starts.push_back(dt::gantryQ(x, 0, 0.05 - depth, turn));
      }
    }
    run("slab", gantryWorld("slab", dt::slabCollisions()), starts, each);
  }
  {
    std::vector<Eigen::VectorXd> starts;
    for (double x : {0.0, 0.001, 0.002, 0.004}) {
      for (double depth : {0.01, 0.02, 0.03, 0.04}) {
        for (double turn : {0.0, 0.3}) starts.push_back(dt::gantryQ(x, 0, 0.15 - depth, turn));
      }
    }
    run("U", gantryWorld("u", dt::uCollisions()), starts, each);
  }
  for (const std::string scene : {"table", "shelf", "narrow_passage"}) {
    const auto world = deepcheck::bench::bundledArmWorld(scene);
    std::mt19937_64 rng(1234);
    const std::vector<Eigen::VectorXd> starts = deepcheck::bench::penetratingStarts(*world, 100, 0.02, rng);
    run("arm/" + scene, world, starts, false);
  }
  return 0;
}
