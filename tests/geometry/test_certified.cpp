// The certified penetration depth (internal/certified.h): exact and certified against the exact
// reference, the bracket always containing the exact depth, degenerate starts, swap symmetry,
// warm equal to cold along motions, the cap, and the saved reproducers of DEEP's misses.
//
// Error measure as in test_geometry.cpp: |sd - sd_exact| / max(|sd_exact|, 1e-3 L).

#include "shapes.h"

#include "deepcheck/geometry/internal/certified.h"
#include "deepcheck/geometry/exact.h"
#include "deepcheck/geometry/signed_distance.h"
#include "deepcheck/geometry/tolerances.h"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

using namespace deepcheck::geometry;
using namespace deepcheck::geometry::detail;
using namespace deepcheck::geometry::testing;
using Eigen::Isometry3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

/// Slack on the bracket's ends beyond the exact reference: both are computed from face planes of
/// M whose offsets carry a few ulps of the pair's length scale.
constexpr double kBracketSlackRelative = 1e-14;

/// Pair length scale of the certificate (tolerances.h): larger bounding radius plus the centre
/// distance.
double certifyScale(const ConvexPolytope& A, const Isometry3d& X_WA, const ConvexPolytope& B, const Isometry3d& X_WB) {
  const Vector3d cA = X_WA * A.center(), cB = X_WB * B.center();
  return std::max(A.lengthScale(), B.lengthScale()) + (cB - cA).norm();
}

/// Checks one certified answer against the exact reference; returns "" when it is exact, certified
/// and its bracket contains the exact depth.
std::string checkCertified(const ConvexPolytope& A, const Isometry3d& X_WA, const ConvexPolytope& B,
                           const Isometry3d& X_WB, const SignedDistanceResult& r, double tolRel) {
  std::ostringstream why;
  const ExactResult exact = exactSignedDistance(A, X_WA, B, X_WB);
  const double err = depthError(r.distance, exact.distance, depthScale(A, B));
  if (!(err <= tolRel)) why << "sd " << r.distance << " exact " << exact.distance << " (error " << err << "); ";
  if (exact.distance < 0) {
    if (!r.certified) why << "not certified; ";
    const double slack = kBracketSlackRelative * certifyScale(A, X_WA, B, X_WB);
    const double depth = -exact.distance;
    if (!(r.depthLower <= depth + slack && depth <= r.depthUpper + slack))
      why << "bracket [" << r.depthLower << ", " << r.depthUpper << "] misses " << depth << "; ";
  }
  return why.str();
}

/// A random overlapping pair of ellipsoid hulls of `n` vertices (aspect up to 1:10).
struct Pair {
  ConvexPolytope A, B;
  Isometry3d X_WA, X_WB;
};

Pair randomPair(std::mt19937& rng, int nA, int nB, const Vector3d& base) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const Vector3d sA(1.0, 0.2 + 0.8 * U(rng), 0.1 + 0.9 * U(rng));
  const Vector3d sB(0.3 + 0.7 * U(rng), 0.2 + 0.8 * U(rng), 0.1 + 0.5 * U(rng));
  Pair p{ConvexPolytope::fromPoints(ellipsoidPoints(rng, nA, sA)),
         ConvexPolytope::fromPoints(ellipsoidPoints(rng, nB, sB)), makePose(randomRotation(rng), base),
         makePose(randomRotation(rng), base + 0.8 * U(rng) * randomUnit(rng))};
  return p;
}

/// A random overlapping pair as the certified expansion starts from it: the pair, its frame and
/// GJK's enclosing answer; nothing when GJK finds the pair apart.
struct StartedPair {
  Pair p;
  PairFrame frame;
  GjkResult gjk;
};
std::optional<StartedPair> startedPair(std::mt19937& rng, int nA, int nB) {
  Pair p = randomPair(rng, nA, nB, Vector3d::Zero());
  const PairFrame frame = PairFrame::make(p.A, p.X_WA, p.B, p.X_WB);
  const GjkResult gjk = gjkDistance(p.A, p.B, frame);
  if (gjk.status != GjkStatus::Overlapping) return std::nullopt;
  return StartedPair{std::move(p), frame, gjk};
}

/// B's poses along a smooth random motion of `steps` steps from near the pair's pose: a turn of
/// 0.01 rad and a drift of 5 mm per step, plus up to 2 mm of jitter per coordinate.
std::vector<Isometry3d> randomMotion(std::mt19937& rng, const Pair& p, int steps = 100) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Quaterniond q(p.X_WB.linear());
  Vector3d t = 0.4 * randomUnit(rng);
  const Vector3d w = 0.01 * randomUnit(rng), v = 0.005 * randomUnit(rng);
  std::vector<Isometry3d> poses;
  for (int k = 0; k < steps; ++k) {
    q = Quaterniond(Eigen::AngleAxisd(w.norm(), w.normalized())) * q;
    t += v + 0.002 * Vector3d(U(rng), U(rng), U(rng));
    poses.push_back(makePose(q, t));
  }
  return poses;
}

