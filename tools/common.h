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

#include <cstdint>
#include <istream>
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

/// The value of an option given at most once (`name VALUE` or `name=VALUE`, removed from `args`);
/// `fallback` when absent. Throws UsageError when it is given more than once.
std::string takeSingleOption(std::vector<std::string>& args, const std::string& name, const std::string& fallback = "");

/// Package roots given by `--package-path DIR` (repeatable), in the order given, to search for
/// `package://` URIs. The environment (ROS_PACKAGE_PATH, AMENT_PREFIX_PATH) is searched after them
/// by the robots library (robots::packageRoots, LoadOptions::useRosPackagePath).
struct PackageRoots {
  std::vector<std::string> commandLine;
};

/// Removes the `--package-path DIR` / `--package-path=DIR` options from `args`.
PackageRoots takePackageRoots(std::vector<std::string>& args);

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

/// A whole number (decimal digits only) from `min` to `max`, or UsageError naming `option` and the
/// text.
std::uint64_t parseCount(const std::string& text, const std::string& option, std::uint64_t min, std::uint64_t max);

/// Removes `name v1 v2 ...` from `args`: the values up to the next `--option` (negative numbers
/// are values). Empty when absent; UsageError when given twice or without values.
std::vector<double> takeVector(std::vector<std::string>& args, const std::string& name);

/// Removes --robot (required), --scene (each optionally followed by --scene-pose) and every
/// --srdf from `args`, in command-line order. Throws UsageError for a missing value or a repeated
/// --robot.
void takeWorldOptions(std::vector<std::string>& args, std::string& robot, std::vector<SceneArg>& scenes,
                      std::vector<std::string>& srdfs);

/// A duration for people: "850 us", "12.3 ms", "4.56 s" (never "0.000 s").
std::string formatDuration(double seconds);

/// One non-blank, non-comment line of an input read from stdin.
struct InputLine {
  int number = 0;                   ///< 1-based, counting every line
  std::string text;                 ///< as read, without the line terminator (CR LF too)
  std::vector<std::string> tokens;  ///< whitespace-separated
};

/// Reads the next line of `in` that has a token and whose first token does not start with '#'
/// (comment); `lineNumber` counts every line read. False at the end of the input.
bool nextInputLine(std::istream& in, int& lineNumber, InputLine& line);

/// Throws InputError "line N: <problem>: '<text>'".
[[noreturn]] void failAt(const InputLine& line, const std::string& problem);

/// A finite number, or InputError naming the line and the token ("is not a number" / "is not a
/// finite number").
double parseNumber(const InputLine& line, const std::string& token);

}  // namespace deepcheck::tools
