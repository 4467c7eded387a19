// Tests of GJK distance and overlap (geometry/src/gjk.cpp).
//
// The reference is a brute-force distance written here, independent of GJK: for separated convex
// polytopes the distance is the smallest distance between a feature of A and a feature of B
// (vertex-vertex, vertex-edge, vertex-triangle, edge-edge; faces triangulated as fans). Overlap
// and separation are checked by certificates instead: a separating plane from the normal and
// witness points (optimality conditions), a common point from the enclosing simplex.

#include "deepcheck/geometry/gjk.h"
#include "deepcheck/geometry/polytope.h"
#include "deepcheck/geometry/tolerances.h"
#include "shapes.h"

#include <boost/test/unit_test.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

using deepcheck::geometry::ConvexPolytope;
using deepcheck::geometry::GjkCache;
using deepcheck::geometry::GjkResult;
using deepcheck::geometry::GjkStatus;
using deepcheck::geometry::PairFrame;
using deepcheck::geometry::PolytopeKind;
using deepcheck::geometry::testing::randomRotation;
using deepcheck::geometry::testing::randomUnit;
using Eigen::Vector3d;

// Acceptance bands of this suite (relative to the pair length scale or to the distance).
constexpr double kDistanceRelative = 1e-12;  // |d - d_ref| / d_ref for well-separated pairs
constexpr double kWitnessRelative = 1e-12;   // optimality conditions, times the pair scale

std::string statusName(GjkStatus s) { return toString(s); }

// ---------------------------------------------------------------------------------------------
// Brute-force reference

double pointSegment(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  const Vector3d e = b - a;
  const double ee = e.squaredNorm();
  const double s = ee > 0.0 ? std::clamp((p - a).dot(e) / ee, 0.0, 1.0) : 0.0;
  return (a + s * e - p).norm();
}

double segmentSegment(const Vector3d& p0, const Vector3d& p1, const Vector3d& q0, const Vector3d& q1) {
  double best = std::min(
      {pointSegment(p0, q0, q1), pointSegment(p1, q0, q1), pointSegment(q0, p0, p1), pointSegment(q1, p0, p1)});
  // Interior-interior minimum: the closest points of the two lines, from cross products (relative
  // error eps / sin(angle); the textbook a e - b^2 loses twice as many digits). Whatever round-off
  // does to (s, t), two points on the segments never underestimate the minimum; when the lines are
  // so close to parallel that (s, t) is noise, the endpoint distances above are exact enough.
  const Vector3d d1 = p1 - p0;
  const Vector3d d2 = q1 - q0;
  const Vector3d n = d1.cross(d2);
  const double nn = n.squaredNorm();
  if (nn > 0.0) {
    const Vector3d r = q0 - p0;
    const double s = r.cross(d2).dot(n) / nn;
    const double t = r.cross(d1).dot(n) / nn;
    if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0) {
      best = std::min(best, (p0 + s * d1 - q0 - t * d2).norm());
    }
  }
  return best;
}

double pointTriangle(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  double best = std::min({pointSegment(p, a, b), pointSegment(p, b, c), pointSegment(p, c, a)});
  // Projection inside: take it as the convex combination given by the (scaled) barycentric
  // weights, which is a point of the triangle even for a sliver.
  const Vector3d n = (b - a).cross(c - a);
  const double la = n.dot((b - p).cross(c - p));
  const double lb = n.dot((c - p).cross(a - p));
  const double lc = n.dot((a - p).cross(b - p));
  const double sum = la + lb + lc;
  if (la >= 0.0 && lb >= 0.0 && lc >= 0.0 && sum > 0.0) {
    best = std::min(best, ((la * a + lb * b + lc * c) / sum - p).norm());
  }
  return best;
}

/// Vertices, edges and fan triangles of a polytope, vertices mapped into frame P.
struct Features {
  std::vector<Vector3d> v;
  std::vector<std::pair<int, int>> edges;
  std::vector<std::array<int, 3>> tris;
};

Features featuresOf(const ConvexPolytope& P, const std::vector<Vector3d>& inFrameP) {
  Features f;
  f.v = inFrameP;
  if (P.kind() == PolytopeKind::Segment) f.edges.emplace_back(0, 1);
  for (int face = 0; face < P.numFaces(); ++face) {
    const auto verts = P.faceVertices(face);
    const int k = verts.size();
    for (int i = 0; i < k; ++i) {
      const int u = verts[i], w = verts[(i + 1) % k];
      f.edges.emplace_back(std::min(u, w), std::max(u, w));
    }
    for (int i = 1; i + 1 < k; ++i) f.tris.push_back({verts[0], verts[i], verts[i + 1]});
  }
  std::sort(f.edges.begin(), f.edges.end());
  f.edges.erase(std::unique(f.edges.begin(), f.edges.end()), f.edges.end());
  return f;
}

/// Distance between two separated convex polytopes given by their features (frame P).
double bruteForceDistance(const Features& A, const Features& B) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vector3d& x : A.v) {
    for (const Vector3d& y : B.v) best = std::min(best, (x - y).norm());
  }
  for (const auto& [i, j] : A.edges) {
    for (const Vector3d& y : B.v) best = std::min(best, pointSegment(y, A.v[i], A.v[j]));
    for (const auto& [k, l] : B.edges) {
      best = std::min(best, segmentSegment(A.v[i], A.v[j], B.v[k], B.v[l]));
    }
  }
  for (const auto& [k, l] : B.edges) {
    for (const Vector3d& x : A.v) best = std::min(best, pointSegment(x, B.v[k], B.v[l]));
  }
  for (const auto& t : A.tris) {
    for (const Vector3d& y : B.v) best = std::min(best, pointTriangle(y, A.v[t[0]], A.v[t[1]], A.v[t[2]]));
  }
  for (const auto& t : B.tris) {
    for (const Vector3d& x : A.v) best = std::min(best, pointTriangle(x, B.v[t[0]], B.v[t[1]], B.v[t[2]]));
  }
  return best;
}

