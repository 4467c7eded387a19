#pragma once
// One signed-distance call per pair: GJK distance when apart, the certified penetration depth
// (or DEEP's walk, DeepOptions::method) when overlapping.
//
// Contract: for convex shapes A and B,
//   distance > 0  is their Euclidean distance;
//   distance < 0  means they overlap, and -distance is the penetration depth: the length of the
//                 shortest translation that separates them;
//   normal        unit, points from A towards B: translating B by -distance * normal makes the
//                 two shapes touch, for both signs;
//   pointA/B      witness points on A and on B (world frame) with pointB - pointA = distance * normal.
// The function is continuous through contact.
//
// A shape is a convex core (a ConvexPolytope: point, segment, polygon or polyhedron) plus a
// radius >= 0: a sphere is a point core with a radius, a capsule a segment core with a radius.
// The radius is handled exactly: sd(A, B) = sd(coreA, coreB) - radiusA - radiusB.

#include "deepcheck/deep/certified.h"
#include "deepcheck/deep/deep.h"
#include "deepcheck/deep/gjk.h"

#include <memory>

namespace deepcheck::deep {

/// A convex shape: a core polytope (not owned; must outlive the shape) and a radius.
struct ConvexShape {
  const ConvexPolytope* core = nullptr;
  double radius = 0.0;
};

enum class SignedDistanceStatus {
  Separated,       ///< distance > 0 from GJK, converged
  Penetrating,     ///< distance <= 0 from DEEP, the walk ended at a facet containing its foot point
  NotConverged,    ///< an iteration cap was hit; the answer is still a valid separating
                   ///< translation (an upper bound on the depth) or a distance upper bound
};

const char* toString(SignedDistanceStatus s);

/// Which feature of a polytope a witness point lies on.
struct Feature {
  enum class Type { Vertex, Edge, Face } type = Type::Vertex;
  int index = 0;    ///< vertex index, first edge vertex, or face index
  int index2 = -1;  ///< second edge vertex (edges only)
};

struct SignedDistanceResult {
  SignedDistanceStatus status = SignedDistanceStatus::NotConverged;
  double distance = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero();
  Eigen::Vector3d pointB = Eigen::Vector3d::Zero();
  Feature featureA;
  Feature featureB;
  DeepStats deep;  ///< walk statistics when DEEP ran (zero otherwise)
  /// Bracket on the penetration depth -distance (radii included): depthLower <= the true depth
  /// <= depthUpper. Overlapping shapes, Certified method: the expansion's bounds (depthUpper is
  /// the answer's depth); DeepWalk: [0, depth] (a walk gives no lower bound). Separated shapes:
  /// both equal -distance.
  double depthLower = 0.0;
  double depthUpper = 0.0;
  /// The answer is certified: the depth is within tol::kCertifyRelative * L of its lower bound
  /// (or, separated, GJK converged). False for the DeepWalk method on overlapping shapes.
  bool certified = false;
  int expansions = 0;  ///< support points the certified expansion added (0 otherwise)
};

/// Warm-start state for one pair of shapes, owned by the caller (one per pair and thread).
/// Reusing it for consecutive queries of the same pair makes them cheap; it never changes the
/// answer's validity, only how fast it is found. reset() makes the next query cold.
struct PairCache {
  GjkCache gjk;
  /// Scratch space of the certified expansion, owned by the caller; null: a local one is used
  /// (on the stack, about 60 KB). Share one per thread across pairs to keep the stack small.
  ExpansionSurface* surface = nullptr;
  /// Scratch space of DEEP's walk (walk_scratch.h), owned by the caller; null: each query that
  /// walks makes a local one (an allocation). Share one per thread across pairs, like `surface`.
  WalkScratch* walk = nullptr;
  DeepCache deep;
  /// The certified method's warm start (about 4 KB), allocated by the pair's first overlapping
  /// query with that method and reused after; copies of the cache copy it.
  std::unique_ptr<CertifiedWarmStart> certified;
  /// The last query found the shapes apart: the next one starts with GJK, not with the certified
  /// warm query (which proves overlap when it certifies, and is wasted work on separated shapes).
  bool apart = false;

  PairCache() = default;
  PairCache(const PairCache& other) { *this = other; }
  PairCache& operator=(const PairCache& other) {
    if (this == &other) return *this;
    gjk = other.gjk;
    surface = other.surface;
    walk = other.walk;
    deep = other.deep;
    apart = other.apart;
    if (!other.certified) certified.reset();
    else if (certified) *certified = *other.certified;
    else certified = std::make_unique<CertifiedWarmStart>(*other.certified);
    return *this;
  }
  PairCache(PairCache&&) = default;
  PairCache& operator=(PairCache&&) = default;

  /// Makes the next query cold (keeps the scratch pointers and the warm start's allocation).
  void reset() {
    gjk = GjkCache{};
    deep = DeepCache{};
    apart = false;
    if (certified) certified->valid = false;
  }
};

/// Signed distance between two posed shapes. Throws std::invalid_argument for a null core, a
/// negative or non-finite radius, or a non-finite / non-orthonormal pose.
SignedDistanceResult signedDistance(const ConvexShape& A, const Eigen::Isometry3d& X_WA,
                                    const ConvexShape& B, const Eigen::Isometry3d& X_WB,
                                    PairCache* cache = nullptr, const DeepOptions& options = {});

/// Same, for polytopes without radius.
SignedDistanceResult signedDistance(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA,
                                    const ConvexPolytope& B, const Eigen::Isometry3d& X_WB,
                                    PairCache* cache = nullptr, const DeepOptions& options = {});

/// Boolean overlap of two posed shapes (GJK only, early exit). Touching counts as overlap.
bool overlaps(const ConvexShape& A, const Eigen::Isometry3d& X_WA, const ConvexShape& B,
              const Eigen::Isometry3d& X_WB, PairCache* cache = nullptr);

/// overlaps() without its argument checks (null core, radius, finite and orthonormal poses), for
/// callers that validated their shapes once and compute their poses as rigid motions themselves
/// (the checker's isFree). The same answer and cache update as overlaps() on valid arguments;
/// undefined on invalid ones.
bool overlapsUnchecked(const ConvexShape& A, const Eigen::Isometry3d& X_WA, const ConvexShape& B,
                       const Eigen::Isometry3d& X_WB, PairCache* cache = nullptr);

/// True when the points of the cores' Minkowski difference named by t enclose its origin at these
/// poses (gjk.h, enclosesOrigin): the shapes overlap. t is the GjkCache::enclosing of an earlier
/// overlap of the same pair, so a pair that still overlaps at a nearby pose is confirmed without
/// a GJK run. A certificate only: false says nothing. Unchecked arguments, as overlapsUnchecked.
bool enclosesOrigin(const ConvexShape& A, const Eigen::Isometry3d& X_WA, const ConvexShape& B,
                    const Eigen::Isometry3d& X_WB, const MinkowskiTetrahedron& t);

}  // namespace deepcheck::deep
