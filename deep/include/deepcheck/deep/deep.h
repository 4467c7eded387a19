#pragma once
// DEEP: Dual-space Expansion for Estimating Penetration depth between convex polytopes
// (Y. J. Kim, M. C. Lin, D. Manocha, ICRA 2002).
//
// Penetration depth of overlapping convex polytopes A and B is the distance from the origin to the
// boundary of the Minkowski difference M = B - A: PD = min over facets F of M of d_F, the offset
// of F's plane, attained at a facet whose normal u is a vertex of the overlay of the Gauss maps of
// B and -A. Such a vertex is a face normal of B inside a vertex region of -A (VF), a face normal
// of -A inside a vertex region of B (FV), or the crossing of an edge arc of each (EE).
//
// The algorithm, as in the paper:
//  1. Start from a vertex hub pair (a, b): the vertices of A and B extreme in -u0 and u0 for an
//     initial direction u0 (centroid difference, or the previous answer: warm start). b - a is a
//     vertex of M; its Gauss region is N_B(b) ∩ -N_A(a).
//  2. Local Gauss maps: the region of b is a convex spherical polygon whose corners are the normals
//     of b's faces; the region of -a is bounded by the planes orthogonal to a's edges. Their
//     intersection is computed by clipping the first by the second (Sutherland-Hodgman on
//     homogeneous direction vectors: interpolating two directions and renormalizing is exactly the
//     central projection onto a plane, without choosing the plane). Its corners are the candidate
//     facets of M around b - a, labelled VF / FV / EE by the two arcs meeting there. Each
//     candidate's depth is u . (b - a).
//  3. Walk to the best candidate's facet and on to an adjacent hub pair; stop when nothing improves.
//
// Where this implementation departs from the paper, and why:
//  - The stopping test is exact: the walk stops at a facet F that contains its foot point d_F * u_F
//    (the KKT condition of min d over the boundary of M). If the foot lies outside F, beyond an
//    edge, the facet across that edge has a strictly smaller offset, so the walk moves to the hub
//    pair at that edge's end nearest the foot. This is the paper's "move to an adjacent vertex
//    pair" with the choice made deterministic, and it yields the witness points.
//  - Degenerate facets (parallel faces or edges, e.g. stacked boxes) are handled by computing the
//    facet as the Minkowski difference of the supporting features of A and B within
//    kFeatureRelative, instead of assuming general position.
//  - Local minima are real (8 % to 52 % of single walks on random hulls end in one), so a query runs
//    several walks: the warm start, the centroid difference and its opposite, and both signs of
//    the principal axes of A and B. Walks that reach an already visited hub pair stop early, so
//    the extra starts cost little when they lead to the same facet.
//  - Points and segments (sphere and capsule cores) have no Gauss regions of positive area; their
//    Minkowski differences with a polytope have O(F + E) facets, enumerated directly.

#include "deepcheck/deep/pair_frame.h"
#include "deepcheck/deep/walk_scratch.h"

