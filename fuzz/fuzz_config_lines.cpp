// Fuzz harness: the command-line and stdin parsers of the `deepcheck` subcommands. The first line
// of the input is split into arguments and given to the option parsers (--robot/--scene/
// --scene-pose/--srdf, --lock, --package-path, --start/--goal joint vectors, counts and values; the
// --lock joints are then held on the bundled arm); the rest is read as configuration
// lines (`deepcheck check`'s stdin) for the bundled arm, and each accepted configuration is
// checked against its limits and posed by forward kinematics. Bad input must end in the tool's
// UsageError/InputError (or the library's std::invalid_argument), never a crash.

#include "common.h"
#include "harness_support.h"
#include "load_world.h"

#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/robot_model.h"

#include <cstddef>
#include <cstdint>
#include <exception>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace deepcheck::tools;

const deepcheck::robots::RobotModel& arm() { return deepcheck::fuzz::bundledArm(); }

/// The bundled arm with the --lock joints held, posed at its default configuration.
void lockJoints(const std::map<std::string, double>& locks) {
  try {
    const deepcheck::robots::RobotModel locked = arm().withLockedVariables(locks);
    deepcheck::robots::forwardKinematics(locked, locked.defaultConfiguration());
  } catch (const std::invalid_argument&) {
    // Not a variable of the arm, or outside its limits: the tool reports it and exits 1.
  }
}

void parseArguments(const std::string& firstLine) {
  std::vector<std::string> args;
  std::istringstream words(firstLine);
  for (std::string w; words >> w;) args.push_back(w);
  try {
    takeFlag(args, "--gradient");
    takeVector(args, "--start");
    takeVector(args, "--goal");
    takePackageRoots(args);
    parseValue(takeSingleOption(args, "--time", "5"), "--time");
    parseCount(takeSingleOption(args, "--seed", "0"), "--seed", 0, 4294967295u);
    std::string robot;
    std::vector<std::string> srdfs;
    std::vector<SceneArg> scenes;
    takeWorldOptions(args, robot, scenes, srdfs);
    const std::map<std::string, double> locks = takeLocks(args);
    rejectUnknownOptions(args);
    lockJoints(locks);
  } catch (const UsageError&) {
    // Rejected command line: the tool prints the usage and exits 2.
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::string firstLine;
  std::getline(in, firstLine);
  parseArguments(firstLine);
  try {
    for (const Eigen::VectorXd& q : readConfigurations(in, arm())) {
      try {
        deepcheck::robots::checkConfiguration(arm(), q);
        deepcheck::robots::forwardKinematics(arm(), q);
      } catch (const std::invalid_argument&) {
        // Outside the joint limits: `check` reports it per configuration.
      }
    }
  } catch (const InputError&) {
    // Rejected line: the tool prints the message and exits 1.
  }
  return 0;
}
