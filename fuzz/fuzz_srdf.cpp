// Fuzz harness: an SRDF document (the bytes, as text) through the robots readers (srdf.h,
// planning_group.h) against the bundled arm. The disabled pairs are checked against the arm's
// links and written back with srdfText, which must read back the same pairs; each planning group
// is resolved (groupVariables), the other variables locked (lockAllBut) and the locked arm posed
// by forward kinematics. Bad input must end in std::invalid_argument naming the problem (the
// readers' documented error), never a crash or another exception.

#include "harness_support.h"

#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/planning_group.h"
#include "deepcheck/robots/robot_model.h"
#include "deepcheck/robots/srdf.h"

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace robots = deepcheck::robots;

const robots::RobotModel& arm() { return deepcheck::fuzz::bundledArm(); }

void disabledPairs(const std::string& xml) {
  std::vector<robots::DisabledPair> pairs;
  try {
    pairs = robots::parseSrdfDisabledPairs(xml, "fuzz.srdf");
  } catch (const std::invalid_argument&) {
    return;  // rejected as a pair list
  }
  // What was read must survive a write and a read unchanged (names escaped, reasons spelled).
  const std::vector<robots::DisabledPair> again =
      robots::parseSrdfDisabledPairs(robots::srdfText("fuzz", pairs), "written.srdf");
  bool same = again.size() == pairs.size();
  for (std::size_t i = 0; same && i < pairs.size(); ++i) {
    same = again[i].link1 == pairs[i].link1 && again[i].link2 == pairs[i].link2 && again[i].reason == pairs[i].reason;
  }
  deepcheck::fuzz::require(same, "srdfText", "does not read back as the pairs it was given");
  try {
    robots::checkDisabledPairs(arm(), pairs, "fuzz.srdf");
  } catch (const std::invalid_argument&) {
    // A pair naming a link the arm does not have.
  }
}

void planningGroups(const std::string& xml) {
  std::vector<robots::SrdfGroup> groups;
  try {
    groups = robots::parseSrdfGroups(xml, "fuzz.srdf");
  } catch (const std::invalid_argument&) {
    return;  // rejected as a group list
  }
  for (const robots::SrdfGroup& group : groups) {
    try {
      const std::vector<int> moved = robots::groupVariables(arm(), groups, group.name, "fuzz.srdf");
      const robots::RobotModel locked = robots::lockAllBut(arm(), moved, {}, "group '" + group.name + "'");
      robots::forwardKinematics(locked, locked.defaultConfiguration());
    } catch (const std::invalid_argument&) {
      // A group naming what the arm does not have, or a cycle of subgroups.
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  disabledPairs(xml);
  planningGroups(xml);
  return 0;
}
