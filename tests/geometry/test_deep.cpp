// DEEP penetration depth and the signed-distance entry point, against the exact reference.
//
// Accuracy measure used throughout: the error of a signed distance is |sd - sd_exact| divided by
// max(|sd_exact|, 1e-3 * L), L the larger bounding radius of the two shapes: relative to the
// depth, except that depths below a thousandth of the shapes' size are compared in absolute
// terms at that scale (no method can be 1e-12 relative on a depth of 1e-12 * L).

#include "shapes.h"

#include "deepcheck/geometry/exact.h"
#include "deepcheck/geometry/signed_distance.h"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

using namespace deepcheck::geometry;
using namespace deepcheck::geometry::testing;
using Eigen::Isometry3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

// Band of the single-walk miss rate (see single_walk_local_minimum_rate_is_in_its_band):
// measured 16.5 % (315 of 1907), binomial standard deviation 0.85 %; the band is about +-4 sigma.
constexpr double kSingleWalkMinRate = 0.13;
constexpr double kSingleWalkMaxRate = 0.20;

Isometry3d translated(const Isometry3d& X, const Vector3d& d) {
  Isometry3d Y = X;
  Y.translation() += d;
  return Y;
}

/// Checks the properties every answer must have; returns a description of what failed ("" if ok).
std::string checkAnswer(const ConvexPolytope& A, const Isometry3d& X_WA, const ConvexPolytope& B,
                        const Isometry3d& X_WB, const SignedDistanceResult& r) {
  std::ostringstream why;
  const double L = depthScale(A, B);
  if (!std::isfinite(r.distance) || !r.normal.allFinite() || !r.pointA.allFinite() || !r.pointB.allFinite())
    why << "non-finite output; ";
  if (std::abs(r.normal.norm() - 1) > 1e-9) why << "normal not unit; ";
  // Witnesses: pB - pA = sd * n.
  const double witnessGap = (r.pointB - r.pointA - r.distance * r.normal).norm();
  // World coordinates carry about 1e-16 of their magnitude: far from the origin, tiny shapes'
  // witnesses cannot be closer to consistent than that.
  const double worldUlp = 1e-15 * std::max(r.pointA.norm(), r.pointB.norm());
  if (witnessGap > 1e-9 * L + worldUlp)
    why << "witnesses inconsistent by " << witnessGap / L << " L (sd " << r.distance / L << " L); ";
  if (r.distance < 0) {
    // Translating B by depth * n makes the shapes touch; by 0.99 * depth * n they still overlap.
    const double depth = -r.distance;
    const ExactResult moved = exactSignedDistance(A, X_WA, B, translated(X_WB, depth * r.normal));
    if (std::abs(moved.distance) > 1e-9 * L)
      why << "after translating by depth*n, exact sd = " << moved.distance << "; ";
    if (depth > 1e-6 * L) {
      const ExactResult partly = exactSignedDistance(A, X_WA, B, translated(X_WB, 0.99 * depth * r.normal));
      if (partly.distance >= 0) why << "after 0.99*depth*n no overlap; ";
    }
  }
  return why.str();
}

struct RandomPair {
  std::vector<Vector3d> a, b;
  Isometry3d X_WA, X_WB;
  bool far = false;
};

/// Random ellipsoid hulls: vertex counts mostly 4..100 with a few up to 1,000, aspect ratios up
/// to 1:1000, scales 1e-3..1e3, a third of the pairs 1e4 from the origin (in units of the scale's
/// world, i.e. absolute), placed so that most pairs overlap.
RandomPair makePair(std::mt19937& rng, int i) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  auto count = [&](bool large) {
    if (large) return 100 + static_cast<int>(U(rng) * 900);
    return 4 + static_cast<int>(U(rng) * 97);
  };
  const bool large = i % 40 == 0;  // 2.5 % of the pairs have one side with 100..1000 vertices
  const double aspects[] = {1, 1, 3, 10, 100, 1000};
  auto semi = [&](double scale) {
    const double aspect = aspects[static_cast<int>(U(rng) * 6)];
    Vector3d s(1.0, 0.3 + 0.7 * U(rng), 1.0 / aspect);
    return Vector3d(s * scale);
  };
  const double scale = std::pow(10.0, -3 + 6 * U(rng));
  RandomPair p;
  p.a = ellipsoidPoints(rng, count(large), semi(scale));
  p.b = ellipsoidPoints(rng, count(false), semi(scale * (0.3 + U(rng))));
  p.far = i % 3 == 0;
  const Vector3d base = p.far ? Vector3d(1e4 * randomUnit(rng)) : Vector3d::Zero();
  p.X_WA = makePose(randomRotation(rng), base);
  // B's centre within 0.6 of A's largest semi-axis: mostly overlapping.
  p.X_WB = makePose(randomRotation(rng), base + scale * 0.6 * U(rng) * randomUnit(rng));
  return p;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(deep_random)

