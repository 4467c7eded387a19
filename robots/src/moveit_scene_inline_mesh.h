#pragma once
// Reading a mesh given inline in a planning scene (shape_msgs/Mesh: triangles and vertices, as
// MoveIt publishes a mesh collision object) for the YAML loader (moveit_scene.h).

#include "deepcheck/robots/mesh.h"
#include "scene_yaml.h"

#include <cstddef>

namespace deepcheck::robots {

/// True when the mesh entry `node` is given inline (has `vertices` or `triangles`).
bool isInlineMesh(const YAML::Node& node);

/// The mesh of {vertices: [{x, y, z}...] (or [x, y, z] each), triangles: [{vertex_indices: [i, j,
/// k]}...] (or [i, j, k] each)}, vertex indices 0-based. Both lists are required and not empty;
/// `budget` (vertices and triangles the scene may still hold, SceneLoadOptions::
/// maxInlineMeshElements) is checked before a list is read and then reduced. Throws
/// (Context::fail) for a missing list, a vertex as read by readVector3, an index that is not an
/// integer or names no vertex, a triangle without three indices, or a list past the budget.
TriangleMesh readInlineMesh(const scene_yaml::Context& ctx, const YAML::Node& node, std::size_t& budget);

}  // namespace deepcheck::robots