// ---------------------------------------------------------------------------------------------
// Random shapes and pairs

Eigen::Matrix3d randomRotationMatrix(std::mt19937& rng) { return randomRotation(rng).toRotationMatrix(); }

double logUniform(std::mt19937& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(std::log10(lo), std::log10(hi));
  return std::pow(10.0, u(rng));
}

/// A random hull: n points in a box or on an ellipsoid, semi-axes scale * (1, a, b) with aspect
/// ratios down to 1:100, randomly rotated and placed at `centre` in its own frame.
ConvexPolytope randomHull(std::mt19937& rng, int n, double scale, const Vector3d& centre) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vector3d semi = scale * Vector3d(1.0, logUniform(rng, 0.01, 1.0), logUniform(rng, 0.01, 1.0));
  const Eigen::Matrix3d Q = randomRotationMatrix(rng);
  const bool onSurface = std::uniform_int_distribution<int>(0, 2)(rng) == 0;
  std::vector<Vector3d> pts;
  for (int i = 0; i < n; ++i) {
    const Vector3d x = onSurface ? randomUnit(rng) : Vector3d(u(rng), u(rng), u(rng));
    pts.push_back(Q * semi.cwiseProduct(x) + centre);
  }
  return ConvexPolytope::fromPoints(pts, "random hull");
}

std::vector<Vector3d> verticesA(const ConvexPolytope& A) {
  std::vector<Vector3d> out;
  for (int i = 0; i < A.numVertices(); ++i) out.push_back(PairFrame::vertexA(A, i));
  return out;
}

std::vector<Vector3d> verticesB(const ConvexPolytope& B, const PairFrame& frame) {
  std::vector<Vector3d> out;
  for (int j = 0; j < B.numVertices(); ++j) out.push_back(frame.vertexB(B, j));
  return out;
}

double pairScale(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame) {
  return std::max(A.lengthScale(), B.lengthScale()) + frame.t.norm();
}

/// Places B (rotation R) so that a slab of width `gap` normal to `n` separates it from A, with a
/// random sideways offset: the distance is then at least `gap`.
PairFrame separatedFrame(std::mt19937& rng, const ConvexPolytope& A, const ConvexPolytope& B, const Eigen::Matrix3d& R,
                         const Vector3d& n, double gap) {
  PairFrame frame;
  frame.R = R;
  double hA = -std::numeric_limits<double>::infinity();
  for (const Vector3d& x : verticesA(A)) hA = std::max(hA, n.dot(x));
  double hB = std::numeric_limits<double>::infinity();
  for (int j = 0; j < B.numVertices(); ++j) hB = std::min(hB, n.dot(R * (B.vertex(j) - B.center())));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector3d side = Vector3d(u(rng), u(rng), u(rng));
  side -= n * n.dot(side);
  side *= 0.5 * (A.boundingRadius() + B.boundingRadius());
  frame.t = n * (hA - hB + gap) + side;
  return frame;
}

PairFrame swapped(const PairFrame& frame) {
  PairFrame inv;
  inv.R = frame.R.transpose();
  inv.t = -(frame.R.transpose() * frame.t);
  return inv;
}

/// Checks of a Separated result: witness points are the convex combinations the simplex says,
/// pointB - pointA = distance * normal, and the planes through them normal to `normal` support
/// A and B (optimality conditions of the distance).
void checkWitnesses(const GjkResult& r, const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame) {
  const double L = pairScale(A, B, frame);
  const double tolW = kWitnessRelative * L;
  BOOST_TEST(std::abs(r.normal.norm() - 1.0) < 1e-14);
  BOOST_TEST((r.pointB - r.pointA - r.distance * r.normal).norm() < tolW);
  BOOST_REQUIRE(r.simplexSize >= 1);
  BOOST_REQUIRE(r.simplexSize <= 3);
  Vector3d pA = Vector3d::Zero(), pB = Vector3d::Zero();
  double sum = 0.0;
  for (int i = 0; i < r.simplexSize; ++i) {
    BOOST_TEST(r.weights[i] >= 0.0);
    sum += r.weights[i];
    pA += r.weights[i] * PairFrame::vertexA(A, r.simplexA[i]);
    pB += r.weights[i] * frame.vertexB(B, r.simplexB[i]);
  }
  BOOST_TEST(std::abs(sum - 1.0) < 1e-14);
  BOOST_TEST((pA - r.pointA).norm() < tolW);
  BOOST_TEST((pB - r.pointB).norm() < tolW);
  double worstA = -std::numeric_limits<double>::infinity();
  for (const Vector3d& x : verticesA(A)) worstA = std::max(worstA, r.normal.dot(x - r.pointA));
  double worstB = std::numeric_limits<double>::infinity();
  for (const Vector3d& y : verticesB(B, frame)) worstB = std::min(worstB, r.normal.dot(y - r.pointB));
  BOOST_TEST(worstA <= tolW, "A above its witness plane by " << worstA << " (L = " << L << ")");
  BOOST_TEST(worstB >= -tolW, "B below its witness plane by " << -worstB << " (L = " << L << ")");
}