// The main accuracy claim: 10,000 random pairs against the exact reference.
BOOST_AUTO_TEST_CASE(agrees_with_exact_reference_on_10000_pairs) {
  std::mt19937 rng(20021);
  const int kPairs = 10000;
  int overlapping = 0, separated = 0, depthMisses = 0, distanceMisses = 0, invalid = 0;
  int notConverged = 0, uncertified = 0, walkMisses = 0;
  PenetrationOptions deepWalk;
  deepWalk.method = PenetrationMethod::GaussMapWalk;
  for (int i = 0; i < kPairs; ++i) {
    const RandomPair p = makePair(rng, i);
    const ConvexPolytope A = ConvexPolytope::fromPoints(p.a);
    const ConvexPolytope B = ConvexPolytope::fromPoints(p.b);
    const double L = depthScale(A, B);
    const ExactResult exact = exactSignedDistance(A, p.X_WA, B, p.X_WB);
    const SignedDistanceResult r = signedDistance(A, p.X_WA, B, p.X_WB);
    const double err = depthError(r.distance, exact.distance, L);
    const double bound = p.far ? 1e-10 : 1e-12;
    if (exact.distance < 0) {
      ++overlapping;
      if (!r.certified) ++uncertified;
      const SignedDistanceResult walk = signedDistance(A, p.X_WA, B, p.X_WB, nullptr, deepWalk);
      if (depthError(walk.distance, exact.distance, L) > bound) ++walkMisses;
      if (err > bound) ++depthMisses;
      if (r.status == SignedDistanceStatus::NotConverged) ++notConverged;
      const std::string why = checkAnswer(A, p.X_WA, B, p.X_WB, r);
      if (!why.empty()) ++invalid;
      BOOST_TEST(why.empty(), "pair " << i << ": " << why);
    } else {
      ++separated;
      // GJK distance against the exact distance.
      const double derr = std::abs(r.distance - exact.distance) / std::max(exact.distance, 1e-3 * L);
      if (derr > (p.far ? 1e-9 : 1e-10)) ++distanceMisses;
      BOOST_TEST(derr <= (p.far ? 1e-9 : 1e-10),
                 "pair " << i << ": distance " << r.distance << " exact " << exact.distance);
    }
  }
  // Both outcomes are in the sample, mostly overlapping.
  BOOST_TEST(overlapping > kPairs / 2);
  BOOST_TEST(separated > kPairs / 50);
  // The certified method: every overlapping pair exact and certified. DEEP's walk: at least
  // 99.9 % exact.
  BOOST_TEST(depthMisses == 0);
  BOOST_TEST(uncertified == 0);
  BOOST_TEST(notConverged == 0);
  BOOST_TEST(walkMisses <= overlapping / 1000);
  BOOST_TEST(distanceMisses == 0);
  BOOST_TEST(invalid == 0);
}

