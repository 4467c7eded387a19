// World::isFree: does any checked pair overlap; World::isClear: is every checked pair farther apart
// than a demanded clearance (world_queries_internal.h). One traversal serves both: isClear grows
// each robot piece, its bounding volumes and its link's sphere by its pair's demand.

#include "world_clearance_internal.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace deepcheck::checker {

using namespace detail;  // NOLINT: the queries' own internals

// --- isFree ----------------------------------------------------------------------------------

namespace {

/// isFree's narrow phase calls geometry::overlapsUnchecked, skipping the shape and pose checks of
/// geometry::overlaps on every pair: the pieces are checked when built, world poses when set
/// (obstacles) or loaded (scenes: URDF origins, a checked base pose), and a robot piece's pose is
/// a link pose from forward kinematics of a finite q times a fixed offset: rotations orthonormal
/// by construction. Only a translation can leave the doubles (a prismatic joint near 1e308); that
/// is checked here, once per query, and reported as geometry::overlaps would.
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
  const geometry::ConvexPolytope& B = *w.core;
  const int faces = B.numFaces();
  if (faces == 0 || faces > kCentroidTestMaxFaces) return false;
  const Eigen::Vector3d x = w.X_WP.linear().transpose() * (x_W - w.X_WP.translation());  // in B's frame
  const double margin = 2.0 * B.hullTolerance();
  for (int f = 0; f < faces; ++f) {
    if (!(B.faceNormal(f).dot(x) < B.faceOffset(f) - margin)) return false;  // NaN: not inside
  }
  return true;
}

/// The narrow phase of a pair: first the tetrahedron that enclosed the origin when the pair last
/// overlapped (the same four vertex pairs usually still enclose it at a nearby configuration:
/// four vertex transforms instead of a GJK run), then GJK.
bool overlapPair(Impl& c, const geometry::ConvexShape& A, const Eigen::Isometry3d& X_WA, const geometry::ConvexShape& B,
                 const Eigen::Isometry3d& X_WB, geometry::PairCache& pairCache) {
  geometry::PairCache* cache = warm(c, pairCache, FarStep::KeepGjk);
  if (cache->gjk.enclosed && geometry::enclosesOrigin(A, X_WA, B, X_WB, cache->gjk.enclosing)) {
    ++c.stats.enclosedAgain;
    return true;
  }
  return geometry::overlapsUnchecked(A, X_WA, B, X_WB, cache);
}

/// Narrow phase of robot piece i against world piece wp of `set`, of pair kind `kind` (after the
/// bounding tests).
bool overlapWorld(Impl& c, const RobotData& robot, const PieceSet& set, PairKey::Kind kind, int i, int wp,
                  double margin) {
  const RobotPiece& p = robot.pieces[i];
  const WorldPiece& w = set.pieces[wp];
  ++c.stats.narrowPhase;
  notify(c, p.link, bodyOfWorldPiece(set, w));
  if (c.snap->shortcuts.centroidTest && centroidInside(w, c.pieceCenter[i])) {
    ++c.stats.centroidInside;
    c.lastHit = PairKey{kind, i, wp, -1};
    return true;
  }
  const bool hit = overlapPair(c, grown(shapeOf(p), margin), pieceTransform(c, robot, i), shapeOf(w), w.X_WP,
                               worldCaches(c, kind)[pairIndex(set, i, wp)]);
  if (hit) c.lastHit = PairKey{kind, i, wp, -1};
  return hit;
}

bool overlapSelf(Impl& c, const RobotData& robot, int i, int j, int cache, double margin) {
  const RobotPiece& a = robot.pieces[i];
  const RobotPiece& b = robot.pieces[j];
  ++c.stats.narrowPhase;
  ++c.stats.selfNarrowPhase;
  notify(c, a.link, robotBody(b.link));
  const bool hit = overlapPair(c, grown(shapeOf(a), margin), pieceTransform(c, robot, i), shapeOf(b),
                               pieceTransform(c, robot, j), c.selfCaches[cache]);
  if (hit) c.lastHit = PairKey{PairKey::Kind::Self, i, j, cache};
  return hit;
}

