// World::signedDistance: the closest pair, its gradient and the contact list
// (world_queries_internal.h).

#include "world_queries_internal.h"

#include "deepcheck/robots/kinematics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace deepcheck::checker {

using namespace detail;  // NOLINT: the queries' own internals

// --- signedDistance --------------------------------------------------------------------------

namespace {

/// State of one signedDistance query: candidates are gathered with their bounding-volume lower
/// bounds (and the cheap upper bound of their centres' distance), sorted, and measured nearest
/// first until the lower bound reaches the best distance found.
struct DistanceSearch {
  Impl& c;
  const Snapshot& s;
  const DistanceOptions& options;
  bool found = false;
  double best = std::numeric_limits<double>::infinity();
  /// An upper bound on the minimum: the smallest |c_A - c_B| - r_A - r_B over the pairs seen
  /// (piece centres lie inside their cores, so each is an upper bound on that pair's distance).
  double upper = std::numeric_limits<double>::infinity();
  PairKey bestKey;
  geometry::SignedDistanceResult bestResult;
  PairKey skip;  // already evaluated first (the previous closest pair)

  DistanceSearch(Impl& c_, const Snapshot& s_, const DistanceOptions& options_) : c(c_), s(s_), options(options_) {}

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

  void record(const PairKey& key, int groupA, int setKind, int body, const geometry::SignedDistanceResult& r) {
    if (r.distance < options.maxDistance && (!found || r.distance < best)) {
      found = true;
      best = r.distance;
      bestKey = key;
      bestResult = r;
    }
    if (!collectContacts() || !(r.distance <= options.contactMargin)) return;
    for (BodyPairBest& e : c.bodyPairs) {
      if (e.groupA == groupA && e.setKind == setKind && e.body == body) {
        if (r.distance < e.result.distance) {
          e.key = key;
          e.result = r;
        }
        return;
      }
    }
    c.bodyPairs.push_back(BodyPairBest{groupA, setKind, body, key, r});
  }

  /// Measures the pair (both pieces posed).
  /// Signed distance of a pair. When the shapes overlap and the full DEEP (several walks) is
  /// asked for, one walk runs first: its depth is a valid separating translation, an upper bound
  /// on the depth, so its distance is a LOWER bound on the pair's signed distance; when that is
  /// already at least bound(), the pair cannot matter and the restarts are skipped.
  geometry::SignedDistanceResult pairDistance(const geometry::ConvexShape& A, const Eigen::Isometry3d& X_WA,
                                              const geometry::ConvexShape& B, const Eigen::Isometry3d& X_WB,
                                              geometry::PairCache& cache) {
    warm(c, cache, FarStep::KeepEnclosing);
    // The certified method runs no restarts: one call is the whole query.
    if (!options.penetration.walk.restarts ||
        options.penetration.method == geometry::PenetrationMethod::CertifiedExpansion)
      return geometry::signedDistance(A, X_WA, B, X_WB, &cache, options.penetration);
    geometry::PenetrationOptions quick = options.penetration;
    quick.walk.restarts = false;
    geometry::SignedDistanceResult r = geometry::signedDistance(A, X_WA, B, X_WB, &cache, quick);
    if (r.status == geometry::SignedDistanceStatus::Separated || r.distance >= bound()) return r;
    ++c.stats.fullDepth;
    return geometry::signedDistance(A, X_WA, B, X_WB, &cache, options.penetration);
  }

  /// Measures the pair (both pieces posed).
  void measure(const PairKey& k) {
    const RobotData& robot = *s.robot;
    const RobotPiece& a = robot.pieces[k.robotPiece];
    ++c.stats.narrowPhase;
    if (k.kind == PairKey::Kind::Self) {
      const RobotPiece& b = robot.pieces[k.other];
      ++c.stats.selfNarrowPhase;
      notify(c, a.link, robotBody(b.link));
      const geometry::SignedDistanceResult r =
          pairDistance(shapeOf(a), pieceTransform(c, robot, k.robotPiece), shapeOf(b),
                       pieceTransform(c, robot, k.other), c.selfCaches[k.cache]);
      record(k, a.group, 0, b.group, r);
      return;
    }
    const PieceSet& set = worldPieces(s, k.kind);
    const WorldPiece& w = set.pieces[k.other];
    notify(c, a.link, bodyOfWorldPiece(set, w));
    const geometry::SignedDistanceResult r =
        pairDistance(shapeOf(a), pieceTransform(c, robot, k.robotPiece), shapeOf(w), w.X_WP,
                     worldCaches(c, k.kind)[pairIndex(set, k.robotPiece, k.other)]);
    record(k, a.group, k.kind == PairKey::Kind::Scene ? 1 : 2, w.body, r);
  }

  /// Lower bound from support functions (see supportLowerBound), along the best pair's normal and
  /// along the centres' difference.
  double supportBound(const PairKey& k) const {
    const RobotData& robot = *s.robot;
    const RobotPiece& a = robot.pieces[k.robotPiece];
    const Eigen::Isometry3d& X_WA = pieceTransform(c, robot, k.robotPiece);
    const geometry::ConvexPolytope* coreB;
    const Eigen::Isometry3d* X_WB;
    double rB;
    Eigen::Vector3d centerB;
    if (k.kind == PairKey::Kind::Self) {
      const RobotPiece& b = robot.pieces[k.other];
      coreB = b.core.get();
      X_WB = &pieceTransform(c, robot, k.other);
      rB = b.radius;
      centerB = c.pieceCenter[k.other];
    } else {
      const WorldPiece& w = worldPieces(s, k.kind).pieces[k.other];
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
    const PieceSet& set = worldPieces(s, kind);
    if (set.pieces.empty()) return;
    const RobotData& robot = *s.robot;
    const LinkGeometry& lg = robot.links[g];
    forEachNear(
        set, c.state->options.broadPhase, c.linkCenter[g], lg.radius, [this] { return bound(); },
        [&](int wp, double /*linkLowerBound*/) {
          const WorldPiece& w = set.pieces[wp];
          ++c.stats.linkCandidates;
          if (worldPairAllowed(s, kind, g, w.body)) return;
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

/// The name of robot geometry g: its link's, or "attached/<name>".
std::string geometryName(const Snapshot& s, int g) {
  const LinkGeometry& lg = s.robot->links[g];
  if (lg.attached < 0) return s.robot->model.link(lg.link).name;
  return "attached/" + s.attached[lg.attached]->source.name;
}

/// Fills names and, when asked, the gradient of a pair's distance.
Contact makeContact(Impl& c, const Snapshot& s, const PairKey& key, const geometry::SignedDistanceResult& r,
                    bool gradient) {
  const RobotData& robot = *s.robot;
  Contact out;
  out.distance = r.distance;
  out.normal = r.normal;
  out.pointA = r.pointA;
  out.pointB = r.pointB;
  out.status = r.status;
  out.linkA = robot.pieces[key.robotPiece].link;
  out.nameA = geometryName(s, robot.pieces[key.robotPiece].group);
  int linkB = -1;
  if (key.kind == PairKey::Kind::Self) {
    const RobotPiece& b = robot.pieces[key.other];
    linkB = b.link;
    out.bodyB = robotBody(linkB);
    if (robot.links[b.group].attached >= 0) {
      out.bodyB.kind = BodyRef::Kind::Attached;
      out.bodyB.scene = robot.links[b.group].attached;
    }
    out.nameB = geometryName(s, b.group);
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
  DistanceSearch search(c, s, options);
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

}  // namespace deepcheck::checker
