#pragma once
// Internals of the body penetration depth (body_depth.h), shared by its source files: the pieces
// posed in the body frame P and the Minkowski differences of relevant pairs, in P.

#include "deepcheck/geometry/body_depth.h"

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace deepcheck::geometry::body {

/// A piece posed in frame P (world orientation, origin at A's position): x_P = X_PP * vertex.
struct PosedPiece {
  const ConvexPolytope* core = nullptr;
  Eigen::Isometry3d X_PP = Eigen::Isometry3d::Identity();
  /// In P, computed once per query by posePiece: the vertices and the face normals.
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3d> faceNormals;
  /// Unit edge directions in P, parallel ones (either sense) kept once: filled on first need by
  /// edgeDirections(), once per piece and query rather than once per difference it takes part in.
  mutable std::vector<Eigen::Vector3d> edgeDirections;
  mutable bool hasEdgeDirections = false;
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
///
/// Facets whose offset is `keep` or more are left out: the query only asks about points nearer
/// the origin than a known upper bound R on the depth, and with keep = R + margin such a facet
/// has n.x - offset <= -margin there, so for those points it decides neither "strictly inside"
/// nor "on" (margin > tol), and a ray leaving through it leaves beyond R. The result is then the
/// polytope cut by the kept planes only, which may include far points outside the difference.
bool buildDifference(const PosedPiece& A, const PosedPiece& B, Difference& out,
                     double keep = std::numeric_limits<double>::infinity());
/// The estimated cost of buildDifference(A, B) (microseconds on a current x86-64 core; the unit of
/// BodyDepthOptions::maxBuildCost).
double differenceCost(const PosedPiece& A, const PosedPiece& B);
/// From the pieces' face normals and edge-direction cross products (body_difference_features.cpp);
/// a candidate normal whose support value is `keep` or more is skipped before its face polygon
/// is formed (most of the cost).
bool buildDifferenceFromFeatures(const PosedPiece& A, const PosedPiece& B, Difference& out, double keep);
/// Removes the facets whose offset is `keep` or more (buildDifference's rule, for a smaller bound
/// found later).
void dropFacetsBeyond(Difference& d, double keep);
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
  int difference = -1;      ///< index of the difference whose face holds it (-1: the start point)
  double lowerBound = 0.0;  ///< no point of the complement is nearer than this
  int facesSearched = 0;
  bool finished = false;  ///< the search ended before the face cap
};

/// Nearest point to the origin of the complement of the union of the differences' interiors,
/// starting from a known point of that complement (`start`). `tol` is the membership tolerance.
/// Faces are searched for points nearer than `reach` (at least |start|; more lets a face's point
/// as near as the start, up to round-off, take its place and name its difference).
SearchResult searchNearestBoundary(const std::vector<Difference>& diffs, const Eigen::Vector3d& start, double reach,
                                   int maxFaces, double tol);

}  // namespace deepcheck::geometry::body
