// Exact reference signed distance (exact.h): analytic cases, lower-dimensional differences, far
// from the world origin, swap symmetry, and the support-function optimality of its answers.
//
// Oracle used for random hulls: for a unit direction n (from A to B) let
//   gap(n) = min over b in B of n.b - max over a in A of n.a.
// Then sd = max over unit n of gap(n) in both cases (separating axis theorem when apart; when
// overlapping the depth is min over n of h_M(-n) = -gap(n)), attained at the answer's normal.

#include "deepcheck/geometry/exact.h"
#include "deepcheck/geometry/tolerances.h"
#include "shapes.h"

#include <boost/test/unit_test.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <vector>

using namespace deepcheck::geometry;
using deepcheck::geometry::testing::randomRotation;
using deepcheck::geometry::testing::randomUnit;

namespace {

// Accuracy demanded of the exact answer, relative to the pair's length scale: the round-off of
// forming differences and fitting facet planes is ~1e-16 * L, far below this.
constexpr double kAccuracy = tol::kInsideRelative;

Eigen::Isometry3d pose(const Eigen::Vector3d& t, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity()) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.normalized().toRotationMatrix();
  X.translation() = t;
  return X;
}

ConvexPolytope randomHull(std::mt19937& rng, int n, const Eigen::Vector3d& scale) {
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < n; ++i) pts.push_back(randomUnit(rng).cwiseProduct(scale));
  return ConvexPolytope::fromPoints(pts, "random");
}

ConvexPolytope square(double h) {
  return ConvexPolytope::fromPoints({{-h, -h, 0.0}, {h, -h, 0.0}, {h, h, 0.0}, {-h, h, 0.0}}, "square");
}

double pairScale(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA, const ConvexPolytope& B,
                 const Eigen::Isometry3d& X_WB) {
  return std::max(A.lengthScale(), B.lengthScale()) + (X_WB * B.center() - X_WA * A.center()).norm();
}

double gap(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA, const ConvexPolytope& B,
           const Eigen::Isometry3d& X_WB, const Eigen::Vector3d& n_W) {
  double maxA = -INFINITY;
  double minB = INFINITY;
  for (const auto& a : A.vertices()) maxA = std::max(maxA, n_W.dot(X_WA * a));
  for (const auto& b : B.vertices()) minB = std::min(minB, n_W.dot(X_WB * b));
  return minB - maxA;
}

/// Box-box signed distance of axis-aligned boxes (half extents hA, hB, centres 0 and t).
void boxBoxAnalytic(const Eigen::Vector3d& hA, const Eigen::Vector3d& hB, const Eigen::Vector3d& t, double& sd,
                    Eigen::Vector3d& n) {
  const Eigen::Vector3d overlap = hA + hB - t.cwiseAbs();
  if ((overlap.array() > 0.0).all()) {
    int k = 0;
    sd = -overlap.minCoeff(&k);
    n = Eigen::Vector3d::Zero();
    n[k] = t[k] >= 0.0 ? 1.0 : -1.0;
  } else {
    Eigen::Vector3d g = (-overlap).cwiseMax(0.0);
    for (int i = 0; i < 3; ++i) g[i] = t[i] >= 0.0 ? g[i] : -g[i];
    sd = g.norm();
    n = g / sd;
  }
}

void checkOptimal(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA, const ConvexPolytope& B,
                  const Eigen::Isometry3d& X_WB, std::mt19937& rng) {
  const ExactResult r = exactSignedDistance(A, X_WA, B, X_WB);
  const double L = pairScale(A, X_WA, B, X_WB);
  BOOST_TEST(std::abs(r.normal.norm() - 1.0) <= kAccuracy);
  BOOST_TEST(std::abs(gap(A, X_WA, B, X_WB, r.normal) - r.distance) <= kAccuracy * L);
  for (int k = 0; k < 200; ++k) {
    BOOST_TEST(gap(A, X_WA, B, X_WB, randomUnit(rng)) <= r.distance + kAccuracy * L);
  }
  // Translating B by -sd * n makes the shapes touch.
  Eigen::Isometry3d moved = X_WB;
  moved.pretranslate(-r.distance * r.normal);
  BOOST_TEST(std::abs(exactSignedDistance(A, X_WA, B, moved).distance) <= kAccuracy * L);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(exact)

BOOST_AUTO_TEST_CASE(axis_aligned_boxes_match_analytic) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> ext(0.1, 1.0);
  std::uniform_real_distribution<double> off(-2.0, 2.0);
  int overlapping = 0;
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d hA(ext(rng), ext(rng), ext(rng));
    const Eigen::Vector3d hB(ext(rng), ext(rng), ext(rng));
    const Eigen::Vector3d t(off(rng), off(rng), off(rng));
    const ConvexPolytope A = ConvexPolytope::box(2.0 * hA);
    const ConvexPolytope B = ConvexPolytope::box(2.0 * hB);
    double sd = 0.0;
    Eigen::Vector3d n;
    boxBoxAnalytic(hA, hB, t, sd, n);
    overlapping += sd < 0.0 ? 1 : 0;
    const double L = std::max(hA.norm(), hB.norm()) + t.norm();
    const ExactResult r = exactSignedDistance(A, pose(Eigen::Vector3d::Zero()), B, pose(t));
    BOOST_TEST(std::abs(r.distance - sd) <= kAccuracy * L);
    BOOST_TEST((r.normal - n).norm() <= kAccuracy * L / std::max(std::abs(sd), kAccuracy));
  }
  // The sample contains both outcomes.
  BOOST_TEST(overlapping > 20);
  BOOST_TEST(overlapping < 180);
}