// Characterization: how often a single walk from the centroid difference (no restarts) ends in
// a worse local minimum, on 2,000 random overlapping pairs. The band is what was measured when
// the README's accuracy table was written; leaving it in either direction means the walk changed
// and the table needs re-measuring.
BOOST_AUTO_TEST_CASE(single_walk_local_minimum_rate_is_in_its_band) {
  std::mt19937 rng(31337);
  PenetrationOptions single;
  single.method = PenetrationMethod::GaussMapWalk;
  single.walk.restarts = false;
  int overlapping = 0, misses = 0;
  for (int i = 0; i < 2000; ++i) {
    const RandomPair p = makePair(rng, i + 1);
    const ConvexPolytope A = ConvexPolytope::fromPoints(p.a);
    const ConvexPolytope B = ConvexPolytope::fromPoints(p.b);
    const ExactResult exact = exactSignedDistance(A, p.X_WA, B, p.X_WB);
    if (exact.distance >= 0) continue;
    ++overlapping;
    const SignedDistanceResult r = signedDistance(A, p.X_WA, B, p.X_WB, nullptr, single);
    if (depthError(r.distance, exact.distance, depthScale(A, B)) > (p.far ? 1e-10 : 1e-12)) ++misses;
  }
  const double rate = static_cast<double>(misses) / overlapping;
  BOOST_TEST(rate >= kSingleWalkMinRate);
  BOOST_TEST(rate <= kSingleWalkMaxRate);
}

BOOST_AUTO_TEST_CASE(swapping_shapes_gives_same_depth_and_opposite_normal) {
  std::mt19937 rng(777);
  int checked = 0;
  for (int i = 0; i < 1000; ++i) {
    const RandomPair p = makePair(rng, i + 1);
    const ConvexPolytope A = ConvexPolytope::fromPoints(p.a);
    const ConvexPolytope B = ConvexPolytope::fromPoints(p.b);
    const SignedDistanceResult ab = signedDistance(A, p.X_WA, B, p.X_WB);
    const SignedDistanceResult ba = signedDistance(B, p.X_WB, A, p.X_WA);
    const double L = depthScale(A, B);
    BOOST_TEST(
        std::abs(ab.distance - ba.distance) <= (p.far ? 1e-10 : 1e-12) * std::max(std::abs(ab.distance), 1e-3 * L),
        "pair " << i << ": " << ab.distance << " vs " << ba.distance);
    // The swapped answer, read back for (A, B), must be a valid answer too (normals may differ
    // only where two facets tie in depth).
    SignedDistanceResult back = ba;
    back.normal = -ba.normal;
    back.pointA = ba.pointB;
    back.pointB = ba.pointA;
    const std::string why = checkAnswer(A, p.X_WA, B, p.X_WB, back);
    BOOST_TEST(why.empty(), "pair " << i << ": " << why);
    ++checked;
  }
  BOOST_TEST(checked == 1000);
}

BOOST_AUTO_TEST_CASE(warm_start_along_a_motion_matches_cold) {
  std::mt19937 rng(4242);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int steps = 0, mismatches = 0, walkMismatches = 0;
  PenetrationOptions deepWalk;
  deepWalk.method = PenetrationMethod::GaussMapWalk;
  for (int trial = 0; trial < 20; ++trial) {
    const ConvexPolytope A = ConvexPolytope::fromPoints(ellipsoidPoints(rng, 100, Vector3d(1, 0.6, 0.4)));
    const ConvexPolytope B = ConvexPolytope::fromPoints(ellipsoidPoints(rng, 100, Vector3d(0.7, 0.5, 0.3)));
    PairCache cache, walkCache;
    const Isometry3d X_WA = Isometry3d::Identity();
    Quaterniond q = randomRotation(rng);
    Vector3d t = 0.5 * randomUnit(rng);
    const Vector3d w = 0.01 * randomUnit(rng);
    const Vector3d v = 0.005 * randomUnit(rng);
    for (int k = 0; k < 200; ++k) {
      q = Quaterniond(Eigen::AngleAxisd(w.norm(), w.normalized())) * q;
      t += v + 0.002 * Vector3d(U(rng), U(rng), U(rng));
      const Isometry3d X_WB = makePose(q, t);
      const SignedDistanceResult warm = signedDistance(A, X_WA, B, X_WB, &cache);
      const SignedDistanceResult cold = signedDistance(A, X_WA, B, X_WB);
      const SignedDistanceResult walkWarm = signedDistance(A, X_WA, B, X_WB, &walkCache, deepWalk);
      const SignedDistanceResult walkCold = signedDistance(A, X_WA, B, X_WB, nullptr, deepWalk);
      ++steps;
      if (std::abs(warm.distance - cold.distance) > 1e-12) ++mismatches;
      if (std::abs(walkWarm.distance - walkCold.distance) > 1e-12) ++walkMismatches;
    }
  }
  BOOST_TEST(mismatches == 0);
  // DEEP's warm walks may miss a new global minimum right where two facets swap; rare and tiny.
  BOOST_TEST(walkMismatches <= steps / 200);
}

