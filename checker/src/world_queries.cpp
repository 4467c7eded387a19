// World queries: isFree, signedDistance (+ gradient, contact list), and the per-thread Context.
//
// Both queries share one preparation step: refresh the context when the world changed (one
// atomic load otherwise), forward kinematics into the context's scratch poses, and the world
// centres of the links' bounding spheres. Robot pieces are posed lazily (a stamp per piece), so a
// query only poses the pieces whose link came near something.
//
// Bounding volumes: a robot piece has a sphere (centre in its link frame); a robot link the sphere
// around its pieces' spheres; a world piece a box (of its vertices, grown by its radius) and a
// sphere. A pair reaches the narrow phase only when every bounding test passes.

#include "deepcheck/checker/world.h"

#include "fcl_broad_phase.h"
#include "world_internal.h"

#include "deepcheck/robots/kinematics.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <unordered_map>

namespace deepcheck::checker {

using detail::LinkGeometry;
using detail::PieceSet;
using detail::RobotData;
using detail::RobotPiece;
using detail::SelfPair;
using detail::Snapshot;
using detail::WorldPiece;
using detail::WorldState;

namespace {

/// Identifies one narrow-phase pair within a snapshot.
struct PairKey {
  enum class Kind { None, Self, Scene, Obstacle } kind = Kind::None;
  int robotPiece = -1;  ///< piece of A
  int other = -1;       ///< Self: robot piece of B; Scene / Obstacle: world piece index
  int cache = -1;       ///< Self: index into selfCaches
  bool operator==(const PairKey& o) const {
    return kind == o.kind && robotPiece == o.robotPiece && other == o.other;
  }
};

/// The minimum over the piece pairs of one body pair, for the contact list.
struct BodyPairBest {
  int linkA = -1;
  int setKind = 0;  ///< 0 robot link, 1 scene body, 2 obstacle body
  int body = -1;    ///< robot link index or body index in its set
  PairKey key;
  deep::SignedDistanceResult result;
};

/// A piece pair that passed the bounding tests, waiting for the narrow phase.
struct Candidate {
  double lowerBound;
  PairKey key;
};

}  // namespace

struct World::Context::Impl {
  const WorldState* state = nullptr;
  std::uint64_t worldUid = 0;
  std::uint64_t generation = 0;
  std::shared_ptr<const Snapshot> snap;

  std::vector<deep::PairCache> selfCaches;
  std::vector<deep::PairCache> sceneCaches;     // robot piece * scene pieces + world piece
  std::vector<deep::PairCache> obstacleCaches;  // robot piece * obstacle pieces + world piece

  std::vector<Eigen::Isometry3d> X_WL;
  std::vector<Eigen::Isometry3d> X_WP;  // robot pieces, valid when pieceStamp == stamp
  std::vector<Eigen::Vector3d> pieceCenter;
  std::vector<Obb> pieceObb;
  std::vector<std::uint32_t> pieceStamp;
  std::uint32_t stamp = 0;
  std::vector<Eigen::Vector3d> linkCenter;  // per LinkGeometry

