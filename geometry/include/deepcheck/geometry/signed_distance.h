#pragma once
// One signed-distance call per pair: GJK distance when apart, the penetration depth when
// overlapping (by the method PenetrationOptions::method selects, penetration_options.h).
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

#include "deepcheck/geometry/gjk.h"
#include "deepcheck/geometry/internal/certified_warm_start.h"
#include "deepcheck/geometry/internal/walk_cache.h"
#include "deepcheck/geometry/penetration_options.h"

#include <memory>

namespace deepcheck::geometry {

namespace detail {
class ExpansionSurface;
class WalkScratch;
struct ScratchAccess;
}  // namespace detail

/// A convex shape: a core polytope (not owned; must outlive the shape) and a radius.
struct ConvexShape {
  const ConvexPolytope* core = nullptr;
  double radius = 0.0;
};

enum class SignedDistanceStatus {
  Separated,     ///< distance > 0 from GJK, converged
  Penetrating,   ///< distance <= 0, the depth converged (certified, or the walk ended at a
                 ///< facet containing its foot point)
  NotConverged,  ///< an iteration cap was hit; the answer is still a valid separating
                 ///< translation (an upper bound on the depth) or a distance upper bound
};

const char* toString(SignedDistanceStatus s);

/// Which feature of a polytope a witness point lies on.
struct Feature {
  enum class Type { Vertex, Edge, Face } type = Type::Vertex;
  int index = 0;    ///< vertex index, first edge vertex, or face index
  int index2 = -1;  ///< second edge vertex (edges only)
};

/// What the Gauss-map walk did in a query (all zero when no walk ran).
struct WalkStats {
  int starts = 0;       ///< walks started
  int hubs = 0;         ///< hub pairs evaluated (local Gauss map intersections)
  int steps = 0;        ///< facet-to-facet moves over all walks
  int localMinima = 0;  ///< walks that ended at a facet deeper than the final answer
  bool warm = false;    ///< the warm start was used
};

struct SignedDistanceResult {
  SignedDistanceStatus status = SignedDistanceStatus::NotConverged;
  double distance = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero();
  Eigen::Vector3d pointB = Eigen::Vector3d::Zero();
  Feature featureA;
  Feature featureB;
  WalkStats walk;  ///< the Gauss-map walk's statistics, when one ran
  /// Bracket on the penetration depth -distance (radii included): depthLower <= the true depth
  /// <= depthUpper. Overlapping shapes, CertifiedExpansion: the expansion's bounds (depthUpper is
  /// the answer's depth); GaussMapWalk: [0, depth] (a walk gives no lower bound). Separated
  /// shapes: both equal -distance.
  double depthLower = 0.0;
  double depthUpper = 0.0;
  /// The answer is certified: the depth is within tol::kCertifyRelative * L of its lower bound
  /// (or, separated, GJK converged). False for the GaussMapWalk method on overlapping shapes.
  bool certified = false;
  int expansions = 0;  ///< support points the certified expansion added (0 otherwise)
};

/// Scratch space of the penetration depth methods (the certified expansion's surface, about
/// 60 KB, and the walk's buffers), owned by the caller: one per thread, shared by all its pairs
/// through PairCache::scratch. Allocated once when constructed; queries given it allocate nothing.
class PenetrationScratch {
 public:
  PenetrationScratch();
  ~PenetrationScratch();
  PenetrationScratch(PenetrationScratch&&) noexcept;
  PenetrationScratch& operator=(PenetrationScratch&&) noexcept;
  PenetrationScratch(const PenetrationScratch&) = delete;
  PenetrationScratch& operator=(const PenetrationScratch&) = delete;

 private:
  friend struct detail::ScratchAccess;
  std::unique_ptr<detail::ExpansionSurface> surface_;
  std::unique_ptr<detail::WalkScratch> walk_;
};

/// Warm-start state for one pair of shapes, owned by the caller (one per pair and thread).
/// Reusing it for consecutive queries of the same pair makes them cheap; it never changes the
/// answer's validity, only how fast it is found. reset() makes the next query cold.
struct PairCache {
  /// The thread's scratch space, owned by the caller; null: each query uses a local one (the
  /// certified expansion's on the stack, about 60 KB; the walk's allocated when a query walks).
  PenetrationScratch* scratch = nullptr;

