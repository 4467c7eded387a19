// A planning scene's allowed_collision_matrix (moveit_scene_acm.h).
#include "moveit_scene_acm.h"

#include <map>
#include <string>
#include <vector>

namespace deepcheck::robots {
namespace {

using scene_yaml::Context;

/// The list under `key` of the matrix (absent or null: empty).
YAML::Node list(const Context& ctx, const YAML::Node& acm, const char* key) {
  const YAML::Node node = acm[key];
  if (!node.IsDefined() || node.IsNull()) return YAML::Node(YAML::NodeType::Sequence);
  if (!node.IsSequence()) ctx.fail(node, std::string("allowed_collision_matrix.") + key + " must be a list");
  return node;
}

/// Names, each once.
std::vector<std::string> readNames(const Context& ctx, const YAML::Node& node, const char* key) {
  std::vector<std::string> names;
  std::map<std::string, int> lines;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string what = std::string(key) + "[" + std::to_string(i) + "]";
    names.push_back(scene_yaml::readString(ctx, node[i], what));
    const auto [it, inserted] = lines.emplace(names.back(), scene_yaml::lineOf(node[i]));
    if (!inserted) {
      ctx.fail(node[i],
               what + " '" + names.back() + "' is listed twice (first at line " + std::to_string(it->second) + ")");
    }
  }
  return names;
}

/// Fails unless `values` has as many entries as `names`; the message names the line of `values`,
/// else (when it is absent) that of `parent`.
void checkSameSize(const Context& ctx, const YAML::Node& parent, const YAML::Node& values, const std::string& valuesKey,
                   std::size_t names, const char* namesKey) {
  if (values.size() == names) return;
  ctx.fail(scene_yaml::lineOf(values) > 0 ? values : parent, valuesKey + " has " + std::to_string(values.size()) +
                                                                 " entries, " + namesKey + " has " +
                                                                 std::to_string(names) + ": one per name expected");
}

void readMatrix(const Context& ctx, const YAML::Node& acm, AllowedCollisions& out) {
  const std::vector<std::string> names = readNames(ctx, list(ctx, acm, "entry_names"), "entry_names");
  const YAML::Node rows = list(ctx, acm, "entry_values");
  checkSameSize(ctx, acm, rows, "entry_values", names.size(), "entry_names");
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string what = "entry_values[" + std::to_string(i) + "]";
    scene_yaml::checkKeys(ctx, rows[i], what.c_str(), {"enabled"});
    const YAML::Node enabled = scene_yaml::required(ctx, rows[i], "enabled");
    if (!enabled.IsSequence()) ctx.fail(enabled, what + ".enabled must be a list");
    checkSameSize(ctx, rows[i], enabled, what + ".enabled", names.size(), "entry_names");
    for (std::size_t j = 0; j < enabled.size(); ++j) {
      const bool allowed = scene_yaml::readBool(ctx, enabled[j], what + ".enabled[" + std::to_string(j) + "]");
      if (allowed && j > i) out.pairs.emplace_back(names[i], names[j]);
    }
  }
}

void readDefaults(const Context& ctx, const YAML::Node& acm, AllowedCollisions& out) {
  const std::vector<std::string> names = readNames(ctx, list(ctx, acm, "default_entry_names"), "default_entry_names");
  const YAML::Node values = list(ctx, acm, "default_entry_values");
  checkSameSize(ctx, acm, values, "default_entry_values", names.size(), "default_entry_names");
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (scene_yaml::readBool(ctx, values[i], "default_entry_values[" + std::to_string(i) + "]")) {
      out.always.push_back(names[i]);
    }
  }
}

}  // namespace

AllowedCollisions readAllowedCollisions(const Context& ctx, const YAML::Node& node) {
  AllowedCollisions out;
  if (!node.IsDefined() || node.IsNull()) return out;
  scene_yaml::checkKeys(ctx, node, "allowed_collision_matrix",
                        {"entry_names", "entry_values", "default_entry_names", "default_entry_values"});
  readMatrix(ctx, node, out);
  readDefaults(ctx, node, out);
  return out;
}

}  // namespace deepcheck::robots