BOOST_AUTO_TEST_SUITE_END()

// ---------------------------------------------------------------------------------------------

BOOST_AUTO_TEST_SUITE(deep_hard_cases)

namespace {

/// Runs signedDistance both ways and compares with the exact reference and the expected value
/// (when given). Returns the A-B result.
SignedDistanceResult expectExact(const ConvexPolytope& A, const Isometry3d& X_WA, const ConvexPolytope& B,
                                 const Isometry3d& X_WB, double tolRel = 1e-12) {
  const double L = depthScale(A, B);
  const ExactResult exact = exactSignedDistance(A, X_WA, B, X_WB);
  const SignedDistanceResult r = signedDistance(A, X_WA, B, X_WB);
  const SignedDistanceResult s = signedDistance(B, X_WB, A, X_WA);
  BOOST_TEST(depthError(r.distance, exact.distance, L) <= tolRel, "sd " << r.distance << " exact " << exact.distance);
  BOOST_TEST(depthError(s.distance, exact.distance, L) <= tolRel,
             "swapped sd " << s.distance << " exact " << exact.distance);
  BOOST_TEST(r.certified);
  BOOST_TEST(s.certified);
  // Warm: a second query of the same pair through a cache that saw the first.
  PairCache cache;
  signedDistance(A, X_WA, B, X_WB, &cache);
  const SignedDistanceResult warm = signedDistance(A, X_WA, B, X_WB, &cache);
  BOOST_TEST(depthError(warm.distance, exact.distance, L) <= tolRel,
             "warm sd " << warm.distance << " exact " << exact.distance);
  PenetrationOptions deepWalk;
  deepWalk.method = PenetrationMethod::GaussMapWalk;
  const SignedDistanceResult walk = signedDistance(A, X_WA, B, X_WB, nullptr, deepWalk);
  BOOST_TEST(depthError(walk.distance, exact.distance, L) <= tolRel,
             "DEEP walk sd " << walk.distance << " exact " << exact.distance);
  const std::string why = checkAnswer(A, X_WA, B, X_WB, r);
  BOOST_TEST(why.empty(), why);
  return r;
}

ConvexPolytope boxOf(double hx, double hy, double hz) { return ConvexPolytope::box(2.0 * Vector3d(hx, hy, hz)); }

Isometry3d poseRt(const Eigen::Matrix3d& R, const Vector3d& t) {
  Isometry3d X = Isometry3d::Identity();
  X.linear() = R;
  X.translation() = t;
  return X;
}

}  // namespace

BOOST_AUTO_TEST_CASE(touching_depth_one_billionth) {
  std::mt19937 rng(1);
  for (int k = 0; k < 50; ++k) {
    const double s = std::pow(10.0, -3 + 6 * (k % 7) / 6.0);
    const ConvexPolytope A = boxOf(s / 3, s / 2, s);
    const ConvexPolytope B = ConvexPolytope::fromPoints(ellipsoidPoints(rng, 60, Vector3d(s, s / 2, s / 3)));
    // Place B along a random direction so that it penetrates A by 1e-9 * s.
    const Quaterniond qB = randomRotation(rng);
    const Vector3d dir = randomUnit(rng);
    Isometry3d X_WB = makePose(qB, 10 * s * dir);
    const ExactResult far = exactSignedDistance(A, Isometry3d::Identity(), B, X_WB);
    X_WB = translated(X_WB, -(far.distance + 1e-9 * s) * far.normal);
    const SignedDistanceResult r = expectExact(A, Isometry3d::Identity(), B, X_WB);
    // The depth is at most the 1e-9 * s the pair was pushed in (less only at a corner).
    BOOST_TEST(r.distance < 0);
    BOOST_TEST(r.distance >= -1e-9 * s * (1 + 1e-6));
  }
}