/// An Overlapping or Touching result carries a common point: the simplex weights combine A's and
/// B's vertices to (nearly) the same point.
void checkCommonPoint(const GjkResult& r, const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame) {
  BOOST_TEST(r.distance == 0.0);
  BOOST_TEST((r.pointB - r.pointA).norm() <= 1e-12 * pairScale(A, B, frame));
}

ConvexPolytope polygonFrom(std::mt19937& rng, int n, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Matrix3d Q = randomRotationMatrix(rng);
  std::vector<Vector3d> pts;
  for (int i = 0; i < n; ++i) pts.push_back(Q * Vector3d(scale * u(rng), scale * u(rng), 0.0));
  return ConvexPolytope::fromPoints(pts, "random polygon");
}

/// A random core of the given kind, of size about `scale`.
ConvexPolytope randomCore(std::mt19937& rng, PolytopeKind kind, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  switch (kind) {
    case PolytopeKind::Point:
      return ConvexPolytope::fromPoints({scale * Vector3d(u(rng), u(rng), u(rng))}, "point");
    case PolytopeKind::Segment:
      return ConvexPolytope::fromPoints(
          {scale * Vector3d(u(rng), u(rng), u(rng)), scale * Vector3d(u(rng), u(rng), u(rng))}, "segment");
    case PolytopeKind::Polygon:
      return polygonFrom(rng, 3 + std::uniform_int_distribution<int>(0, 10)(rng), scale);
    case PolytopeKind::Polyhedron:
      break;
  }
  return randomHull(rng, 4 + std::uniform_int_distribution<int>(0, 30)(rng), scale, Vector3d::Zero());
}

const std::array<PolytopeKind, 4> kAllKinds = {PolytopeKind::Point, PolytopeKind::Segment, PolytopeKind::Polygon,
                                               PolytopeKind::Polyhedron};

/// A point strictly inside face f of A (frame P) and a vertex j of B supporting -normal(f).
Vector3d pointInFace(std::mt19937& rng, const ConvexPolytope& A, int f) {
  std::uniform_real_distribution<double> u(0.2, 1.0);
  const auto verts = A.faceVertices(f);
  Vector3d q = Vector3d::Zero();
  double sum = 0.0;
  for (int v : verts) {
    const double w = u(rng);
    q += w * PairFrame::vertexA(A, v);
    sum += w;
  }
  return q / sum;
}

/// Frame placing B's vertex supporting -n (in P) at the point q.
PairFrame vertexAt(const ConvexPolytope& B, const Eigen::Matrix3d& R, const Vector3d& n, const Vector3d& q) {
  PairFrame frame;
  frame.R = R;
  const int j = B.supportBruteForce(R.transpose() * (-n));
  frame.t = q - R * (B.vertex(j) - B.center());
  return frame;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(gjk)

BOOST_AUTO_TEST_CASE(status_names) {
  BOOST_TEST(std::string(toString(GjkStatus::Separated)) == "Separated");
  BOOST_TEST(std::string(toString(GjkStatus::Overlapping)) == "Overlapping");
  BOOST_TEST(std::string(toString(GjkStatus::Touching)) == "Touching");
  BOOST_TEST(std::string(toString(GjkStatus::MaxIterations)) == "MaxIterations");
}

// Random hulls (4-200 points, aspect ratios to 1:100, sizes 1e-3..1e3, own-frame offsets and
// pair offsets up to 1e4) placed apart by a random slab: distance against the brute force,
// optimality conditions, symmetry under swapping A and B, and the boolean test.
BOOST_AUTO_TEST_CASE(random_hulls_match_brute_force) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int farPairs = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const double scale = logUniform(rng, 1e-3, 1e3);
    const int nA = 4 + static_cast<int>(196 * std::pow(u(rng), 2.0));
    const int nB = 4 + static_cast<int>(196 * std::pow(u(rng), 2.0));
    const Vector3d offA = randomUnit(rng) * logUniform(rng, 1e-3, 1e4);
    const Vector3d offB = randomUnit(rng) * logUniform(rng, 1e-3, 1e4);
    const ConvexPolytope A = randomHull(rng, nA, scale * logUniform(rng, 0.3, 3.0), offA);
    const ConvexPolytope B = randomHull(rng, nB, scale * logUniform(rng, 0.3, 3.0), offB);
    BOOST_REQUIRE(A.kind() == PolytopeKind::Polyhedron);
    BOOST_REQUIRE(B.kind() == PolytopeKind::Polyhedron);
    const double size = std::max(A.boundingRadius(), B.boundingRadius());
    // Mostly gaps of 1 % to 3x the size; one pair in ten is far apart (up to 1e4).
    const bool far = u(rng) < 0.1;
    farPairs += far ? 1 : 0;
    const double gap = far ? logUniform(rng, 10.0 * size, 1e4) : size * logUniform(rng, 1e-2, 3.0);
    const PairFrame frame = separatedFrame(rng, A, B, randomRotationMatrix(rng), randomUnit(rng), gap);

    const GjkResult r = gjkDistance(A, B, frame);
    BOOST_TEST_CONTEXT("trial " << trial << " nA " << A.numVertices() << " nB " << B.numVertices() << " gap " << gap
                                << " size " << size) {
      BOOST_REQUIRE(statusName(r.status) == "Separated");
      const double ref = bruteForceDistance(featuresOf(A, verticesA(A)), featuresOf(B, verticesB(B, frame)));
      BOOST_TEST(ref >= gap * (1.0 - 1e-9));
      const double err = std::abs(r.distance - ref) / ref;
      BOOST_TEST(err <= kDistanceRelative, "distance " << r.distance << " reference " << ref);
      checkWitnesses(r, A, B, frame);

      const GjkResult s = gjkDistance(B, A, swapped(frame));
      BOOST_REQUIRE(statusName(s.status) == "Separated");
      BOOST_TEST(std::abs(s.distance - r.distance) <= kDistanceRelative * ref);
      BOOST_TEST(!gjkOverlap(A, B, frame));
    }
  }
  BOOST_TEST(farPairs > 5);
}