  PairCache() = default;
  PairCache(const PairCache& other) { *this = other; }
  PairCache& operator=(const PairCache& other) {
    if (this == &other) return *this;
    scratch = other.scratch;
    gjk = other.gjk;
    walk = other.walk;
    apart = other.apart;
    // The warm start's allocation is reused when this cache has one already.
    if (!other.certified) certified.reset();
    else if (certified) *certified = *other.certified;
    else certified = std::make_unique<detail::CertifiedWarmStart>(*other.certified);
    return *this;
  }
  PairCache(PairCache&&) = default;
  PairCache& operator=(PairCache&&) = default;

  /// Makes the next query cold (keeps the scratch pointer and the warm start's allocation).
  void reset() {
    gjk = GjkCache{};
    walk = detail::WalkCache{};
    apart = false;
    if (certified) certified->valid = false;
  }

  // The methods' warm starts: GJK's (gjk.h), the walk's and the certified expansion's
  // (internal/walk_cache.h, internal/certified_warm_start.h).
  GjkCache gjk;
  detail::WalkCache walk;
  /// The certified expansion's warm start (about 4 KB), allocated by the pair's first
  /// overlapping query with that method and reused after; copies of the cache copy it.
  std::unique_ptr<detail::CertifiedWarmStart> certified;
  /// The last query found the shapes apart: the next one starts with GJK, not with the certified
  /// warm query (which proves overlap when it certifies, and is wasted work on separated shapes).
  bool apart = false;
};

/// Signed distance between two posed shapes. Throws std::invalid_argument for a null core, a
/// negative or non-finite radius, or a non-finite / non-orthonormal pose.
SignedDistanceResult signedDistance(const ConvexShape& A, const Eigen::Isometry3d& X_WA, const ConvexShape& B,
                                    const Eigen::Isometry3d& X_WB, PairCache* cache = nullptr,
                                    const PenetrationOptions& options = {});

/// Same, for polytopes without radius.
SignedDistanceResult signedDistance(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA, const ConvexPolytope& B,
                                    const Eigen::Isometry3d& X_WB, PairCache* cache = nullptr,
                                    const PenetrationOptions& options = {});

/// Boolean overlap of two posed shapes (GJK only, early exit). Touching counts as overlap.
bool overlaps(const ConvexShape& A, const Eigen::Isometry3d& X_WA, const ConvexShape& B, const Eigen::Isometry3d& X_WB,
              PairCache* cache = nullptr);

/// overlaps() without its argument checks (null core, radius, finite and orthonormal poses), for
/// callers that validated their shapes once and compute their poses as rigid motions themselves
/// (the checker's isFree). The same answer and cache update as overlaps() on valid arguments;
/// undefined on invalid ones.
bool overlapsUnchecked(const ConvexShape& A, const Eigen::Isometry3d& X_WA, const ConvexShape& B,
                       const Eigen::Isometry3d& X_WB, PairCache* cache = nullptr);

/// For callers testing a pair's distance against two thresholds near <= far, unchecked as
/// overlapsUnchecked: `within` when the shapes come within `near` of each other (or cannot be
/// shown farther apart, as gjkWithin), else `lower`, a lower bound on their distance above `near`
/// that stops improving once it exceeds `far` or lies within the fraction tol::kGjkBoundGap of
/// the distance (gjk.h, gjkBound; the radii are taken off the cores' bound).
GjkBound distanceBoundUnchecked(const ConvexShape& A, const Eigen::Isometry3d& X_WA, const ConvexShape& B,
                                const Eigen::Isometry3d& X_WB, double near, double far, PairCache* cache = nullptr);

/// True when the points of the cores' Minkowski difference named by t enclose its origin at these
/// poses (gjk.h, enclosesOrigin): the shapes overlap. t is the GjkCache::enclosing of an earlier
/// overlap of the same pair, so a pair that still overlaps at a nearby pose is confirmed without
/// a GJK run. A certificate only: false says nothing. Unchecked arguments, as overlapsUnchecked.
bool enclosesOrigin(const ConvexShape& A, const Eigen::Isometry3d& X_WA, const ConvexShape& B,
                    const Eigen::Isometry3d& X_WB, const MinkowskiTetrahedron& t);

}  // namespace deepcheck::geometry
