#pragma once
// Reading a planning scene's allowed_collision_matrix (moveit_scene.h: AllowedCollisions).

#include "deepcheck/robots/moveit_scene.h"
#include "scene_yaml.h"

namespace deepcheck::robots {

/// moveit_msgs/AllowedCollisionMatrix: entry_names, entry_values (entry_values[i].enabled, one
/// bool per entry name), default_entry_names, default_entry_values (one bool per default name).
/// As MoveIt reads the message, only the upper triangle of the matrix counts: pair (i, j), i < j,
/// is allowed when entry_values[i].enabled[j] is true; the diagonal and the lower triangle are read
/// and checked but not used. Names allowed by default are those whose default value is true.
/// False entries are dropped: AllowedCollisions holds what is allowed. An absent or null node is
/// an empty matrix. Names are not checked against any robot or object here. Throws (Context::fail)
/// for an unknown key, a name listed twice, lists of mismatched sizes, a value that is no bool.
AllowedCollisions readAllowedCollisions(const scene_yaml::Context& ctx, const YAML::Node& node);

}  // namespace deepcheck::robots
