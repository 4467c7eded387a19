#include "load_world.h"

#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/planning_group.h"
#include "deepcheck/robots/robot_model.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::tools {

void applyJointLimits(const robots::RobotModel& robot, Eigen::VectorXd& q, const std::string& what,
                      JointLimitPolicy& policy) {
  for (int v = 0; v < robot.numVariables(); ++v) {
    const robots::Joint& joint = robot.joint(robot.variableJoint(v));
    const double lower = robot.lowerLimits()[v];
    const double upper = robot.upperLimits()[v];
    if (joint.type == robots::JointType::Continuous || (q[v] >= lower && q[v] <= upper)) continue;
    const std::string& name = robot.variableNames()[static_cast<std::size_t>(v)];
    if (policy.clamp) {
      q[v] = std::min(std::max(q[v], lower), upper);
      policy.clamped.insert(name);
      continue;
    }
    const char* unit = joint.type == robots::JointType::Prismatic ? "m" : "rad";
    const bool below = q[v] < lower;
    char text[240];
    std::snprintf(text, sizeof text, " = %.6g %s is %s its %s limit %.6g %s (limits [%.6g, %.6g] %s)", q[v], unit,
                  below ? "below" : "above", below ? "lower" : "upper", below ? lower : upper, unit, lower, upper,
                  unit);
    throw InputError(what + " is outside the joint limits: joint '" + name + "'" + text +
                     "; --clamp-to-limits clamps it");
  }
}

namespace {

/// 'a', 'b', 'c'
template <class Names>
std::string quotedNames(const Names& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "'" : ", '") + name + "'";
  return text;
}

}  // namespace

void warnClamped(const std::string& subcommand, const JointLimitPolicy& policy) {
  if (policy.clamped.empty()) return;
  std::fprintf(stderr, "deepcheck %s: warning: values clamped to the joint limits of %s\n", subcommand.c_str(),
               quotedNames(policy.clamped).c_str());
}

void warnVisualOnlyLinks(const std::string& subcommand, const robots::RobotModel& robot) {
  std::vector<std::string> visualOnly;
  bool anyCollision = false;
  for (const robots::Link& link : robot.links()) {
    anyCollision = anyCollision || !link.collisions.empty();
    if (link.hasVisual && link.collisions.empty()) visualOnly.push_back(link.name);
  }
  if (visualOnly.empty()) return;
  std::fprintf(stderr,
               "deepcheck %s: warning: robot '%s'%s: links with <visual> but no <collision> geometry, "
               "not checked: %s\n",
               subcommand.c_str(), robot.name().c_str(), anyCollision ? "" : " has no collision geometry at all",
               quotedNames(visualOnly).c_str());
}

std::vector<Eigen::VectorXd> readConfigurations(std::istream& in, const robots::RobotModel& robot,
                                                JointLimitPolicy* limits) {
  std::vector<Eigen::VectorXd> out;
  int lineNumber = 0;
  InputLine line;
  while (nextInputLine(in, lineNumber, line)) {
    Eigen::VectorXd q(static_cast<Eigen::Index>(line.tokens.size()));
    for (Eigen::Index v = 0; v < q.size(); ++v) q[v] = parseNumber(line, line.tokens[static_cast<std::size_t>(v)]);
    if (q.size() != robot.numVariables()) {
      failAt(line, std::to_string(q.size()) + " values, robot '" + robot.name() + "' has " +
                       std::to_string(robot.numVariables()) + " variables");
    }
    try {
      if (limits != nullptr) applyJointLimits(robot, q, "the configuration", *limits);
    } catch (const InputError& e) {
      failAt(line, e.what());
    }
    out.push_back(std::move(q));
  }
  return out;
}

robots::FrameAliases takeFrameAliases(std::vector<std::string>& args) {
  robots::FrameAliases aliases;
  for (const std::string& text : takeOption(args, "--frame-alias")) {
    std::pair<std::string, std::string> alias;
    try {
      alias = robots::parseFrameAlias(text);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--frame-alias: ") + e.what());
    }
    const auto [it, added] = aliases.insert(alias);
    if (!added && it->second != alias.second) {
      throw UsageError("--frame-alias: frame '" + alias.first + "' mapped twice, to '" + it->second + "' and '" +
                       alias.second + "'");
    }
  }
  return aliases;
}

std::map<std::string, double> takeLocks(std::vector<std::string>& args) {
  std::map<std::string, double> locks;
  for (const std::string& text : takeOption(args, "--lock")) {
    const std::size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
      throw UsageError("--lock needs JOINT=VALUE, got '" + text + "'");
    }
    const std::string joint = text.substr(0, eq);
    const double value = parseValue(text.substr(eq + 1), "--lock " + joint);
    if (!locks.emplace(joint, value).second) throw UsageError("--lock: joint '" + joint + "' given twice");
  }
  return locks;
}

