// Fast paths used by the checker's isFree: the polytope's direction index (where support() starts
// its climb), PairFrame::makeUnchecked and overlapsUnchecked; and the caller's scratch spaces
// (PairCache::surface and ::walk) shared across pairs. Each must give what the checked or plain
// path gives.

#include "deepcheck/geometry/pair_frame.h"
#include "deepcheck/geometry/polytope.h"
#include "deepcheck/geometry/signed_distance.h"
#include "deepcheck/geometry/internal/polytope_access.h"

#include "shapes.h"

#include <boost/test/unit_test.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

using deepcheck::geometry::ConvexPolytope;
using deepcheck::geometry::ConvexShape;
using deepcheck::geometry::PairCache;
using deepcheck::geometry::PairFrame;
using deepcheck::geometry::detail::supportStart;
using Eigen::Vector3d;
namespace t = deepcheck::geometry::testing;

namespace {

/// Directions that stress the cube map: random, on the coordinate axes and diagonals (ties
/// between cube faces), on and near cell boundaries, tiny and huge magnitudes.
std::vector<Vector3d> testDirections(std::mt19937& rng) {
  std::vector<Vector3d> dirs;
  std::normal_distribution<double> g(0.0, 1.0);
  for (int i = 0; i < 600; ++i) dirs.emplace_back(g(rng), g(rng), g(rng));
  for (int a = -1; a <= 1; ++a) {
    for (int b = -1; b <= 1; ++b) {
      for (int c = -1; c <= 1; ++c) {
        if (a != 0 || b != 0 || c != 0) dirs.emplace_back(a, b, c);
      }
    }
  }
  std::uniform_int_distribution<int> cell(0, 8);
  for (int i = 0; i < 300; ++i) {
    // A cell boundary of the 8 x 8 grid is at u = -1 + k / 4; put a coordinate on it or 1 ulp off.
    const double u = -1.0 + cell(rng) / 4.0;
    const double w = -1.0 + cell(rng) / 4.0;
    Vector3d d(1.0, u, w);
    if (i % 3 == 1) d.y() = std::nextafter(d.y(), 2.0);
    if (i % 3 == 2) d.z() = std::nextafter(d.z(), -2.0);
    const int axis = i % 3;
    std::swap(d[0], d[axis]);
    if (i % 2) d = -d;
    dirs.push_back(d);
  }
  for (double scale : {1e-300, 1e-12, 1e12, 1e300}) dirs.push_back(scale * Vector3d(0.3, -0.8, 0.5));
  return dirs;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(fast_paths)

BOOST_AUTO_TEST_CASE(direction_index_start_and_support) {
  std::mt19937 rng(2025);
  for (int n : {8, 17, 40, 150, 600, 3000}) {
    for (int trial = 0; trial < 4; ++trial) {
      const Vector3d semi(0.05 + 0.3 * trial, 0.2, 0.02 + 0.1 * trial);
      const ConvexPolytope poly = ConvexPolytope::fromPoints(t::ellipsoidPoints(rng, n, semi));
      const bool indexed = poly.numVertices() > 16;
      const double tol = poly.hullTolerance() + 4.0 * std::numeric_limits<double>::epsilon() * poly.lengthScale();
      std::uniform_int_distribution<int> hint(-2, poly.numVertices() + 2);
      int bad = 0;
      int startFar = 0;
      const std::vector<Vector3d> dirs = testDirections(rng);
      for (const Vector3d& d : dirs) {
        const int start = supportStart(poly, d);
        if (!indexed) {
          BOOST_TEST(start == -1);
        } else {
          BOOST_REQUIRE(start >= 0);
          BOOST_REQUIRE(start < poly.numVertices());
        }
        const int s = poly.support(d, hint(rng));
        const int b = poly.supportBruteForce(d);
        BOOST_REQUIRE(s >= 0);
        BOOST_REQUIRE(s < poly.numVertices());
        const Vector3d u = d.normalized();
        if (std::abs(u.dot(poly.localVertex(s)) - u.dot(poly.localVertex(b))) > tol) ++bad;
        // The start is near the support: the support function is R-Lipschitz (R the bounding
        // radius), and d is within about 0.18 (the half diagonal of a cell) of its cell's centre
        // direction, whose support the start is, so the start is lower by at most 2 R 0.18.
        if (indexed && u.dot(poly.localVertex(b) - poly.localVertex(start)) > 0.4 * poly.boundingRadius()) {
          ++startFar;
        }
      }
      BOOST_TEST(bad == 0, "n " << n << " trial " << trial);
      BOOST_TEST(startFar == 0, "n " << n << " trial " << trial);
    }
  }
}

BOOST_AUTO_TEST_CASE(direction_index_rejects_zero_and_non_finite) {
  std::mt19937 rng(7);
  const ConvexPolytope poly = ConvexPolytope::fromPoints(t::ellipsoidPoints(rng, 200, Vector3d(0.3, 0.2, 0.1)));
  BOOST_REQUIRE(poly.numVertices() > 16);
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  BOOST_TEST(supportStart(poly, Vector3d::Zero()) == -1);
  BOOST_TEST(supportStart(poly, Vector3d(inf, 0, 0)) == -1);
  BOOST_TEST(supportStart(poly, Vector3d(1, nan, 0)) == -1);
  BOOST_TEST(supportStart(poly, Vector3d(nan, nan, nan)) == -1);
  // support() still returns a vertex (the hint's climb) for such directions.
  for (const Vector3d& d : {Vector3d::Zero().eval(), Vector3d(nan, 1, 0), Vector3d(1, inf, 0)}) {
    const int s = poly.support(d, 5);
    BOOST_TEST(s >= 0);
    BOOST_TEST(s < poly.numVertices());
  }
  // Small hulls are searched by brute force and have no index.
  const ConvexPolytope box = ConvexPolytope::box(Vector3d(2, 4, 6));
  BOOST_TEST(supportStart(box, Vector3d(1, 1, 1)) == -1);
}

BOOST_AUTO_TEST_CASE(unchecked_frame_equals_checked) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const ConvexPolytope A = ConvexPolytope::fromPoints(t::ellipsoidPoints(rng, 40, Vector3d(0.3, 0.2, 0.1)));
    const ConvexPolytope B = ConvexPolytope::fromPoints(t::ellipsoidPoints(rng, 60, Vector3d(0.1, 0.4, 0.2)));
    const Eigen::Isometry3d X_WA = t::makePose(t::randomRotation(rng), t::randomUnit(rng) * (trial % 7));
    const Eigen::Isometry3d X_WB = t::makePose(t::randomRotation(rng), t::randomUnit(rng) * (trial % 5));
    const PairFrame checked = PairFrame::make(A, X_WA, B, X_WB);
    const PairFrame unchecked = PairFrame::makeUnchecked(A, X_WA, B, X_WB);
    BOOST_TEST((checked.R - unchecked.R).norm() == 0.0);
    BOOST_TEST((checked.t - unchecked.t).norm() == 0.0);
    BOOST_TEST((checked.X_WP.matrix() - unchecked.X_WP.matrix()).norm() == 0.0);
  }
}

