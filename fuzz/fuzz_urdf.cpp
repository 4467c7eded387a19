// Fuzz harness: a URDF document (the bytes, as text) through the robots loader, then forward
// kinematics at the default configuration of whatever loads. The same bytes are read as an SRDF
// too (both are <robot> documents): every planning group it defines is resolved against the
// loaded robot, the variables outside it locked, and the locked robot's kinematics computed.
// Bad input must end in an exception naming the problem, never a crash. Mesh URIs are resolved
// against an empty base directory, so no mesh file is opened (mesh bytes have their own harness,
// fuzz_mesh).

#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/planning_group.h"
#include "deepcheck/robots/robot_model.h"

#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

namespace {

void kinematicsAtDefault(const deepcheck::robots::RobotModel& model) {
  const Eigen::VectorXd q = model.defaultConfiguration();
  deepcheck::robots::checkConfiguration(model, q);
  deepcheck::robots::forwardKinematics(model, q);
}

/// Each group of the document as an SRDF, locked on `model`.
void planningGroups(const deepcheck::robots::RobotModel& model, const std::string& xml) {
  std::vector<deepcheck::robots::SrdfGroup> groups;
  try {
    groups = deepcheck::robots::parseSrdfGroups(xml, "fuzz.srdf");
  } catch (const std::exception&) {
    return;  // rejected as an SRDF
  }
  for (const deepcheck::robots::SrdfGroup& group : groups) {
    try {
      const std::vector<int> moved = deepcheck::robots::groupVariables(model, groups, group.name, "fuzz.srdf");
      kinematicsAtDefault(deepcheck::robots::lockAllBut(model, moved, {}, "group '" + group.name + "'"));
    } catch (const std::exception&) {
      // Rejected group.
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  try {
    deepcheck::robots::LoadOptions options;
    options.useRosPackagePath = false;
    const auto model =
        deepcheck::robots::RobotModel::fromUrdfString(xml, "/nonexistent-deepcheck-fuzz", options, "fuzz.urdf");
    kinematicsAtDefault(model);
    planningGroups(model, xml);
  } catch (const std::exception&) {
    // Rejected input.
  }
  return 0;
}