BOOST_AUTO_TEST_CASE(face_to_face_stacked_boxes) {
  const ConvexPolytope A = boxOf(0.5, 0.5, 0.5);
  const ConvexPolytope B = boxOf(0.5, 0.5, 0.5);
  for (double overlap : {0.1, 1.0 / 3, 1e-6, 0.0}) {
    const Isometry3d X_WB = makePose(Quaterniond::Identity(), Vector3d(0, 0, 1.0 - overlap));
    const SignedDistanceResult r = expectExact(A, Isometry3d::Identity(), B, X_WB);
    BOOST_TEST(std::abs(r.distance + overlap) <= 1e-15);
    BOOST_TEST(std::abs(r.normal.z() - 1) <= 1e-12);
  }
  // Same, offset sideways so the faces only partly overlap, and far from the origin.
  const Vector3d base(1e4, -1e4, 1e4);
  const SignedDistanceResult r = expectExact(A, makePose(Quaterniond::Identity(), base), B,
                                             makePose(Quaterniond::Identity(), base + Vector3d(0.3, 0.7, 0.9)), 1e-10);
  BOOST_TEST(std::abs(r.distance + 0.1) <= 1e-11);
}

BOOST_AUTO_TEST_CASE(identical_shapes_at_same_pose) {
  std::mt19937 rng(3);
  const ConvexPolytope box = boxOf(0.5, 1.0, 1.5);
  const SignedDistanceResult r = expectExact(box, Isometry3d::Identity(), box, Isometry3d::Identity());
  BOOST_TEST(std::abs(r.distance + 1.0) <= 1e-15);  // the box's smallest width
  const ConvexPolytope blob = ConvexPolytope::fromPoints(ellipsoidPoints(rng, 200, Vector3d(1, 0.5, 0.25)));
  const Isometry3d X = makePose(randomRotation(rng), Vector3d(1e3, 2e3, -3e3));
  expectExact(blob, X, blob, X, 1e-11);
}

BOOST_AUTO_TEST_CASE(one_shape_deep_inside_the_other) {
  std::mt19937 rng(5);
  const ConvexPolytope big = ConvexPolytope::fromPoints(ellipsoidPoints(rng, 300, Vector3d(10, 8, 6)));
  const ConvexPolytope small = ConvexPolytope::fromPoints(ellipsoidPoints(rng, 30, Vector3d(0.1, 0.1, 0.1)));
  for (int k = 0; k < 20; ++k)
    expectExact(big, Isometry3d::Identity(), small, makePose(randomRotation(rng), 2.0 * randomUnit(rng)));
}

BOOST_AUTO_TEST_CASE(needles_and_plates) {
  std::mt19937 rng(7);
  const ConvexPolytope needle = ConvexPolytope::fromPoints(prismPoints(0.001, 1.0, 12));
  const ConvexPolytope plate = boxOf(1.0, 1.0, 0.001);
  for (int k = 0; k < 30; ++k) {
    const Isometry3d X_WB = makePose(randomRotation(rng), 0.2 * randomUnit(rng));
    expectExact(plate, Isometry3d::Identity(), needle, X_WB);
    expectExact(needle, X_WB, needle, makePose(randomRotation(rng), 0.01 * randomUnit(rng)));
  }
}

BOOST_AUTO_TEST_CASE(flat_polygons) {
  std::mt19937 rng(11);
  for (int k = 0; k < 30; ++k) {
    // A random convex polygon: points on an ellipse in a random plane.
    std::vector<Vector3d> pts;
    for (int i = 0; i < 12; ++i) {
      const double a = 2 * M_PI * i / 12 + 0.1 * k;
      pts.emplace_back(std::cos(a), 0.5 * std::sin(a), 0.0);
    }
    const ConvexPolytope poly = ConvexPolytope::fromPoints(pts);
    BOOST_TEST(static_cast<int>(poly.kind()) == static_cast<int>(PolytopeKind::Polygon));
    const ConvexPolytope solid = ConvexPolytope::fromPoints(ellipsoidPoints(rng, 40, Vector3d(0.5, 0.4, 0.3)));
    const Isometry3d X_poly = makePose(randomRotation(rng), 0.1 * randomUnit(rng));
    expectExact(poly, X_poly, solid, makePose(randomRotation(rng), 0.2 * randomUnit(rng)));
    // Two crossing polygons: their Minkowski difference is a solid.
    expectExact(poly, X_poly, poly, makePose(randomRotation(rng), 0.1 * randomUnit(rng)));
  }
}

