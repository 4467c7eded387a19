#pragma once
// Signed distance of two bodies, each a union of posed convex pieces (a non-convex link or
// object given by its convex decomposition).
//
// Contract: the same as signedDistance (signed_distance.h) with "the bodies" for "the shapes":
//   distance > 0  the smallest distance between a piece of A and a piece of B;
//   distance < 0  -distance is the body's translational penetration depth: the length of the
//                 shortest translation of B after which no piece of A overlaps a piece of B;
//   normal        unit, from A towards B: translating B by -distance * normal makes the bodies
//                 touch (no two pieces overlap, some pair touches), for both signs;
//   pointA/B      witnesses in the world frame, on piece pieceA of A and piece pieceB of B,
//                 pointB - pointA = distance * normal.
// The function is continuous through contact.
//
// Method. Let M_ij = B_j - A_i be the Minkowski difference of piece i of A and piece j of B (a
// convex polytope). B translated by t overlaps A in pieces i, j iff -t lies in the interior of
// M_ij, so the depth is the distance from the origin to the complement of U = union of the
// interiors of the M_ij. When no pair overlaps that is the smallest pairwise GJK distance. When
// some pair overlaps:
//   1. every pair gets its own signed distance (GJK or the certified depth); the largest pairwise
//      depth is a lower bound (the complement of U lies outside each M_ij containing the origin);
//   2. an upper bound: if no other pair covers the deepest pair's separating point x0 = sd * n
//      (a pairwise query with B moved by -x0), x0 is the answer. Otherwise, from each overlapping
//      pair's separating point, march outwards along its ray across every M_ij whose interior
//      holds the current point (each step jumps to that M_ij's exit); the first point inside
//      none is a point of the complement; the nearest of these marches, or the translation
//      that separates the bodies' bounding boxes along an axis when nearer, is the upper bound;
//   3. every pair whose distance from the origin (its own signed distance) is below that bound
//      gets its difference M_ij built exactly as a polytope, including pairs that do not overlap
//      (they can still cover boundary points of the others): for small pieces its facet normals
//      are found among the pieces' face normals and the cross products of their edge directions,
//      each kept when the supporting vertices' differences span a polygon; for larger pieces
//      (beyond about ten vertices) they are the facets of the hull of all vertex differences;
//      either way each offset is the exact support value. Only facets nearer the origin than a
//      separating translation read off the bodies' bounding boxes are kept (the marches of step
//      2 stop there, and no point asked about lies beyond, so a farther facet decides nothing);
//      before the search, only those nearer than the upper bound;
//   4. best-first search over the faces of those differences, in order of their plane's distance
//      to the origin (a lower bound for every point of the face). For a face, the nearest point
//      of (the face minus the interiors of all other differences) is one of: the origin's
//      projection onto the plane, its projection onto the face's edge lines or onto the traces of
//      the other differences' face planes in this plane, or an intersection of two such lines;
//      candidates are tried nearest first, each tested exactly against the face planes of every
//      difference. The search stops when the best point found is no farther than the next face's
//      plane: that point is the nearest point of the complement.
// All of it runs in a frame with the world's orientation and its origin at A's position, so
// coordinates are of the size of the bodies, not of the world.
//
// Cost: step 1 is one pairwise query per piece pair (microseconds each); steps 3 and 4 build and
// search the differences, whose cost grows with the number of relevant pairs times the product of
// their vertex counts. BodyDepthOptions::maxBuildCost caps the building; past it the answer is the
// best verified upper bound found so far (status BuildLimit).
//
// Limits: pieces must be polytopes (radius 0); spheres and capsules (radius > 0) are rejected
// with std::invalid_argument, since their differences are not polytopes. A pair whose difference
// is flat (coplanar polygons, segments, points) has no interior and never overlaps. Building a
// difference costs O(eA eB (vA + vB)) (e: edges, v: vertices) or a hull of vA vB points, so
// pieces of a few dozen vertices are the intended use (convex decompositions), not large hulls.

#include "deepcheck/geometry/signed_distance.h"

