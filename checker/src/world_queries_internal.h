#pragma once
// Internal to deepcheck::checker: what the world queries share (world_context.cpp,
// world_is_free.cpp, world_distance.cpp): the per-thread Context's state and the inline steps of
// both queries.
//
// Both queries share one preparation step: refresh the context when the world changed (one
// atomic load otherwise), forward kinematics into the context's scratch poses, and the world
// centres of the links' bounding spheres. Robot pieces are posed lazily (a stamp per piece), so a
// query only poses the pieces whose link came near something, and only the pieces that reach a
// narrow phase get their full pose (most stop at the bounding tests).
//
// Bounding volumes: a robot piece has a sphere (centre in its link frame); a robot link the sphere
// around its pieces' spheres; a world piece a box (of its vertices, grown by its radius) and a
// sphere. A pair reaches the narrow phase only when every bounding test passes.

#include "deepcheck/checker/world.h"

#include "batch_bounds.h"
#include "world_internal.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace deepcheck::checker {

namespace detail {

/// Identifies one narrow-phase pair within a snapshot.
struct PairKey {
  enum class Kind { None, Self, Scene, Obstacle } kind = Kind::None;
  int robotPiece = -1;  ///< piece of A
  int other = -1;       ///< Self: robot piece of B; Scene / Obstacle: world piece index
  int cache = -1;       ///< Self: index into selfCaches
  bool operator==(const PairKey& o) const { return kind == o.kind && robotPiece == o.robotPiece && other == o.other; }
};

/// The minimum over the piece pairs of one body pair, for the contact list.
struct BodyPairBest {
  int groupA = -1;  ///< robot geometry (RobotData::links) of A
  int setKind = 0;  ///< 0 robot link, 1 scene body, 2 obstacle body
  int body = -1;    ///< robot geometry or body index in its set
  PairKey key;
  geometry::SignedDistanceResult result;
};

/// A piece pair that passed the bounding tests, waiting for the narrow phase.
struct Candidate {
  double lowerBound;
  PairKey key;
};

}  // namespace detail

struct World::Context::Impl {
  const detail::WorldState* state = nullptr;
  std::uint64_t worldUid = 0;
  std::uint64_t generation = 0;
  std::shared_ptr<const detail::Snapshot> snap;

  std::vector<geometry::PairCache> selfCaches;
  std::vector<geometry::PairCache> sceneCaches;     // robot piece * scene pieces + world piece
  std::vector<geometry::PairCache> obstacleCaches;  // robot piece * obstacle pieces + world piece
  /// Per pair, indexed as the caches above: the oriented-box axis that last separated it (obb.h).
  std::vector<std::uint8_t> selfAxes, sceneAxes, obstacleAxes;
  /// Scratch of the penetration depth methods, shared by every pair of this context (a context
  /// runs one query at a time): no allocation or large stack frame per pair.
  std::unique_ptr<geometry::PenetrationScratch> scratch = std::make_unique<geometry::PenetrationScratch>();

  std::vector<Eigen::Isometry3d> X_WL;
  std::vector<Eigen::Isometry3d> X_WP;       // robot pieces, valid when transformStamp == stamp
  std::vector<Eigen::Vector3d> pieceCenter;  // valid when pieceStamp == stamp, as pieceObb
  std::vector<Obb> pieceObb;
  std::vector<std::uint32_t> pieceStamp;
  std::vector<std::uint32_t> transformStamp;
  std::uint32_t stamp = 0;
  std::vector<Eigen::Vector3d> linkCenter;  // per LinkGeometry

  Eigen::VectorXd lastQ;        // the previous query's configuration
  bool coherent = false;        // this query is within tol::kWarmStartMaxStep of the previous one
  detail::PairKey lastHit;      // isFree: the pair that overlapped last time
  detail::PairKey lastClosest;  // signedDistance: the closest pair last time
  std::vector<detail::BodyPairBest> bodyPairs;
  std::vector<detail::Candidate> candidates;
  Eigen::Matrix3Xd J_A, J_B;
  QueryStats stats;
  std::unique_ptr<detail::BatchScratch> batch;  // isFreeBatch's, made by its first call
};