  Eigen::VectorXd lastQ;  // the previous query's configuration
  bool coherent = false;  // this query is within tol::kWarmStartMaxStep of the previous one
  PairKey lastHit;      // isFree: the pair that overlapped last time
  PairKey lastClosest;  // signedDistance: the closest pair last time
  std::vector<BodyPairBest> bodyPairs;
  std::vector<Candidate> candidates;
  Eigen::Matrix3Xd J_A, J_B;
  QueryStats stats;
};

World::Context::Context(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
World::Context::Context(Context&&) noexcept = default;
World::Context& World::Context::operator=(Context&&) noexcept = default;
World::Context::~Context() = default;
const QueryStats& World::Context::stats() const { return impl_->stats; }
void World::Context::resetStats() { impl_->stats = QueryStats{}; }
void World::Context::resetCaches() {
  for (auto* v : {&impl_->selfCaches, &impl_->sceneCaches, &impl_->obstacleCaches}) {
    for (deep::PairCache& c : *v) c.reset();
  }
  impl_->lastHit = PairKey{};
  impl_->lastClosest = PairKey{};
}

World::Context World::makeContext() const {
  auto impl = std::make_unique<Context::Impl>();
  impl->state = state_.get();
  impl->worldUid = state_->uid;
  return Context(std::move(impl));
}

namespace {

using Impl = World::Context::Impl;

/// Brings the context up to the world's current snapshot, keeping what warm starts it can.
void refresh(Impl& c) {
  std::shared_ptr<const Snapshot> next;
  std::uint64_t generation;
  {
    std::lock_guard<std::mutex> lock(c.state->mutex);
    next = c.state->current;
    generation = c.state->generation.load(std::memory_order_relaxed);
  }
  const Snapshot* prev = c.snap.get();
  const RobotData& robot = *next->robot;
  const std::size_t nRobot = robot.pieces.size();
  if (prev == nullptr) {
    c.X_WL.assign(robot.model.numLinks(), Eigen::Isometry3d::Identity());
    c.X_WP.assign(nRobot, Eigen::Isometry3d::Identity());
    c.pieceCenter.assign(nRobot, Eigen::Vector3d::Zero());
    c.pieceObb.assign(nRobot, Obb{});
    c.pieceStamp.assign(nRobot, 0);
    c.linkCenter.assign(robot.links.size(), Eigen::Vector3d::Zero());
    c.J_A.resize(3, robot.model.numVariables());
    c.J_B.resize(3, robot.model.numVariables());
  }
  // Self caches: kept when the pair list is unchanged.
  bool sameSelf = prev != nullptr && prev->selfPairs.size() == next->selfPairs.size();
  for (std::size_t i = 0; sameSelf && i < next->selfPairs.size(); ++i) {
    sameSelf = prev->selfPairs[i].a == next->selfPairs[i].a && prev->selfPairs[i].b == next->selfPairs[i].b;
  }
  if (!sameSelf) c.selfCaches.assign(next->selfCacheSize, deep::PairCache{});
  if (prev == nullptr || prev->scenePieces != next->scenePieces) {
    c.sceneCaches.assign(nRobot * next->scenePieces->pieces.size(), deep::PairCache{});
  }
  if (prev == nullptr || prev->obstaclePieces != next->obstaclePieces) {
    // Obstacle pieces are renumbered by every change; carry the caches over by piece uid.
    const std::vector<WorldPiece>& now = next->obstaclePieces->pieces;
    std::vector<deep::PairCache> caches(nRobot * now.size());
    if (prev != nullptr) {
      const std::vector<WorldPiece>& before = prev->obstaclePieces->pieces;
      std::unordered_map<std::uint64_t, std::size_t> old;
      for (std::size_t j = 0; j < before.size(); ++j) old.emplace(before[j].uid, j);
      for (std::size_t j = 0; j < now.size(); ++j) {
        auto it = old.find(now[j].uid);
        if (it == old.end()) continue;
        for (std::size_t i = 0; i < nRobot; ++i) {
          caches[i * now.size() + j] = c.obstacleCaches[i * before.size() + it->second];
        }
      }
    }
    c.obstacleCaches = std::move(caches);
  }
  c.lastHit = PairKey{};
  c.lastClosest = PairKey{};
  c.snap = std::move(next);
  c.generation = generation;
}

/// Refresh, check q, forward kinematics, link sphere centres; a new stamp for piece poses.
const Snapshot& prepare(const WorldState& state, Impl& c,
                        const Eigen::Ref<const Eigen::VectorXd>& q) {
  if (c.worldUid != state.uid) {
    throw std::invalid_argument("World: the Context was made by another world");
  }
  if (c.generation != state.generation.load(std::memory_order_acquire)) refresh(c);
  const Snapshot& s = *c.snap;
  const RobotData& robot = *s.robot;
  robots::forwardKinematics(robot.model, q, c.X_WL);  // checks q (size, finite), naming the variable
  c.coherent = c.lastQ.size() == q.size() && (q - c.lastQ).cwiseAbs().maxCoeff() <= tol::kWarmStartMaxStep;
  c.lastQ = q;
  for (std::size_t g = 0; g < robot.links.size(); ++g) {
    c.linkCenter[g] = c.X_WL[robot.links[g].link] * robot.links[g].center_L;
  }
  if (++c.stamp == 0) {
    std::fill(c.pieceStamp.begin(), c.pieceStamp.end(), 0);
    c.stamp = 1;
  }
  ++c.stats.queries;
  return s;
}

/// World pose and sphere centre of robot piece i (computed once per query).
inline void posePiece(Impl& c, const RobotData& robot, int i) {
  if (c.pieceStamp[i] == c.stamp) return;
  const RobotPiece& p = robot.pieces[i];
  c.X_WP[i] = c.X_WL[p.link] * p.X_LP;
  c.pieceCenter[i] = c.X_WL[p.link] * p.center_L;
  c.pieceObb[i] = p.obb_L.transformed(c.X_WL[p.link]);
  c.pieceStamp[i] = c.stamp;
}

/// The pair's warm-start cache for this query: kept when the query is near the previous one,
/// reset first otherwise (a start from an unrelated configuration is worse than a cold start:
/// measured 20 % slower on random configurations, and DEEP runs fewer restarts when warm). A cold
/// pair's support climbs start from each hull's direction index (deep::ConvexPolytope::support).
inline deep::PairCache* warm(const Impl& c, deep::PairCache& cache) {
  if (!c.coherent) cache.reset();
  return &cache;
}

/// Lower bound on the distance between robot piece i (posed) and world piece w.
inline double pieceWorldLowerBound(const Impl& c, const RobotPiece& p, int i, const WorldPiece& w) {
  const double toBox = w.box.distance(c.pieceCenter[i]) - p.sphereRadius;
  const double toSphere = (c.pieceCenter[i] - w.center_W).norm() - p.sphereRadius - w.sphereRadius;
  return std::max(toBox, toSphere);
}

/// The bounding tests of robot piece i (posed) against world piece w: false when its bounding
/// sphere's lower bound is positive or the oriented boxes are apart.
inline bool worldBoundsMeet(const Impl& c, const RobotData& robot, int i, const WorldPiece& w) {
  return !(pieceWorldLowerBound(c, robot.pieces[i], i, w) > 0) && !separated(c.pieceObb[i], w.obb_W);
}

/// The bounding tests of robot pieces i and j (both posed): spheres, then oriented boxes.
inline bool selfBoundsMeet(const Impl& c, const RobotData& robot, int i, int j) {
  return !((c.pieceCenter[i] - c.pieceCenter[j]).norm() > robot.pieces[i].sphereRadius + robot.pieces[j].sphereRadius) &&
         !separated(c.pieceObb[i], c.pieceObb[j]);
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
/// true) when visit returns true. FCL's tree takes std::function: built from std::ref, it never
/// allocates (a std::function copy of a lambda with many captures would, on every query).
template <class Visit>
bool forEachOverlapping(const PieceSet& set, BroadPhase broadPhase, const Aabb& query, Visit&& visit) {
  switch (broadPhase) {
    case BroadPhase::AabbTree: return set.tree.visitOverlapping(query, visit);
    case BroadPhase::FclTree:
      return set.fclTree != nullptr && set.fclTree->visitOverlapping(query, std::function<bool(int)>(std::ref(visit)));
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
void forEachNear(const PieceSet& set, BroadPhase broadPhase, const Eigen::Vector3d& center, double r,
                 Bound&& bound, Visit&& visit) {
  switch (broadPhase) {
    case BroadPhase::AabbTree: set.tree.visitNear(center, r, bound, visit); return;
    case BroadPhase::FclTree:
      if (set.fclTree != nullptr) {
        set.fclTree->visitNear(center, r, std::function<double()>(std::ref(bound)),
                               std::function<void(int, double)>(std::ref(visit)));
      }
      return;
    case BroadPhase::None:
      for (int i = 0; i < static_cast<int>(set.pieces.size()); ++i) {
        const double lb = set.pieces[i].box.distance(center) - r;
        if (lb < bound()) visit(i, lb);
      }
      return;
  }
}

inline deep::ConvexShape shapeOf(const RobotPiece& p) { return deep::ConvexShape{p.core.get(), p.radius}; }
inline deep::ConvexShape shapeOf(const WorldPiece& p) { return deep::ConvexShape{p.core.get(), p.radius}; }

void notify(const World::Context& context, int linkA, const BodyRef& bodyB) {
  if (context.onNarrowPhase) context.onNarrowPhase(NarrowPhaseEvent{linkA, bodyB});
}

BodyRef bodyOfWorldPiece(const PieceSet& set, const WorldPiece& w) { return set.bodies[w.body].ref; }

BodyRef robotBody(int link) {
  BodyRef b;
  b.kind = BodyRef::Kind::RobotLink;
  b.index = link;
  return b;
}

}  // namespace

// --- isFree ----------------------------------------------------------------------------------

namespace {

/// isFree's narrow phase calls deep::overlapsUnchecked, skipping the shape and pose checks of
/// deep::overlaps on every pair: the pieces are checked when built, world poses when set
/// (obstacles) or loaded (scenes: URDF origins, a checked base pose), and a robot piece's pose is
/// a link pose from forward kinematics of a finite q times a fixed offset: rotations orthonormal
/// by construction. Only a translation can leave the doubles (a prismatic joint near 1e308); that
/// is checked here, once per query, and reported as deep::overlaps would.
void checkLinkTranslations(const Impl& c) {
  bool finite = true;
  for (const Eigen::Isometry3d& X : c.X_WL) finite &= X.translation().allFinite();
  if (!finite) throw std::invalid_argument("isFree: a link pose of the robot is not finite (configuration too large)");
}

/// World pieces with more faces than this skip the centroid test (centroidInside).
constexpr int kCentroidTestMaxFaces = 32;

/// True when the point x_W lies inside the world piece's core, deeper than twice its hull
/// tolerance below every face plane. The faces are the hull's facets fitted within
/// hullTolerance() of its vertices, so such a point lies in the convex hull of the vertices, the
/// polytope GJK works on. Used with a robot piece's centroid (inside its core): the pieces then
/// overlap, and GJK would say so (it reports touching as overlap, too). World pieces are mostly
/// boxes and slabs of a few faces; about a third of the robot-world overlaps on random Panda
/// configurations in the kitchen are decided here, without GJK.
inline bool centroidInside(const WorldPiece& w, const Eigen::Vector3d& x_W) {
  const deep::ConvexPolytope& B = *w.core;
  const int faces = B.numFaces();
  if (faces == 0 || faces > kCentroidTestMaxFaces) return false;
  const Eigen::Vector3d x = w.X_WP.linear().transpose() * (x_W - w.X_WP.translation());  // in B's frame
  const double margin = 2.0 * B.hullTolerance();
  for (int f = 0; f < faces; ++f) {
    if (!(B.faceNormal(f).dot(x) < B.faceOffset(f) - margin)) return false;  // NaN: not inside
  }
  return true;
}

/// Narrow phase of robot piece i against world piece wp of `set` (after the bounding tests).
bool overlapWorld(World::Context& context, Impl& c, const RobotData& robot, const PieceSet& set,
                  std::vector<deep::PairCache>& caches, PairKey::Kind kind, int i, int wp) {
  const RobotPiece& p = robot.pieces[i];
  const WorldPiece& w = set.pieces[wp];
  ++c.stats.narrowPhase;
  notify(context, p.link, bodyOfWorldPiece(set, w));
  if (c.state->options.centroidTest && centroidInside(w, c.pieceCenter[i])) {
    ++c.stats.centroidInside;
    c.lastHit = PairKey{kind, i, wp, -1};
    return true;
  }
  const bool hit = deep::overlapsUnchecked(shapeOf(p), c.X_WP[i], shapeOf(w), w.X_WP,
                                           warm(c, caches[static_cast<std::size_t>(i) * set.pieces.size() + wp]));
  if (hit) c.lastHit = PairKey{kind, i, wp, -1};
  return hit;
}

bool overlapSelf(World::Context& context, Impl& c, const RobotData& robot, int i, int j, int cache) {
  const RobotPiece& a = robot.pieces[i];
  const RobotPiece& b = robot.pieces[j];
  ++c.stats.narrowPhase;
  ++c.stats.selfNarrowPhase;
  notify(context, a.link, robotBody(b.link));
  const bool hit = deep::overlapsUnchecked(shapeOf(a), c.X_WP[i], shapeOf(b), c.X_WP[j], warm(c, c.selfCaches[cache]));
  if (hit) c.lastHit = PairKey{PairKey::Kind::Self, i, j, cache};
  return hit;
}

/// The robot link `g` against the world pieces of `set` near it: true at the first overlap.
bool linkHitsSet(World::Context& context, Impl& c, const Snapshot& s, const PieceSet& set,
                 std::vector<deep::PairCache>& caches, PairKey::Kind kind, int g) {
  if (set.pieces.empty()) return false;
  const RobotData& robot = *s.robot;
  const LinkGeometry& lg = robot.links[g];
  const Eigen::Vector3d& center = c.linkCenter[g];
  return forEachOverlapping(set, c.state->options.broadPhase, Aabb::ofSphere(center, lg.radius), [&](int wp) {
    const WorldPiece& w = set.pieces[wp];
    ++c.stats.linkCandidates;
    if (w.box.distance(center) > lg.radius) return false;
    for (int i = lg.firstPiece; i < lg.firstPiece + lg.numPieces; ++i) {
      posePiece(c, robot, i);
      ++c.stats.pieceTests;
      if (worldBoundsMeet(c, robot, i, w) && overlapWorld(context, c, robot, set, caches, kind, i, wp)) return true;
    }
    return false;
  });
}

bool selfPairHits(World::Context& context, Impl& c, const RobotData& robot, const SelfPair& sp) {
  const LinkGeometry& la = robot.links[sp.a];
  const LinkGeometry& lb = robot.links[sp.b];
  ++c.stats.linkCandidates;
  if (sp.grid != nullptr && sp.grid->certifiedFree(c.lastQ)) {
    ++c.stats.certifiedSelf;
    return false;
  }
  if ((c.linkCenter[sp.a] - c.linkCenter[sp.b]).norm() > la.radius + lb.radius) return false;
  return forEachSelfPiecePair(c, robot, sp, [&](int i, int j, int cache) {
    return selfBoundsMeet(c, robot, i, j) && overlapSelf(context, c, robot, i, j, cache);
  });
}

/// Re-tests the pair that overlapped in the previous query (motions overlap the same pair in a
/// row): true when it still overlaps.
bool lastHitStillHits(World::Context& context, Impl& c, const Snapshot& s) {
  const PairKey k = c.lastHit;
  const RobotData& robot = *s.robot;
  posePiece(c, robot, k.robotPiece);
  if (k.kind == PairKey::Kind::Self) {
    posePiece(c, robot, k.other);
    return selfBoundsMeet(c, robot, k.robotPiece, k.other) &&
           overlapSelf(context, c, robot, k.robotPiece, k.other, k.cache);
  }
  const bool scene = k.kind == PairKey::Kind::Scene;
  const PieceSet& set = scene ? *s.scenePieces : *s.obstaclePieces;
  return worldBoundsMeet(c, robot, k.robotPiece, set.pieces[k.other]) &&
         overlapWorld(context, c, robot, set, scene ? c.sceneCaches : c.obstacleCaches, k.kind, k.robotPiece,
                      k.other);
}

}  // namespace

bool World::isFree(const Eigen::Ref<const Eigen::VectorXd>& q, Context& context) const {
  Impl& c = *context.impl_;
  const Snapshot& s = prepare(*state_, c, q);
  const RobotData& robot = *s.robot;
  checkLinkTranslations(c);
  if (c.lastHit.kind != PairKey::Kind::None) {
    if (lastHitStillHits(context, c, s)) return false;
    c.lastHit = PairKey{};
  }
  // Links from the tip of the tree to the root: the distal links sweep the most space and meet
  // the world most often, so a colliding configuration is found sooner (the answer is the same).
  for (int g = static_cast<int>(robot.links.size()) - 1; g >= 0; --g) {
    if (linkHitsSet(context, c, s, *s.scenePieces, c.sceneCaches, PairKey::Kind::Scene, g)) return false;
    if (linkHitsSet(context, c, s, *s.obstaclePieces, c.obstacleCaches, PairKey::Kind::Obstacle, g)) return false;
  }
  for (const SelfPair& sp : s.selfPairs) {
    if (selfPairHits(context, c, robot, sp)) return false;
  }
  return true;
}

// --- signedDistance --------------------------------------------------------------------------

namespace {

/// Lower bound on sd(A, B) from the support functions in direction u (unit, world frame):
/// with M = B - A (cores), h_M(u) = h_B(u) + h_A(-u) >= |m| for no m in general, but
///   - if the cores overlap, the penetration depth is min over unit v of h_M(v) <= h_M(u);
///   - if they are apart, every m in M has u.m <= h_M(u), so |m| >= -h_M(u) when h_M(u) < 0;
/// in both cases the core signed distance is >= -h_M(u). Radii are subtracted as usual.
inline double supportLowerBound(const deep::ConvexPolytope& A, const Eigen::Isometry3d& X_WA, double rA,
                                const deep::ConvexPolytope& B, const Eigen::Isometry3d& X_WB, double rB,
                                const Eigen::Vector3d& u) {
  const Eigen::Vector3d uA = X_WA.linear().transpose() * u;
  const Eigen::Vector3d uB = X_WB.linear().transpose() * u;
  const double hB = uB.dot(B.vertex(B.support(uB))) + u.dot(X_WB.translation());
  const double minA = uA.dot(A.vertex(A.support(-uA))) + u.dot(X_WA.translation());
  return -(hB - minA) - rA - rB;
}

/// State of one signedDistance query: candidates are gathered with their bounding-volume lower
/// bounds (and the cheap upper bound of their centres' distance), sorted, and measured nearest
/// first until the lower bound reaches the best distance found.
struct DistanceSearch {
  World::Context& context;
  Impl& c;
  const Snapshot& s;
  const DistanceOptions& options;
  bool found = false;
  double best = std::numeric_limits<double>::infinity();
  /// An upper bound on the minimum: the smallest |c_A - c_B| - r_A - r_B over the pairs seen
  /// (piece centres lie inside their cores, so each is an upper bound on that pair's distance).
  double upper = std::numeric_limits<double>::infinity();
  PairKey bestKey;
  deep::SignedDistanceResult bestResult;
  PairKey skip;  // already evaluated first (the previous closest pair)

  DistanceSearch(World::Context& context_, Impl& c_, const Snapshot& s_, const DistanceOptions& options_)
      : context(context_), c(c_), s(s_), options(options_) {}

  bool collectContacts() const { return options.contactMargin > -std::numeric_limits<double>::infinity(); }

  /// Pairs whose lower bound is at least this need not be measured: they cannot beat the best
  /// distance found, cannot be below the upper bound (a pair exactly at it may be the minimum,
  /// hence the next double), are not contacts within the margin, or are beyond maxDistance.
  double bound() const {
    constexpr double inf = std::numeric_limits<double>::infinity();
    const double minimum = std::min(best, std::nextafter(upper, inf));
    const double need = collectContacts() ? std::max(minimum, std::nextafter(options.contactMargin, inf)) : minimum;
    return std::min(need, options.maxDistance);
  }

  void record(const PairKey& key, int linkA, int setKind, int body, const deep::SignedDistanceResult& r) {
    if (r.distance < options.maxDistance && (!found || r.distance < best)) {
      found = true;
      best = r.distance;
      bestKey = key;
      bestResult = r;
    }
    if (!collectContacts() || !(r.distance <= options.contactMargin)) return;
    for (BodyPairBest& e : c.bodyPairs) {
      if (e.linkA == linkA && e.setKind == setKind && e.body == body) {
        if (r.distance < e.result.distance) {
          e.key = key;
          e.result = r;
        }
        return;
      }
    }
    c.bodyPairs.push_back(BodyPairBest{linkA, setKind, body, key, r});
  }

  const PieceSet& setOf(PairKey::Kind kind) const {
    return kind == PairKey::Kind::Scene ? *s.scenePieces : *s.obstaclePieces;
  }
  std::vector<deep::PairCache>& cachesOf(PairKey::Kind kind) const {
    return kind == PairKey::Kind::Scene ? c.sceneCaches : c.obstacleCaches;
  }

  /// Measures the pair (both pieces posed).
  /// Signed distance of a pair. When the shapes overlap and the full DEEP (several walks) is
  /// asked for, one walk runs first: its depth is a valid separating translation, an upper bound
  /// on the depth, so its distance is a LOWER bound on the pair's signed distance; when that is
  /// already at least bound(), the pair cannot matter and the restarts are skipped.
  deep::SignedDistanceResult pairDistance(const deep::ConvexShape& A, const Eigen::Isometry3d& X_WA,
                                          const deep::ConvexShape& B, const Eigen::Isometry3d& X_WB,
                                          deep::PairCache& cache) {
    warm(c, cache);
    // The certified method runs no restarts: one call is the whole query.
    if (!options.deep.restarts || options.deep.method == deep::PenetrationMethod::Certified)
      return deep::signedDistance(A, X_WA, B, X_WB, &cache, options.deep);
    deep::DeepOptions quick = options.deep;
    quick.restarts = false;
    deep::SignedDistanceResult r = deep::signedDistance(A, X_WA, B, X_WB, &cache, quick);
    if (r.status == deep::SignedDistanceStatus::Separated || r.distance >= bound()) return r;
    ++c.stats.fullDepth;
    return deep::signedDistance(A, X_WA, B, X_WB, &cache, options.deep);
  }

  /// Measures the pair (both pieces posed).
  void measure(const PairKey& k) {
    const RobotData& robot = *s.robot;
    const RobotPiece& a = robot.pieces[k.robotPiece];
    ++c.stats.narrowPhase;
    if (k.kind == PairKey::Kind::Self) {
      const RobotPiece& b = robot.pieces[k.other];
      ++c.stats.selfNarrowPhase;
      notify(context, a.link, robotBody(b.link));
      const deep::SignedDistanceResult r =
          pairDistance(shapeOf(a), c.X_WP[k.robotPiece], shapeOf(b), c.X_WP[k.other], c.selfCaches[k.cache]);
      record(k, a.link, 0, b.link, r);
      return;
    }
    const PieceSet& set = setOf(k.kind);
    const WorldPiece& w = set.pieces[k.other];
    notify(context, a.link, bodyOfWorldPiece(set, w));
    const deep::SignedDistanceResult r =
        pairDistance(shapeOf(a), c.X_WP[k.robotPiece], shapeOf(w), w.X_WP,
                     cachesOf(k.kind)[static_cast<std::size_t>(k.robotPiece) * set.pieces.size() + k.other]);
    record(k, a.link, k.kind == PairKey::Kind::Scene ? 1 : 2, w.body, r);
  }

  /// Lower bound from support functions (see supportLowerBound), along the best pair's normal and
  /// along the centres' difference.
  double supportBound(const PairKey& k) const {
    const RobotData& robot = *s.robot;
    const RobotPiece& a = robot.pieces[k.robotPiece];
    const Eigen::Isometry3d& X_WA = c.X_WP[k.robotPiece];
    const deep::ConvexPolytope* coreB;
    const Eigen::Isometry3d* X_WB;
    double rB;
    Eigen::Vector3d centerB;
    if (k.kind == PairKey::Kind::Self) {
      const RobotPiece& b = robot.pieces[k.other];
      coreB = b.core.get();
      X_WB = &c.X_WP[k.other];
      rB = b.radius;
      centerB = c.pieceCenter[k.other];
    } else {
      const WorldPiece& w = setOf(k.kind).pieces[k.other];
      coreB = w.core.get();
      X_WB = &w.X_WP;
      rB = w.radius;
      centerB = w.center_W;
    }
    double lb = -std::numeric_limits<double>::infinity();
    const Eigen::Vector3d d = centerB - c.pieceCenter[k.robotPiece];
    const double dn = d.norm();
    if (dn > 0) lb = supportLowerBound(*a.core, X_WA, a.radius, *coreB, *X_WB, rB, d / dn);
    if (found && lb < bound()) {
      lb = std::max(lb, supportLowerBound(*a.core, X_WA, a.radius, *coreB, *X_WB, rB, bestResult.normal));
    }
    return lb;
  }

  void gatherWorld(PairKey::Kind kind, int g) {
    const PieceSet& set = setOf(kind);
    if (set.pieces.empty()) return;
    const RobotData& robot = *s.robot;
    const LinkGeometry& lg = robot.links[g];
    forEachNear(set, c.state->options.broadPhase, c.linkCenter[g], lg.radius, [this] { return bound(); },
                [&](int wp, double /*linkLowerBound*/) {
                  const WorldPiece& w = set.pieces[wp];
                  ++c.stats.linkCandidates;
                  for (int i = lg.firstPiece; i < lg.firstPiece + lg.numPieces; ++i) {
                    posePiece(c, robot, i);
                    const RobotPiece& p = robot.pieces[i];
                    ++c.stats.pieceTests;
                    upper = std::min(upper, (c.pieceCenter[i] - w.center_W).norm() - p.radius - w.radius);
                    const double lb = pieceWorldLowerBound(c, p, i, w);
                    if (lb >= bound()) continue;
                    const PairKey key{kind, i, wp, -1};
                    if (key == skip) continue;
                    c.candidates.push_back(Candidate{lb, key});
                  }
                });
  }

  void gatherSelf(const SelfPair& sp) {
    const RobotData& robot = *s.robot;
    const LinkGeometry& la = robot.links[sp.a];
    const LinkGeometry& lb = robot.links[sp.b];
    ++c.stats.linkCandidates;
    if ((c.linkCenter[sp.a] - c.linkCenter[sp.b]).norm() - la.radius - lb.radius >= bound()) return;
    forEachSelfPiecePair(c, robot, sp, [&](int i, int j, int cache) {
      const RobotPiece& a = robot.pieces[i];
      const RobotPiece& b = robot.pieces[j];
      const double centers = (c.pieceCenter[i] - c.pieceCenter[j]).norm();
      upper = std::min(upper, centers - a.radius - b.radius);
      const double lower = centers - a.sphereRadius - b.sphereRadius;
      const PairKey key{PairKey::Kind::Self, i, j, cache};
      if (!(lower >= bound()) && !(key == skip)) c.candidates.push_back(Candidate{lower, key});
      return false;
    });
  }

  /// The previous closest pair, measured first: its distance is usually near the new minimum
  /// (motions), which prunes most of the search.
  void previousClosest() {
    const PairKey k = c.lastClosest;
    if (k.kind == PairKey::Kind::None) return;
    if (!(k.kind == PairKey::Kind::Self ? options.selfPairs : options.worldPairs)) return;
    const RobotData& robot = *s.robot;
    posePiece(c, robot, k.robotPiece);
    if (k.kind == PairKey::Kind::Self) posePiece(c, robot, k.other);
    measure(k);
    skip = k;
  }

  void run() {
    const RobotData& robot = *s.robot;
    c.candidates.clear();
    previousClosest();
    for (int g = 0; options.worldPairs && g < static_cast<int>(robot.links.size()); ++g) {
      gatherWorld(PairKey::Kind::Scene, g);
      gatherWorld(PairKey::Kind::Obstacle, g);
    }
    if (options.selfPairs) {
      for (const SelfPair& sp : s.selfPairs) gatherSelf(sp);
    }
    std::sort(c.candidates.begin(), c.candidates.end(),
              [](const Candidate& x, const Candidate& y) { return x.lowerBound < y.lowerBound; });
    for (const Candidate& cand : c.candidates) {
      if (cand.lowerBound >= bound()) break;
      if (supportBound(cand.key) >= bound()) continue;
      measure(cand.key);
    }
  }
};

/// Fills names and, when asked, the gradient of a pair's distance.
Contact makeContact(Impl& c, const Snapshot& s, const PairKey& key, const deep::SignedDistanceResult& r,
                    bool gradient) {
  const RobotData& robot = *s.robot;
  Contact out;
  out.distance = r.distance;
  out.normal = r.normal;
  out.pointA = r.pointA;
  out.pointB = r.pointB;
  out.status = r.status;
  out.linkA = robot.pieces[key.robotPiece].link;
  out.nameA = robot.model.link(out.linkA).name;
  int linkB = -1;
  if (key.kind == PairKey::Kind::Self) {
    linkB = robot.pieces[key.other].link;
    out.bodyB = robotBody(linkB);
    out.nameB = robot.model.link(linkB).name;
  } else {
    const PieceSet& set = key.kind == PairKey::Kind::Scene ? *s.scenePieces : *s.obstaclePieces;
    const detail::WorldBody& body = set.bodies[set.pieces[key.other].body];
    out.bodyB = body.ref;
    out.nameB = body.name;
  }
  if (gradient) {
    // d sd / dq = n^T (J_B(p_B) - J_A(p_A)): the witness points are taken as points fixed on
    // their links (their link-frame coordinates at this configuration).
    const Eigen::Vector3d p_LA = c.X_WL[out.linkA].inverse() * r.pointA;
    robots::pointJacobian(robot.model, c.X_WL, out.linkA, p_LA, c.J_A);
    out.gradient = -(c.J_A.transpose() * r.normal);
    if (linkB >= 0) {
      const Eigen::Vector3d p_LB = c.X_WL[linkB].inverse() * r.pointB;
      robots::pointJacobian(robot.model, c.X_WL, linkB, p_LB, c.J_B);
      out.gradient += c.J_B.transpose() * r.normal;
    }
  }
  return out;
}

}  // namespace

DistanceResult World::signedDistance(const Eigen::Ref<const Eigen::VectorXd>& q, Context& context,
                                     const DistanceOptions& options) const {
  if (std::isnan(options.maxDistance) || std::isnan(options.contactMargin)) {
    throw std::invalid_argument("signedDistance: maxDistance and contactMargin must not be NaN");
  }
  Impl& c = *context.impl_;
  const Snapshot& s = prepare(*state_, c, q);
  c.bodyPairs.clear();
  DistanceSearch search(context, c, s, options);
  search.run();

  DistanceResult result;
  result.found = search.found;
  c.lastClosest = search.found ? search.bestKey : PairKey{};
  if (search.found) result.closest = makeContact(c, s, search.bestKey, search.bestResult, options.gradient);
  if (search.collectContacts()) {
    std::sort(c.bodyPairs.begin(), c.bodyPairs.end(),
              [](const BodyPairBest& a, const BodyPairBest& b) { return a.result.distance < b.result.distance; });
    for (const BodyPairBest& e : c.bodyPairs) {
      result.contacts.push_back(makeContact(c, s, e.key, e.result, options.gradient));
    }
  }
  return result;
}

// --- the thread's own contexts ---------------------------------------------------------------

namespace {

/// The calling thread's context for `state`'s world: a thread_local table keyed by the world's
/// uid (never reused), with entries of dead worlds swept as the table grows.
World::Context& threadContext(const World& world, const std::shared_ptr<WorldState>& state) {
  struct Entry {
    std::weak_ptr<WorldState> state;
    std::unique_ptr<World::Context> context;
  };
  thread_local std::unordered_map<std::uint64_t, Entry> table;
  thread_local std::uint64_t lastUid = 0;
  thread_local World::Context* last = nullptr;
  if (lastUid == state->uid) return *last;
  auto it = table.find(state->uid);
  if (it == table.end()) {
    if (table.size() >= 4) {
      for (auto e = table.begin(); e != table.end();) {
        e = e->second.state.expired() ? table.erase(e) : std::next(e);
      }
    }
    it = table.emplace(state->uid, Entry{state, std::make_unique<World::Context>(world.makeContext())}).first;
  }
  lastUid = state->uid;
  last = it->second.context.get();
  return *last;
}

}  // namespace

bool World::isFree(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  return isFree(q, threadContext(*this, state_));
}

DistanceResult World::signedDistance(const Eigen::Ref<const Eigen::VectorXd>& q, const DistanceOptions& options) const {
  return signedDistance(q, threadContext(*this, state_), options);
}

}  // namespace deepcheck::checker