// Every pair of core kinds (point, segment, polygon, polyhedron), separated by a random slab.
BOOST_AUTO_TEST_CASE(all_core_kinds_match_brute_force) {
  std::mt19937 rng(77);
  for (PolytopeKind kindA : kAllKinds) {
    for (PolytopeKind kindB : kAllKinds) {
      for (int trial = 0; trial < 12; ++trial) {
        const double scale = logUniform(rng, 1e-2, 1e2);
        const ConvexPolytope A = randomCore(rng, kindA, scale);
        const ConvexPolytope B = randomCore(rng, kindB, scale);
        BOOST_REQUIRE(A.kind() == kindA);
        BOOST_REQUIRE(B.kind() == kindB);
        const PairFrame frame =
            separatedFrame(rng, A, B, randomRotationMatrix(rng), randomUnit(rng), scale * logUniform(rng, 1e-2, 2.0));
        const GjkResult r = gjkDistance(A, B, frame);
        BOOST_TEST_CONTEXT(toString(kindA) << " vs " << toString(kindB) << " trial " << trial) {
          BOOST_REQUIRE(statusName(r.status) == "Separated");
          const double ref = bruteForceDistance(featuresOf(A, verticesA(A)), featuresOf(B, verticesB(B, frame)));
          BOOST_TEST(std::abs(r.distance - ref) <= kDistanceRelative * ref,
                     "distance " << r.distance << " reference " << ref);
          checkWitnesses(r, A, B, frame);
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(point_point_is_exact) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  for (int trial = 0; trial < 50; ++trial) {
    const ConvexPolytope A = ConvexPolytope::fromPoints({Vector3d(u(rng), u(rng), u(rng))});
    const ConvexPolytope B = ConvexPolytope::fromPoints({Vector3d(u(rng), u(rng), u(rng))});
    PairFrame frame;
    frame.R = randomRotationMatrix(rng);
    frame.t = Vector3d(u(rng), u(rng), u(rng)) / 3.0;
    const GjkResult r = gjkDistance(A, B, frame);
    BOOST_REQUIRE(statusName(r.status) == "Separated");
    BOOST_TEST(r.distance == (frame.vertexB(B, 0) - PairFrame::vertexA(A, 0)).norm());
    BOOST_TEST(r.simplexSize == 1);
    BOOST_TEST(r.weights[0] == 1.0);
  }
}

// Degenerate Minkowski differences: parallel segments, parallel faces, coplanar polygons apart
// in their plane, axis-aligned boxes (many ties and collinear support points).
BOOST_AUTO_TEST_CASE(degenerate_configurations) {
  const double third = 1.0 / 3.0;
  // Parallel segments at distance 2/3, overlapping in projection.
  {
    const ConvexPolytope A = ConvexPolytope::fromPoints({Vector3d(0, 0, 0), Vector3d(1, 0, 0)});
    const ConvexPolytope B = ConvexPolytope::fromPoints({Vector3d(0, 0, 0), Vector3d(1, 0, 0)});
    PairFrame frame;
    frame.t = Vector3d(third, 2 * third, 0);
    const GjkResult r = gjkDistance(A, B, frame);
    BOOST_REQUIRE(statusName(r.status) == "Separated");
    BOOST_TEST(std::abs(r.distance - 2 * third) < 1e-15);
    checkWitnesses(r, A, B, frame);
  }
  // Boxes face to face with a gap of 1/3, sideways offsets, in random common rotations.
  std::mt19937 rng(11);
  const ConvexPolytope box1 = ConvexPolytope::box(Vector3d(2 * third, 1.0, 0.4));
  const ConvexPolytope box2 = ConvexPolytope::box(Vector3d(1.4, 2 * third, 0.2));
  for (int trial = 0; trial < 40; ++trial) {
    PairFrame frame;
    const Vector3d sideways = trial < 20 ? Vector3d(0, 0.1 * trial / 20.0, 0) : Vector3d(0, 0.1, 0.05);
    frame.t = Vector3d(third + 0.7 + third, 0, 0) + sideways;
    const GjkResult r = gjkDistance(box1, box2, frame);
    BOOST_REQUIRE(statusName(r.status) == "Separated");
    BOOST_TEST(std::abs(r.distance - third) < 1e-15);
    checkWitnesses(r, box1, box2, frame);
    // Same, in a rotated pair frame: rotate both boxes by Q, i.e. A's frame is rotated: use
    // rotated copies of the boxes built from their points.
    const Eigen::Matrix3d Q = randomRotationMatrix(rng);
    std::vector<Vector3d> p1, p2;
    for (const Vector3d& x : box1.vertices()) p1.push_back(Q * x);
    for (const Vector3d& x : box2.vertices()) p2.push_back(Q * x);
    const ConvexPolytope A = ConvexPolytope::fromPoints(p1);
    const ConvexPolytope B = ConvexPolytope::fromPoints(p2);
    PairFrame rotated;
    rotated.t = Q * frame.t;
    const GjkResult q = gjkDistance(A, B, rotated);
    BOOST_REQUIRE(statusName(q.status) == "Separated");
    BOOST_TEST(std::abs(q.distance - third) < 1e-14);
    checkWitnesses(q, A, B, rotated);
  }
  // Coplanar polygons, apart within their common plane.
  for (int trial = 0; trial < 20; ++trial) {
    const ConvexPolytope A = polygonFrom(rng, 3 + trial % 7, 1.0);
    std::vector<Vector3d> pts;
    for (const Vector3d& x : A.vertices()) pts.push_back(x);
    const ConvexPolytope B = ConvexPolytope::fromPoints(pts);
    const Vector3d inPlane = A.faceNormal(0).cross(randomUnit(rng)).normalized();
    PairFrame frame;
    frame.t = inPlane * (2.0 * A.boundingRadius() + 0.25);
    const GjkResult r = gjkDistance(A, B, frame);
    BOOST_REQUIRE(statusName(r.status) == "Separated");
    const double ref = bruteForceDistance(featuresOf(A, verticesA(A)), featuresOf(B, verticesB(B, frame)));
    BOOST_TEST(std::abs(r.distance - ref) <= kDistanceRelative * ref);
    checkWitnesses(r, A, B, frame);
  }
}

// Near contact between nearly parallel features, where the exact distance is known by
// construction: the simplex is a sliver and the support choice is decided by round-off.
// (1) Two segments in horizontal planes z = 0 and z = d whose projections cross at a small angle:
// the distance is d. (2) A box slightly tilted above another, its lowest corner at height d over
// the interior of the top face: the distance is d. The whole scene is rotated at random.
BOOST_AUTO_TEST_CASE(near_contact_nearly_parallel) {
  std::mt19937 rng(97);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Matrix3d Q = randomRotationMatrix(rng);
    const double d = logUniform(rng, 1e-9, 1e-1);
    const double angle = logUniform(rng, 1e-12, 1e-2);
    {
      const double half = logUniform(rng, 0.3, 2.0);
      const Vector3d dir(std::cos(angle), std::sin(angle), 0.0);
      const ConvexPolytope A = ConvexPolytope::fromPoints({Q * Vector3d(-1, 0, 0), Q * Vector3d(1, 0, 0)});
      const ConvexPolytope B = ConvexPolytope::fromPoints({Q * (half * dir), Q * (-half * dir)});
      PairFrame frame;
      frame.t = Q * Vector3d(0.8 * u(rng), 0.0, d);
      const GjkResult r = gjkDistance(A, B, frame);
      BOOST_REQUIRE(statusName(r.status) == "Separated");
      const double err = std::abs(r.distance - d) / pairScale(A, B, frame);
      BOOST_TEST(err < 1e-14, "segments: distance " << r.distance << " expected " << d);
    }
    {
      const ConvexPolytope A = ConvexPolytope::box(Vector3d(2.0, 1.4, 0.6));
      const ConvexPolytope box = ConvexPolytope::box(Vector3d(0.8, 1.0, 0.4));
      const Eigen::Matrix3d tilt =
          Eigen::AngleAxisd(angle, Vector3d(u(rng), u(rng), 0.0).normalized()).toRotationMatrix();
      const int low = box.supportBruteForce(tilt.transpose() * Vector3d(0, 0, -1));
      const Vector3d target(0.5 * u(rng), 0.3 * u(rng), 0.3 + d);
      // Rotate the scene by Q: A's vertices and the pose of B.
      std::vector<Vector3d> pa;
      for (const Vector3d& x : A.vertices()) pa.push_back(Q * x);
      const ConvexPolytope QA = ConvexPolytope::fromPoints(pa);
      PairFrame frame;
      frame.R = Q * tilt;
      frame.t = Q * (target - tilt * (box.vertex(low) - box.center()));
      const GjkResult r = gjkDistance(QA, box, frame);
      BOOST_REQUIRE(statusName(r.status) == "Separated");
      const double err = std::abs(r.distance - d) / pairScale(QA, box, frame);
      BOOST_TEST(err < 1e-14, "boxes: distance " << r.distance << " expected " << d << " angle " << angle);
    }
  }
}

// B's vertex placed inside A (between A's centroid and a boundary point): overlapping.
BOOST_AUTO_TEST_CASE(overlapping_pairs) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(0.0, 0.9);
  for (int trial = 0; trial < 100; ++trial) {
    const double scale = logUniform(rng, 1e-3, 1e3);
    const ConvexPolytope A = randomHull(rng, 4 + trial, scale, Vector3d::Zero());
    const ConvexPolytope B =
        randomHull(rng, 4 + (trial * 7) % 100, scale * logUniform(rng, 0.1, 10.0), Vector3d::Zero());
    const Vector3d n = randomUnit(rng);
    const Vector3d boundary = PairFrame::vertexA(A, A.supportBruteForce(n));
    const PairFrame frame = vertexAt(B, randomRotationMatrix(rng), n, u(rng) * boundary);
    const GjkResult r = gjkDistance(A, B, frame);
    BOOST_TEST_CONTEXT("trial " << trial) {
      BOOST_TEST(statusName(r.status) == "Overlapping");
      checkCommonPoint(r, A, B, frame);
      BOOST_TEST(gjkOverlap(A, B, frame));
    }
  }
}

// Deep overlaps whose supports are symmetric: the origin lands on a lower-dimensional simplex.
BOOST_AUTO_TEST_CASE(symmetric_deep_overlaps) {
  const ConvexPolytope box = ConvexPolytope::box(Vector3d(2.0, 2.0, 2.0));
  const ConvexPolytope flat = ConvexPolytope::box(Vector3d(2.0, 1.0, 0.5));
  PairFrame same;
  GjkResult r = gjkDistance(box, box, same);
  BOOST_TEST(statusName(r.status) == "Overlapping");
  checkCommonPoint(r, box, box, same);
  r = gjkDistance(flat, flat, same);
  BOOST_TEST(statusName(r.status) == "Overlapping");
  PairFrame turned;
  turned.R = Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitZ()).toRotationMatrix();
  r = gjkDistance(box, flat, turned);
  BOOST_TEST(statusName(r.status) == "Overlapping");
  PairFrame shifted;
  shifted.t = Vector3d(0.5, 0.0, 0.0);
  r = gjkDistance(box, box, shifted);
  BOOST_TEST(statusName(r.status) == "Overlapping");
  BOOST_TEST(gjkOverlap(box, box, same));
  BOOST_TEST(gjkOverlap(box, flat, turned));
}

// B's vertex on A's face (interior point), edge or vertex, with B on the outside: touching. Moving
// B off the face by delta gives distance delta; into it, an overlap.
BOOST_AUTO_TEST_CASE(touching_contacts) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(0.2, 0.8);
  int faceCases = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const double scale = logUniform(rng, 1e-2, 1e2);
    const ConvexPolytope A = randomHull(rng, 8 + trial, scale, Vector3d::Zero());
    const ConvexPolytope B = randomHull(rng, 8 + (3 * trial) % 50, scale, Vector3d::Zero());
    const Eigen::Matrix3d R = randomRotationMatrix(rng);
    const int f = std::uniform_int_distribution<int>(0, A.numFaces() - 1)(rng);
    const auto verts = A.faceVertices(f);
    Vector3d q, n;
    switch (trial % 3) {
      case 0: {  // vertex on face
        q = pointInFace(rng, A, f);
        n = A.faceNormal(f);
        break;
      }
      case 1: {  // vertex on edge: the edge (v0, v1) of face f and the normal between its faces
        const int v0 = verts[0], v1 = verts[1];
        const double s = u(rng);
        q = (1 - s) * PairFrame::vertexA(A, v0) + s * PairFrame::vertexA(A, v1);
        int other = -1;
        for (int g = 0; g < A.numFaces(); ++g) {
          const auto gv = A.faceVertices(g);
          for (int i = 0; i < gv.size(); ++i) {
            if (gv[i] == v1 && gv[(i + 1) % gv.size()] == v0) other = g;
          }
        }
        BOOST_REQUIRE(other >= 0);
        n = (A.faceNormal(f) + A.faceNormal(other)).normalized();
        break;
      }
      default: {  // vertex on vertex: the mean of the vertex's face normals
        const int v = verts[0];
        q = PairFrame::vertexA(A, v);
        n = Vector3d::Zero();
        for (int g : A.vertexFaces(v)) n += A.faceNormal(g);
        n.normalize();
        break;
      }
    }
    const PairFrame frame = vertexAt(B, R, n, q);
    BOOST_TEST_CONTEXT("trial " << trial) {
      const GjkResult r = gjkDistance(A, B, frame);
      BOOST_TEST(statusName(r.status) == "Touching");
      checkCommonPoint(r, A, B, frame);
      BOOST_TEST(gjkOverlap(A, B, frame));
      const double delta = 1e-4 * scale;
      PairFrame apart = frame;
      apart.t += delta * n;
      const GjkResult s = gjkDistance(A, B, apart);
      BOOST_REQUIRE(statusName(s.status) == "Separated");
      BOOST_TEST(std::abs(s.distance - delta) <= 1e-9 * delta);
      checkWitnesses(s, A, B, apart);
      BOOST_TEST(!gjkOverlap(A, B, apart));
      if (trial % 3 == 0) {
        ++faceCases;
        PairFrame into = frame;
        into.t -= delta * n;
        BOOST_TEST(statusName(gjkDistance(A, B, into).status) == "Overlapping");
        BOOST_TEST(gjkOverlap(A, B, into));
      }
    }
  }
  BOOST_TEST(faceCases == 20);
}