BOOST_AUTO_TEST_CASE(overlaps_unchecked_equals_overlaps) {
  // Pairs from far apart to deeply overlapping, with and without radii, cold and warm caches:
  // the same booleans, and the same cache contents afterwards.
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> distance(0.0, 1.2);
  int overlapping = 0;
  int apart = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const ConvexPolytope A =
        ConvexPolytope::fromPoints(t::ellipsoidPoints(rng, 20 + trial % 150, Vector3d(0.3, 0.2, 0.1)));
    const ConvexPolytope B = trial % 4 == 0
                                 ? ConvexPolytope::box(Vector3d(0.4, 0.6, 0.1))
                                 : ConvexPolytope::fromPoints(t::ellipsoidPoints(rng, 30, Vector3d(0.1, 0.4, 0.2)));
    const double rA = trial % 3 == 0 ? 0.02 : 0.0;
    const double rB = trial % 5 == 0 ? 0.05 : 0.0;
    const ConvexShape a{&A, rA};
    const ConvexShape b{&B, rB};
    const Eigen::Isometry3d X_WA = t::makePose(t::randomRotation(rng), Vector3d(0.1, -0.2, 0.3));
    const Eigen::Isometry3d X_WB =
        t::makePose(t::randomRotation(rng), Vector3d(0.1, -0.2, 0.3) + distance(rng) * t::randomUnit(rng));
    PairCache c1;
    PairCache c2;
    if (trial % 2) {  // a warm cache from another pose of the pair
      const Eigen::Isometry3d X_other = t::makePose(t::randomRotation(rng), Vector3d(0.5, 0.5, 0.5));
      deepcheck::geometry::overlaps(a, X_WA, b, X_other, &c1);
      c2 = c1;
    }
    const bool checked = deepcheck::geometry::overlaps(a, X_WA, b, X_WB, &c1);
    const bool unchecked = deepcheck::geometry::overlapsUnchecked(a, X_WA, b, X_WB, &c2);
    BOOST_TEST(checked == unchecked, "trial " << trial);
    BOOST_TEST((c1.gjk.direction - c2.gjk.direction).norm() == 0.0);
    BOOST_TEST(c1.gjk.hintA == c2.gjk.hintA);
    BOOST_TEST(c1.gjk.hintB == c2.gjk.hintB);
    BOOST_TEST(deepcheck::geometry::overlapsUnchecked(a, X_WA, b, X_WB) == checked);
    (checked ? overlapping : apart)++;
  }
  BOOST_TEST(overlapping > 300);
  BOOST_TEST(apart > 300);
}

