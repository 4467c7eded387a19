// Fuzz harness: `deepcheck plan`'s --goal-pose with its tolerances (tools/goal_pose.h). The input
// is one command line, split at whitespace into arguments. Bad input must end in the tool's
// UsageError (exit status 2), never a crash or another exception; an accepted goal must be a
// rigid, finite pose with positive, finite tolerances, and take its words out of the arguments.

#include "common.h"
#include "goal_pose.h"
#include "harness_support.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace {

using deepcheck::fuzz::rigid;

void require(bool ok, const char* what) { deepcheck::fuzz::require(ok, "takeGoalPose accepted a goal with", what); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream words(std::string(reinterpret_cast<const char*>(data), size));
  std::vector<std::string> args;
  for (std::string w; words >> w;) args.push_back(w);
  try {
    const auto pose = deepcheck::tools::takeGoalPose(args);
    for (const std::string& a : args) {
      require(a != "--goal-pose" && a != "--position-tol" && a != "--orientation-tol" && a != "--position-box",
              "one of its options left in the arguments");
    }
    if (!pose) return 0;
    require(!pose->link.empty(), "an empty link");
    require(rigid(pose->X_WT), "a pose that is not rigid and finite");
    require(std::isfinite(pose->positionTolerance) && pose->positionTolerance > 0.0, "a bad position tolerance");
    require(std::isfinite(pose->orientationTolerance) && pose->orientationTolerance > 0.0,
            "a bad orientation tolerance");
    if (pose->positionBox) {
      require(pose->positionBox->allFinite() && (pose->positionBox->array() > 0.0).all(), "a bad position box");
    }
  } catch (const deepcheck::tools::UsageError&) {
    // Rejected command line: the tool prints the usage and exits 2.
  }
  return 0;
}