BOOST_AUTO_TEST_CASE(duplicate_and_near_duplicate_points) {
  std::mt19937 rng(13);
  std::vector<Vector3d> pts = ellipsoidPoints(rng, 50, Vector3d(1, 1, 1));
  const std::size_t n = pts.size();
  for (std::size_t i = 0; i < n; ++i) {
    pts.push_back(pts[i]);
    pts.push_back(pts[i] + 1e-14 * randomUnit(rng));
  }
  const ConvexPolytope A = ConvexPolytope::fromPoints(pts);
  for (int k = 0; k < 20; ++k)
    expectExact(A, Isometry3d::Identity(), A, makePose(randomRotation(rng), 0.8 * randomUnit(rng)));
}

BOOST_AUTO_TEST_CASE(spheres_with_2000_vertices) {
  std::mt19937 rng(17);
  const ConvexPolytope A = ConvexPolytope::fromPoints(ellipsoidPoints(rng, 2000, Vector3d(1, 1, 1)));
  const ConvexPolytope B = ConvexPolytope::fromPoints(ellipsoidPoints(rng, 2000, Vector3d(0.5, 0.5, 0.5)));
  for (int k = 0; k < 3; ++k)
    expectExact(A, Isometry3d::Identity(), B, makePose(randomRotation(rng), 1.2 * randomUnit(rng)));
}

BOOST_AUTO_TEST_CASE(parallel_edges) {
  // Boxes rotated about a shared axis: many edge pairs are exactly parallel.
  const ConvexPolytope A = boxOf(0.5, 0.3, 1.0);
  const ConvexPolytope B = boxOf(0.4, 0.4, 2.0);
  for (double angle : {M_PI / 4, M_PI / 6, 1e-9, M_PI / 2}) {
    const Quaterniond q(Eigen::AngleAxisd(angle, Vector3d::UnitZ()));
    expectExact(A, Isometry3d::Identity(), B, makePose(q, Vector3d(0.7, 0.2, 0.5)));
    expectExact(A, Isometry3d::Identity(), B, makePose(q, Vector3d(0.0, 0.0, 0.0)));
  }
}

// Configurations reported in other libraries' bug trackers.

BOOST_AUTO_TEST_CASE(fcl_issue_493_boxes_epa_failure) {
  // FCL #493: two 0.5 m cubes, same rotation; libccd's EPA threw "origin is outside the polytope".
  Eigen::Matrix3d R;
  R << 0.96193976625564348026, 0.15401279915737359216, 0.22572537250328919556, -0.19134171618254486313,
      0.96936494951283913579, 0.15401279915737359216, -0.19509032201612822033, -0.19134171618254486313,
      0.96193976625564348026;
  const ConvexPolytope box = boxOf(0.25, 0.25, 0.25);
  expectExact(box, poseRt(R, Vector3d(2.0770063995786869349, 0.48468247475641951239, 1.1543291419087275962)), box,
              poseRt(R, Vector3d(2, 0, 1.25)));
}

BOOST_AUTO_TEST_CASE(fcl_issue_399_thin_boxes) {
  // FCL #399: a thin box against a flat one; libccd's EPA was called on a separated pair.
  Eigen::Matrix3d R1, R2;
  R1 << -0.099432387353076273628, 0.99504432079443971837, 0, -0.99504432079443971837, -0.099432387353076273628, 0, 0, 0,
      1;
  R2 << 0.99506598442099225554, 0.099215354901756730444, 0, -0.099215354901756730444, 0.99506598442099225554, 0, 0, 0,
      1;
  const ConvexPolytope A = boxOf(0.23768037557601928711 / 2, 0.15702305734157562256 / 2, 0.125);
  const ConvexPolytope B = boxOf(0.010000000000000000208 / 2, 0.78165709972381591797 / 2, 0.125);
  expectExact(A, poseRt(R1, Vector3d(0.29526406526565551758, -0.013230856508016586304, 0)), B,
              poseRt(R2, Vector3d(0.22759585694545214629, 0.14974093549228112421, 0)));
}