BOOST_AUTO_TEST_CASE(shared_scratch_gives_the_local_scratch_answers) {
  // One PenetrationScratch shared by pairs of different sizes and kinds, queried
  // in turn along a motion (warm), must give bit for bit what queries with local scratch give.
  std::mt19937 rng(71);
  std::vector<ConvexPolytope> cores;
  for (int n : {8, 40, 300})
    cores.push_back(ConvexPolytope::fromPoints(t::ellipsoidPoints(rng, n, Vector3d(1.0, 0.6, 0.3))));
  cores.push_back(ConvexPolytope::fromPoints({Vector3d(-0.5, 0, 0), Vector3d(0.5, 0.1, 0)}));  // segment
  cores.push_back(ConvexPolytope::fromPoints({Vector3d(0.2, 0.1, -0.3)}));                     // point
  cores.push_back(ConvexPolytope::fromPoints(
      {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(1, 1, 0), Vector3d(0, 1, 0)}));  // polygon
  deepcheck::geometry::PenetrationScratch scratch;
  for (auto method : {deepcheck::geometry::PenetrationMethod::CertifiedExpansion,
                      deepcheck::geometry::PenetrationMethod::GaussMapWalk}) {
    deepcheck::geometry::PenetrationOptions options;
    options.method = method;
    const int numPairs = static_cast<int>(cores.size() * cores.size());
    std::vector<PairCache> shared(numPairs);
    std::vector<PairCache> local(numPairs);
    for (PairCache& c : shared) c.scratch = &scratch;
    std::vector<Eigen::Quaterniond> spin(numPairs);
    for (auto& q : spin) q = t::randomRotation(rng);
    int overlapping = 0;
    for (int step = 0; step < 5; ++step) {
      for (int k = 0; k < numPairs; ++k) {
        const ConvexShape A{&cores[k / cores.size()], 0.1};
        const ConvexShape B{&cores[k % cores.size()], 0.05};
        const Eigen::Quaterniond q = Eigen::Quaterniond::Identity().slerp(0.02 * step, spin[k]);
        const auto X_WB = t::makePose(q, Vector3d(0.3 - 0.01 * step, 0.1, 0.05));
        const auto X_WA = Eigen::Isometry3d::Identity();
        const auto r1 = deepcheck::geometry::signedDistance(A, X_WA, B, X_WB, &shared[k], options);
        const auto r2 = deepcheck::geometry::signedDistance(A, X_WA, B, X_WB, &local[k], options);
        BOOST_TEST(r1.distance == r2.distance, "pair " << k << " step " << step);
        BOOST_TEST((r1.normal - r2.normal).norm() == 0.0);
        BOOST_TEST((r1.pointA - r2.pointA).norm() == 0.0);
        BOOST_TEST((r1.pointB - r2.pointB).norm() == 0.0);
        BOOST_TEST(r1.certified == r2.certified);
        overlapping += r1.distance < 0.0;
      }
    }
    BOOST_TEST(overlapping > numPairs);  // most pairs overlap: the depth paths ran
  }
}

BOOST_AUTO_TEST_SUITE_END()
