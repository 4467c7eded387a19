#pragma once
// Checked reading of YAML values for the planning-scene loader (moveit_scene.h): every failure
// throws std::invalid_argument naming the file, the line (yaml-cpp's Mark, 1-based) and the
// object being read.

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>

#include <initializer_list>
#include <string>
#include <vector>

namespace deepcheck::robots::scene_yaml {

/// Where values are read: the file and the object, for messages.
struct Context {
  std::string source;
  std::string object;  ///< "object 'Can1'", "object 3" or "" (outside objects)

  /// "planning scene '<source>', line <n>, <object>", the start of every message.
  std::string where(const YAML::Node& node) const;
  /// Throws "planning scene '<source>', line <n>, <object>: <what>". `node` gives the line; an
  /// undefined node gives none.
  [[noreturn]] void fail(const YAML::Node& node, const std::string& what) const;
};

/// The first document of YAML text. Throws std::invalid_argument "planning scene '<source>',
/// line <n>: collections nested <d> levels deep, more than the limit of kMaxNestingDepth" when
/// maps and sequences nest deeper than kMaxNestingDepth (robot_model.h); the depth is checked
/// by an event pass that stops there, before yaml-cpp builds the nodes. Malformed YAML throws
/// YAML::Exception.
YAML::Node loadYaml(const std::string& text, const std::string& source);

/// 1-based line of a node, 0 when it has none.
int lineOf(const YAML::Node& node);

/// parent[key], which must exist (the error names the key and the parent's line).
YAML::Node required(const Context& ctx, const YAML::Node& parent, const char* key);
/// Throws unless `node` is a map whose keys are all in `allowed` (the error lists them).
void checkKeys(const Context& ctx, const YAML::Node& node, const char* what,
               std::initializer_list<const char*> allowed);

std::string readString(const Context& ctx, const YAML::Node& node, const std::string& what);
/// true or false (also True, yes, on... as YAML 1.1 spells them).
bool readBool(const Context& ctx, const YAML::Node& node, const std::string& what);
/// A finite number.
double readNumber(const Context& ctx, const YAML::Node& node, const std::string& what);
/// A sequence of finite numbers.
std::vector<double> readNumbers(const Context& ctx, const YAML::Node& node, const std::string& what);
/// [x, y, z] or {x:, y:, z:}.
Eigen::Vector3d readVector3(const Context& ctx, const YAML::Node& node, const std::string& what);
/// [x, y, z, w] or {x:, y:, z:, w:}, normalised (tol::kSceneQuaternionNorm).
Eigen::Quaterniond readQuaternion(const Context& ctx, const YAML::Node& node, const std::string& what);
/// {position, orientation}, both required.
Eigen::Isometry3d readPose(const Context& ctx, const YAML::Node& node, const std::string& what);
/// {translation, rotation} (geometry_msgs/Transform).
Eigen::Isometry3d readTransform(const Context& ctx, const YAML::Node& node, const std::string& what);

}  // namespace deepcheck::robots::scene_yaml