BOOST_AUTO_TEST_CASE(fcl_issue_545_cube_on_the_diagonal) {
  // FCL #545: a small cube centred on the big cube's diagonal; the reported normal pointed along
  // the diagonal and the depth was sqrt(3) too large. The answer is 0.3 along a face normal.
  const ConvexPolytope big = boxOf(0.5, 0.5, 0.5);
  const ConvexPolytope small = boxOf(0.2, 0.2, 0.2);
  const SignedDistanceResult r =
      expectExact(big, Isometry3d::Identity(), small, makePose(Quaterniond::Identity(), Vector3d(0.4, 0.4, 0.4)));
  BOOST_TEST(std::abs(r.distance + 0.3) <= 1e-15);
  BOOST_TEST(r.normal.cwiseAbs().maxCoeff() >= 1 - 1e-12);
}

BOOST_AUTO_TEST_CASE(fcl_issue_319_box_against_cylinder) {
  // FCL #319: box .05 x .39 x 1.47 against a cylinder (length .18, radius .18, here a 64-sided
  // prism); libccd's EPA hit "this should not happen".
  const ConvexPolytope box = boxOf(0.025, 0.195, 0.735);
  const ConvexPolytope cyl = ConvexPolytope::fromPoints(prismPoints(0.18, 0.18, 64));
  const Isometry3d X_box = makePose(Quaterniond(0.707107, 0, 0, 0.707107).normalized(), Vector3d(0.8, -0.385, 0.735));
  const Isometry3d X_cyl = makePose(Quaterniond(0.991445, 0, 0, -0.130526).normalized(), Vector3d(0.4, -0.4, 0.93));
  expectExact(box, X_box, cyl, X_cyl);
  // And pushed into each other.
  expectExact(box, X_box, cyl, translated(X_cyl, Vector3d(0.25, 0, 0)));
}

BOOST_AUTO_TEST_CASE(fcl_issue_375_cylinder_resting_on_box) {
  // FCL #375: a thin cylinder (radius 0.08, length 0.002) resting on a box 0.49 x 0.63 x 0.015;
  // the contact normal came back zero. Touching and slightly penetrating.
  const ConvexPolytope box = boxOf(0.245, 0.315, 0.0075);
  const ConvexPolytope cyl = ConvexPolytope::fromPoints(prismPoints(0.08, 0.002, 48));
  Eigen::Matrix3d R;
  R << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  const Isometry3d X_box = poseRt(R, Vector3d(-0.25, 0, 0));
  for (double pen : {0.0, 1e-9, 1e-4}) {
    const Isometry3d X_cyl = makePose(Quaterniond::Identity(), Vector3d(-0.25, 0.1, 0.0075 + 0.001 - pen));
    const SignedDistanceResult r = expectExact(box, X_box, cyl, X_cyl);
    BOOST_TEST(std::abs(r.normal.z() - 1) <= 1e-9);
  }
}

BOOST_AUTO_TEST_CASE(libccd_issue_17_large_box_small_box) {
  // libccd #17: a 5 m box and a 0.2 m box; contact location was wrong.
  std::mt19937 rng(19);
  const ConvexPolytope big = boxOf(2.5, 2.5, 2.5);
  const ConvexPolytope small = boxOf(0.1, 0.1, 0.1);
  for (int k = 0; k < 20; ++k) {
    const Isometry3d X = makePose(randomRotation(rng), Vector3d(1.0, -0.5, 2.5 + 0.05));
    const SignedDistanceResult r = expectExact(big, Isometry3d::Identity(), small, X);
    // Witness on the big box's top face region.
    BOOST_TEST(std::abs(r.pointA.z() - 2.5) <= 1e-9);
  }
}

BOOST_AUTO_TEST_CASE(jolt_issue_671_box_hovering_over_hull) {
  // Jolt #671: a box hovering just above a hull; the penetration axis came back flipped.
  std::mt19937 rng(23);
  const ConvexPolytope hull = ConvexPolytope::fromPoints(boxCorners(Vector3d(1, 1, 0.25)));
  const ConvexPolytope box = boxOf(0.25, 0.25, 0.25);
  for (int k = 0; k < 36; ++k) {
    const Quaterniond q(Eigen::AngleAxisd(k * M_PI / 18, Vector3d::UnitZ()));
    for (double gap : {5e-4, 1e-9, 0.0, -1e-9, -5e-4}) {
      const Isometry3d X_hull = makePose(q, Vector3d::Zero());
      const Isometry3d X_box = makePose(q, Vector3d(0.1, 0.2, 0.5 + gap));
      const SignedDistanceResult r = expectExact(hull, X_hull, box, X_box);
      BOOST_TEST(r.normal.z() > 0.999);
    }
  }
}