/// Queries the pair along `poses` with one cache (warm, `options`) and without (cold, defaults):
/// they must agree to 1e-12 and in `certified`; calls onOverlap(step, X_WB, warm, cold) at the
/// overlapping steps.
template <class OnOverlap>
void compareWarmAndCold(const Pair& p, const std::vector<Isometry3d>& poses, const PenetrationOptions& options,
                        int trial, OnOverlap&& onOverlap) {
  PairCache cache;
  for (int k = 0; k < static_cast<int>(poses.size()); ++k) {
    const SignedDistanceResult warm = signedDistance(p.A, p.X_WA, p.B, poses[k], &cache, options);
    const SignedDistanceResult cold = signedDistance(p.A, p.X_WA, p.B, poses[k]);
    BOOST_TEST(std::abs(warm.distance - cold.distance) <= 1e-12, "trial " << trial << " step " << k);
    BOOST_TEST(warm.certified == cold.certified);
    BOOST_TEST(cache.apart == (warm.distance > 0), "trial " << trial << " step " << k);
    if (cold.distance < 0) onOverlap(k, poses[k], warm, cold);
  }
}

PenetrationOptions methodOptions(PenetrationMethod m) {
  PenetrationOptions o;
  o.method = m;
  return o;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(certified)

BOOST_AUTO_TEST_CASE(names) {
  BOOST_TEST(std::string(toString(CertifiedStatus::Certified)) == "certified");
  BOOST_TEST(std::string(toString(CertifiedStatus::NotConverged)) == "not-converged");
  BOOST_TEST(std::string(toString(PenetrationMethod::CertifiedExpansion)) == "certified");
  BOOST_TEST(std::string(toString(PenetrationMethod::GaussMapWalk)) == "deep-walk");
}

// Cold, warm (a cache reused across perturbed re-queries) and swapped, on hulls of 4 to 1,000
// vertices, near the origin and 1e4 away.
BOOST_AUTO_TEST_CASE(exact_and_certified_on_random_pairs) {
  std::mt19937 rng(11);
  const int sizes[] = {4, 8, 30, 100, 300, 1000};
  int overlapping = 0;
  for (int i = 0; i < 240; ++i) {
    const bool far = i % 4 == 3;
    const Vector3d base = far ? Vector3d(1e4 * randomUnit(rng)) : Vector3d::Zero();
    const Pair p = randomPair(rng, sizes[i % 6], sizes[(i / 6) % 6], base);
    const double tol = far ? 1e-10 : 1e-12;
    const SignedDistanceResult cold = signedDistance(p.A, p.X_WA, p.B, p.X_WB);
    if (cold.distance >= 0) continue;
    ++overlapping;
    std::string why = checkCertified(p.A, p.X_WA, p.B, p.X_WB, cold, tol);
    BOOST_TEST(why.empty(), "pair " << i << " cold: " << why);
    BOOST_TEST(cold.expansions > 0);
    const SignedDistanceResult swapped = signedDistance(p.B, p.X_WB, p.A, p.X_WA);
    BOOST_TEST(depthError(swapped.distance, cold.distance, depthScale(p.A, p.B)) <= tol,
               "pair " << i << ": swapped " << swapped.distance << " vs " << cold.distance);
    BOOST_TEST(swapped.certified);
    PairCache cache;
    signedDistance(p.A, p.X_WA, p.B, p.X_WB, &cache);
    const Isometry3d moved = makePose(Quaterniond(p.X_WB.linear()), p.X_WB.translation() + 0.01 * randomUnit(rng));
    const SignedDistanceResult warm = signedDistance(p.A, p.X_WA, p.B, moved, &cache);
    why = checkCertified(p.A, p.X_WA, p.B, moved, warm, tol);
    BOOST_TEST(why.empty(), "pair " << i << " warm: " << why);
  }
  BOOST_TEST(overlapping > 120);
}

// The bracket of the expansion itself, before naming, at every cap: always contains the exact
// depth; certified exactly when its width is within tau.
BOOST_AUTO_TEST_CASE(bracket_contains_the_exact_depth_at_every_cap) {
  std::mt19937 rng(12);
  ExpansionSurface surface;
  int checked = 0;
  for (int i = 0; i < 40; ++i) {
    const std::optional<StartedPair> started = startedPair(rng, 100, 60);
    if (!started) continue;
    const Pair& p = started->p;
    const PairFrame& frame = started->frame;
    const GjkResult& g = started->gjk;
    const double depth = -exactSignedDistance(p.A, p.X_WA, p.B, p.X_WB).distance;
    const double slack = kBracketSlackRelative * certifyScale(p.A, p.X_WA, p.B, p.X_WB);
    for (int cap : {0, 1, 2, 5, 10, 20, 128}) {
      CertifiedOptions o;
      o.maxExpansions = cap;
      const CertifiedResult c = certifiedPenetration(p.A, p.B, frame, g, surface, o);
      BOOST_TEST(c.lower <= depth + slack, "pair " << i << " cap " << cap);
      BOOST_TEST(depth <= c.upper + slack, "pair " << i << " cap " << cap);
      BOOST_TEST(c.expansions <= cap);
      BOOST_TEST((c.status == CertifiedStatus::Certified) == (c.upper - c.lower <= c.tau));
      ++checked;
    }
  }
  BOOST_TEST(checked > 100);
}

// Identical shapes at one pose (the origin on GJK's simplex), touching contact, one shape deep
// inside the other, stacked boxes: each start has its own path, all exact and certified.
BOOST_AUTO_TEST_CASE(degenerate_starts) {
  std::mt19937 rng(13);
  const ConvexPolytope box = ConvexPolytope::box(Vector3d(1.0, 2.0, 3.0));
  const ConvexPolytope blob = ConvexPolytope::fromPoints(ellipsoidPoints(rng, 200, Vector3d(1, 0.5, 0.25)));
  const ConvexPolytope small = ConvexPolytope::fromPoints(ellipsoidPoints(rng, 30, Vector3d(0.1, 0.1, 0.1)));
  struct Case {
    const ConvexPolytope* A;
    Isometry3d X_WA;
    const ConvexPolytope* B;
    Isometry3d X_WB;
    const char* what;
  };
  const Isometry3d I = Isometry3d::Identity();
  const Isometry3d X = makePose(randomRotation(rng), Vector3d(0.3, -0.2, 0.1));
  std::vector<Case> cases = {
      {&box, I, &box, I, "identical boxes"},
      {&blob, X, &blob, X, "identical blobs"},
      {&box, I, &box, makePose(Quaterniond::Identity(), Vector3d(0, 0, 3.0)), "boxes touching face to face"},
      {&box, I, &box, makePose(Quaterniond::Identity(), Vector3d(0, 0, 3.0 - 1e-9)), "boxes 1e-9 deep"},
      {&blob, I, &small, makePose(randomRotation(rng), Vector3d(0.05, 0, 0)), "small inside blob"},
      {&box, I, &box, makePose(Quaterniond::Identity(), Vector3d(0.3, 0.7, 0.9)), "stacked, offset"},
  };
  for (const Case& c : cases) {
    const SignedDistanceResult r = signedDistance(*c.A, c.X_WA, *c.B, c.X_WB);
    const std::string why = checkCertified(*c.A, c.X_WA, *c.B, c.X_WB, r, 1e-12);
    BOOST_TEST(why.empty(), c.what << ": " << why);
  }
}

// Warm answers (one cache along the motion) equal cold ones at every step, and the cached surface
// certifies most steps without an expansion.
BOOST_AUTO_TEST_CASE(warm_equals_cold_along_motions) {
  std::mt19937 rng(14);
  int overlapping = 0, withoutExpansion = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const Pair p = randomPair(rng, 100, 100, Vector3d::Zero());
    compareWarmAndCold(p, randomMotion(rng, p), PenetrationOptions{}, trial,
                       [&](int, const Isometry3d&, const SignedDistanceResult& warm, const SignedDistanceResult& cold) {
                         ++overlapping;
                         withoutExpansion += warm.expansions == 0;
                         BOOST_TEST(cold.expansions > 0);
                       });
  }
  BOOST_TEST(overlapping > 200);
  BOOST_TEST(withoutExpansion > overlapping / 2);
}