// Lower-dimensional overlaps have no penetration depth: crossing segments, a point on a polygon,
// coplanar overlapping polygons (M is flat). A segment piercing a polygon does have one (M is a
// prism around the origin): overlapping.
BOOST_AUTO_TEST_CASE(flat_overlaps_are_touching) {
  std::mt19937 rng(53);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d Q = randomRotationMatrix(rng);
    const Vector3d e1 = Q.col(0), e2 = Q.col(1), e3 = Q.col(2);
    const double third = 1.0 / 3.0;
    const ConvexPolytope segA = ConvexPolytope::fromPoints({-e1, e1});
    const ConvexPolytope segB = ConvexPolytope::fromPoints({-e2 * third, e2});
    const ConvexPolytope square = ConvexPolytope::fromPoints({e1 + e2, e1 - e2, -e1 + e2, -e1 - e2});
    const ConvexPolytope point = ConvexPolytope::fromPoints({third * e1 + 0.2 * e2});
    const ConvexPolytope normalSeg = ConvexPolytope::fromPoints({-e3, 0.5 * e3});
    BOOST_REQUIRE(square.kind() == PolytopeKind::Polygon);
    PairFrame frame;
    frame.t = 0.1 * e1 - 0.05 * e2;  // B's centroid offset, inside the overlap region
    const std::vector<std::pair<const ConvexPolytope*, const ConvexPolytope*>> cases = {
        {&segA, &segB}, {&square, &point}, {&square, &square}};
    for (const auto& [A, B] : cases) {
      const GjkResult r = gjkDistance(*A, *B, frame);
      BOOST_TEST(statusName(r.status) == "Touching",
                 "trial " << trial << ": " << toString(A->kind()) << " vs " << toString(B->kind()));
      checkCommonPoint(r, *A, *B, frame);
      BOOST_TEST(gjkOverlap(*A, *B, frame));
    }
    for (const auto& [A, B] : {std::make_pair(&square, &normalSeg), std::make_pair(&normalSeg, &square)}) {
      const GjkResult r = gjkDistance(*A, *B, frame);
      BOOST_TEST(statusName(r.status) == "Overlapping");
      checkCommonPoint(r, *A, *B, frame);
    }
  }
}