BOOST_AUTO_TEST_CASE(rotated_boxes_match_analytic) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> off(-1.0, 1.0);
  const Eigen::Vector3d hA(1.0 / 3.0, 0.5, 0.7);
  const Eigen::Vector3d hB(0.2, 1.0 / 7.0, 0.45);
  const ConvexPolytope A = ConvexPolytope::box(2.0 * hA);
  const ConvexPolytope B = ConvexPolytope::box(2.0 * hB);
  for (int k = 0; k < 100; ++k) {
    const Eigen::Vector3d t(off(rng), off(rng), off(rng));
    double sd = 0.0;
    Eigen::Vector3d n;
    boxBoxAnalytic(hA, hB, t, sd, n);
    // The same relative configuration under a random rigid transform of the whole scene.
    const Eigen::Isometry3d X = pose(3.0 * Eigen::Vector3d(off(rng), off(rng), off(rng)), randomRotation(rng));
    const ExactResult r = exactSignedDistance(A, X, B, X * pose(t));
    const double L = hA.norm() + hB.norm() + t.norm() + X.translation().norm();
    BOOST_TEST(std::abs(r.distance - sd) <= kAccuracy * L);
    BOOST_TEST((r.normal - X.linear() * n).norm() <= kAccuracy * L / std::max(std::abs(sd), kAccuracy));
  }
}

BOOST_AUTO_TEST_CASE(touching_boxes_have_zero_distance) {
  const Eigen::Vector3d h(0.3, 1.0 / 3.0, 0.4);
  const ConvexPolytope A = ConvexPolytope::box(2.0 * h);
  const Eigen::Isometry3d X = pose(Eigen::Vector3d(0.1, 0.2, 0.3),
                                   Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())));
  // Face to face, edge to edge, corner to corner.
  for (const Eigen::Vector3d& t :
       {Eigen::Vector3d(0.6, 0.1, 0.0), Eigen::Vector3d(0.6, 2.0 / 3.0, 0.0), Eigen::Vector3d(0.6, 2.0 / 3.0, 0.8)}) {
    const ExactResult r = exactSignedDistance(A, X, A, X * pose(t));
    BOOST_TEST(std::abs(r.distance) <= kAccuracy * 2.0);
    BOOST_TEST(r.normal.dot(X.linear() * t) > 0.0);
  }
}

BOOST_AUTO_TEST_CASE(spheres_as_point_cores) {
  const ConvexPolytope P = ConvexPolytope::fromPoints({Eigen::Vector3d(0.1, -0.2, 0.3)}, "sphere");
  const Eigen::Vector3d t(0.5, -1.0 / 3.0, 0.25);
  const double rA = 0.35;
  const double rB = 0.4;
  const ExactResult r = exactSignedDistance(P, pose(Eigen::Vector3d::Zero()), P, pose(t), rA, rB);
  BOOST_TEST(std::abs(r.distance - (t.norm() - rA - rB)) <= kAccuracy);
  BOOST_TEST((r.normal - t.normalized()).norm() <= kAccuracy);
  BOOST_TEST(r.distance < 0.0);

  // Coincident spheres: depth rA + rB, some unit normal.
  const ExactResult c = exactSignedDistance(P, pose(t), P, pose(t), rA, rB);
  BOOST_TEST(std::abs(c.distance + rA + rB) <= kAccuracy);
  BOOST_TEST(std::abs(c.normal.norm() - 1.0) <= kAccuracy);
  BOOST_TEST(c.minkowskiVertices == 1);
}