/// Calls f(key, margin) for every pair of robot link geometry `g` and a world piece of pair kind
/// `kind` whose bounding volumes meet, grown by the pair's margin; stops when f returns true.
template <class F>
bool linkPairsNear(Impl& c, const Snapshot& s, PairKey::Kind kind, int g, const Margins& margins, F& f) {
  const PieceSet& set = worldPieces(s, kind);
  if (set.pieces.empty()) return false;
  std::vector<std::uint8_t>& axes = worldAxes(c, kind);
  const RobotData& robot = *s.robot;
  const LinkGeometry& lg = robot.links[g];
  const Eigen::Vector3d& center = c.linkCenter[g];
  // The broad phase with the cheaper upper margin; the margin itself once a candidate needs it.
  double radius = lg.radius + margins.worldUpper(g);
  double m = -1.0;
  return forEachOverlapping(set, c.state->options.broadPhase, Aabb::ofSphere(center, radius), [&](int wp) {
    const WorldPiece& w = set.pieces[wp];
    ++c.stats.linkCandidates;
    if (worldPairAllowed(s, kind, g, w.body)) return false;
    if (m < 0.0) {
      m = margins.world(g);
      radius = lg.radius + m;
    }
    if (fartherThan(w.box.squaredDistance(center), radius)) return false;
    for (int i = lg.firstPiece; i < lg.firstPiece + lg.numPieces; ++i) {
      posePiece(c, robot, i);
      ++c.stats.pieceTests;
      if (worldBoundsMeet(c, robot, i, w, axes[pairIndex(set, i, wp)], m) && f(PairKey{kind, i, wp, -1}, m)) {
        return true;
      }
    }
    return false;
  });
}

/// The same for the piece pairs of self pair sp.
template <class F>
bool selfPairsNear(Impl& c, const RobotData& robot, const SelfPair& sp, const Margins& margins, F& f) {
  const LinkGeometry& la = robot.links[sp.a];
  const LinkGeometry& lb = robot.links[sp.b];
  ++c.stats.linkCandidates;
  if (sp.grid != nullptr && margins.gridCertifies(*sp.grid, c.lastQ, margins.selfUpper(sp.a, sp.b))) {
    ++c.stats.certifiedSelf;
    return false;
  }
  const double m = margins.self(sp.a, sp.b);
  if (fartherThan((c.linkCenter[sp.a] - c.linkCenter[sp.b]).squaredNorm(), la.radius + lb.radius + m)) return false;
  return forEachSelfPiecePair(c, robot, sp, [&](int i, int j, int cache) {
    return selfBoundsMeet(c, robot, i, j, c.selfAxes[cache], m) && f(PairKey{PairKey::Kind::Self, i, j, cache}, m);
  });
}

/// Every pair whose bounding volumes meet (grown by its margin), for f(key, margin) until it
/// returns true: the links from the tip of the tree to the root (the distal links sweep the most
/// space and meet the world most often, so a colliding configuration is found sooner), then the
/// self pairs.
template <class F>
bool forEachPairNear(Impl& c, const Snapshot& s, const Margins& margins, F& f, const NearFilter* only = nullptr) {
  const std::size_t links = s.robot->links.size();
  for (int g = static_cast<int>(links) - 1; g >= 0; --g) {
    if (only != nullptr && !only->link(static_cast<std::size_t>(g))) continue;
    if (linkPairsNear(c, s, PairKey::Kind::Scene, g, margins, f)) return true;
    if (linkPairsNear(c, s, PairKey::Kind::Obstacle, g, margins, f)) return true;
  }
  for (std::size_t i = 0; i < s.selfPairs.size(); ++i) {
    if (only != nullptr && !only->self(i)) continue;
    if (selfPairsNear(c, *s.robot, s.selfPairs[i], margins, f)) return true;
  }
  return false;
}

bool narrowWithin(Impl& c, const Snapshot& s, const PairKey& k, double margin) {
  const RobotData& robot = *s.robot;
  if (k.kind == PairKey::Kind::Self) return overlapSelf(c, robot, k.robotPiece, k.other, k.cache, margin);
  return overlapWorld(c, robot, worldPieces(s, k.kind), k.kind, k.robotPiece, k.other, margin);
}

/// Poses pair k's pieces and sets m to its margin: true when its bounding volumes, grown by m, meet.
bool pairBoundsMeet(Impl& c, const Snapshot& s, const PairKey& k, const Margins& margins, double& m) {
  const RobotData& robot = *s.robot;
  posePiece(c, robot, k.robotPiece);
  const int group = robot.pieces[k.robotPiece].group;
  if (k.kind == PairKey::Kind::Self) {
    posePiece(c, robot, k.other);
    m = margins.self(group, robot.pieces[k.other].group);
    return selfBoundsMeet(c, robot, k.robotPiece, k.other, c.selfAxes[k.cache], m);
  }
  const PieceSet& set = worldPieces(s, k.kind);
  std::uint8_t& axis = worldAxes(c, k.kind)[pairIndex(set, k.robotPiece, k.other)];
  m = margins.world(group);
  return worldBoundsMeet(c, robot, k.robotPiece, set.pieces[k.other], axis, m);
}

/// Bounding tests and narrow phase of pair k, with its margin.
bool pairWithin(Impl& c, const Snapshot& s, const PairKey& k, const Margins& margins) {
  double m = 0.0;
  return pairBoundsMeet(c, s, k, margins, m) && narrowWithin(c, s, k, m);
}

