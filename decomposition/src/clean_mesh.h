#pragma once
// Internal to deepcheck::decomposition: the input mesh, cleaned (mesh_repair.cpp).

#include "deepcheck/decomposition/mesh.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <string>
#include <vector>

namespace deepcheck::decomposition::detail {

using Eigen::Vector3d;

// The input, cleaned: identical vertices welded, degenerate triangles dropped, edge adjacency.

struct CleanMesh {
  std::vector<Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> edgeOf;     ///< 3 per triangle: the undirected edge (v[e], v[e+1 mod 3])
  std::vector<int> edgeStart;  ///< edge k's triangles: edgeTris[edgeStart[k] .. edgeStart[k+1])
  std::vector<int> edgeTris;
  std::vector<int> component;  ///< connected component of each triangle (through edges)
  int numComponents = 0;
  std::vector<int> group;  ///< components with overlapping bounding boxes, per triangle
  int numGroups = 0;
  double diagonal = 0.0;
  bool closed = false;  ///< after filling holes
  int holesFilled = 0;
  int voidsRemoved = 0;       ///< closed inward-facing components sealed inside others
  int duplicatesRemoved = 0;  ///< triangles on the same three vertices as an earlier one
  int inputVertices = 0;      ///< before filling holes
  int inputTriangles = 0;
  double volume = 0.0;  ///< sum of the components' volumes (voids count negative); NaN when open
};

/// The input, cleaned (mesh_repair.cpp): welded, holes filled, oriented outward.
CleanMesh cleanMesh(const TriangleMesh& mesh);

/// Throws std::invalid_argument naming the mesh (`name`, as meshName gives) for a mesh without
/// triangles, a vertex that is not finite or an index out of range.
void checkInput(const TriangleMesh& mesh, const std::string& name);
/// The bounding box of the vertices the triangles use.
Eigen::AlignedBox3d usedBox(const TriangleMesh& mesh);
/// A triangle whose area is at most (kDegenerateRelative * diagonal)^2: cleanMesh drops it.
bool isDegenerate(const Vector3d& a, const Vector3d& b, const Vector3d& c, double diagonal);

}  // namespace deepcheck::decomposition::detail
