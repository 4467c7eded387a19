#include "deepcheck/geometry/signed_distance.h"

#include "deepcheck/geometry/internal/certified.h"
#include "deepcheck/geometry/internal/gauss_map_walk.h"
#include "deepcheck/geometry/internal/scratch_access.h"
#include "deepcheck/geometry/tolerances.h"
#include "deepcheck/geometry/internal/polytope_access.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace deepcheck::geometry {

using namespace detail;

const char* toString(SignedDistanceStatus s) {
  switch (s) {
    case SignedDistanceStatus::Separated:
      return "separated";
    case SignedDistanceStatus::Penetrating:
      return "penetrating";
    case SignedDistanceStatus::NotConverged:
      return "not-converged";
  }
  return "unknown";
}

const char* toString(PenetrationMethod m) {
  switch (m) {
    case PenetrationMethod::CertifiedExpansion:
      return "certified";
    case PenetrationMethod::GaussMapWalk:
      return "deep-walk";
  }
  return "unknown";
}

namespace {

void checkShape(const ConvexShape& s, const char* which) {
  if (s.core == nullptr)
    throw std::invalid_argument(std::string("signedDistance: shape ") + which + " has no core polytope");
  if (!std::isfinite(s.radius) || s.radius < 0) {
    std::ostringstream msg;
    msg << "signedDistance: shape " << which << " has an invalid radius " << s.radius << " (must be finite and >= 0)";
    throw std::invalid_argument(msg.str());
  }
}

/// Feature of polytope P touched by a GJK simplex (its distinct vertex indices).
Feature simplexFeature(const ConvexPolytope& P, const int* idx, int n, const Eigen::Vector3d& outward_P,
                       const Eigen::Matrix3d& R_PtoP) {
  int distinct[4];
  int m = 0;
  for (int i = 0; i < n; ++i) {
    bool seen = false;
    for (int j = 0; j < m; ++j) seen = seen || distinct[j] == idx[i];
    if (!seen) distinct[m++] = idx[i];
  }
  Feature f;
  if (m == 1) {
    f.type = Feature::Type::Vertex;
    f.index = distinct[0];
  } else if (m == 2) {
    f.type = Feature::Type::Edge;
    f.index = distinct[0];
    f.index2 = distinct[1];
  } else {
    // A face: the ring face of the first vertex whose normal best matches the outward direction.
    f.type = Feature::Type::Face;
    f.index = -1;
    double bestDot = -2;
    const Eigen::Vector3d dirLocal = R_PtoP.transpose() * outward_P;
    for (int face : P.vertexFaces(distinct[0])) {
      const double d = P.faceNormal(face).dot(dirLocal);
      if (d > bestDot) {
        bestDot = d;
        f.index = face;
      }
    }
    if (f.index < 0) {
      f.type = Feature::Type::Vertex;
      f.index = distinct[0];
    }
  }
  return f;
}

Feature deepFeatureA(const WalkResult& d) {
  Feature f;
  switch (d.type) {
    case WalkResult::FacetType::VF:
      f.type = Feature::Type::Vertex;
      f.index = d.featureA;
      break;
    case WalkResult::FacetType::FV:
      f.type = Feature::Type::Face;
      f.index = d.featureA;
      break;
    case WalkResult::FacetType::EE:
      f.type = Feature::Type::Edge;
      f.index = d.featureA;
      f.index2 = d.featureA2;
      break;
  }
  return f;
}

Feature deepFeatureB(const WalkResult& d) {
  Feature f;
  switch (d.type) {
    case WalkResult::FacetType::VF:
      f.type = Feature::Type::Face;
      f.index = d.featureB;
      break;
    case WalkResult::FacetType::FV:
      f.type = Feature::Type::Vertex;
      f.index = d.featureB;
      break;
    case WalkResult::FacetType::EE:
      f.type = Feature::Type::Edge;
      f.index = d.featureB;
      f.index2 = d.featureB2;
      break;
  }
  return f;
}

bool isLowDim(const ConvexPolytope& P) { return P.kind() == PolytopeKind::Point || P.kind() == PolytopeKind::Segment; }

/// A penetration depth with its bracket (core depths, frame P).
struct Penetration {
  WalkResult deep;
  double lower = 0.0;
  bool certified = false;
  int expansions = 0;
};

/// The walk's warm start at a certified answer: one basin, at its support pair and direction.
WalkCache walkStartAt(const CertifiedResult& c) {
  WalkCache start;
  start.valid = true;
  start.count = 1;
  start.hubA[0] = c.supportA;
  start.hubB[0] = c.supportB;
  start.u[0] = c.direction;
  return start;
}

/// One walk from the cache's basins: no extra start from the centroid difference, no periodic
/// cold refresh.
WalkOptions oneWalk() {
  WalkOptions one;
  one.warmCentroidStart = false;
  one.refreshEvery = 0;
  return one;
}

/// Names the facet of M the bracket converged on, for the faces certifiedFacet() cannot name
/// (parallel faces or edges: the face's corners span a facet larger than a VF, FV or EE one):
/// DEEP's facet at the certified direction (VF, FV or EE, witnesses, exact normal) when its depth
/// is certified by the bracket's lower bound, else DEEP's walk from that direction. A facet's
/// depth is a facet offset of M, an upper bound; the walk's answer is the better of it and the
/// expansion's own upper bound.
WalkResult nameFacet(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, const CertifiedResult& c,
                     WalkScratch* walk) {
  WalkResult d = facetInDirection(A, B, frame, c.direction, c.supportA, c.supportB, walk);
  if (d.status == WalkStatus::Converged && d.depth - c.lower <= c.tau) return d;
  WalkCache start = walkStartAt(c);
  d = walkPenetration(A, B, frame, &start, oneWalk(), true, walk);
  if (d.depth <= c.upper) return d;
  // The walk found nothing better than the support: answer with the support itself.
  d.status = WalkStatus::Converged;
  d.depth = c.upper;
  d.normal = -c.direction;
  d.pointB = frame.vertexB(B, c.supportB);
  d.pointA = d.pointB + c.upper * d.normal;
  d.type = WalkResult::FacetType::FV;
  d.featureA = A.vertexFaces(c.supportA)[0];
  d.featureB = c.supportB;
  return d;
}

/// Names a certified result's facet (certifiedFacet, else DEEP's walk from its direction) and
/// fills `p` with it and the bracket's lower bound.
void nameCertified(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, const CertifiedResult& c,
                   PairCache* cache, Penetration& p) {
  p.lower = c.lower;
  p.expansions = c.expansions;
  if (!certifiedFacet(A, B, frame, c, p.deep)) p.deep = nameFacet(A, B, frame, c, scratchWalk(cache));
  p.certified = p.deep.depth - p.lower <= c.tau;
}

/// Whether the certified warm query runs before GJK (warmPenetration) with these options.
bool warmFirst(const PenetrationOptions& options, const PairCache* cache) {
  return options.method == PenetrationMethod::CertifiedExpansion && options.warmStart && cache && cache->certified &&
         !cache->apart;
}

/// Keeps a cold query's surface as the pair's warm start (allocated by the pair's first).
void keepWarmStart(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                   const ExpansionSurface& surface, const CertifiedResult& c, PairCache* cache) {
  if (!cache) return;
  if (!cache->certified) cache->certified = std::make_unique<CertifiedWarmStart>();
  saveWarmStart(A, B, frame, surface, c, *cache->certified);
}

/// The certified warm query: the cached surface's supports (certifiedWarm), else its best-first
/// expansion (expandWarm).
CertifiedResult warmCertified(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                              const PenetrationOptions& options, PairCache& cache, ExpansionSurface& surface) {
  CertifiedResult c = certifiedWarm(A, B, frame, *cache.certified);
  if (c.status == CertifiedStatus::Certified) return c;
  return expandWarm(A, B, frame, *cache.certified, surface, options.certified);
}

/// Before a cold expansion (tens of support climbs over both hulls): their support data
/// requested at once, so that on hulls out of cache the climbs do not each wait on memory. Not
/// before the warm query, which climbs once or twice.
void prefetchForExpansion(const ConvexPolytope& A, const ConvexPolytope& B) {
  prefetchSupportData(A);
  prefetchSupportData(B);
}

/// The certified method's warm query, tried before GJK: a certified answer from the cached
/// surface also proves the shapes overlap (the moved surface, made of points of M, winds around
/// the origin), so GJK is not needed. True, with `p` set, when the surface certifies the depth.
bool warmPenetration(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                     const PenetrationOptions& options, PairCache* cache, ExpansionSurface& surface, Penetration& p) {
  if (!warmFirst(options, cache) || isLowDim(A) || isLowDim(B)) return false;
  const CertifiedResult c = warmCertified(A, B, frame, options, *cache, surface);
  if (c.status != CertifiedStatus::Certified) return false;
  nameCertified(A, B, frame, c, cache, p);
  return true;
}

/// The twelve-direction start (certifiedFromProbes) is tried only where it usually makes a start,
/// since a failed attempt costs twelve supports for nothing: on hulls of more vertices than this
/// each (on smaller ones two directions often share a support: boxes, 8-vertex hulls)...
constexpr int kMinProbedVertices = 17;
/// ...and on pairs whose inside radii add up to at least this share of their bounding radii: the
/// supports of an elongated pair rarely form a convex surface.
constexpr double kMinProbedRoundness = 0.2;

/// The twelve-direction start where it is tried (above): false when it makes no start, else true
/// with the expansion's result in `c`.
bool twelveDirectionStart(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                          const PenetrationOptions& options, ExpansionSurface& surface, CertifiedResult& c) {
  if (A.numVertices() < kMinProbedVertices || B.numVertices() < kMinProbedVertices) return false;
  if (A.insideRadius() + B.insideRadius() < kMinProbedRoundness * (A.boundingRadius() + B.boundingRadius()))
    return false;
  return certifiedFromProbes(A, B, frame, surface, options.certified, c);
}

/// The certified method's cold query without GJK, for polyhedra whose inscribed balls about their
/// centroids overlap: they overlap for certain, so GJK has nothing to decide. The surface starts
/// from the supports in twelve directions where that start is tried and made (it leaves fewer
/// expansions than GJK's simplex), else from four generic directions (as many expansions as
/// GJK's simplex, without GJK's run). Not while a warm start waits to be tried (it comes first).
/// True, with `p` set and the warm start saved, when the expansion certifies the depth; otherwise
/// (a cap hit) the caller goes on with GJK.
bool probedPenetration(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                       const PenetrationOptions& options, PairCache* cache, bool triedWarm, ExpansionSurface& surface,
                       Penetration& p) {
  if (options.method != PenetrationMethod::CertifiedExpansion || A.kind() != PolytopeKind::Polyhedron ||
      B.kind() != PolytopeKind::Polyhedron)
    return false;
  if (options.warmStart && cache && cache->certified && cache->certified->valid && !triedWarm) return false;
  if (!(frame.t.norm() < A.insideRadius() + B.insideRadius())) return false;
  prefetchForExpansion(A, B);
  CertifiedResult c;
  if (!twelveDirectionStart(A, B, frame, options, surface, c))
    c = certifiedWithoutGjk(A, B, frame, surface, options.certified);
  if (c.status != CertifiedStatus::Certified) return false;
  keepWarmStart(A, B, frame, surface, c, cache);
  nameCertified(A, B, frame, c, cache, p);
  return true;
}

/// The certified method: the expansion's bracket, the answer named by DEEP's facets. Points and
/// segments (M's facets are enumerated exactly) and expansions that did not converge (flat M,
/// cap) go to DEEP's walks with all restarts; the bracket's lower bound is kept. `triedWarm`: the
/// warm query already ran (warmPenetration) and did not certify.
Penetration certifiedDepth(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, const GjkResult& g,
                           ExpansionSurface& surface, const PenetrationOptions& options, PairCache* cache,
                           bool triedWarm) {
  Penetration p;
  WalkScratch* walk = scratchWalk(cache);
  if (isLowDim(A) || isLowDim(B)) {
    p.deep = walkPenetration(A, B, frame, nullptr, options.walk, options.warmStart, walk);
    p.lower = p.deep.depth;
    p.certified = true;
    return p;
  }
  CertifiedResult c;
  const bool warm = options.warmStart && cache && cache->certified;
  if (warm && !triedWarm) c = warmCertified(A, B, frame, options, *cache, surface);
  if (c.status != CertifiedStatus::Certified) {
    prefetchForExpansion(A, B);
    c = certifiedPenetration(A, B, frame, g, surface, options.certified);
    keepWarmStart(A, B, frame, surface, c, cache);
  }
  if (c.status == CertifiedStatus::Certified) {
    nameCertified(A, B, frame, c, cache, p);
    return p;
  }
  p.lower = c.lower;
  p.expansions = c.expansions;
  WalkOptions full = options.walk;
  full.restarts = true;
  p.deep = walkPenetration(A, B, frame, nullptr, full, false, walk);
  if (c.upper < p.deep.depth) p.deep = nameFacet(A, B, frame, c, walk);
  p.certified = p.deep.depth - p.lower <= c.tau;
  return p;
}

/// signedDistance() in the pair frame, with the certified method's scratch surface (non-null for
/// that method).
SignedDistanceResult signedDistanceIn(const ConvexShape& A, const ConvexShape& B, const PairFrame& frame,
                                      PairCache* cache, const PenetrationOptions& options, ExpansionSurface* surface) {
  const ConvexPolytope& a = *A.core;
  const ConvexPolytope& b = *B.core;
  SignedDistanceResult r;
  Eigen::Vector3d n_P, pA_P, pB_P;
  double coreSd;
  Penetration p;
  const bool triedWarm = warmFirst(options, cache);
  const bool done = surface && (warmPenetration(a, b, frame, options, cache, *surface, p) ||
                                probedPenetration(a, b, frame, options, cache, triedWarm, *surface, p));
  bool apart = false;
  if (!done) {
    const GjkResult g = gjkDistance(a, b, frame, cache ? &cache->gjk : nullptr);
    apart = g.status == GjkStatus::Separated || (g.status == GjkStatus::MaxIterations && g.distance > 0);
    if (apart) {
      coreSd = g.distance;
      n_P = g.normal;
      pA_P = g.pointA;
      pB_P = g.pointB;
      r.status =
          g.status == GjkStatus::Separated ? SignedDistanceStatus::Separated : SignedDistanceStatus::NotConverged;
      r.featureA = simplexFeature(a, g.simplexA.data(), g.simplexSize, n_P, Eigen::Matrix3d::Identity());
      r.featureB = simplexFeature(b, g.simplexB.data(), g.simplexSize, -n_P, frame.R);
      // The certified warm start stays: its check measures the motion from its own reference.
      if (cache) cache->walk.valid = false;
    } else if (options.method == PenetrationMethod::CertifiedExpansion) {
      p = certifiedDepth(a, b, frame, g, *surface, options, cache, triedWarm);
    } else {
      p.deep = walkPenetration(a, b, frame, cache ? &cache->walk : nullptr, options.walk, options.warmStart,
                               scratchWalk(cache));
    }
  }
  if (cache) cache->apart = apart;
  if (!apart) {
    const WalkResult& d = p.deep;
    coreSd = -d.depth;
    n_P = d.normal;
    pA_P = d.pointA;
    pB_P = d.pointB;
    r.certified = p.certified;
    r.status = d.status == WalkStatus::Converged && (p.certified || options.method == PenetrationMethod::GaussMapWalk)
                   ? SignedDistanceStatus::Penetrating
                   : SignedDistanceStatus::NotConverged;
    r.featureA = deepFeatureA(d);
    r.featureB = deepFeatureB(d);
    r.walk = d.stats;
    r.expansions = p.expansions;
    r.depthLower = p.lower + A.radius + B.radius;
  }
  // Radii: A grows towards B along n, B towards A along -n.
  r.distance = coreSd - A.radius - B.radius;
  r.depthUpper = -r.distance;
  if (apart) {
    r.depthLower = r.depthUpper;
    r.certified = r.status == SignedDistanceStatus::Separated;
  }
  r.normal = frame.X_WP.linear() * n_P;
  r.pointA = frame.X_WP * (pA_P + A.radius * n_P);
  r.pointB = frame.X_WP * (pB_P - B.radius * n_P);
  return r;
}

}  // namespace

