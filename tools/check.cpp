// `deepcheck check`: signed distance of a robot in its scenes for configurations read from stdin.
//
//   deepcheck check --robot R.urdf [--scene S.urdf [--scene-pose x y z roll pitch yaw]]...
//                   [--srdf FILE] [--package-path DIR]... [--gradient] < configs.txt
//
// Input: one configuration per line, the joint values in configuration order (the order
// `deepcheck info` prints: RobotModel::variableNames()), separated by blanks; lines whose first
// non-blank character is '#', and blank lines, are skipped.
// Output: one line per configuration, "sd linkA linkB" (%.17g): the minimum signed distance over
// the checked pairs (robot-scene and robot self-collision; < 0 is minus the penetration depth),
// its robot link and the other body (a robot link, or "scene/<link>" for a scene link); with
// --gradient, the nq components of d sd / dq follow. When the world has no pair at all the line
// is "inf none none". On stderr: the world's summary, then a last line
// "configurations N total_us T", T the time spent in the queries (loading excluded).
//
// The whole input is parsed before the first query, so a bad line produces no output on stdout,
// one error line naming the line, and exit status 1.

#include "common.h"
#include "load_world.h"
#include "subcommands.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/robot_model.h"

#include <Eigen/Geometry>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::tools {
namespace {

constexpr const char* kUsage =
    "usage: deepcheck check --robot R.urdf [--scene S.urdf [--scene-pose x y z roll pitch yaw]]...\n"
    "                       [--srdf FILE] [--package-path DIR]... [--gradient] < configs.txt\n"
    "\n"
    "Minimum signed distance of the robot to its scenes and to itself, one configuration per\n"
    "input line (joint values in the order `deepcheck info` prints; '#' comments and blank lines\n"
    "are skipped). Output per line: 'sd linkA linkB' (%.17g; sd < 0 is minus the penetration\n"
    "depth; scene links are named scene/<link>), and with --gradient the components of d sd/dq.\n"
    "On stderr: the world's summary and a last line 'configurations N total_us T'.\n"
    "\n"
    "options:\n"
    "  --robot FILE        the robot's URDF (required)\n"
    "  --scene FILE        a scene URDF, its joints at their default values (repeatable)\n"
    "  --scene-pose x y z roll pitch yaw\n"
    "                      places the scene given just before (metres, radians; URDF rpy:\n"
    "                      R = Rz(yaw) Ry(pitch) Rx(roll)); default: the identity\n"
    "  --srdf FILE         disable the self-collision pairs of this SRDF\n"
    "  --package-path DIR  a root to search for package:// URIs (repeatable; ROS_PACKAGE_PATH is\n"
    "                      also read)\n"
    "  --gradient          append the gradient of sd with respect to the joint values\n";

int run(std::vector<std::string> args) {
  const bool gradient = takeFlag(args, "--gradient");
  const PackagePaths paths = takePackagePaths(args);
  std::string robotPath;
  std::string srdf;
  std::vector<SceneArg> scenes;
  takeWorldOptions(args, robotPath, scenes, srdf);
  rejectUnknownOptions(args);
  if (!args.empty()) throw UsageError("unexpected argument '" + args[0] + "'");

  checker::World world = loadWorld(robotPath, scenes, srdf, paths);
  const std::vector<Eigen::VectorXd> configurations = readConfigurations(std::cin, world.robot());
  std::fputs(world.summary().c_str(), stderr);

  checker::DistanceOptions query;
  query.gradient = gradient;
  auto context = world.makeContext();
  std::vector<checker::DistanceResult> results;
  results.reserve(configurations.size());
  const auto start = std::chrono::steady_clock::now();
  for (const Eigen::VectorXd& q : configurations) results.push_back(world.signedDistance(q, context, query));
  const auto stop = std::chrono::steady_clock::now();
  for (const checker::DistanceResult& r : results) {
    if (!r.found) {
      std::printf("inf none none");
    } else {
      std::printf("%.17g %s %s", r.closest.distance, r.closest.nameA.c_str(), r.closest.nameB.c_str());
    }
    if (gradient) {
      for (int v = 0; v < world.robot().numVariables(); ++v) {
        std::printf(" %.17g", r.found ? r.closest.gradient[v] : 0.0);
      }
    }
    std::printf("\n");
  }
  std::fflush(stdout);
  std::fprintf(stderr, "configurations %zu total_us %lld\n", configurations.size(),
               static_cast<long long>(std::chrono::duration_cast<std::chrono::microseconds>(stop - start).count()));
  return 0;
}

}  // namespace

const Subcommand kCheckCommand = {"check", "signed distance of a robot in its scenes, per configuration", kUsage,
                                  run};

}  // namespace deepcheck::tools