namespace {

/// Two random overlapping 100-vertex pairs from `seed`: `p`, queried once into `cache`
/// (`first`), and `other`.
struct PrimedPair {
  explicit PrimedPair(unsigned seed)
      : rng(seed),
        p(randomPair(rng, 100, 100, Vector3d::Zero())),
        other(randomPair(rng, 100, 100, Vector3d::Zero())),
        first(signedDistance(p.A, p.X_WA, p.B, p.X_WB, &cache)) {}
  std::mt19937 rng;
  Pair p;
  Pair other;
  PairCache cache;
  SignedDistanceResult first;
};

}  // namespace

// A jump far beyond the cached surface's margin (faces that could have swept over the origin)
// sends the query cold; a cache of another pair is not used.
BOOST_AUTO_TEST_CASE(warm_start_goes_cold_when_it_cannot_certify) {
  PrimedPair primed(17);
  const Pair& p = primed.p;
  const Pair& other = primed.other;
  PairCache& cache = primed.cache;
  const SignedDistanceResult& first = primed.first;
  BOOST_TEST_REQUIRE(first.distance < 0);
  BOOST_TEST(first.expansions > 0);
  // The same pose again: certified from the cache alone.
  const SignedDistanceResult again = signedDistance(p.A, p.X_WA, p.B, p.X_WB, &cache);
  BOOST_TEST(again.expansions == 0);
  BOOST_TEST(again.certified);
  BOOST_TEST(again.distance == first.distance);
  // B turned half around: every face moves by about the shapes' size.
  const Isometry3d turned = makePose(
      Quaterniond(Eigen::AngleAxisd(M_PI, Vector3d::UnitX())) * Quaterniond(p.X_WB.linear()), p.X_WB.translation());
  const SignedDistanceResult jump = signedDistance(p.A, p.X_WA, p.B, turned, &cache);
  const SignedDistanceResult cold = signedDistance(p.A, p.X_WA, p.B, turned);
  BOOST_TEST(jump.expansions > 0);
  BOOST_TEST(std::abs(jump.distance - cold.distance) <= 1e-12);
  // The cache now belongs to (A, B): another pair runs cold.
  const SignedDistanceResult foreign = signedDistance(other.A, other.X_WA, other.B, other.X_WB, &cache);
  const SignedDistanceResult foreignCold = signedDistance(other.A, other.X_WA, other.B, other.X_WB);
  BOOST_TEST(foreign.expansions > 0);
  BOOST_TEST(foreignCold.expansions > 0);
  BOOST_TEST(std::abs(foreign.distance - foreignCold.distance) <= 1e-12);
}