// A pair moving in small steps, from apart to overlapping: the warm-started query gives the cold
// answer, and needs no more iterations in total.
BOOST_AUTO_TEST_CASE(warm_start_matches_cold) {
  std::mt19937 rng(61);
  long coldIterations = 0, warmIterations = 0;
  int separated = 0, overlapping = 0;
  for (int path = 0; path < 8; ++path) {
    const ConvexPolytope A = randomHull(rng, 30 + 20 * path, 1.0, Vector3d::Zero());
    const ConvexPolytope B = randomHull(rng, 150 - 15 * path, 0.7, Vector3d::Zero());
    const Vector3d start = randomUnit(rng) * 3.0;
    const Vector3d axis = randomUnit(rng);
    const Eigen::Matrix3d R0 = randomRotationMatrix(rng);
    GjkCache cache, overlapCache;
    for (int step = 0; step <= 100; ++step) {
      const double s = step / 100.0;
      PairFrame frame;
      frame.R = R0 * Eigen::AngleAxisd(0.8 * s, axis).toRotationMatrix();
      frame.t = (1.0 - s) * start;
      const GjkResult cold = gjkDistance(A, B, frame);
      const GjkResult warm = gjkDistance(A, B, frame, &cache);
      BOOST_TEST_CONTEXT("path " << path << " step " << step) {
        BOOST_TEST(statusName(warm.status) == statusName(cold.status));
        BOOST_TEST(std::abs(warm.distance - cold.distance) <= kDistanceRelative * cold.distance + 1e-15);
        if (warm.status == GjkStatus::Separated) checkWitnesses(warm, A, B, frame);
        BOOST_TEST(gjkOverlap(A, B, frame, &overlapCache) == (cold.status != GjkStatus::Separated));
      }
      BOOST_TEST(cache.direction.squaredNorm() > 0.0);
      coldIterations += cold.iterations;
      warmIterations += warm.iterations;
      (cold.status == GjkStatus::Separated ? separated : overlapping) += 1;
    }
  }
  BOOST_TEST(separated > 100);
  BOOST_TEST(overlapping > 100);
  BOOST_TEST(warmIterations <= coldIterations);
}