#include <Eigen/Geometry>

#include <limits>
#include <vector>

namespace deepcheck::geometry {

/// One convex piece of a body: a shape (radius 0, see the header comment) and its pose in the
/// body's frame.
struct BodyPiece {
  ConvexShape shape;
  Eigen::Isometry3d X_BP = Eigen::Isometry3d::Identity();
};

/// A body: the union of its pieces (at least one).
struct Body {
  std::vector<BodyPiece> pieces;
};

enum class BodyDepthStatus {
  Separated,         ///< no pair of pieces overlaps: the smallest pairwise distance
  Certified,         ///< overlapping; the search finished: the depth is the nearest point of the
                     ///< complement of the union (within tol::kBodyMemberRelative * L)
  FaceLimit,         ///< overlapping; BodyDepthOptions::maxFaces faces were searched before the
                     ///< search finished: the answer is a verified separating translation (depth
                     ///< upper bound), [depthLower, depthUpper] brackets the depth
  PairNotCertified,  ///< overlapping; the answer is the deepest pair's, not covered by another
                     ///< pair, but that pair's own query hit a cap: a verified separating
                     ///< translation whose depth is an upper bound, bracketed as above
  BuildLimit,        ///< overlapping; the differences the search needs would cost more than
                     ///< BodyDepthOptions::maxBuildCost to build: the answer is the nearest verified
                     ///< separating translation found before (a march's end, else the bounding boxes'
                     ///< separation along an axis), an upper bound, bracketed as above
};

const char* toString(BodyDepthStatus s);

struct BodyDepthOptions {
  /// Options of the pairwise queries (method, iteration caps).
  PenetrationOptions pair;
  /// Cap on the faces the best-first search examines.
  int maxFaces = 100000;
  /// Cap on the estimated cost of building Minkowski differences in one query, in microseconds of
  /// a current x86-64 core (a deterministic estimate from the pieces' vertex, edge and face
  /// counts, not a clock). Between bodies of a few small pieces a query needs a few hundred; two
  /// links decomposed into dozens of pieces of dozens of vertices each, deeply overlapping, can
  /// need over a hundred thousand. Past the cap the answer is BuildLimit. Infinity (the default):
  /// no cap, the answer is exact however long it takes.
  double maxBuildCost = std::numeric_limits<double>::infinity();
};

struct BodySignedDistanceResult {
  BodyDepthStatus status = BodyDepthStatus::Separated;
  double distance = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero();
  Eigen::Vector3d pointB = Eigen::Vector3d::Zero();
  int pieceA = 0;  ///< the piece of A holding pointA
  int pieceB = 0;  ///< the piece of B holding pointB
  /// Bracket on the depth -distance: depthLower <= depth <= depthUpper. Separated: both equal
  /// -distance. Overlapping: depthUpper = -distance; depthLower is the largest pairwise depth
  /// lower bound, raised to the answer when the search finished.
  double depthLower = 0.0;
  double depthUpper = 0.0;
  /// Certified: separated, the nearest pair's GJK converged; overlapping, status Certified.
  bool certified = false;
  int overlappingPairs = 0;  ///< piece pairs whose signed distance is negative
  int differences = 0;       ///< Minkowski differences built (overlapping: the relevant pairs)
  int facesSearched = 0;     ///< faces the best-first search examined
  /// The largest pairwise depth (0 when separated) and its normal: the pairwise answer, for
  /// comparison.
  double pairDepth = 0.0;
  Eigen::Vector3d pairNormal = Eigen::Vector3d::UnitZ();
};

/// Signed distance between body A at X_WA and body B at X_WB (each piece at X_W * X_BP).
/// Throws std::invalid_argument for an empty body, a piece without core, a piece with a radius
/// other than 0, or a non-finite / non-orthonormal pose (the message names body and piece).
BodySignedDistanceResult bodySignedDistance(const Body& A, const Eigen::Isometry3d& X_WA, const Body& B,
                                            const Eigen::Isometry3d& X_WB, const BodyDepthOptions& options = {});

}  // namespace deepcheck::geometry
