#pragma once
// The collision world of the command line (--robot, --scene [--scene-pose], --srdf,
// --package-path, --frame-alias), shared by the subcommands that query it.
//
// A scene's kind is chosen by its file's extension: .urdf is a URDF scene (a model whose links
// are obstacles, placed by --scene-pose); .yaml or .yml is a MoveIt planning scene
// (robots/moveit_scene.h) whose collision objects are posed in the frames their header.frame_id
// names: robot links, or names that --frame-alias maps to robot links, or the parent frame of an
// --srdf's virtual joint (the robot's root link); .scene is MoveIt's scene text format, its
// objects in the model frame (the robot's root link). A planning scene's objects are already
// placed by their frames, so --scene-pose after one is an error.

#include "common.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/moveit_scene.h"

#include <Eigen/Core>

#include <istream>
#include <map>
#include <set>
#include <string>
#include <vector>

/// The help text of the world options, for the usage text of the subcommands that take them.
#define DEEPCHECK_WORLD_OPTIONS_HELP                                                                   \
  "  --robot FILE        the robot's URDF (required)\n"                                                \
  "  --scene FILE        a scene (repeatable): FILE.urdf is a URDF whose links are obstacles (its\n"   \
  "                      joints at their default values); FILE.yaml or FILE.yml is a MoveIt\n"         \
  "                      planning scene, its collision objects posed in the robot links their\n"       \
  "                      header.frame_id names (at the robot's default configuration);\n"              \
  "                      FILE.scene is MoveIt's scene text (Export/Import), posed on the root link\n"  \
  "  --scene-pose x y z roll pitch yaw\n"                                                              \
  "                      places the URDF scene given just before (metres, radians; URDF rpy:\n"        \
  "                      R = Rz(yaw) Ry(pitch) Rx(roll)); default: the identity. Not after a\n"        \
  "                      planning scene, whose objects are placed by their frames\n"                   \
  "  --frame-alias NAME=LINK\n"                                                                        \
  "                      a planning scene's frame NAME is the robot's link LINK (repeatable),\n"       \
  "                      e.g. base_link=panda_link0 for MotionBenchMaker scenes with the Panda;\n"     \
  "                      an --srdf's virtual_joint parent frame (world, odom_combined) is already\n"   \
  "                      an alias of its child link\n"                                                 \
  "  --srdf FILE         disable the self-collision pairs of this SRDF and read its planning groups\n" \
  "                      (repeatable: the files' pairs and groups are merged; a group two files\n"     \
  "                      define differently is an error)\n"                                            \
  "  --group NAME        move only the variables of the SRDF's planning group NAME (needs --srdf);\n"  \
  "                      the others are held at their --lock value, else their default\n"              \
  "  --lock JOINT=VALUE  hold JOINT at VALUE (rad or m; repeatable); configurations then omit it\n"    \
  "  --package-path DIR  a root to search for package:// URIs (repeatable; ROS_PACKAGE_PATH is\n"      \
  "                      also read)\n"                                                                 \
  "  --allow-collision A:B\n"                                                                          \
  "                      let bodies A and B touch (repeatable); A:* lets A touch anything. Names:\n"   \
  "                      robot links, obstacles and planning-scene object ids, scene links\n"          \
  "                      (scene/LINK), attached objects; e.g. base_link:table for a robot bolted\n"    \
  "                      to a table\n"