// Random placements, about half overlapping: the boolean test agrees with the distance query.
BOOST_AUTO_TEST_CASE(overlap_agrees_with_distance) {
  std::mt19937 rng(71);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int overlaps = 0;
  const int trials = 400;
  for (int trial = 0; trial < trials; ++trial) {
    const double scale = logUniform(rng, 1e-2, 1e2);
    const ConvexPolytope A = randomHull(rng, 4 + trial % 60, scale, Vector3d::Zero());
    const ConvexPolytope B = randomHull(rng, 4 + (trial * 13) % 60, scale, Vector3d::Zero());
    PairFrame frame;
    frame.R = randomRotationMatrix(rng);
    frame.t = randomUnit(rng) * scale * 0.8 * std::cbrt(u(rng));
    const GjkResult r = gjkDistance(A, B, frame);
    BOOST_REQUIRE(statusName(r.status) != "MaxIterations");
    const bool apart = r.status == GjkStatus::Separated;
    BOOST_TEST_CONTEXT("trial " << trial << " " << toString(r.status)) {
      BOOST_TEST(gjkOverlap(A, B, frame) == !apart);
      if (apart) {
        BOOST_TEST(r.distance > 0.0);
        checkWitnesses(r, A, B, frame);
      } else {
        checkCommonPoint(r, A, B, frame);
      }
    }
    overlaps += apart ? 0 : 1;
  }
  BOOST_TEST(overlaps > 0.3 * trials);
  BOOST_TEST(overlaps < 0.7 * trials);
}