SignedDistanceResult signedDistance(const ConvexShape& A, const Eigen::Isometry3d& X_WA, const ConvexShape& B,
                                    const Eigen::Isometry3d& X_WB, PairCache* cache,
                                    const PenetrationOptions& options) {
  checkShape(A, "A");
  checkShape(B, "B");
  const PairFrame frame = PairFrame::make(*A.core, X_WA, *B.core, X_WB);
  ExpansionSurface* scratch = scratchSurface(cache);
  if (scratch || options.method != PenetrationMethod::CertifiedExpansion)
    return signedDistanceIn(A, B, frame, cache, options, scratch);
  ExpansionSurface local;  // no scratch from the caller: one on the stack
  return signedDistanceIn(A, B, frame, cache, options, &local);
}

SignedDistanceResult signedDistance(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA, const ConvexPolytope& B,
                                    const Eigen::Isometry3d& X_WB, PairCache* cache,
                                    const PenetrationOptions& options) {
  return signedDistance(ConvexShape{&A, 0.0}, X_WA, ConvexShape{&B, 0.0}, X_WB, cache, options);
}

bool overlaps(const ConvexShape& A, const Eigen::Isometry3d& X_WA, const ConvexShape& B, const Eigen::Isometry3d& X_WB,
              PairCache* cache) {
  checkShape(A, "A");
  checkShape(B, "B");
  checkPose(X_WA, "X_WA");
  checkPose(X_WB, "X_WB");
  return overlapsUnchecked(A, X_WA, B, X_WB, cache);
}