namespace deepcheck::deep {

/// How signedDistance computes the depth of overlapping shapes.
enum class PenetrationMethod {
  Certified,  ///< the expanding surface's certified bracket (certified.h), named by DEEP's facets
  DeepWalk,   ///< DEEP's walks with restarts (below): fast warm, can stop in a local minimum
};

const char* toString(PenetrationMethod m);

struct DeepOptions {
  /// The algorithm for overlapping shapes. The walk options below apply to DeepWalk, and to the
  /// Certified method only where it falls back on a walk (an expansion that did not converge).
  PenetrationMethod method = PenetrationMethod::Certified;
  /// Cap on support points the certified expansion adds to its surface.
  int maxExpansions = 128;
  /// Use the warm start of the cache when it is valid.
  bool warmStart = true;
  /// Certified method, warm: first walk from the pair's last facet (one DEEP walk, no restarts)
  /// and ask the cached surface to certify that facet's depth (certifyUpperBound); the surface's
  /// own support queries run only when it cannot. Off by default: measured slower than the
  /// surface alone (docs/penetration-depth.md).
  bool warmWalk = false;
  /// Run the restart directions (centroid difference, its opposite, principal axes). Without
  /// restarts a cold query runs one walk from the centroid difference: faster, can miss.
  bool restarts = true;
  /// Visit the restart directions in order of their supporting plane's offset h_M(u) and skip
  /// those whose plane is no closer than the best facet found so far. Heuristic (a walk can
  /// descend below its start), measured in tests/deep: see the README's accuracy table.
  bool pruneRestarts = false;
  /// A warm query also walks from the centroid difference (one extra start): guards against a
  /// basin that none of the cached ones leads to.
  bool warmCentroidStart = true;
  /// After this many consecutive warm queries the next query runs all cold starts again, to
  /// refresh the cached basins (0 = never).
  int refreshEvery = 32;
  /// Cap on hub pairs evaluated per walk.
  int maxHubsPerWalk = 256;
};

/// Warm-start state of one pair (the caller owns it, one per pair and per thread).
/// It keeps the facets where the last query's walks ended (the best first): when the pair moves,
/// the global minimum usually stays in its basin or switches to one of these competitors, so a
/// warm query restarts from each of them instead of from all cold start directions.
struct DeepCache {
  static constexpr int kBasins = 4;
  bool valid = false;
  int count = 0;                 ///< basins stored (the first is the last answer)
  int hubA[kBasins] = {};        ///< vertex of A of each basin's hub pair
  int hubB[kBasins] = {};        ///< vertex of B of each basin's hub pair
  Eigen::Vector3d u[kBasins];    ///< outward facet normal of M at each basin, frame P
  int warmQueries = 0;           ///< warm queries since the last cold one
};

struct DeepStats {
  int starts = 0;           ///< walks started
  int hubs = 0;             ///< hub pairs evaluated (local Gauss map intersections)
  int steps = 0;            ///< facet-to-facet moves over all walks
  int localMinima = 0;      ///< walks that ended at a facet deeper than the final answer
  bool warm = false;        ///< the warm start was used
};

enum class DeepStatus {
  Converged,     ///< the best facet contains its foot point (a KKT point of the depth)
  NotConverged,  ///< a walk hit maxHubsPerWalk; the answer is still a valid separating translation
};

struct DeepResult {
  DeepStatus status = DeepStatus::NotConverged;
  double depth = 0.0;  ///< penetration depth (>= 0 when the origin is inside M), frame P units
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit, from A towards B, in frame P
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero();   ///< witness on A, frame P
  Eigen::Vector3d pointB = Eigen::Vector3d::Zero();   ///< witness on B, frame P (pointA - pointB = depth * normal)
  enum class FacetType { VF, FV, EE } type = FacetType::VF;
  int featureA = 0;   ///< VF: vertex of A; FV: face of A; EE: first vertex of A's edge
  int featureA2 = -1; ///< EE: second vertex of A's edge
  int featureB = 0;   ///< VF: face of B; FV: vertex of B; EE: first vertex of B's edge
  int featureB2 = -1; ///< EE: second vertex of B's edge
  DeepStats stats;
};

/// Penetration depth of A and B (cores, no radii) in the pair frame. Meaningful when they overlap
/// (the caller checks with GJK first); for separated shapes the result is the smallest offset of
/// a facet reached, possibly negative. `cache` may be null. `scratch` is the caller's scratch space
/// (walk_scratch.h), overwritten; null: a local one is used (allocating what the query uses).
DeepResult deepPenetration(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                           DeepCache* cache = nullptr, const DeepOptions& options = {},
                           WalkScratch* scratch = nullptr);

/// The facet of M at the vertex of M extreme in direction u (found by climbing from the hint
/// vertices), without walking: the nearest facet around that vertex, Converged with its witness
/// points when the origin's foot lies in it, else NotConverged. For naming a facet whose depth is
/// already certified (the certified method's faces that name none, such as parallel faces).
DeepResult facetInDirection(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                            const Eigen::Vector3d& u, int hintA, int hintB, WalkScratch* scratch = nullptr);

}  // namespace deepcheck::deep