// A query at the pose of the previous one, warm from its cache, gives the cold answer to the bit,
// on prisms and boxes, whose caps and sides tie many support vertices. (The planes test below is
// what keeps the warm and cold face planes one formula; a planners test, with the bundled arm in
// the shelf, catches the two drifting apart at the checker's level.)
BOOST_AUTO_TEST_CASE(warm_at_the_same_pose_equals_cold_to_the_bit) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int overlapping = 0, fromCache = 0;
  for (int i = 0; i < 200; ++i) {
    const ConvexPolytope A = ConvexPolytope::fromPoints(prismPoints(0.2 + 0.8 * U(rng), 0.5 + U(rng), 6 + i % 20));
    const ConvexPolytope B =
        ConvexPolytope::fromPoints(i % 2 == 0 ? boxCorners(Vector3d(0.2 + U(rng), 0.2 + U(rng), 0.2 + U(rng)))
                                              : prismPoints(0.2 + 0.5 * U(rng), 0.3 + U(rng), 5 + i % 13));
    const Isometry3d X_WA = makePose(randomRotation(rng), Vector3d::Zero());
    const Isometry3d X_WB = makePose(randomRotation(rng), 0.6 * U(rng) * randomUnit(rng));
    PairCache cache;
    const SignedDistanceResult cold = signedDistance(A, X_WA, B, X_WB, &cache);
    if (!(cold.distance < 0)) continue;
    ++overlapping;
    const SignedDistanceResult warm = signedDistance(A, X_WA, B, X_WB, &cache);
    BOOST_TEST(warm.distance == cold.distance, "pair " << i);
    BOOST_TEST((warm.normal == cold.normal), "pair " << i);
    fromCache += warm.expansions == 0;
  }
  BOOST_TEST(overlapping > 120);
  BOOST_TEST(fromCache > overlapping * 9 / 10);
}

// Every face of an expanded surface has the plane planeThrough() gives for its corners, to the bit.
BOOST_AUTO_TEST_CASE(surface_planes_are_plane_through_their_corners) {
  std::mt19937 rng(32);
  ExpansionSurface surface;
  int faces = 0;
  for (int i = 0; i < 20; ++i) {
    const std::optional<StartedPair> started = startedPair(rng, 100, 100);
    if (!started) continue;
    const Pair& p = started->p;
    const CertifiedResult c = certifiedPenetration(p.A, p.B, started->frame, started->gjk, surface, CertifiedOptions{});
    BOOST_TEST_REQUIRE(c.expansions > 0);
    for (int f = 0; f < surface.numFaceSlots(); ++f) {
      const ExpansionSurface::Face& face = surface.face(f);
      if (!face.alive) continue;
      Vector3d n;
      double d;
      BOOST_TEST_REQUIRE(ExpansionSurface::planeThrough(surface.vertex(face.v[0]).p, surface.vertex(face.v[1]).p,
                                                        surface.vertex(face.v[2]).p, n, d));
      BOOST_TEST((n == face.n), "pair " << i << " face " << f);
      BOOST_TEST(d == face.d, "pair " << i << " face " << f);
      ++faces;
    }
  }
  BOOST_TEST(faces > 400);
  // Collinear corners have no plane.
  Vector3d n;
  double d;
  BOOST_TEST(!ExpansionSurface::planeThrough(Vector3d(0, 0, 0), Vector3d(1, 1, 1), Vector3d(2, 2, 2), n, d));
}

