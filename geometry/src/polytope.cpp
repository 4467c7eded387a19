// ConvexPolytope: kinds, adjacency accessors and the derived data (centre, local vertices,
// principal axes, face offsets). Building is in polytope_build.cpp and polytope_solid.cpp.

#include "polytope_internal.h"

#include <Eigen/Eigenvalues>

namespace deepcheck::geometry {

const char* toString(PolytopeKind kind) {
  switch (kind) {
    case PolytopeKind::Point:
      return "Point";
    case PolytopeKind::Segment:
      return "Segment";
    case PolytopeKind::Polygon:
      return "Polygon";
    case PolytopeKind::Polyhedron:
      return "Polyhedron";
  }
  return "unknown";
}

int ConvexPolytope::numEdges() const {
  switch (kind_) {
    case PolytopeKind::Point:
      return 0;
    case PolytopeKind::Segment:
      return 1;
    default:
      return static_cast<int>(adjVerts_.size() / 2);
  }
}

IndexRange ConvexPolytope::faceVertices(int f) const {
  const int* base = faceVerts_.data();
  return {base + faceStart_[f], base + faceStart_[f + 1]};
}

IndexRange ConvexPolytope::neighbors(int v) const {
  const int* base = adjVerts_.data();
  return {base + adjStart_[v], base + adjStart_[v + 1]};
}

IndexRange ConvexPolytope::vertexFaces(int v) const {
  if (adjFaces_.empty()) return {};  // points and segments have no faces
  const int* base = adjFaces_.data();
  return {base + adjStart_[v], base + adjStart_[v + 1]};
}

void ConvexPolytope::finish() {
  const int n = numVertices();
  // Centroid as base + mean offset: the offsets are small, so no digits are lost far from 0.
  Vector3d sum = Vector3d::Zero();
  for (const Vector3d& v : vertices_) sum += v - vertices_[0];
  center_ = vertices_[0] + sum / static_cast<double>(n);
  local_.resize(n);
  radius_ = 0.0;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int v = 0; v < n; ++v) {
    local_[v] = vertices_[v] - center_;
    radius_ = std::max(radius_, local_[v].norm());
    cov += local_[v] * local_[v].transpose();
  }
  // Never zero, so that tolerances scaled by it are well defined; for a Point it is the smallest
  // normal double, which makes every relative tolerance of the point alone exact (zero in effect):
  // a pair's tolerances take their size from the other shape and the distance.
  lengthScale_ = std::max(radius_, std::numeric_limits<double>::min());

  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov / static_cast<double>(n));
  const Eigen::Matrix3d& ev = eig.eigenvectors();  // ascending eigenvalues
  for (int c = 0; c < 2; ++c) {
    Vector3d axis = ev.col(2 - c);
    int big = 0;
    axis.cwiseAbs().maxCoeff(&big);
    if (axis[big] < 0.0) axis = -axis;
    axes_.col(c) = axis.normalized();
  }
  axes_.col(2) = axes_.col(0).cross(axes_.col(1)).normalized();

  faceOffsets_.resize(faceNormals_.size());
  insideRadius_ = kind_ == PolytopeKind::Polyhedron ? std::numeric_limits<double>::infinity() : 0.0;
  for (int f = 0; f < numFaces(); ++f) {
    const Vector3d& nrm = faceNormals_[f];
    double mean = 0.0;
    for (int v : faceVertices(f)) mean += nrm.dot(local_[v]);
    mean /= static_cast<double>(faceVertices(f).size());
    faceOffsets_[f] = nrm.dot(center_) + mean;
    insideRadius_ = std::min(insideRadius_, std::max(mean, 0.0));
  }
  buildDirectionIndex();
  buildFaceSupports();
  buildProbeSupports();
}

}  // namespace deepcheck::geometry
