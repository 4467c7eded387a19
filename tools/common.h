#pragma once
// Helpers shared by the subcommands of the `deepcheck` program.
//
// Conventions of every subcommand:
//   - run(args) receives the arguments after the subcommand's name and returns the exit status;
//   - exit status 0 on success, 1 when the input (a file, stdin, a robot) is bad or a computation
//     fails, 2 when the command line itself is wrong (UsageError);
//   - errors are reported on stderr as one line "deepcheck <subcommand>: <message>", the message
//     naming the offending input (line number and text, file, shape id ...).

#include <Eigen/Geometry>

#include <stdexcept>
#include <string>
#include <vector>

namespace deepcheck::tools {

/// A malformed command line (unknown option, missing value): exit status 2 with the usage text.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Bad input data: exit status 1.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Removes every occurrence of the flag `name` (e.g. "--cold") from `args`; true when it was there.
bool takeFlag(std::vector<std::string>& args, const std::string& name);

/// Removes every `name VALUE` and `name=VALUE` from `args` and returns the values in order.
/// Throws UsageError when `name` is the last argument (no value) or the value is empty.
std::vector<std::string> takeOption(std::vector<std::string>& args, const std::string& name);

/// Splits a colon-separated path list (ROS_PACKAGE_PATH style); empty entries are dropped.
std::vector<std::string> splitPathList(const std::string& list);

/// Package roots used to resolve `package://` URIs, as given by `--package-path DIR` (repeatable)
/// and the ROS_PACKAGE_PATH environment variable.
struct PackagePaths {
  std::vector<std::string> commandLine;  ///< `--package-path` values, in the order given
  std::vector<std::string> environment;  ///< ROS_PACKAGE_PATH entries, in order

  /// All roots to search: the command-line ones first, then the environment's; each path once.
  std::vector<std::string> roots() const;
};

/// Removes the `--package-path DIR` / `--package-path=DIR` options from `args` and reads
/// ROS_PACKAGE_PATH (unless `useEnvironment` is false).
PackagePaths takePackagePaths(std::vector<std::string>& args, bool useEnvironment = true);

/// Throws UsageError naming the first remaining argument that starts with '-' (an unknown option).
void rejectUnknownOptions(const std::vector<std::string>& args);

/// A `--scene FILE [--scene-pose x y z roll pitch yaw]` of the command line.
struct SceneArg {
  std::string path;
  bool posed = false;
  Eigen::Isometry3d X_WS = Eigen::Isometry3d::Identity();
};

/// A finite number, or UsageError naming `what` and the text.
double parseValue(const std::string& text, const std::string& what);

/// Removes --robot (required), --scene (each optionally followed by --scene-pose) and --srdf from
/// `args`, in command-line order. Throws UsageError for a missing or repeated value.
void takeWorldOptions(std::vector<std::string>& args, std::string& robot, std::vector<SceneArg>& scenes,
                      std::string& srdf);

}  // namespace deepcheck::tools
