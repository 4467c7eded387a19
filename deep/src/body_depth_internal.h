#pragma once
// Internals of the body penetration depth (body_depth.h), shared by its source files: the pieces
// posed in the body frame P and the Minkowski differences of relevant pairs, in P.

#include "deepcheck/deep/body_depth.h"

#include <Eigen/Core>

#include <vector>

namespace deepcheck::deep::body {

/// A piece posed in frame P (world orientation, origin at A's position): x_P = X_PP * vertex.
struct PosedPiece {
  const ConvexPolytope* core = nullptr;
  Eigen::Isometry3d X_PP = Eigen::Isometry3d::Identity();
  /// In P, computed once per query by posePiece: the vertices and the face normals.
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3d> faceNormals;
};

/// The piece `core` at X_PP in P, with its vertices and face normals there.
PosedPiece posePiece(const ConvexPolytope& core, const Eigen::Isometry3d& X_PP);

/// M = B_j - A_i for one pair, in P, as face planes {x : normal.x <= offset} and face polygons.
struct Difference {
  int pieceA = 0;
  int pieceB = 0;
  std::vector<Eigen::Vector3d> normals;  ///< unit, outward
  std::vector<double> offsets;           ///< support values of M in the normals
  /// Face f's vertices, on its plane, counter-clockwise about its normal.
  std::vector<std::vector<Eigen::Vector3d>> faces;
  /// Face f's vertex centroid and the largest distance of a vertex from it (quick rejections).
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> radii;
};

/// Builds the difference of A and B as its facets, offsets exact support values, by the cheaper of
/// the two constructions below for the pieces' sizes. Returns false when the difference is flat
/// (no interior: the pair never overlaps).
bool buildDifference(const PosedPiece& A, const PosedPiece& B, Difference& out);
/// From the pieces' face normals and edge-direction cross products (body_difference_features.cpp).
bool buildDifferenceFromFeatures(const PosedPiece& A, const PosedPiece& B, Difference& out);
/// From Qhull's hull of all vertex differences (body_difference_hull.cpp).
bool buildDifferenceFromHull(const PosedPiece& A, const PosedPiece& B, Difference& out);
/// Appends a facet (unit normal, offset, polygon counter-clockwise about the normal) to d.
void addFace(Difference& d, const Eigen::Vector3d& normal, double offset, std::vector<Eigen::Vector3d> face);

/// max over faces of normal.x - offset: below -tol the point is strictly inside M, above tol
/// strictly outside.
double planeExcess(const Difference& d, const Eigen::Vector3d& x);

/// The largest s with s * u in M (u unit, the origin inside M or not): where the ray from the
/// origin along u leaves M. Only meaningful when some point of the ray is inside M.
double rayExit(const Difference& d, const Eigen::Vector3d& u);

/// Outcome of the best-first search (body_depth_search.cpp).
struct SearchResult {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< nearest point of the complement found
  int difference = -1;  ///< index of the difference whose face holds it (-1: the start point)
  double lowerBound = 0.0;  ///< no point of the complement is nearer than this
  int facesSearched = 0;
  bool finished = false;    ///< the search ended before the face cap
};

/// Nearest point to the origin of the complement of the union of the differences' interiors,
/// starting from a known point of that complement (`start`). `tol` is the membership tolerance.
SearchResult searchNearestBoundary(const std::vector<Difference>& diffs,
                                   const Eigen::Vector3d& start, int maxFaces, double tol);

}  // namespace deepcheck::deep::body