BOOST_AUTO_TEST_CASE(points_and_segments_with_radii) {
  // Spheres and capsules: cores with radii, exact against analytic answers.
  const ConvexPolytope point = ConvexPolytope::fromPoints({Vector3d::Zero()});
  const ConvexPolytope segment = ConvexPolytope::fromPoints({Vector3d(0, 0, -0.5), Vector3d(0, 0, 0.5)});
  const ConvexPolytope box = boxOf(1, 1, 1);
  const ConvexShape sphere{&point, 0.3};
  const ConvexShape capsule{&segment, 0.2};
  const ConvexShape solid{&box, 0.0};
  // Sphere centre inside the box, 0.1 below the top face: depth 0.1 + 0.3.
  SignedDistanceResult r =
      signedDistance(solid, Isometry3d::Identity(), sphere, makePose(Quaterniond::Identity(), Vector3d(0.2, 0.1, 0.9)));
  BOOST_TEST(std::abs(r.distance + 0.4) <= 1e-15);
  BOOST_TEST(std::abs(r.normal.z() - 1) <= 1e-15);
  // Capsule lying across the box's top face, axis along x, 0.1 above it: distance -0.1.
  r = signedDistance(solid, Isometry3d::Identity(), capsule,
                     makePose(Quaterniond(Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitY())), Vector3d(0, 0, 1.1)));
  BOOST_TEST(std::abs(r.distance + 0.1) <= 1e-15);
  // Two spheres: distance between centres minus radii, both signs.
  for (double d : {1.0, 0.6, 0.2, 0.0}) {
    r = signedDistance(sphere, Isometry3d::Identity(), sphere, makePose(Quaterniond::Identity(), Vector3d(d, 0, 0)));
    BOOST_TEST(std::abs(r.distance - (d - 0.6)) <= 1e-15);
  }
  // Crossing capsules.
  r = signedDistance(capsule, Isometry3d::Identity(), capsule,
                     makePose(Quaterniond(Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitX())), Vector3d(0.1, 0, 0)));
  BOOST_TEST(std::abs(r.distance - (0.1 - 0.4)) <= 1e-15);
}

BOOST_AUTO_TEST_CASE(segments_and_points_inside_polytopes_against_exact) {
  std::mt19937 rng(29);
  for (int k = 0; k < 50; ++k) {
    const ConvexPolytope blob = ConvexPolytope::fromPoints(ellipsoidPoints(rng, 80, Vector3d(1, 0.7, 0.5)));
    const ConvexPolytope seg = ConvexPolytope::fromPoints({0.4 * randomUnit(rng), 0.4 * randomUnit(rng)});
    const ConvexPolytope pt = ConvexPolytope::fromPoints({0.3 * randomUnit(rng)});
    const Isometry3d X = makePose(randomRotation(rng), 0.2 * randomUnit(rng));
    expectExact(blob, X, seg, Isometry3d::Identity());
    expectExact(blob, X, pt, Isometry3d::Identity());
  }
}

BOOST_AUTO_TEST_CASE(bad_input_is_rejected_with_a_message) {
  const ConvexPolytope box = boxOf(1, 1, 1);
  Isometry3d bad = Isometry3d::Identity();
  bad.translation().x() = std::nan("");
  BOOST_CHECK_THROW(signedDistance(box, Isometry3d::Identity(), box, bad), std::invalid_argument);
  const ConvexShape negative{&box, -1.0};
  BOOST_CHECK_THROW(signedDistance(negative, Isometry3d::Identity(), ConvexShape{&box, 0}, Isometry3d::Identity()),
                    std::invalid_argument);
  const ConvexShape null{nullptr, 0.0};
  BOOST_CHECK_THROW(signedDistance(null, Isometry3d::Identity(), ConvexShape{&box, 0}, Isometry3d::Identity()),
                    std::invalid_argument);
}

BOOST_AUTO_TEST_SUITE_END()
