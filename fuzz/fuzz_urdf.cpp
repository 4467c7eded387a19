// Fuzz harness: a URDF document (the bytes, as text) through the robots loader, then forward
// kinematics at the default configuration of whatever loads. Bad input must end in an exception
// naming the problem, never a crash. Mesh URIs are resolved against an empty base directory, so
// no mesh file is opened (mesh bytes have their own harness, fuzz_mesh).

#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/robot_model.h"

#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  try {
    deepcheck::robots::LoadOptions options;
    options.useRosPackagePath = false;
    const auto model = deepcheck::robots::RobotModel::fromUrdfString(xml, "/nonexistent-deepcheck-fuzz", options,
                                                                     "fuzz.urdf");
    const Eigen::VectorXd q = model.defaultConfiguration();
    deepcheck::robots::checkConfiguration(model, q);
    deepcheck::robots::forwardKinematics(model, q);
  } catch (const std::exception&) {
    // Rejected input.
  }
  return 0;
}
