// `deepcheck check`: signed distance of a robot in its scenes for configurations read from stdin.
//
//   deepcheck check --robot R.urdf [--scene S.urdf [--scene-pose x y z roll pitch yaw]]...
//                   [--scene S.yaml]... [--frame-alias NAME=LINK]...
//                   [--srdf FILE]... [--group NAME] [--lock JOINT=VALUE]... [--package-path DIR]... [--gradient]
//                   [--clamp-to-limits] < configs.txt
//
// Input: one configuration per line, the joint values in configuration order (the order
// `deepcheck info` prints: RobotModel::variableNames()), separated by blanks; lines whose first
// non-blank character is '#', and blank lines, are skipped.
// Output: one line per configuration, three triples "sd linkA linkB" (%.17g) then, with
// --gradient, the nq components of d sd / dq of the first triple:
//   1. the minimum signed distance over all checked pairs (< 0 is minus the penetration depth),
//      its robot link and the other body (a robot link, "scene/<link>" for a URDF scene's link,
//      "obstacle/<id>" or "obstacle/<id>/<k>" for a planning scene's object or its k-th shape);
//   2. the same over the robot-scene pairs only (scene clearance);
//   3. the same over the robot's self pairs only (self clearance).
// The scene and self clearances are separate because an arm's nearest pair is usually a fixed
// wrist pair a few centimetres apart in every configuration, which hides the scene. A triple
// with no pair to measure is "inf none none". On stderr: the world's summary, then a last line
// "configurations N total_us T", T the time spent in the queries (loading excluded).
//
// The whole input is parsed before the first query, so a bad line produces no output on stdout,
// one error line naming the line, and exit status 1.

#include "common.h"
#include "load_world.h"
#include "subcommands.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/joint_angles.h"
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

constexpr const char* kCheckUsage =
    "usage: deepcheck check --robot R.urdf [--scene S.urdf [--scene-pose x y z roll pitch yaw]]...\n"
    "                       [--scene S.yaml]... [--frame-alias NAME=LINK]...\n"
    "                       [--srdf FILE]... [--group NAME] [--lock JOINT=VALUE]... [--package-path DIR]... "
    "[--gradient]\n"
    "                       [--clamp-to-limits] < configs.txt\n"
    "\n"
    "Minimum signed distance of the robot to its scenes and to itself, one configuration per\n"
    "input line (joint values in the order `deepcheck info` prints; '#' comments and blank lines\n"
    "are skipped). Output per line: three triples 'sd linkA linkB' (%.17g; sd < 0 is minus the\n"
    "penetration depth; scene links are named scene/<link>, planning-scene objects obstacle/<id>):\n"
    "the minimum over all pairs, over the robot-scene pairs, over the robot's self pairs; then\n"
    "with --gradient the components of d sd/dq of the first. A joint value outside its limits is an\n"
    "error naming the line, the joint, the value and the limits (see --clamp-to-limits).\n"
    "On stderr: the world's summary and a last line 'configurations N total_us T'.\n"
    "\n"
    "options:\n" DEEPCHECK_WORLD_OPTIONS_HELP
    "  --gradient          append the gradient of sd with respect to the joint values\n" DEEPCHECK_CLAMP_HELP;

int runCheck(std::vector<std::string> args) {
  const bool gradient = takeFlag(args, "--gradient");
  JointLimitPolicy limits;
  limits.clamp = takeFlag(args, "--clamp-to-limits");
  const WorldArgs worldArgs = takeWorldArgs(args);
  rejectUnknownOptions(args);
  if (!args.empty()) throw UsageError("unexpected argument '" + args[0] + "'");

  checker::World world = loadWorld(worldArgs);
  std::vector<Eigen::VectorXd> configurations = readConfigurations(std::cin, world.robot(), &limits);
  for (Eigen::VectorXd& q : configurations) robots::normalizeWrappingVariables(world.robot(), q);  // 4.0 -> 4.0 - 2 pi
  std::fputs(world.summary().c_str(), stderr);
  warnVisualOnlyLinks("check", world.robot());
  warnClamped("check", limits);

  // Two pruned searches, one per kind of pair; the overall minimum is the smaller.
  checker::DistanceOptions sceneQuery;
  sceneQuery.gradient = gradient;
  sceneQuery.selfPairs = false;
  checker::DistanceOptions selfQuery = sceneQuery;
  selfQuery.selfPairs = true;
  selfQuery.worldPairs = false;
  auto context = world.makeContext();
  std::vector<std::pair<checker::DistanceResult, checker::DistanceResult>> results;
  results.reserve(configurations.size());
  const auto start = std::chrono::steady_clock::now();
  for (const Eigen::VectorXd& q : configurations) {
    results.emplace_back(world.signedDistance(q, context, sceneQuery), world.signedDistance(q, context, selfQuery));
  }
  const auto stop = std::chrono::steady_clock::now();
  const auto printTriple = [](const checker::DistanceResult& r) {
    if (!r.found) {
      std::printf("inf none none");
    } else {
      std::printf("%.17g %s %s", r.closest.distance, r.closest.nameA.c_str(), r.closest.nameB.c_str());
    }
  };
  for (const auto& [scene, self] : results) {
    const bool sceneNearer = scene.found && (!self.found || scene.closest.distance <= self.closest.distance);
    const checker::DistanceResult& overall = sceneNearer ? scene : self;
    printTriple(overall);
    std::printf(" ");
    printTriple(scene);
    std::printf(" ");
    printTriple(self);
    if (gradient) {
      for (int v = 0; v < world.robot().numVariables(); ++v) {
        std::printf(" %.17g", overall.found ? overall.closest.gradient[v] : 0.0);
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

const Subcommand kCheckCommand = {"check", "signed distance of a robot in its scenes, per configuration", kCheckUsage,
                                  runCheck};

}  // namespace deepcheck::tools