// gjkBound against the distance, on random pairs from overlapping to apart, with thresholds
// below, around and above the distance: `within` exactly when gjkWithin(near) says so; otherwise a
// lower bound above `near`, at most the distance, and within tol::kGjkBoundGap of it unless it
// already exceeds `far`; warm (a cache kept along the trials of a pair) or cold.
BOOST_AUTO_TEST_CASE(bound_brackets_the_distance) {
  std::mt19937 rng(2611);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int lowers = 0, withins = 0, beyondFar = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const double scale = logUniform(rng, 1e-3, 1e3);
    const ConvexPolytope A = randomHull(rng, 4 + trial % 50, scale, randomUnit(rng) * scale * u(rng));
    const ConvexPolytope B = randomHull(rng, 4 + (trial * 7) % 50, scale, Vector3d::Zero());
    PairFrame frame;
    frame.R = randomRotationMatrix(rng);
    frame.t = randomUnit(rng) * scale * 3.0 * u(rng);
    const GjkResult r = gjkDistance(A, B, frame);
    BOOST_REQUIRE(statusName(r.status) != "MaxIterations");
    const double d = r.distance;
    GjkCache cache;
    for (int k = 0; k < 4; ++k) {
      const double near = d * logUniform(rng, 1e-3, 2.0) * (k == 0 ? 0.0 : 1.0);
      const double far = near + scale * logUniform(rng, 1e-3, 3.0);
      const deepcheck::geometry::GjkBound b = gjkBound(A, B, frame, near, far, k % 2 == 0 ? &cache : nullptr);
      BOOST_TEST_CONTEXT("trial " << trial << " distance " << d << " near " << near << " far " << far) {
        BOOST_TEST(b.within == (near > 0.0 ? gjkWithin(A, B, frame, near) : gjkOverlap(A, B, frame)));
        if (b.within) {
          ++withins;
          continue;
        }
        ++lowers;
        BOOST_TEST(b.lower > near);
        BOOST_TEST(b.lower <= d * (1.0 + kDistanceRelative));
        if (b.lower > far) {
          ++beyondFar;
        } else {
          BOOST_TEST(b.lower >= (1.0 - deepcheck::geometry::tol::kGjkBoundGap) * d * (1.0 - kDistanceRelative));
        }
      }
    }
  }
  BOOST_TEST(withins > 100);
  BOOST_TEST(lowers > 100);
  BOOST_TEST(beyondFar > 20);
}

// The tetrahedron a run that enclosed the origin leaves in the cache: at the same pose it encloses
// the origin again; along a motion it is re-tested at the next pose, and whenever it still
// encloses the origin the pair overlaps (a certificate: it never claims a separated pair).
BOOST_AUTO_TEST_CASE(enclosing_tetrahedron_certifies_overlap_at_nearby_poses) {
  std::mt19937 rng(67);
  int confirmed = 0, notConfirmed = 0;
  for (int path = 0; path < 12; ++path) {
    const ConvexPolytope A = randomHull(rng, 8 + 15 * path, 1.0, Vector3d::Zero());
    const ConvexPolytope B = path % 3 == 0 ? ConvexPolytope::box(Vector3d(1.8, 0.8, 1.2))
                                           : randomHull(rng, 120 - 9 * path, 0.7, Vector3d::Zero());
    const Vector3d start = randomUnit(rng) * 2.5;
    const Vector3d axis = randomUnit(rng);
    const Eigen::Matrix3d R0 = randomRotationMatrix(rng);
    GjkCache cache;
    for (int step = 0; step <= 200; ++step) {
      const double s = step / 100.0;  // through B and out the other side
      PairFrame frame;
      frame.R = R0 * Eigen::AngleAxisd(0.8 * s, axis).toRotationMatrix();
      frame.t = (1.0 - s) * start;
      const bool apart = gjkDistance(A, B, frame).status == GjkStatus::Separated;
      BOOST_TEST_CONTEXT("path " << path << " step " << step) {
        if (cache.enclosed && deepcheck::geometry::enclosesOrigin(A, B, frame, cache.enclosing)) {
          BOOST_TEST(!apart);
          ++confirmed;
        } else if (cache.enclosed && !apart) {
          ++notConfirmed;
        }
        const bool hit = gjkOverlap(A, B, frame, &cache);
        BOOST_TEST(hit == !apart);
        if (apart) BOOST_TEST(!cache.enclosed);
        if (cache.enclosed) BOOST_TEST(deepcheck::geometry::enclosesOrigin(A, B, frame, cache.enclosing));
      }
    }
  }
  BOOST_TEST(confirmed > 300);    // the usual case along a motion
  BOOST_TEST(notConfirmed > 10);  // and a certificate only: then GJK decides
}

// A cache from another pair (hints out of range, any direction) is harmless, and is updated.
BOOST_AUTO_TEST_CASE(foreign_cache_is_harmless) {
  std::mt19937 rng(83);
  const ConvexPolytope A = randomHull(rng, 20, 1.0, Vector3d::Zero());
  const ConvexPolytope B = randomHull(rng, 20, 1.0, Vector3d::Zero());
  const PairFrame frame = separatedFrame(rng, A, B, randomRotationMatrix(rng), randomUnit(rng), 0.5);
  const GjkResult cold = gjkDistance(A, B, frame);
  GjkCache cache;
  cache.direction = Vector3d(-1.0, 2.0, 0.5);
  cache.hintA = 1000;
  cache.hintB = -3;
  const GjkResult warm = gjkDistance(A, B, frame, &cache);
  BOOST_REQUIRE(statusName(warm.status) == "Separated");
  BOOST_TEST(std::abs(warm.distance - cold.distance) <= kDistanceRelative * cold.distance);
  BOOST_TEST(cache.hintA >= 0);
  BOOST_TEST(cache.hintA < A.numVertices());
  BOOST_TEST(cache.hintB >= 0);
  BOOST_TEST(cache.hintB < B.numVertices());
  BOOST_TEST(cache.direction.normalized().dot(cold.normal) > 0.999);
}

BOOST_AUTO_TEST_SUITE_END()