BOOST_AUTO_TEST_CASE(sphere_against_box) {
  const Eigen::Vector3d h(0.5, 0.4, 0.3);
  const ConvexPolytope box = ConvexPolytope::box(2.0 * h);
  const ConvexPolytope point = ConvexPolytope::fromPoints({Eigen::Vector3d::Zero()}, "sphere");
  const double r = 0.2;
  // Centre inside the box, nearest face +y: core depth 0.4 - 0.3 = 0.1.
  ExactResult e =
      exactSignedDistance(box, pose(Eigen::Vector3d::Zero()), point, pose(Eigen::Vector3d(0.1, 0.3, 0.05)), 0.0, r);
  BOOST_TEST(std::abs(e.distance - (-0.1 - r)) <= kAccuracy);
  BOOST_TEST((e.normal - Eigen::Vector3d::UnitY()).norm() <= kAccuracy);
  // Centre outside, nearest the edge (+x, +z).
  const Eigen::Vector3d c(0.5 + 0.3, 0.1, 0.3 + 0.4);
  e = exactSignedDistance(box, pose(Eigen::Vector3d::Zero()), point, pose(c), 0.0, r);
  BOOST_TEST(std::abs(e.distance - (0.5 - r)) <= kAccuracy);
  BOOST_TEST((e.normal - Eigen::Vector3d(0.6, 0.0, 0.8)).norm() <= kAccuracy);
}

BOOST_AUTO_TEST_CASE(tetrahedra_are_optimal) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> off(-0.8, 0.8);
  const ConvexPolytope T =
      ConvexPolytope::fromPoints({{1.0, 1.0, 1.0}, {1.0, -1.0, -1.0}, {-1.0, 1.0, -1.0}, {-1.0, -1.0, 1.0}}, "tetra");
  int overlapping = 0;
  for (int k = 0; k < 50; ++k) {
    const Eigen::Isometry3d X_WA = pose(Eigen::Vector3d::Zero(), randomRotation(rng));
    const Eigen::Isometry3d X_WB = pose(2.0 * Eigen::Vector3d(off(rng), off(rng), off(rng)), randomRotation(rng));
    overlapping += exactSignedDistance(T, X_WA, T, X_WB).distance < 0.0 ? 1 : 0;
    checkOptimal(T, X_WA, T, X_WB, rng);
  }
  BOOST_TEST(overlapping > 5);
  BOOST_TEST(overlapping < 45);
}

BOOST_AUTO_TEST_CASE(random_hulls_are_optimal) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> off(-1.0, 1.0);
  for (int k = 0; k < 30; ++k) {
    const ConvexPolytope A = randomHull(rng, 30, Eigen::Vector3d(1.0, 0.5, 0.3));
    const ConvexPolytope B = randomHull(rng, 25, Eigen::Vector3d(0.4, 0.9, 0.6));
    checkOptimal(A, pose(Eigen::Vector3d(off(rng), off(rng), off(rng)), randomRotation(rng)), B,
                 pose(Eigen::Vector3d(off(rng), off(rng), off(rng)), randomRotation(rng)), rng);
  }
}

BOOST_AUTO_TEST_CASE(coplanar_polygons) {
  const ConvexPolytope S = square(0.5);
  const Eigen::Isometry3d X = pose(Eigen::Vector3d(0.3, -0.1, 0.2),
                                   Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -1, 2).normalized())));
  const Eigen::Vector3d z_W = X.linear() * Eigen::Vector3d::UnitZ();
  // Overlapping in their common plane: depth 0, normal along the plane normal.
  ExactResult r = exactSignedDistance(S, X, S, X * pose(Eigen::Vector3d(0.3, 0.2, 0.0)));
  BOOST_TEST(std::abs(r.distance) <= kAccuracy);
  BOOST_TEST(std::abs(std::abs(r.normal.dot(z_W)) - 1.0) <= kAccuracy);
  // Apart in the plane by 0.25 along x.
  r = exactSignedDistance(S, X, S, X * pose(Eigen::Vector3d(1.25, 0.2, 0.0)));
  BOOST_TEST(std::abs(r.distance - 0.25) <= kAccuracy);
  BOOST_TEST((r.normal - X.linear() * Eigen::Vector3d::UnitX()).norm() <= kAccuracy);
  // Parallel planes 1/3 apart, overlapping in projection.
  r = exactSignedDistance(S, X, S, X * pose(Eigen::Vector3d(0.1, 0.2, -1.0 / 3.0)));
  BOOST_TEST(std::abs(r.distance - 1.0 / 3.0) <= kAccuracy);
  BOOST_TEST((r.normal + z_W).norm() <= kAccuracy);
  // Swapped, the in-plane overlap has the same depth; the side of the plane is arbitrary there.
  const ExactResult b = exactSignedDistance(S, X * pose(Eigen::Vector3d(0.3, 0.2, 0.0)), S, X);
  BOOST_TEST(std::abs(b.distance) <= kAccuracy);
  BOOST_TEST(std::abs(std::abs(b.normal.dot(z_W)) - 1.0) <= kAccuracy);
}

