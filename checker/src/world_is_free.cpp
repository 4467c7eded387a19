// World::isFree: does any checked pair overlap (world_queries_internal.h).

#include "world_queries_internal.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace deepcheck::checker {

using namespace detail;  // NOLINT: the queries' own internals

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

/// The narrow phase of a pair: first the tetrahedron that enclosed the origin when the pair last
/// overlapped (the same four vertex pairs usually still enclose it at a nearby configuration:
/// four vertex transforms instead of a GJK run), then GJK.
bool overlapPair(Impl& c, const deep::ConvexShape& A, const Eigen::Isometry3d& X_WA, const deep::ConvexShape& B,
                 const Eigen::Isometry3d& X_WB, deep::PairCache& pairCache) {
  deep::PairCache* cache = warm(c, pairCache, FarStep::KeepGjk);
  if (cache->gjk.enclosed && deep::enclosesOrigin(A, X_WA, B, X_WB, cache->gjk.enclosing)) {
    ++c.stats.enclosedAgain;
    return true;
  }
  return deep::overlapsUnchecked(A, X_WA, B, X_WB, cache);
}

/// Narrow phase of robot piece i against world piece wp of `set`, of pair kind `kind` (after the
/// bounding tests).
bool overlapWorld(Impl& c, const RobotData& robot, const PieceSet& set, PairKey::Kind kind, int i, int wp) {
  const RobotPiece& p = robot.pieces[i];
  const WorldPiece& w = set.pieces[wp];
  ++c.stats.narrowPhase;
  notify(c, p.link, bodyOfWorldPiece(set, w));
  if (c.state->options.centroidTest && centroidInside(w, c.pieceCenter[i])) {
    ++c.stats.centroidInside;
    c.lastHit = PairKey{kind, i, wp, -1};
    return true;
  }
  const bool hit = overlapPair(c, shapeOf(p), pieceTransform(c, robot, i), shapeOf(w), w.X_WP,
                               worldCaches(c, kind)[pairIndex(set, i, wp)]);
  if (hit) c.lastHit = PairKey{kind, i, wp, -1};
  return hit;
}

bool overlapSelf(Impl& c, const RobotData& robot, int i, int j, int cache) {
  const RobotPiece& a = robot.pieces[i];
  const RobotPiece& b = robot.pieces[j];
  ++c.stats.narrowPhase;
  ++c.stats.selfNarrowPhase;
  notify(c, a.link, robotBody(b.link));
  const bool hit = overlapPair(c, shapeOf(a), pieceTransform(c, robot, i), shapeOf(b), pieceTransform(c, robot, j),
                               c.selfCaches[cache]);
  if (hit) c.lastHit = PairKey{PairKey::Kind::Self, i, j, cache};
  return hit;
}

/// The robot link `g` against the world pieces of pair kind `kind` near it: true at the first
/// overlap.
bool linkHitsSet(Impl& c, const Snapshot& s, PairKey::Kind kind, int g) {
  const PieceSet& set = worldPieces(s, kind);
  if (set.pieces.empty()) return false;
  std::vector<std::uint8_t>& axes = worldAxes(c, kind);
  const RobotData& robot = *s.robot;
  const LinkGeometry& lg = robot.links[g];
  const Eigen::Vector3d& center = c.linkCenter[g];
  return forEachOverlapping(set, c.state->options.broadPhase, Aabb::ofSphere(center, lg.radius), [&](int wp) {
    const WorldPiece& w = set.pieces[wp];
    ++c.stats.linkCandidates;
    if (worldPairAllowed(s, kind, g, w.body)) return false;
    if (fartherThan(w.box.squaredDistance(center), lg.radius)) return false;
    for (int i = lg.firstPiece; i < lg.firstPiece + lg.numPieces; ++i) {
      posePiece(c, robot, i);
      ++c.stats.pieceTests;
      if (worldBoundsMeet(c, robot, i, w, axes[pairIndex(set, i, wp)]) &&
          overlapWorld(c, robot, set, kind, i, wp)) {
        return true;
      }
    }
    return false;
  });
}

bool selfPairHits(Impl& c, const RobotData& robot, const SelfPair& sp) {
  const LinkGeometry& la = robot.links[sp.a];
  const LinkGeometry& lb = robot.links[sp.b];
  ++c.stats.linkCandidates;
  if (sp.grid != nullptr && sp.grid->certifiedFree(c.lastQ)) {
    ++c.stats.certifiedSelf;
    return false;
  }
  if (fartherThan((c.linkCenter[sp.a] - c.linkCenter[sp.b]).squaredNorm(), la.radius + lb.radius)) return false;
  return forEachSelfPiecePair(c, robot, sp, [&](int i, int j, int cache) {
    return selfBoundsMeet(c, robot, i, j, c.selfAxes[cache]) && overlapSelf(c, robot, i, j, cache);
  });
}

/// Re-tests the pair that overlapped in the previous query (motions overlap the same pair in a
/// row): true when it still overlaps.
bool lastHitStillHits(Impl& c, const Snapshot& s) {
  const PairKey k = c.lastHit;
  const RobotData& robot = *s.robot;
  posePiece(c, robot, k.robotPiece);
  if (k.kind == PairKey::Kind::Self) {
    posePiece(c, robot, k.other);
    return selfBoundsMeet(c, robot, k.robotPiece, k.other, c.selfAxes[k.cache]) &&
           overlapSelf(c, robot, k.robotPiece, k.other, k.cache);
  }
  const PieceSet& set = worldPieces(s, k.kind);
  std::uint8_t& axis = worldAxes(c, k.kind)[pairIndex(set, k.robotPiece, k.other)];
  return worldBoundsMeet(c, robot, k.robotPiece, set.pieces[k.other], axis) &&
         overlapWorld(c, robot, set, k.kind, k.robotPiece, k.other);
}

}  // namespace

bool World::isFree(const Eigen::Ref<const Eigen::VectorXd>& q, Context& context) const {
  Impl& c = *context.impl_;
  const Snapshot& s = prepare(*state_, c, q);
  const RobotData& robot = *s.robot;
  checkLinkTranslations(c);
  if (c.lastHit.kind != PairKey::Kind::None) {
    if (lastHitStillHits(c, s)) return false;
    c.lastHit = PairKey{};
  }
  // Links from the tip of the tree to the root: the distal links sweep the most space and meet
  // the world most often, so a colliding configuration is found sooner (the answer is the same).
  for (int g = static_cast<int>(robot.links.size()) - 1; g >= 0; --g) {
    if (linkHitsSet(c, s, PairKey::Kind::Scene, g)) return false;
    if (linkHitsSet(c, s, PairKey::Kind::Obstacle, g)) return false;
  }
  for (const SelfPair& sp : s.selfPairs) {
    if (selfPairHits(c, robot, sp)) return false;
  }
  return true;
}

}  // namespace deepcheck::checker