namespace deepcheck::tools {

/// What `check` and `plan` do with a joint value outside its joint's limits: refuse it (an error
/// naming the joint, the value and the limits) or, with --clamp-to-limits, clamp it and warn.
/// Continuous joints have no limits: their values are taken as they are.
struct JointLimitPolicy {
  bool clamp = false;             ///< clamp instead of refusing
  std::set<std::string> clamped;  ///< the joints clamped so far, for warnClamped()
};

/// The help line of --clamp-to-limits.
#define DEEPCHECK_CLAMP_HELP                                                                         \
  "  --clamp-to-limits   clamp a joint value outside its limits into them (one warning line names\n" \
  "                      the clamped joints) instead of refusing it; continuous joints have none\n"

/// Applies `policy` to q (one value per variable of `robot`): a value outside its bounded joint's
/// limits is clamped (its joint added to policy.clamped) or refused with an InputError whose
/// message starts with `what` and names the joint, the value and the limits.
void applyJointLimits(const robots::RobotModel& robot, Eigen::VectorXd& q, const std::string& what,
                      JointLimitPolicy& policy);

/// One line on stderr, "deepcheck <subcommand>: warning: ...", naming the clamped joints; nothing
/// when none was clamped.
void warnClamped(const std::string& subcommand, const JointLimitPolicy& policy);

/// One line on stderr, "deepcheck <subcommand>: warning: ...", naming the robot's links that have
/// a <visual> but no <collision> element: the checker cannot see them, so a robot drawn only with
/// visuals would be found free everywhere. Nothing when there is no such link.
void warnVisualOnlyLinks(const std::string& subcommand, const robots::RobotModel& robot);

/// Configurations, one per line (joint values in the robot's variable order; '#' comments and
/// blank lines skipped), each taken within the joint limits by `limits` when given (a path file
/// is read as written); throws InputError naming the line (a bad number, a wrong count, a value
/// that `limits` refuses).
std::vector<Eigen::VectorXd> readConfigurations(std::istream& in, const robots::RobotModel& robot,
                                                JointLimitPolicy* limits = nullptr);

/// Removes every `--frame-alias NAME=LINK` (or `--frame-alias=NAME=LINK`) from `args`: the scene
/// frame NAME is the robot's link LINK. UsageError for a malformed or repeated NAME.
robots::FrameAliases takeFrameAliases(std::vector<std::string>& args);

/// The world options of a command line.
struct WorldArgs {
  std::string robot;
  std::vector<SceneArg> scenes;
  std::vector<std::string> srdfs;  ///< --srdf, in command-line order
  PackageRoots packages;
  robots::FrameAliases frameAliases;
  std::string group;                    ///< --group
  std::map<std::string, double> locks;  ///< --lock
  /// --allow-collision A:B, in command-line order ("*" for anything).
  std::vector<std::pair<std::string, std::string>> allowed;
};

/// Removes every `--allow-collision A:B` from `args`. UsageError unless the text is two non-empty
/// names joined by one ':' (B may be "*").
std::vector<std::pair<std::string, std::string>> takeAllowedCollisions(std::vector<std::string>& args);

/// Removes every `--lock JOINT=VALUE` from `args`. UsageError for a malformed one, a value that is
/// not a finite number, or a joint given twice.
std::map<std::string, double> takeLocks(std::vector<std::string>& args);

/// Removes --robot, --scene [--scene-pose], --srdf, --group, --lock, --package-path and
/// --frame-alias from `args`
/// (takeWorldOptions, takePackageRoots, takeFrameAliases, takeLocks). UsageError for --scene-pose
/// after a planning-scene YAML, a --frame-alias without any such scene, or --group without --srdf.
WorldArgs takeWorldArgs(std::vector<std::string>& args);

/// True for a .yaml, .yml or .scene file (any case): a MoveIt planning scene.
bool isPlanningSceneFile(const std::string& path);

/// The kind of a scene file, from its extension (any case).
enum class SceneKind { Urdf, PlanningScene };
/// Throws UsageError naming the file and the extensions known for any other extension.
SceneKind sceneKind(const std::string& path);

/// Loads the robot (its --group's variables only, its --lock joints held), disables the pairs of
/// every SRDF (an unknown link in one is an error naming the file), adds the scenes in
/// command-line order and allows the --allow-collision pairs (an unknown name is an error naming
/// it and its near matches); the world reports its fixed pairs (world.h) after all of that. Throws
/// std::invalid_argument naming the bad file (for a planning scene, its line, object and frame; an unknown frame's
/// message suggests
/// --frame-alias).
checker::World loadWorld(const WorldArgs& args);

}  // namespace deepcheck::tools