/// True when k is a self pair whose grid certifies it over the sub-motion (Margins::gridCertifies).
bool gridCertifiesPair(const Impl& c, const Snapshot& s, const PairKey& k, const Margins& margins) {
  if (k.kind != PairKey::Kind::Self) return false;
  // The self pair whose block of caches holds k's.
  const auto sp = std::upper_bound(s.selfPairs.begin(), s.selfPairs.end(), k.cache,
                                   [](int cache, const SelfPair& p) { return cache < p.cacheOffset; }) -
                  1;
  const RobotData& robot = *s.robot;
  return sp->grid != nullptr &&
         margins.gridCertifies(*sp->grid, c.lastQ,
                               margins.self(robot.pieces[k.robotPiece].group, robot.pieces[k.other].group));
}

/// pairCover's narrow phase, once the bounding volumes meet within margin m (poses made).
double narrowCover(Impl& c, const Snapshot& s, const PairKey& k, double base, double m) {
  const RobotData& robot = *s.robot;
  const RobotPiece& p = robot.pieces[k.robotPiece];
  ++c.stats.narrowPhase;
  geometry::GjkBound bound;
  if (k.kind == PairKey::Kind::Self) {
    ++c.stats.selfNarrowPhase;
    const RobotPiece& q = robot.pieces[k.other];
    notify(c, p.link, robotBody(q.link));
    bound = geometry::distanceBoundUnchecked(shapeOf(p), pieceTransform(c, robot, k.robotPiece), shapeOf(q),
                                             pieceTransform(c, robot, k.other), base, m,
                                             warm(c, c.selfCaches[k.cache], FarStep::KeepGjk));
  } else {
    const PieceSet& set = worldPieces(s, k.kind);
    const WorldPiece& w = set.pieces[k.other];
    notify(c, p.link, bodyOfWorldPiece(set, w));
    bound = geometry::distanceBoundUnchecked(
        shapeOf(p), pieceTransform(c, robot, k.robotPiece), shapeOf(w), w.X_WP, base, m,
        warm(c, worldCaches(c, k.kind)[pairIndex(set, k.robotPiece, k.other)], FarStep::KeepGjk));
  }
  if (bound.within) {
    c.lastHit = k;
    return kCoverCollides;
  }
  if (!(bound.lower <= m) || !(m > base)) return kCoverClear;
  return std::min((bound.lower - base) / (m - base), 1.0);
}

}  // namespace

namespace detail {

bool clearOfAll(Impl& c, const Snapshot& s, const Margins& margins) {
  checkLinkTranslations(c);
  if (c.lastHit.kind != PairKey::Kind::None) {
    // The pair that was within its margin last time usually still is (motions check nearby
    // configurations in a row).
    if (pairWithin(c, s, c.lastHit, margins)) return false;
    c.lastHit = PairKey{};
  }
  auto narrow = [&](const PairKey& k, double m) { return narrowWithin(c, s, k, m); };
  return !forEachPairNear(c, s, margins, narrow);
}

Clearance collectNear(Impl& c, const Snapshot& s, const Margins& margins, std::vector<PairKey>& near, double& cover,
                      const NearFilter* only) {
  checkLinkTranslations(c);
  near.clear();
  cover = kCoverClear;
  Margins base = margins;
  base.dropToBase();
  // The pair that collided last time first: motions test nearby configurations in a row.
  if (c.lastHit.kind != PairKey::Kind::None) {
    if (pairWithin(c, s, c.lastHit, base)) return Clearance::Collides;
    c.lastHit = PairKey{};
  }
  auto test = [&](const PairKey& k, double m) {
    const double f = narrowCover(c, s, k, margins.base(), m);
    if (f == kCoverCollides) return true;
    if (f == kCoverClear) return false;
    cover = std::min(cover, f);
    near.push_back(k);
    return false;
  };
  if (forEachPairNear(c, s, margins, test, only)) return Clearance::Collides;
  return near.empty() ? Clearance::Clear : Clearance::Near;
}

double pairCover(Impl& c, const Snapshot& s, const PairKey& k, const Margins& margins) {
  double m = 0.0;
  if (gridCertifiesPair(c, s, k, margins) || !pairBoundsMeet(c, s, k, margins, m)) return kCoverClear;
  return narrowCover(c, s, k, margins.base(), m);
}

}  // namespace detail

bool World::isFree(const Eigen::Ref<const Eigen::VectorXd>& q, Context& context) const {
  Impl& c = *context.impl_;
  return clearOfAll(c, prepare(*state_, c, q), Margins());
}

bool World::isClear(const Eigen::Ref<const Eigen::VectorXd>& q, Context& context, const ClearanceDemand& demand) const {
  Impl& c = *context.impl_;
  const Snapshot& s = prepare(*state_, c, q);
  return clearOfAll(c, s, Margins(demand, *s.robot, demand.scale));
}

}  // namespace deepcheck::checker
