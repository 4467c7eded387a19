// plan_certify: what certification makes of the paths plan_bench's FCL check rejected.
//
// For every rejected_<problem>_<checker>_<planner>_<run>.txt in DIR (written by plan_bench): the
// path through certifyPath (setup.h: the clearance motion validator, repairing where it fails) on
// our setup of that problem, then the fine FCL check again. Writes DIR/plan_bench_certify.md (also
// printed).
//
// Usage: plan_certify DIR

#include "plan_problems.h"

#include "deepcheck/planners/path_tools.h"
#include "deepcheck/planners/state_space.h"

#include <ompl/base/ScopedState.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace dp = deepcheck::planners;
using namespace deepcheck::bench;

namespace {

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
      if (name.rfind("rejected_" + p.name + "_", 0) == 0 &&
          (problem == nullptr || p.name.size() > problem->name.size())) {
        problem = &p;
      }
    }
    if (problem == nullptr || (problem->needsShared && !haveShared())) {
      std::fprintf(stderr, "plan_certify: %s: no such problem here, skipped\n", name.c_str());
      continue;
    }
    auto world = dp::loadWorld(problem->robotUrdf, problem->scenes, problem->options);
    auto ss = dp::makeSimpleSetup(world, problem->options);
    dp::setStartAndGoal(*ss, problem->start, problem->goal);
    ss->setup();
    std::shared_ptr<deepcheck::fcl_reference::FclStateValidityChecker> fcl;
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

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    std::fprintf(stderr,
                 "usage: plan_certify DIR\n"
                 "  certifyPath + fine FCL check of the rejected_*.txt paths plan_bench wrote in DIR;\n"
                 "  writes DIR/plan_bench_certify.md\n");
    return 2;
  }
  if (!std::filesystem::is_directory(argv[1])) {
    std::fprintf(stderr, "plan_certify: '%s' is not a folder\n", argv[1]);
    return 2;
  }
  return certifyRejected(argv[1]);
}
