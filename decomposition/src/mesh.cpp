#include "deepcheck/decomposition/mesh.h"

namespace deepcheck::decomposition {

double TriangleMesh::boundingBoxDiagonal() const {
  if (vertices.empty()) return 0.0;
  Eigen::Vector3d lo = vertices.front();
  Eigen::Vector3d hi = vertices.front();
  for (const Eigen::Vector3d& v : vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return (hi - lo).norm();
}

}  // namespace deepcheck::decomposition