// When the cached surface's supports do not settle a step (the answer moved to a facet the
// surface has no face on), expandWarm expands the moved surface: certified, its bracket around the
// exact depth, fewer expansions than a cold query, and the result is the new reference (the same
// pose again certifies without expanding).
BOOST_AUTO_TEST_CASE(warm_expansion_of_the_moved_surface) {
  std::mt19937 rng(31);
  int expanded = 0, fewer = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const Pair p = randomPair(rng, 100, 100, Vector3d::Zero());
    PairCache cache;
    for (const Isometry3d& X_WB : randomMotion(rng, p, 60)) {
      const PairFrame frame = PairFrame::make(p.A, p.X_WA, p.B, X_WB);
      const bool usable = cache.certified && cache.certified->belongsTo(p.A, p.B);
      CertifiedWarmStart warm;
      if (usable) warm = *cache.certified;
      const SignedDistanceResult cold = signedDistance(p.A, p.X_WA, p.B, X_WB);
      signedDistance(p.A, p.X_WA, p.B, X_WB, &cache);
      if (!usable || cold.distance >= 0 || certifiedWarm(p.A, p.B, frame, warm).status == CertifiedStatus::Certified)
        continue;
      ExpansionSurface surface;
      const CertifiedResult c = expandWarm(p.A, p.B, frame, warm, surface);
      if (c.status != CertifiedStatus::Certified) continue;
      ++expanded;
      fewer += c.expansions < cold.expansions;
      const double depth = -exactSignedDistance(p.A, p.X_WA, p.B, X_WB).distance;
      const double slack = kBracketSlackRelative * certifyScale(p.A, p.X_WA, p.B, X_WB);
      BOOST_TEST(c.lower <= depth + slack);
      BOOST_TEST(depth <= c.upper + slack);
      BOOST_TEST(c.upper - c.lower <= c.tau);
      BOOST_TEST(std::abs(c.upper + cold.distance) <= c.tau);
      BOOST_TEST(warm.belongsTo(p.A, p.B));
      const CertifiedResult again = certifiedWarm(p.A, p.B, frame, warm);
      BOOST_TEST((again.status == CertifiedStatus::Certified));
      BOOST_TEST(again.expansions == 0);
    }
  }
  BOOST_TEST(expanded > 10);
  BOOST_TEST(fewer > expanded / 2);
}