BOOST_AUTO_TEST_CASE(polygon_penetrating_box) {
  const ConvexPolytope box = ConvexPolytope::box(Eigen::Vector3d(2.0, 2.0, 1.0));
  const ConvexPolytope S = square(0.25);
  // A small square standing upright (normal along x), its lower edge 0.2 into the box's top face.
  const Eigen::Isometry3d X_WS = pose(Eigen::Vector3d(0.1, 0.0, 0.5 + 0.25 - 0.2),
                                      Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitY())));
  const ExactResult r = exactSignedDistance(box, pose(Eigen::Vector3d::Zero()), S, X_WS);
  BOOST_TEST(std::abs(r.distance + 0.2) <= kAccuracy);
  BOOST_TEST((r.normal - Eigen::Vector3d::UnitZ()).norm() <= kAccuracy);
}

BOOST_AUTO_TEST_CASE(segments_and_capsules) {
  const ConvexPolytope seg = ConvexPolytope::fromPoints({{-0.5, 0.0, 0.0}, {0.5, 0.0, 0.0}}, "segment");
  // Crossing segments at right angles, 0.3 apart: M is a flat rectangle off the origin.
  const Eigen::Isometry3d X_WB =
      pose(Eigen::Vector3d(0.1, 0.0, 0.3), Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitZ())));
  ExactResult r = exactSignedDistance(seg, pose(Eigen::Vector3d::Zero()), seg, X_WB, 0.1, 0.15);
  BOOST_TEST(std::abs(r.distance - (0.3 - 0.25)) <= kAccuracy);
  BOOST_TEST((r.normal - Eigen::Vector3d::UnitZ()).norm() <= kAccuracy);
  // Collinear overlapping segments: M is a segment through the origin, depth 0 (plus radii).
  r = exactSignedDistance(seg, pose(Eigen::Vector3d::Zero()), seg, pose(Eigen::Vector3d(0.4, 0.0, 0.0)), 0.1, 0.15);
  BOOST_TEST(std::abs(r.distance + 0.25) <= kAccuracy);
  BOOST_TEST(std::abs(r.normal.x()) <= kAccuracy);
  BOOST_TEST(std::abs(r.normal.norm() - 1.0) <= kAccuracy);
  // Parallel segments side by side: M is a segment off the origin.
  r = exactSignedDistance(seg, pose(Eigen::Vector3d::Zero()), seg, pose(Eigen::Vector3d(0.2, 0.0, -0.6)), 0.1, 0.15);
  BOOST_TEST(std::abs(r.distance - (0.6 - 0.25)) <= kAccuracy);
  BOOST_TEST((r.normal + Eigen::Vector3d::UnitZ()).norm() <= kAccuracy);
  // Collinear and apart: the gap along the line.
  r = exactSignedDistance(seg, pose(Eigen::Vector3d::Zero()), seg, pose(Eigen::Vector3d(-1.5, 0.0, 0.0)));
  BOOST_TEST(std::abs(r.distance - 0.5) <= kAccuracy);
  BOOST_TEST((r.normal + Eigen::Vector3d::UnitX()).norm() <= kAccuracy);
}

BOOST_AUTO_TEST_CASE(far_from_origin_matches_near_origin) {
  std::mt19937 rng(2718);
  std::uniform_real_distribution<double> off(-0.7, 0.7);
  const Eigen::Vector3d far(1e4, -1e4, 1e4);
  for (int k = 0; k < 20; ++k) {
    const ConvexPolytope A = randomHull(rng, 20, Eigen::Vector3d(0.5, 0.4, 0.3));
    const ConvexPolytope B = ConvexPolytope::box(Eigen::Vector3d(0.6, 0.4, 2.0 / 3.0));
    const Eigen::Isometry3d X_WA = pose(Eigen::Vector3d::Zero(), randomRotation(rng));
    const Eigen::Isometry3d X_WB = pose(Eigen::Vector3d(off(rng), off(rng), off(rng)), randomRotation(rng));
    const ExactResult near = exactSignedDistance(A, X_WA, B, X_WB);
    const Eigen::Isometry3d shift = pose(far);
    const ExactResult away = exactSignedDistance(A, shift * X_WA, B, shift * X_WB);
    // The poses themselves carry round-off of 1e4 * 1e-16; the answer loses nothing more.
    BOOST_TEST(std::abs(near.distance - away.distance) <= kAccuracy * far.norm());
    BOOST_TEST((near.normal - away.normal).norm() <= kAccuracy * far.norm());
  }
}

