#pragma once
// Loading collision meshes (STL ASCII/binary, OBJ, DAE, anything assimp reads) into one
// TriangleMesh.
//
// What is done, in order:
//   1. assimp reads the file with aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
//      aiProcess_SortByPType; points and lines are ignored.
//   2. Every mesh instanced by the scene's node tree is placed by its node's accumulated
//      transform (root included) and all are merged into one mesh; identical positions are
//      welded into one vertex.
//   3. The URDF `scale` is applied (componentwise, in the mesh file's frame, after step 2).
//      When the transform of a mesh mirrors (negative determinant), its triangles are re-wound so
//      that they keep facing the same way.
//   4. Degenerate triangles (two equal corners, or a height of at most
//      tol::kDegenerateTriangleRelative times the bounding-box diagonal) are dropped, and vertices
//      no triangle uses are removed.
//
// COLLADA units and up axis. assimp 5.2 applies <unit meter="..."> by scaling the root node's
// transform, and (unless told otherwise) rotates Z_UP and X_UP files into its own Y-up convention
// by the same root transform; it adds no "UnitScaleFactor" metadata for COLLADA (verified on
// 5.2.5). URDF meshes are expressed in their link's frame, whose Z is whatever the URDF says, and
// the ROS tools (RViz, MoveIt's geometric_shapes, Gazebo) take the mesh coordinates as authored.
// So this loader sets AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION (the <up_axis> tag is ignored:
// coordinates are used as written) and keeps the root transform (the unit is honoured: a file in
// millimetres with <unit meter="0.001"/> comes out in metres). STL and OBJ carry no unit: their
// numbers are taken as metres, as URDF does.
//
// Frames and units: vertices are in the mesh file's frame after the URDF scale, in metres.

#include "deepcheck/robots/mesh.h"

#include <Eigen/Core>

#include <cstdint>
#include <string>

namespace deepcheck::robots {

struct MeshLoadOptions {
  /// Largest mesh file read, bytes (assimp holds about twice the file in memory while reading;
  /// real collision meshes are a few MB). A larger file is an error naming its size.
  std::uintmax_t maxFileBytes = std::uintmax_t{256} << 20;
};

/// Loads `path` as described above and returns the merged, cleaned mesh (source = path).
/// Throws std::invalid_argument, naming the file, when the file is missing, unreadable or larger
/// than options.maxFileBytes, when an XML file nests elements deeper than kMaxNestingDepth
/// (robot_model.h), when
/// a COLLADA file has an index list (<p>, <h>, <vcount>) holding anything but digits and
/// whitespace, an array without a count or an accessor reaching beyond its array (assimp 5.2 would
/// exhaust memory or crash on them; the line is named), when assimp fails (assimp's error string
/// is included), when the scale has a zero component or one of magnitude above
/// geometry::range::kMaxCoordinate, when a vertex is not finite or, placed and scaled, lies beyond
/// geometry::range::kMaxCoordinate (the message names the scale), or when no non-degenerate
/// triangle is left.
TriangleMesh loadMesh(const std::string& path, const Eigen::Vector3d& scale = Eigen::Vector3d::Ones(),
                      const MeshLoadOptions& options = {});

/// Drops degenerate triangles and unused vertices of `mesh` in place (step 4 above); returns the
/// number of triangles dropped.
int removeDegenerateTriangles(TriangleMesh& mesh);

}  // namespace deepcheck::robots
