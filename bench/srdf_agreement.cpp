// srdf_agreement: the collision-pair filter (robots/pair_filter.h) against the SRDFs shipped with
// the real robots of ../shared (the Panda's MoveIt config, the UR5 of example-robot-data).
//
// For each robot: computeDisabledPairs with its defaults (10,000 samples, seed 1) on the default
// collision pieces (one hull per mesh), and the shipped SRDF's <disable_collisions>. Printed: the
// link pairs with geometry, the pairs we disable (by reason) and they disable, those both
// disable, and the pairs only one side disables, each with our reason or with the share of our
// samples in which it collided. The robots suite asserts what must hold whatever the meshes
// (their Adjacent pairs are ours, our Never pairs stay free in a fresh sample); this prints the
// table of docs/robots.md, and one row per robot to a CSV. Usage: srdf_agreement [--csv FILE] (a
// few seconds; skips without ../shared; the CSV defaults to bench/results/srdf_agreement.csv, run
// from the source tree).

#include "csv_out.h"

#include "deepcheck/robots/collision_geometry.h"
#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/robot_model.h"
#include "deepcheck/robots/srdf.h"

#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

using namespace deepcheck::robots;

namespace {

using Key = std::pair<std::string, std::string>;

struct Robot {
  std::string name;
  std::string root;  ///< package root under ../shared
  std::string urdf;  ///< relative to root
  std::string srdf;  ///< relative to root
};

std::string reasonCounts(const PairFilterResult& r) {
  std::string out;
  for (DisableReason reason :
       {DisableReason::Adjacent, DisableReason::Default, DisableReason::Always, DisableReason::Never}) {
    const int n = r.count(reason);
    if (n == 0) continue;
    out += (out.empty() ? "" : ", ") + std::to_string(n) + " " + toString(reason);
  }
  return out;
}

void compare(const Robot& robot, const std::string& shared, std::FILE* csv) {
  LoadOptions load;
  load.packageRoots = {shared + "/" + robot.root};
  load.useRosPackagePath = false;
  const RobotModel model = RobotModel::fromUrdfFile(shared + "/" + robot.root + "/" + robot.urdf, load);
  const PairFilterResult ours = computeDisabledPairs(model, collisionPieces(model));
  std::map<Key, const LinkPairReport*> report;
  for (const LinkPairReport& r : ours.pairs) report[pairKey(model.link(r.link1).name, model.link(r.link2).name)] = &r;
  std::set<Key> us;
  for (const DisabledPair& p : ours.disabled) us.insert(pairKey(p.link1, p.link2));
  std::set<Key> them;
  for (const DisabledPair& p : readSrdfDisabledPairs(shared + "/" + robot.root + "/" + robot.srdf)) {
    them.insert(pairKey(p.link1, p.link2));
  }
  int both = 0;
  for (const Key& k : us) both += them.count(k) > 0 ? 1 : 0;
  std::printf("%s: %d link pairs with geometry; we disable %zu (%s), they disable %zu, both %d\n", robot.name.c_str(),
              ours.numPairs(), us.size(), reasonCounts(ours).c_str(), them.size(), both);
  std::fprintf(csv, "%s,%d,%zu,%zu,%d,%zu,%zu\n", robot.name.c_str(), ours.numPairs(), us.size(), them.size(), both,
               us.size() - static_cast<std::size_t>(both), them.size() - static_cast<std::size_t>(both));
  for (const Key& k : us) {
    if (them.count(k)) continue;
    std::printf("  only us:   %s - %s (%s)\n", k.first.c_str(), k.second.c_str(), toString(*report.at(k)->reason));
  }
  for (const Key& k : them) {
    if (us.count(k)) continue;
    const auto it = report.find(k);
    if (it == report.end()) {
      std::printf("  only them: %s - %s (not a pair of links with geometry for us)\n", k.first.c_str(),
                  k.second.c_str());
      continue;
    }
    std::printf("  only them: %s - %s (collides in %d of our %d samples)\n", k.first.c_str(), k.second.c_str(),
                it->second->collisions, ours.samples);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string csvPath = "bench/results/srdf_agreement.csv";
  if (argc == 3 && std::string(argv[1]) == "--csv") {
    csvPath = argv[2];
  } else if (argc != 1) {
    std::fprintf(stderr, "usage: srdf_agreement [--csv FILE]\n");
    return 2;
  }
  std::FILE* csv = deepcheck::bench::openCsv(
      "srdf_agreement", csvPath, "robot,pairs_with_geometry,we_disable,srdf_disables,both,only_us,only_srdf");
  const std::string shared = DEEPCHECK_SHARED_DIR;
  const std::vector<Robot> robots = {
      {"Panda", "robots/panda", "moveit_resources_panda_description/urdf/panda.urdf",
       "moveit_resources_panda_moveit_config/config/panda.srdf"},
      {"UR5", "robots/ur5", "example-robot-data/robots/ur_description/urdf/ur5_robot.urdf",
       "example-robot-data/robots/ur_description/srdf/ur5.srdf"},
  };
  for (const Robot& robot : robots) {
    if (!std::filesystem::is_directory(shared + "/" + robot.root)) {
      std::printf("%s: skipped (%s/%s absent)\n", robot.name.c_str(), shared.c_str(), robot.root.c_str());
      continue;
    }
    compare(robot, shared, csv);
  }
  std::fclose(csv);
  return 0;
}
