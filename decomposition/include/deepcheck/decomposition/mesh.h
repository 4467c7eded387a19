#pragma once
// Triangle meshes: what the convex decomposition takes, and what robots' mesh loader reads from
// collision mesh files (STL, OBJ, DAE).

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace deepcheck::decomposition {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;      ///< in the mesh's frame, metres (after unit/scale)
  std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside when the file says so
  std::string source;                         ///< file it came from, for messages ("" if generated)

  bool empty() const { return triangles.empty(); }
  /// Diagonal of the axis-aligned bounding box (0 for an empty mesh).
  double boundingBoxDiagonal() const;
};

}  // namespace deepcheck::decomposition