bool enclosesOrigin(const ConvexShape& A, const Eigen::Isometry3d& X_WA, const ConvexShape& B,
                    const Eigen::Isometry3d& X_WB, const MinkowskiTetrahedron& t) {
  return enclosesOrigin(*A.core, *B.core, PairFrame::makeUnchecked(*A.core, X_WA, *B.core, X_WB), t);
}

bool overlapsUnchecked(const ConvexShape& A, const Eigen::Isometry3d& X_WA, const ConvexShape& B,
                       const Eigen::Isometry3d& X_WB, PairCache* cache) {
  const PairFrame frame = PairFrame::makeUnchecked(*A.core, X_WA, *B.core, X_WB);
  if (A.radius == 0 && B.radius == 0) return gjkOverlap(*A.core, *B.core, frame, cache ? &cache->gjk : nullptr);
  return gjkWithin(*A.core, *B.core, frame, A.radius + B.radius, cache ? &cache->gjk : nullptr);
}

GjkBound distanceBoundUnchecked(const ConvexShape& A, const Eigen::Isometry3d& X_WA, const ConvexShape& B,
                                const Eigen::Isometry3d& X_WB, double near, double far, PairCache* cache) {
  const PairFrame frame = PairFrame::makeUnchecked(*A.core, X_WA, *B.core, X_WB);
  const double radii = A.radius + B.radius;
  GjkBound b = gjkBound(*A.core, *B.core, frame, near + radii, far + radii, cache ? &cache->gjk : nullptr);
  b.lower -= radii;
  return b;
}

}  // namespace deepcheck::geometry
