// Meshes given inline in a planning scene (moveit_scene_inline_mesh.h).
#include "moveit_scene_inline_mesh.h"

#include <array>
#include <string>

namespace deepcheck::robots {
namespace {

using scene_yaml::Context;

/// The non-empty list under `key`, its size taken from `budget`.
YAML::Node budgetedList(const Context& ctx, const YAML::Node& node, const char* key, std::size_t& budget) {
  const YAML::Node list = scene_yaml::required(ctx, node, key);
  if (!list.IsSequence() || list.size() == 0)
    ctx.fail(list, std::string("inline mesh '") + key + "' must be a list, not empty");
  if (list.size() > budget) {
    ctx.fail(list, std::string("inline mesh '") + key + "' has " + std::to_string(list.size()) +
                       " entries, more than the " + std::to_string(budget) +
                       " left of SceneLoadOptions::maxInlineMeshElements (YAML aliases counted as expanded)");
  }
  budget -= list.size();
  return list;
}

int readIndex(const Context& ctx, const YAML::Node& node, const std::string& what, std::size_t vertices) {
  long long index = -1;
  if (!node.IsScalar() || !YAML::convert<long long>::decode(node, index)) {
    ctx.fail(node, what + " must be a vertex index (0, 1, 2...)");
  }
  if (index < 0 || static_cast<unsigned long long>(index) >= vertices) {
    ctx.fail(node, what + " is " + node.Scalar() + ", not one of the " + std::to_string(vertices) + " vertices");
  }
  return static_cast<int>(index);
}

std::array<int, 3> readTriangle(const Context& ctx, const YAML::Node& node, const std::string& what,
                                std::size_t vertices) {
  YAML::Node indices = node;
  if (node.IsMap()) {
    scene_yaml::checkKeys(ctx, node, what.c_str(), {"vertex_indices"});
    indices = scene_yaml::required(ctx, node, "vertex_indices");
  }
  if (!indices.IsSequence() || indices.size() != 3) ctx.fail(indices, what + " must have three vertex indices");
  std::array<int, 3> triangle{};
  for (std::size_t k = 0; k < 3; ++k) {
    triangle[k] = readIndex(ctx, indices[k], what + "[" + std::to_string(k) + "]", vertices);
  }
  return triangle;
}

}  // namespace

bool isInlineMesh(const YAML::Node& node) {
  return node.IsMap() && (node["vertices"].IsDefined() || node["triangles"].IsDefined());
}

TriangleMesh readInlineMesh(const Context& ctx, const YAML::Node& node, std::size_t& budget) {
  const YAML::Node vertices = budgetedList(ctx, node, "vertices", budget);
  const YAML::Node triangles = budgetedList(ctx, node, "triangles", budget);
  TriangleMesh mesh;
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    mesh.vertices.push_back(scene_yaml::readVector3(ctx, vertices[v], "vertices[" + std::to_string(v) + "]"));
  }
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    mesh.triangles.push_back(readTriangle(ctx, triangles[t], "triangles[" + std::to_string(t) + "]", vertices.size()));
  }
  return mesh;
}

}  // namespace deepcheck::robots
