#pragma once
// Triangle meshes as loaded from collision mesh files (STL, OBJ, DAE through assimp).
// Shared by the mesh loader and the convex decomposition.

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace deepcheck::robots {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;      ///< in the mesh's frame, metres (after unit/scale)
  std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside when the file says so
  std::string source;                         ///< file it came from, for messages ("" if generated)

  bool empty() const { return triangles.empty(); }
  /// Diagonal of the axis-aligned bounding box (0 for an empty mesh).
  double boundingBoxDiagonal() const;
};

}  // namespace deepcheck::robots
