// Coverage of a mesh by convex pieces (decomposition.h): the check a decomposition read from the
// cache passes before it is used.

#include "deepcheck/decomposition/decomposition.h"

#include "basics.h"
#include "clean_mesh.h"

#include <algorithm>
#include <string>
#include <vector>

namespace deepcheck::decomposition {

using detail::kInf;

namespace {

/// Distance from `point` to `piece` (0 inside it): to its nearest face when outside.
double distanceToPiece(const ConvexPiece& piece, const Eigen::Vector3d& point) {
  if (pieceContains(piece, point, 0.0)) return 0.0;
  double best = kInf;
  for (const auto& t : piece.triangles) {
    const Eigen::Vector3d q =
        detail::closestPointOnTriangle(point, piece.vertices[t[0]], piece.vertices[t[1]], piece.vertices[t[2]]);
    best = std::min(best, (q - point).norm());
  }
  for (const Eigen::Vector3d& v : piece.vertices) best = std::min(best, (v - point).norm());
  return best;
}

/// The vertices of the triangles that the decomposition keeps (not degenerate): those that the
/// pieces must cover. A vertex used only by dropped triangles has no surface around it.
std::vector<char> coveredVertices(const TriangleMesh& mesh, double diagonal) {
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const auto& t : mesh.triangles) {
    if (detail::isDegenerate(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], diagonal)) {
      continue;
    }
    for (int k : t) used[k] = 1;
  }
  return used;
}

}  // namespace

std::string coverageProblem(const TriangleMesh& mesh, const std::vector<ConvexPiece>& pieces) {
  detail::checkInput(mesh, detail::meshName(mesh));
  const Eigen::AlignedBox3d meshBox = detail::usedBox(mesh);
  const double diagonal = meshBox.diagonal().norm();
  const double tolerance = tol::kCoverageToleranceRelative * diagonal;
  std::vector<Eigen::AlignedBox3d> boxes(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (const Eigen::Vector3d& v : pieces[i].vertices) boxes[i].extend(v);
    boxes[i].min().array() -= tolerance;
    boxes[i].max().array() += tolerance;
  }
  const std::vector<char> used = coveredVertices(mesh, diagonal);
  // Neighbouring vertices mostly lie in the same piece: the last one that held a vertex is tried
  // first.
  std::size_t last = 0;
  auto covers = [&](std::size_t i, const Eigen::Vector3d& v) {
    return boxes[i].contains(v) && pieceContains(pieces[i], v, tolerance);
  };
  for (std::size_t k = 0; k < mesh.vertices.size(); ++k) {
    const Eigen::Vector3d& v = mesh.vertices[k];
    if (!used[k] || (last < pieces.size() && covers(last, v))) continue;
    bool covered = false;
    for (std::size_t i = 0; i < pieces.size() && !covered; ++i) {
      if (covers(i, v)) {
        covered = true;
        last = i;
      }
    }
    if (covered) continue;
    double distance = kInf;
    for (const ConvexPiece& piece : pieces) distance = std::min(distance, distanceToPiece(piece, v));
    using detail::roundedNumber;
    return "vertex " + std::to_string(k) + " (" + roundedNumber(v.x()) + ", " + roundedNumber(v.y()) + ", " +
           roundedNumber(v.z()) + ") is " +
           (pieces.empty() ? std::string("outside: no piece") : roundedNumber(distance) + " outside every piece") +
           " (tolerance " + roundedNumber(tolerance) + ")";
  }
  return "";
}

}  // namespace deepcheck::decomposition