BOOST_AUTO_TEST_CASE(swap_gives_same_distance_opposite_normal) {
  std::mt19937 rng(31415);
  std::uniform_real_distribution<double> off(-1.0, 1.0);
  for (int k = 0; k < 30; ++k) {
    const ConvexPolytope A = randomHull(rng, 20, Eigen::Vector3d(1.0, 0.6, 0.4));
    const ConvexPolytope B = randomHull(rng, 15, Eigen::Vector3d(0.5, 0.5, 0.8));
    const Eigen::Isometry3d X_WA = pose(Eigen::Vector3d(off(rng), off(rng), off(rng)), randomRotation(rng));
    const Eigen::Isometry3d X_WB = pose(Eigen::Vector3d(off(rng), off(rng), off(rng)), randomRotation(rng));
    const ExactResult ab = exactSignedDistance(A, X_WA, B, X_WB, 0.05, 0.1);
    const ExactResult ba = exactSignedDistance(B, X_WB, A, X_WA, 0.1, 0.05);
    const double L = pairScale(A, X_WA, B, X_WB);
    BOOST_TEST(std::abs(ab.distance - ba.distance) <= kAccuracy * L);
    BOOST_TEST((ab.normal + ba.normal).norm() <= kAccuracy * L);
  }
}

BOOST_AUTO_TEST_CASE(minkowski_hull_of_boxes_is_a_box) {
  const Eigen::Vector3d hA(0.5, 0.25, 1.0 / 3.0);
  const Eigen::Vector3d hB(0.2, 0.3, 0.1);
  const ConvexPolytope A = ConvexPolytope::box(2.0 * hA);
  const ConvexPolytope B = ConvexPolytope::box(2.0 * hB);
  const Eigen::Vector3d t(0.1, -0.2, 0.05);
  const PairFrame frame = PairFrame::make(A, pose(Eigen::Vector3d::Zero()), B, pose(t));
  const MinkowskiHull M = minkowskiDifferenceHull(A, B, frame);
  BOOST_TEST(M.dimension == 3);
  BOOST_TEST(M.vertices.size() == 8u);
  BOOST_REQUIRE(M.facets.size() == 6u);  // the coplanar triangles are merged
  const Eigen::Vector3d h = hA + hB;
  for (const MinkowskiFacet& f : M.facets) {
    int k = 0;
    f.normal.cwiseAbs().maxCoeff(&k);
    BOOST_TEST(std::abs(std::abs(f.normal[k]) - 1.0) <= kAccuracy);
    BOOST_TEST(f.vertices.size() == 4u);
    const double expected = h[k] + (f.normal[k] > 0.0 ? t[k] : -t[k]);
    BOOST_TEST(std::abs(f.offset - expected) <= kAccuracy);
    // Counter-clockwise seen from outside.
    const Eigen::Vector3d turn = (f.vertices[1] - f.vertices[0]).cross(f.vertices[2] - f.vertices[1]);
    BOOST_TEST(turn.dot(f.normal) > 0.0);
  }
  const ExactResult r = exactSignedDistance(A, pose(Eigen::Vector3d::Zero()), B, pose(t));
  BOOST_TEST(r.minkowskiVertices == 8);
  BOOST_TEST(r.minkowskiFacets == 6);
}

BOOST_AUTO_TEST_CASE(rejects_bad_radii) {
  const ConvexPolytope A = ConvexPolytope::box(Eigen::Vector3d(2, 2, 2));
  const Eigen::Isometry3d X = pose(Eigen::Vector3d::Zero());
  BOOST_CHECK_THROW(exactSignedDistance(A, X, A, X, -0.1, 0.0), std::invalid_argument);
  BOOST_CHECK_THROW(exactSignedDistance(A, X, A, X, 0.0, NAN), std::invalid_argument);
}

BOOST_AUTO_TEST_SUITE_END()
