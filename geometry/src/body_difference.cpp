// Minkowski differences of piece pairs as explicit polytopes, for the body depth (body_depth.h):
// posing the pieces, the choice between the two constructions (from the pieces' features, or the
// hull of all vertex differences), and the plane tests the search uses.

#include "body_depth_internal.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepcheck::geometry::body {
namespace {

// The cost estimates are in microseconds, fitted on random hulls of 8 to 100 vertices (the
// features' candidates times the vertices and faces each scans; Qhull's start-up plus its points):
// the features win up to about ten vertices per piece, the hull beyond.
double featuresCost(const PosedPiece& A, const PosedPiece& B) {
  const double eA = A.core->numEdges(), eB = B.core->numEdges();
  const double vA = A.core->numVertices(), vB = B.core->numVertices();
  return 0.002 * eA * eB * (vA + vB + eA + eB + A.core->numFaces() + B.core->numFaces());
}

double hullCost(const PosedPiece& A, const PosedPiece& B) {
  return 30.0 + 0.7 * A.core->numVertices() * B.core->numVertices();
}

}  // namespace

PosedPiece posePiece(const ConvexPolytope& core, const Eigen::Isometry3d& X_PP) {
  PosedPiece p;
  p.core = &core;
  p.X_PP = X_PP;
  p.vertices.reserve(static_cast<std::size_t>(core.numVertices()));
  for (const Eigen::Vector3d& v : core.vertices()) p.vertices.push_back(X_PP * v);
  for (int f = 0; f < core.numFaces(); ++f) p.faceNormals.push_back(X_PP.linear() * core.faceNormal(f));
  return p;
}

void addFace(Difference& d, const Eigen::Vector3d& normal, double offset, std::vector<Eigen::Vector3d> face) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : face) centre += p;
  centre /= static_cast<double>(face.size());
  double radius2 = 0.0;  // the largest squared distance: one square root (sqrt is monotonic)
  for (const Eigen::Vector3d& p : face) radius2 = std::max(radius2, (p - centre).squaredNorm());
  const double radius = std::sqrt(radius2);
  d.normals.push_back(normal);
  d.offsets.push_back(offset);
  d.faces.push_back(std::move(face));
  d.centres.push_back(centre);
  d.radii.push_back(radius);
}

double differenceCost(const PosedPiece& A, const PosedPiece& B) { return std::min(featuresCost(A, B), hullCost(A, B)); }

bool buildDifference(const PosedPiece& A, const PosedPiece& B, Difference& out, double keep) {
  out.normals.clear();
  out.offsets.clear();
  out.faces.clear();
  out.centres.clear();
  out.radii.clear();
  if (featuresCost(A, B) <= hullCost(A, B)) return buildDifferenceFromFeatures(A, B, out, keep);
  if (!buildDifferenceFromHull(A, B, out)) return false;
  // Qhull's facets are all formed at once; the far ones are dropped afterwards.
  dropFacetsBeyond(out, keep);
  return true;
}

void dropFacetsBeyond(Difference& out, double keep) {
  std::size_t kept = 0;
  for (std::size_t f = 0; f < out.normals.size(); ++f) {
    if (!(out.offsets[f] < keep)) continue;
    if (kept != f) {  // (a vector moved onto itself would be emptied)
      out.normals[kept] = out.normals[f];
      out.offsets[kept] = out.offsets[f];
      out.faces[kept] = std::move(out.faces[f]);
      out.centres[kept] = out.centres[f];
      out.radii[kept] = out.radii[f];
    }
    ++kept;
  }
  out.normals.resize(kept);
  out.offsets.resize(kept);
  out.faces.resize(kept);
  out.centres.resize(kept);
  out.radii.resize(kept);
}

double planeExcess(const Difference& d, const Eigen::Vector3d& x) {
  double worst = -std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < d.normals.size(); ++f) worst = std::max(worst, d.normals[f].dot(x) - d.offsets[f]);
  return worst;
}

double rayExit(const Difference& d, const Eigen::Vector3d& u) {
  double exit = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < d.normals.size(); ++f) {
    const double rate = d.normals[f].dot(u);
    if (rate > 0) exit = std::min(exit, d.offsets[f] / rate);
  }
  return exit;
}

}  // namespace deepcheck::geometry::body