namespace detail {

using Impl = World::Context::Impl;

/// Brings the context up to the world's current snapshot, keeping what warm starts it can.
void refresh(Impl& c);

/// The world's current snapshot in context c (refreshed when the world changed); throws when c
/// was made by another world.
const Snapshot& current(const WorldState& state, Impl& c);

/// Refresh, check q, forward kinematics, link sphere centres; a new stamp for piece poses.
const Snapshot& prepare(const WorldState& state, Impl& c, const Eigen::Ref<const Eigen::VectorXd>& q);

/// prepare() for column `lane` of the configurations batchFreeLanes posed last in c (q is that
/// column), with the batch's link poses instead of a forward kinematics of its own: they agree
/// with it to a few ulps of the chain's length (batch_kinematics.h), the round-off forward
/// kinematics itself carries. A lane whose poses are not finite goes through prepare(), which
/// throws as isFree does, and so does every lane once the world has changed since the batch.
const Snapshot& prepareLane(const WorldState& state, Impl& c, const Eigen::Ref<const Eigen::VectorXd>& q, int lane);

/// isFreeBatch's bound stage (world_batch.cpp): refreshes the context to the world's snapshot,
/// poses the configurations (columns of qs, 1 to kLanes) and returns the mask of those it
/// certifies free, or clear by `margins` (bit l: column l); the others are undecided. Counts the
/// certified ones as queries. Throws std::invalid_argument for a qs of the wrong shape or a
/// demand of the wrong size (with its base or scale negative or not finite).
std::uint32_t batchFreeLanes(const WorldState& state, Impl& c, const Eigen::Ref<const Eigen::MatrixXd>& qs,
                             const BatchMargins& margins = {});

/// Bounding volumes of robot piece i in the world: its sphere centre and oriented box (computed
/// once per query).
inline void posePiece(Impl& c, const RobotData& robot, int i) {
  if (c.pieceStamp[i] == c.stamp) return;
  const RobotPiece& p = robot.pieces[i];
  c.pieceCenter[i] = c.X_WL[p.link] * p.center_L;
  c.pieceObb[i] = p.obb_L.transformed(c.X_WL[p.link]);
  c.pieceStamp[i] = c.stamp;
}

/// World pose of robot piece i, for the narrow phase (computed once per query).
inline const Eigen::Isometry3d& pieceTransform(Impl& c, const RobotData& robot, int i) {
  if (c.transformStamp[i] != c.stamp) {
    c.X_WP[i] = c.X_WL[robot.pieces[i].link] * robot.pieces[i].X_LP;
    c.transformStamp[i] = c.stamp;
  }
  return c.X_WP[i];
}

/// How much of a pair's cache a query far from the previous one keeps (warm()).
enum class FarStep {
  /// signedDistance: only the tetrahedron that last enclosed the origin.
  KeepEnclosing,
  /// isFree: all of GJK's cache, its last direction and support hints too. isFree's answer does
  /// not depend on where GJK starts, and in cluttered scenes a pair's separating direction is set
  /// mostly by the world piece. The bisection order of motion checks jumps further than
  /// tol::kWarmStartMaxStep almost every time, so planners gain (docs/checker.md has the
  /// figure); isFree on random configurations takes the same time.
  KeepGjk,
};

/// The pair's warm-start cache for this query: kept when the query is near the previous one,
/// reset first otherwise (a start from an unrelated configuration makes DEEP run fewer
/// restarts, so a stale start costs accuracy), except for what `far` keeps. A cold pair's support
/// climbs start from each hull's direction index (geometry::ConvexPolytope::support). The
/// tetrahedron that last enclosed the origin is kept either way: isFree tests it afresh
/// (geometry::enclosesOrigin, a certificate), never trusts it.
inline geometry::PairCache* warm(const Impl& c, geometry::PairCache& cache, FarStep far) {
  if (!c.coherent) {
    const geometry::GjkCache gjk = cache.gjk;
    cache.reset();
    if (far == FarStep::KeepGjk) {
      cache.gjk = gjk;
    } else {
      cache.gjk.enclosing = gjk.enclosing;
      cache.gjk.enclosed = gjk.enclosed;
    }
  }
  cache.scratch = c.scratch.get();
  return &cache;
}

/// The world pieces of a robot-world pair kind (Scene or Obstacle), and the context's per-pair
/// vectors of that kind, indexed by pairIndex().
inline const PieceSet& worldPieces(const Snapshot& s, PairKey::Kind kind) {
  return kind == PairKey::Kind::Scene ? *s.scenePieces : *s.obstaclePieces;
}
inline std::vector<geometry::PairCache>& worldCaches(Impl& c, PairKey::Kind kind) {
  return kind == PairKey::Kind::Scene ? c.sceneCaches : c.obstacleCaches;
}
inline std::vector<std::uint8_t>& worldAxes(Impl& c, PairKey::Kind kind) {
  return kind == PairKey::Kind::Scene ? c.sceneAxes : c.obstacleAxes;
}

/// Index of the pair (robot piece i, world piece wp of `set`) in the per-pair vectors of that set
/// (sceneCaches, sceneAxes; obstacleCaches, obstacleAxes).
inline std::size_t pairIndex(const PieceSet& set, int i, int wp) {
  return static_cast<std::size_t>(i) * set.pieces.size() + static_cast<std::size_t>(wp);
}

/// Lower bound on the signed distance between robot piece i (posed) and world piece w, however
/// deep they overlap: the exact signed distances of the piece's bounding sphere to w's box and
/// to w's bounding sphere, each containing its piece.
inline double pieceWorldLowerBound(const Impl& c, const RobotPiece& p, int i, const WorldPiece& w) {
  const double toBox = w.box.signedDistance(c.pieceCenter[i]) - p.sphereRadius;
  const double toSphere = (c.pieceCenter[i] - w.center_W).norm() - p.sphereRadius - w.sphereRadius;
  return std::max(toBox, toSphere);
}

/// Lower bound on sd(A, B) from the support functions in direction u (unit, world frame):
/// with M = B - A (cores), h_M(u) = h_B(u) + h_A(-u) >= |m| for no m in general, but
///   - if the cores overlap, the penetration depth is min over unit v of h_M(v) <= h_M(u);
///   - if they are apart, every m in M has u.m <= h_M(u), so |m| >= -h_M(u) when h_M(u) < 0;
/// in both cases the core signed distance is >= -h_M(u). Radii are subtracted as usual.
inline double supportLowerBound(const geometry::ConvexPolytope& A, const Eigen::Isometry3d& X_WA, double rA,
                                const geometry::ConvexPolytope& B, const Eigen::Isometry3d& X_WB, double rB,
                                const Eigen::Vector3d& u) {
  const Eigen::Vector3d uA = X_WA.linear().transpose() * u;
  const Eigen::Vector3d uB = X_WB.linear().transpose() * u;
  const double hB = uB.dot(B.vertex(B.support(uB))) + u.dot(X_WB.translation());
  const double minA = uA.dot(A.vertex(A.support(-uA))) + u.dot(X_WA.translation());
  return -(hB - minA) - rA - rB;
}

/// True when spheres (or a sphere and a box) at squared distance d2 are farther apart than r:
/// the bounding tests compare squares, with no square root on isFree's path.
inline bool fartherThan(double d2, double r) { return d2 > r * r; }

/// `box` grown by `margin` along each of its axes (it then holds everything within margin of it).
inline Obb grownBox(Obb box, double margin) {
  box.half.array() += margin;
  return box;
}

/// The bounding tests of robot piece i (posed), grown by `margin`, against world piece w: false
/// when its bounding sphere's lower bound is positive (pieceWorldLowerBound, compared in squares)
/// or the oriented boxes are apart (`axis`: the pair's last separating axis).
inline bool worldBoundsMeet(const Impl& c, const RobotData& robot, int i, const WorldPiece& w, std::uint8_t& axis,
                            double margin = 0.0) {
  const RobotPiece& p = robot.pieces[i];
  const Eigen::Vector3d& x = c.pieceCenter[i];
  const double r = p.sphereRadius + margin;
  if (fartherThan(w.box.squaredDistance(x), r) || fartherThan((x - w.center_W).squaredNorm(), r + w.sphereRadius)) {
    return false;
  }
  if (margin == 0.0) return !separated(c.pieceObb[i], w.obb_W, axis);
  return !separated(grownBox(c.pieceObb[i], margin), w.obb_W, axis);
}

/// The bounding tests of robot pieces i and j (both posed; i grown by `margin`): spheres, then
/// oriented boxes.
inline bool selfBoundsMeet(const Impl& c, const RobotData& robot, int i, int j, std::uint8_t& axis,
                           double margin = 0.0) {
  if (fartherThan((c.pieceCenter[i] - c.pieceCenter[j]).squaredNorm(),
                  robot.pieces[i].sphereRadius + robot.pieces[j].sphereRadius + margin)) {
    return false;
  }
  if (margin == 0.0) return !separated(c.pieceObb[i], c.pieceObb[j], axis);
  return !separated(grownBox(c.pieceObb[i], margin), c.pieceObb[j], axis);
}

/// Calls f(i, j, cache) for the piece pairs of the self pair sp (both pieces posed; cache indexes
/// selfCaches), until f returns true; true when stopped.
template <class F>
bool forEachSelfPiecePair(Impl& c, const RobotData& robot, const SelfPair& sp, F&& f) {
  const LinkGeometry& la = robot.links[sp.a];
  const LinkGeometry& lb = robot.links[sp.b];
  for (int i = la.firstPiece; i < la.firstPiece + la.numPieces; ++i) {
    posePiece(c, robot, i);
    for (int j = lb.firstPiece; j < lb.firstPiece + lb.numPieces; ++j) {
      posePiece(c, robot, j);
      ++c.stats.pieceTests;
      if (f(i, j, sp.cacheOffset + (i - la.firstPiece) * lb.numPieces + (j - lb.firstPiece))) return true;
    }
  }
  return false;
}

/// Calls visit(worldPiece) for the pieces of `set` whose box overlaps `query`; stops (returns
/// true) when visit returns true. The external tree (WorldOptions::externalBroadPhase) takes
/// std::function: built from std::ref, it never allocates (a std::function copy of a lambda with
/// many captures would, on every query).
template <class Visit>
bool forEachOverlapping(const PieceSet& set, BroadPhase broadPhase, const Aabb& query, Visit&& visit) {
  if (set.external != nullptr) return set.external->visitOverlapping(query, std::function<bool(int)>(std::ref(visit)));
  switch (broadPhase) {
    case BroadPhase::AabbTree:
      return set.tree.visitOverlapping(query, visit);
    case BroadPhase::None:
      for (int i = 0; i < static_cast<int>(set.pieces.size()); ++i) {
        if (visit(i)) return true;
      }
      return false;
  }
  return false;
}

/// Calls visit(worldPiece, lowerBound) for the pieces of `set` whose box is within bound() of
/// the sphere (center, r).
template <class Bound, class Visit>
void forEachNear(const PieceSet& set, BroadPhase broadPhase, const Eigen::Vector3d& center, double r, Bound&& bound,
                 Visit&& visit) {
  if (set.external != nullptr) {
    set.external->visitNear(center, r, std::function<double()>(std::ref(bound)),
                            std::function<void(int, double)>(std::ref(visit)));
    return;
  }
  switch (broadPhase) {
    case BroadPhase::AabbTree:
      set.tree.visitNear(center, r, bound, visit);
      return;
    case BroadPhase::None:
      for (int i = 0; i < static_cast<int>(set.pieces.size()); ++i) {
        const double lb = set.pieces[i].box.signedDistance(center) - r;
        if (lb < bound()) visit(i, lb);
      }
      return;
  }
}

inline geometry::ConvexShape shapeOf(const RobotPiece& p) { return geometry::ConvexShape{p.core.get(), p.radius}; }
inline geometry::ConvexShape shapeOf(const WorldPiece& p) { return geometry::ConvexShape{p.core.get(), p.radius}; }

inline void notify(const World::Context::Impl& c, int linkA, const BodyRef& bodyB) {
  if (c.state->onNarrowPhase) c.state->onNarrowPhase(NarrowPhaseEvent{linkA, bodyB});
}

/// True when the pair (robot geometry g, body `body` of the world set of `kind`) is allowed.
inline bool worldPairAllowed(const Snapshot& s, PairKey::Kind kind, int g, int body) {
  return (kind == PairKey::Kind::Scene ? s.sceneAllowed : s.obstacleAllowed).test(g, body);
}

inline BodyRef bodyOfWorldPiece(const PieceSet& set, const WorldPiece& w) { return set.bodies[w.body].ref; }

inline BodyRef robotBody(int link) {
  BodyRef b;
  b.kind = BodyRef::Kind::RobotLink;
  b.index = link;
  return b;
}

}  // namespace detail
}  // namespace deepcheck::checker
