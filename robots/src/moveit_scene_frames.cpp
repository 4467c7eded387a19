// Placing a planning scene's objects in the world through the robot's links (moveit_scene.h).
#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/moveit_scene.h"

#include <stdexcept>

namespace deepcheck::robots {
namespace {

std::string linkList(const RobotModel& robot) {
  std::string out;
  for (const Link& link : robot.links()) out += (out.empty() ? "" : ", ") + link.name;
  return out;
}

/// The link an object's frame names (after the aliases); throws with the advice of moveit_scene.h.
int frameLink(const PlanningScene& scene, const SceneObject& object, const RobotModel& robot,
              const FrameAliases& aliases) {
  const std::string where =
      "planning scene '" + scene.source + "', line " + std::to_string(object.line) + ", object '" + object.id + "'";
  const auto alias = aliases.find(object.frameId);
  if (alias != aliases.end()) {
    const int link = robot.linkIndex(alias->second);
    if (link >= 0) return link;
    throw std::invalid_argument(where + ": frame '" + object.frameId + "' is aliased to '" + alias->second +
                                "', which is no link of robot '" + robot.name() + "' (links: " + linkList(robot) + ")");
  }
  const int link = robot.linkIndex(object.frameId);
  if (link >= 0) return link;
  if (object.frameId == kModelFrame && robot.numLinks() > 0) return 0;  // the root link
  const std::string root = robot.numLinks() > 0 ? robot.link(0).name : "LINK";
  throw std::invalid_argument(where + ": unknown frame '" + object.frameId + "': robot '" + robot.name() +
                              "' has no such link (links: " + linkList(robot) +
                              "); if the file means one of them, give a "
                              "frame alias, e.g. --frame-alias " +
                              object.frameId + "=" + root + " (FrameAliases {\"" + object.frameId + "\", \"" + root +
                              "\"})");
}

}  // namespace

std::pair<std::string, std::string> parseFrameAlias(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size() || text.find('=', eq + 1) != std::string::npos) {
    throw std::invalid_argument("frame alias '" + text + "' must be NAME=LINK (e.g. base_link=panda_link0)");
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

FrameAliases withVirtualJointAliases(FrameAliases aliases, const std::vector<SrdfVirtualJoint>& virtualJoints,
                                     const RobotModel& robot) {
  for (const SrdfVirtualJoint& joint : virtualJoints) {
    if (robot.linkIndex(joint.parentFrame) >= 0) continue;
    aliases.emplace(joint.parentFrame, joint.childLink);
  }
  return aliases;
}

std::vector<std::vector<Eigen::Isometry3d>> shapeWorldPoses(const PlanningScene& scene, const RobotModel& robot,
                                                            const Eigen::Ref<const Eigen::VectorXd>& q,
                                                            const FrameAliases& aliases) {
  const std::vector<Eigen::Isometry3d> X_WL = forwardKinematics(robot, q);
  std::vector<std::vector<Eigen::Isometry3d>> out;
  out.reserve(scene.objects.size());
  for (const SceneObject& object : scene.objects) {
    const Eigen::Isometry3d& X_WF = X_WL[frameLink(scene, object, robot, aliases)];
    std::vector<Eigen::Isometry3d> poses;
    poses.reserve(object.shapes.size());
    for (const SceneShape& shape : object.shapes) poses.push_back(X_WF * shape.X_FS);
    out.push_back(std::move(poses));
  }
  return out;
}

}  // namespace deepcheck::robots