// A loaded (possibly non-convex) surface refuses an expansion whose replaced faces and new point
// no plane through the origin separates from it (the new surface might not wind around the
// origin); the same expansion of the convex surface it came from is accepted, and so is a loaded
// one that such a plane does separate.
BOOST_AUTO_TEST_CASE(loaded_surface_keeps_the_origin_inside) {
  const Vector3d corners[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  ExpansionSurface::Vertex v[4];
  for (int i = 0; i < 4; ++i) v[i] = {corners[i], i, i};
  ExpansionSurface convex;
  BOOST_TEST_REQUIRE(convex.startTetrahedron(v));
  int faces[4][3], adj[4][3];
  for (int f = 0; f < 4; ++f)
    for (int k = 0; k < 3; ++k) {
      faces[f][k] = convex.face(f).v[k];
      adj[f][k] = convex.face(f).adj[k];
    }
  ExpansionSurface loaded;
  BOOST_TEST_REQUIRE(loaded.load(v, 4, faces, adj, 4));
  BOOST_TEST(loaded.numLiveFaces() == 4);
  // Far beyond face 0 and its first neighbour: both are replaced, and their corners are all four
  // vertices, which surround the origin.
  const int g = convex.face(0).adj[0] >> 2;
  const Vector3d n0 = convex.face(0).n, ng = convex.face(g).n;
  const ExpansionSurface::Vertex beyondTwo{3.0 * (n0 + ng), 9, 9};
  BOOST_TEST(!loaded.expand(0, beyondTwo));
  BOOST_TEST(loaded.numLiveFaces() == 4);
  BOOST_TEST(convex.expand(0, beyondTwo));
  BOOST_TEST(convex.numLiveFaces() == 6);
  // Beyond face 0 alone: its corners and the point lie beyond the plane normal to it.
  const ExpansionSurface::Vertex beyondOne{3.0 * n0, 9, 9};
  BOOST_TEST(loaded.expand(0, beyondOne));
  BOOST_TEST(loaded.numLiveFaces() == 6);
}

/// A double pyramid about the x axis, its faces counter-clockwise seen from outside with their
/// neighbours: apexes `plus` and (-1, 0, 0), a square ring at x = 0.5 of corners (0.5, ±1, 0),
/// (0.5, 0, ±1).
struct DoublePyramid {
  ExpansionSurface::Vertex v[6];
  int faces[8][3];
  int adj[8][3];
  explicit DoublePyramid(const Vector3d& plus) {
    const Vector3d p[6] = {plus, {-1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}, {0.5, 0, -1}};
    for (int i = 0; i < 6; ++i) v[i] = {p[i], i, i};
    const int f[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (int g = 0; g < 8; ++g)
      for (int k = 0; k < 3; ++k) faces[g][k] = f[g][k];
    for (int g = 0; g < 8; ++g)  // edge (a, b) of face g is edge (b, a) of its neighbour
      for (int k = 0; k < 3; ++k)
        for (int h = 0; h < 8; ++h)
          for (int e = 0; e < 3; ++e)
            if (f[h][e] == f[g][(k + 1) % 3] && f[h][(e + 1) % 3] == f[g][k]) adj[g][k] = 4 * h + e;
  }
};

// startConvex takes a convex surface holding the origin strictly inside and refuses one with a
// dent (every face still facing away from the origin) or with the origin outside.
BOOST_AUTO_TEST_CASE(convex_start_is_checked) {
  ExpansionSurface s;
  const DoublePyramid convex(Vector3d(1, 0, 0));
  BOOST_TEST(s.startConvex(convex.v, 6, convex.faces, convex.adj, 8, 1e-12));
  BOOST_TEST(s.numLiveFaces() == 8);
  const int f = s.bestFace();
  BOOST_TEST_REQUIRE(f >= 0);
  BOOST_TEST(s.expand(f, {2.0 * s.face(f).n, 9, 9}));  // a convex surface grows as a hull
  // The +x apex pushed in below its ring: the faces around it still face away from the origin,
  // but the ring's corners lie outside their planes.
  const DoublePyramid dented(Vector3d(0.3, 0, 0));
  for (int g = 0; g < 4; ++g) {
    Vector3d n;
    double d;
    const auto& c = dented.faces[g];
    BOOST_TEST_REQUIRE(ExpansionSurface::planeThrough(dented.v[c[0]].p, dented.v[c[1]].p, dented.v[c[2]].p, n, d));
    BOOST_TEST(d > 0.0);
  }
  BOOST_TEST(!s.startConvex(dented.v, 6, dented.faces, dented.adj, 8, 1e-12));
  BOOST_TEST(s.numLiveFaces() == 0);
  // The origin outside (the pyramid moved by 2 along x), and on the plane of face (0, 2, 4),
  // whose normal is along (1, 0.5, 0.5) at distance 1 / |(1, 0.5, 0.5)|.
  DoublePyramid outside(Vector3d(1, 0, 0));
  for (auto& v : outside.v) v.p.x() += 2.0;
  BOOST_TEST(!s.startConvex(outside.v, 6, outside.faces, outside.adj, 8, 1e-12));
  DoublePyramid onFace(Vector3d(1, 0, 0));
  for (auto& v : onFace.v) v.p -= Vector3d(1, 0.5, 0.5) / 1.5;
  BOOST_TEST(!s.startConvex(onFace.v, 6, onFace.faces, onFace.adj, 8, 1e-12));
  BOOST_TEST(s.startConvex(convex.v, 6, convex.faces, convex.adj, 8, 1e-12));
}

// The start without GJK: on overlapping pairs whose inscribed balls overlap it starts on most, and
// its answer is that of GJK's start, exact and certified; two directions sharing a support (two
// boxes at one pose) or the origin outside (a pair apart) are no start.
BOOST_AUTO_TEST_CASE(probe_start) {
  std::mt19937 rng(17);
  ExpansionSurface surface;
  int tried = 0, started = 0;
  for (int i = 0; i < 80; ++i) {
    const std::optional<StartedPair> sp = startedPair(rng, 100, 300);
    if (!sp) continue;
    const Pair& p = sp->p;
    if (!(sp->frame.t.norm() < p.A.insideRadius() + p.B.insideRadius())) continue;
    ++tried;
    CertifiedResult c;
    if (!certifiedFromProbes(p.A, p.B, sp->frame, surface, {}, c)) continue;
    ++started;
    BOOST_TEST((c.status == CertifiedStatus::Certified), "pair " << i);
    const CertifiedResult g = certifiedPenetration(p.A, p.B, sp->frame, sp->gjk, surface);
    BOOST_TEST(std::abs(c.upper - g.upper) <= c.tau, "pair " << i << ": " << c.upper << " vs " << g.upper);
    const double depth = -exactSignedDistance(p.A, p.X_WA, p.B, p.X_WB).distance;
    const double slack = kBracketSlackRelative * certifyScale(p.A, p.X_WA, p.B, p.X_WB);
    BOOST_TEST(c.lower <= depth + slack, "pair " << i);
    BOOST_TEST(depth <= c.upper + slack, "pair " << i);
  }
  BOOST_TEST(tried > 30);
  BOOST_TEST(started >= tried * 9 / 10);
  const ConvexPolytope box = ConvexPolytope::box(Vector3d(1.0, 2.0, 3.0));
  const Isometry3d I = Isometry3d::Identity();
  CertifiedResult unused;
  BOOST_TEST(!certifiedFromProbes(box, box, PairFrame::make(box, I, box, I), surface, {}, unused));
  const ConvexPolytope blob = ConvexPolytope::fromPoints(ellipsoidPoints(rng, 200, Vector3d(1, 0.5, 0.25)));
  const Isometry3d apart = makePose(Quaterniond::Identity(), Vector3d(5, 0, 0));
  BOOST_TEST(!certifiedFromProbes(blob, blob, PairFrame::make(blob, I, blob, apart), surface, {}, unused));
}

// The start from four generic directions (certifiedWithoutGjk, for pairs known to overlap where
// the twelve-direction start is not tried: small and elongated hulls, boxes): certified, equal to
// the expansion from GJK's simplex within tau, its bracket around the exact depth; signedDistance,
// which starts such pairs there, answers them exactly and certified.
BOOST_AUTO_TEST_CASE(start_from_generic_directions) {
  std::mt19937 rng(37);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  ExpansionSurface surface;
  int tried = 0;
  for (int i = 0; i < 120; ++i) {
    const int n = 4 + static_cast<int>(U(rng) * 40);
    const Vector3d semiA(1.0, 0.05 + U(rng), 0.05 + U(rng)), semiB(0.1 + U(rng), 0.05 + U(rng), 0.02 + 0.5 * U(rng));
    const ConvexPolytope A =
        i % 3 == 0 ? ConvexPolytope::box(semiA) : ConvexPolytope::fromPoints(ellipsoidPoints(rng, n, semiA));
    const ConvexPolytope B =
        i % 3 == 1 ? ConvexPolytope::box(semiB) : ConvexPolytope::fromPoints(ellipsoidPoints(rng, n, semiB));
    const Isometry3d X_WA = makePose(randomRotation(rng), Vector3d::Zero());
    const Isometry3d X_WB = makePose(randomRotation(rng), 0.3 * U(rng) * randomUnit(rng));
    const PairFrame frame = PairFrame::make(A, X_WA, B, X_WB);
    if (!(frame.t.norm() < A.insideRadius() + B.insideRadius())) continue;
    ++tried;
    const CertifiedResult c = certifiedWithoutGjk(A, B, frame, surface);
    BOOST_TEST((c.status == CertifiedStatus::Certified), "pair " << i);
    const GjkResult g = gjkDistance(A, B, frame);
    BOOST_TEST_REQUIRE((g.status == GjkStatus::Overlapping), "pair " << i);
    const CertifiedResult fromGjk = certifiedPenetration(A, B, frame, g, surface);
    BOOST_TEST(std::abs(c.upper - fromGjk.upper) <= c.tau, "pair " << i << ": " << c.upper << " vs " << fromGjk.upper);
    const double depth = -exactSignedDistance(A, X_WA, B, X_WB).distance;
    const double slack = kBracketSlackRelative * certifyScale(A, X_WA, B, X_WB);
    BOOST_TEST(c.lower <= depth + slack, "pair " << i);
    BOOST_TEST(depth <= c.upper + slack, "pair " << i);
    const SignedDistanceResult r = signedDistance(A, X_WA, B, X_WB);
    const std::string why = checkCertified(A, X_WA, B, X_WB, r, 1e-12);
    BOOST_TEST(why.empty(), "pair " << i << ": " << why);
  }
  BOOST_TEST(tried > 40);
}

/// Largest signed distance of world point p_W beyond P's face planes (P posed at X_WP): 0 on
/// P's boundary, negative inside, positive outside.
double beyondFaces(const ConvexPolytope& P, const Isometry3d& X_WP, const Vector3d& p_W) {
  const Vector3d p = X_WP.inverse() * p_W;
  double beyond = -std::numeric_limits<double>::infinity();
  for (int f = 0; f < P.numFaces(); ++f) beyond = std::max(beyond, P.faceNormal(f).dot(p) - P.faceOffset(f));
  return beyond;
}

// Parallel faces (a box on another, one turned by a quarter turn, both turned alike far from the
// origin, side by side with coplanar tops): the certifying face's corners span several features
// of each box, and DEEP's facet at the certified direction names the answer without a walk. The
// depth is exact and certified, the normal is a face normal of A, and the witness points lie on
// both boxes' boundaries; warm and swapped queries agree.
BOOST_AUTO_TEST_CASE(parallel_faces_named_without_a_walk) {
  std::mt19937 rng(31);
  const ConvexPolytope A = ConvexPolytope::box(Vector3d(1.0, 2.0, 3.0));
  const ConvexPolytope B = ConvexPolytope::box(Vector3d(0.8, 0.6, 1.2));
  const Quaterniond quarter(Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitZ()));
  const Quaterniond R = randomRotation(rng);
  const Vector3d far(1e4, -1e4, 1e4);
  struct Case {
    Isometry3d X_WA, X_WB;
    const char* what;
  };
  const std::vector<Case> cases = {
      {Isometry3d::Identity(), makePose(Quaterniond::Identity(), Vector3d(0.2, -0.3, 2.0)), "stacked"},
      {Isometry3d::Identity(), makePose(Quaterniond::Identity(), Vector3d(0.2, -0.3, 2.1 - 1e-3)),
       "stacked, 1e-3 deep"},
      {Isometry3d::Identity(), makePose(quarter, Vector3d(-0.1, 0.4, 1.95)), "stacked, a quarter turn"},
      {makePose(R, far), makePose(R, far + R * Vector3d(0.2, -0.3, 2.0)), "both turned, far"},
      {Isometry3d::Identity(), makePose(Quaterniond::Identity(), Vector3d(0.85, 0.2, 0.9)), "side by side"},
  };
  for (const Case& c : cases) {
    const SignedDistanceResult r = signedDistance(A, c.X_WA, B, c.X_WB);
    const std::string why = checkCertified(A, c.X_WA, B, c.X_WB, r, 1e-12);
    BOOST_TEST(why.empty(), c.what << ": " << why);
    BOOST_TEST(r.walk.starts == 0, c.what);
    const double L = depthScale(A, B);
    // World coordinates carry about 1e-16 of their magnitude: the far case's witnesses are only
    // that close to the boundaries.
    const double onBoundary = 1e-12 * (L + c.X_WB.translation().norm());
    BOOST_TEST(std::abs(beyondFaces(A, c.X_WA, r.pointA)) <= onBoundary, c.what);
    BOOST_TEST(std::abs(beyondFaces(B, c.X_WB, r.pointB)) <= onBoundary, c.what);
    const Vector3d n_A = c.X_WA.linear().transpose() * r.normal;
    BOOST_TEST(n_A.cwiseAbs().maxCoeff() >= 1.0 - 1e-12, c.what << ": normal " << n_A.transpose());
    PairCache cache;
    signedDistance(A, c.X_WA, B, c.X_WB, &cache);
    const SignedDistanceResult warm = signedDistance(A, c.X_WA, B, c.X_WB, &cache);
    const SignedDistanceResult swapped = signedDistance(B, c.X_WB, A, c.X_WA);
    BOOST_TEST(std::abs(warm.distance - r.distance) <= 1e-12 * L, c.what);
    BOOST_TEST(std::abs(swapped.distance - r.distance) <= 1e-12 * L, c.what);
  }
}

// A 500-vertex sphere against itself, rotated: the surface needs hundreds of expansions. Below
// that cap the expansion says NotConverged with a valid bracket; signedDistance then falls back on
// DEEP's walks and still answers exactly.
BOOST_AUTO_TEST_CASE(cap_on_a_round_pair) {
  std::mt19937 rng(15);
  const ConvexPolytope sphere = ConvexPolytope::fromPoints(ellipsoidPoints(rng, 500, Vector3d(1, 1, 1)));
  const Isometry3d X_WA = Isometry3d::Identity();
  const Isometry3d X_WB = makePose(randomRotation(rng), Vector3d(0.01, 0.0, 0.0));
  const PairFrame frame = PairFrame::make(sphere, X_WA, sphere, X_WB);
  const GjkResult g = gjkDistance(sphere, sphere, frame);
  BOOST_TEST_REQUIRE((g.status == GjkStatus::Overlapping));
  const double depth = -exactSignedDistance(sphere, X_WA, sphere, X_WB).distance;
  const double slack = kBracketSlackRelative * certifyScale(sphere, X_WA, sphere, X_WB);
  ExpansionSurface surface;
  CertifiedOptions o;
  o.maxExpansions = 40;
  const CertifiedResult c = certifiedPenetration(sphere, sphere, frame, g, surface, o);
  BOOST_TEST((c.status == CertifiedStatus::NotConverged));
  BOOST_TEST(c.expansions == 40);
  BOOST_TEST(c.lower <= depth + slack);
  BOOST_TEST(depth <= c.upper + slack);
  BOOST_TEST(c.upper - c.lower > c.tau);
  // Through signedDistance with the default cap (beyond the surface's capacity for this pair):
  // NotConverged, the bracket holds, the answer is its upper end, a valid separating translation
  // (DEEP's walks or the expansion's best support, whichever is shallower).
  const SignedDistanceResult r = signedDistance(sphere, X_WA, sphere, X_WB);
  BOOST_TEST(!r.certified);
  BOOST_TEST((r.status == SignedDistanceStatus::NotConverged));
  BOOST_TEST(r.expansions > 40);
  BOOST_TEST(r.depthLower <= depth + slack);
  BOOST_TEST(depth <= r.depthUpper + slack);
  BOOST_TEST(r.depthUpper == -r.distance);
  const ExactResult moved = exactSignedDistance(
      sphere, X_WA, sphere, makePose(Quaterniond(X_WB.linear()), X_WB.translation() + r.depthUpper * r.normal));
  BOOST_TEST(std::abs(moved.distance) <= 1e-9);
}

// The two methods on the same pairs: DEEP's walk is selectable and gives no lower bound.
BOOST_AUTO_TEST_CASE(deep_walk_stays_selectable) {
  std::mt19937 rng(16);
  for (int i = 0; i < 30; ++i) {
    const Pair p = randomPair(rng, 60, 60, Vector3d::Zero());
    const SignedDistanceResult c =
        signedDistance(p.A, p.X_WA, p.B, p.X_WB, nullptr, methodOptions(PenetrationMethod::CertifiedExpansion));
    const SignedDistanceResult w =
        signedDistance(p.A, p.X_WA, p.B, p.X_WB, nullptr, methodOptions(PenetrationMethod::GaussMapWalk));
    if (c.distance >= 0) continue;
    BOOST_TEST(!w.certified);
    BOOST_TEST(w.depthLower == 0.0);
    BOOST_TEST(w.walk.starts > 0);
    BOOST_TEST(c.expansions > 0);
    // DEEP's answer is a valid separating translation: never shallower than the certified one.
    BOOST_TEST(-w.distance >= c.depthLower - 1e-14 * certifyScale(p.A, p.X_WA, p.B, p.X_WB));
  }
}

BOOST_AUTO_TEST_SUITE_END()