std::vector<std::pair<std::string, std::string>> takeAllowedCollisions(std::vector<std::string>& args) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string& text : takeOption(args, "--allow-collision")) {
    const std::size_t colon = text.find(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == text.size() ||
        text.find(':', colon + 1) != std::string::npos) {
      throw UsageError("--allow-collision needs A:B (two body names, or A:* for A against anything), got '" + text +
                       "'");
    }
    out.emplace_back(text.substr(0, colon), text.substr(colon + 1));
  }
  return out;
}

namespace {

std::string lowerCaseExtension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace

bool isPlanningSceneFile(const std::string& path) {
  const std::string extension = lowerCaseExtension(path);
  return extension == ".yaml" || extension == ".yml" || robots::isSceneTextFile(path);
}

SceneKind sceneKind(const std::string& path) {
  if (isPlanningSceneFile(path)) return SceneKind::PlanningScene;
  const std::string extension = lowerCaseExtension(path);
  if (extension == ".urdf") return SceneKind::Urdf;
  throw UsageError("scene '" + path + "': unknown scene type '" + extension +
                   "' (expected .urdf for a URDF scene, .yaml, .yml or .scene for a MoveIt planning scene)");
}

WorldArgs takeWorldArgs(std::vector<std::string>& args) {
  WorldArgs w;
  takeWorldOptions(args, w.robot, w.scenes, w.srdfs);
  w.packages = takePackageRoots(args);
  w.frameAliases = takeFrameAliases(args);
  w.group = takeSingleOption(args, "--group");
  w.locks = takeLocks(args);
  w.allowed = takeAllowedCollisions(args);
  if (!w.group.empty() && w.srdfs.empty()) {
    throw UsageError("--group " + w.group + " needs --srdf: the planning groups are the SRDF's");
  }
  bool planningScene = false;
  for (const SceneArg& s : w.scenes) {
    if (sceneKind(s.path) != SceneKind::PlanningScene) continue;
    planningScene = true;
    if (s.posed) {
      throw UsageError("--scene-pose after planning scene '" + s.path +
                       "': its objects are posed in the frames they name (header.frame_id); --scene-pose "
                       "places URDF scenes only");
    }
  }
  if (!w.frameAliases.empty() && !planningScene) {
    throw UsageError("--frame-alias needs a planning-scene --scene (.yaml, .yml or .scene)");
  }
  return w;
}

checker::World loadWorld(const WorldArgs& args) {
  robots::LoadOptions load;
  load.packageRoots = args.packages.commandLine;
  robots::RobotModel robot = robots::planningGroupModel(robots::RobotModel::fromUrdfFile(args.robot, load), args.srdfs,
                                                        args.group, args.locks);
  checker::WorldOptions options;
  std::vector<robots::SrdfVirtualJoint> virtualJoints;
  for (const std::string& srdf : args.srdfs) {
    const std::vector<robots::DisabledPair> pairs = robots::readSrdfDisabledPairs(srdf);
    robots::checkDisabledPairs(robot, pairs, srdf);
    options.disabledPairs.insert(options.disabledPairs.end(), pairs.begin(), pairs.end());
    const std::vector<robots::SrdfVirtualJoint> joints = robots::readSrdfVirtualJoints(srdf);
    virtualJoints.insert(virtualJoints.end(), joints.begin(), joints.end());
  }
  checker::World world(std::move(robot), options);
  const bool reports = world.setFixedPairReports(false);  // once the allowed pairs are in
  robots::SceneLoadOptions sceneLoad;
  sceneLoad.packageRoots = args.packages.commandLine;
  checker::PlanningSceneOptions placement;
  placement.frameAliases = robots::withVirtualJointAliases(args.frameAliases, virtualJoints, world.robot());
  for (const SceneArg& s : args.scenes) {
    if (sceneKind(s.path) == SceneKind::PlanningScene) {
      world.addPlanningScene(robots::loadPlanningScene(s.path, sceneLoad), placement);
    } else if (s.posed) {
      world.addScene(robots::RobotModel::fromUrdfFile(s.path, load), s.X_WS);
    } else {
      world.addScene(robots::RobotModel::fromUrdfFile(s.path, load));
    }
  }
  for (const auto& [a, b] : args.allowed) {
    try {
      world.allowCollision(a, b);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("--allow-collision " + a + ":" + b + ": " + e.what());
    }
  }
  world.setFixedPairReports(reports);
  return world;
}

}  // namespace deepcheck::tools
