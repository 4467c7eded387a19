// Body penetration depth (body_depth.h) against a brute-force reference, and on named hard cases.
//
// The reference enumerates, exactly and without search order, every candidate point of the
// complement of the union of the pairwise differences' interiors: for every face plane of every
// difference (built by exact.h's hull of vertex differences, in each pair's own frame) within an
// upper bound R of the origin, the origin's projection on each plane, on each pair of planes' line
// and the vertex of each triple of planes; it keeps those strictly inside no difference and takes
// the nearest. R is the nearest exit of the union along fourteen fixed rays. The nearest point of
// a union of polyhedral cells is the projection of the origin onto the span of at most three of
// its active planes, so the enumeration is complete.

#include "shapes.h"

#include "deepcheck/geometry/body_depth.h"
#include "deepcheck/geometry/exact.h"
#include "deepcheck/geometry/pair_frame.h"
#include "deepcheck/geometry/tolerances.h"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using namespace deepcheck::geometry;
using namespace deepcheck::geometry::testing;
using Eigen::Isometry3d;
using Eigen::Vector3d;

namespace {

/// A body that owns its pieces' polytopes (shared, so copies stay valid).
struct TestBody {
  std::vector<std::shared_ptr<ConvexPolytope>> hulls;
  Body body;

  void add(ConvexPolytope hull, const Isometry3d& X_BP) {
    hulls.push_back(std::make_shared<ConvexPolytope>(std::move(hull)));
    body.pieces.push_back({ConvexShape{hulls.back().get(), 0.0}, X_BP});
  }
  void addBox(const Vector3d& size, const Vector3d& centre) {
    add(ConvexPolytope::box(size), Isometry3d(Eigen::Translation3d(centre)));
  }
  /// The same body with every piece scaled by s about the body origin.
  TestBody scaled(double s) const {
    TestBody out;
    for (std::size_t i = 0; i < hulls.size(); ++i) {
      std::vector<Vector3d> pts;
      for (const Vector3d& v : hulls[i]->vertices()) pts.push_back(s * v);
      Isometry3d X = body.pieces[i].X_BP;
      X.translation() *= s;
      out.add(ConvexPolytope::fromPoints(pts), X);
    }
    return out;
  }
};

Isometry3d translation(const Vector3d& t) { return Isometry3d(Eigen::Translation3d(t)); }

/// v rounded to a multiple of 2^-30: added to an integer vector below 2^22 it stays exact.
Vector3d snap(const Vector3d& v) { return (v * 0x1p30).array().round().matrix() / 0x1p30; }

/// One difference of the reference: face planes n.x <= h, world orientation.
struct RefDifference {
  std::vector<Vector3d> normals;
  std::vector<double> offsets;
  bool strictlyInside(const Vector3d& x, double tol) const {
    for (std::size_t f = 0; f < normals.size(); ++f) {
      if (normals[f].dot(x) - offsets[f] >= -tol) return false;
    }
    return true;
  }
};

struct Reference {
  double distance = 0.0;              ///< signed
  Vector3d point = Vector3d::Zero();  ///< overlapping: the nearest point of the complement
  double tol = 0.0;
  double L = 0.0;
};

Isometry3d pieceWorld(const Body& b, const Isometry3d& X_W, std::size_t i) { return X_W * b.pieces[i].X_BP; }

/// Length scale as the library takes it: the farthest piece vertex from A's origin.
double bodiesScale(const Body& A, const Isometry3d& X_WA, const Body& B, const Isometry3d& X_WB) {
  double L = 0.0;
  for (const auto& [b, X] : {std::pair{&A, X_WA}, std::pair{&B, X_WB}}) {
    for (std::size_t i = 0; i < b->pieces.size(); ++i) {
      const Isometry3d Xp = pieceWorld(*b, X, i);
      for (const Vector3d& v : b->pieces[i].shape.core->vertices()) {
        L = std::max(L, (Xp.linear() * v + (Xp.translation() - X_WA.translation())).norm());
      }
    }
  }
  return L;
}

/// Where the ray from the origin along u leaves the union of the interiors.
double rayLeaves(const std::vector<RefDifference>& diffs, const Vector3d& u, double tol) {
  double t = 0.0;
  for (bool moved = true; moved;) {
    moved = false;
    for (const RefDifference& d : diffs) {
      if (!d.strictlyInside(t * u, tol)) continue;
      double exit = std::numeric_limits<double>::infinity();
      for (std::size_t f = 0; f < d.normals.size(); ++f) {
        const double rate = d.normals[f].dot(u);
        if (rate > 0) exit = std::min(exit, d.offsets[f] / rate);
      }
      t = exit;
      moved = true;
    }
  }
  return t;
}

Reference referenceBodyDistance(const Body& A, const Isometry3d& X_WA, const Body& B, const Isometry3d& X_WB) {
  Reference ref;
  ref.L = bodiesScale(A, X_WA, B, X_WB);
  ref.tol = tol::kBodyMemberRelative * ref.L;
  std::vector<RefDifference> diffs;
  double minDistance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < A.pieces.size(); ++i) {
    for (std::size_t j = 0; j < B.pieces.size(); ++j) {
      const ConvexPolytope& a = *A.pieces[i].shape.core;
      const ConvexPolytope& b = *B.pieces[j].shape.core;
      const Isometry3d Xa = pieceWorld(A, X_WA, i);
      const Isometry3d Xb = pieceWorld(B, X_WB, j);
      minDistance = std::min(minDistance, exactSignedDistance(a, Xa, b, Xb).distance);
      const PairFrame frame = PairFrame::make(a, Xa, b, Xb);
      const MinkowskiHull m = minkowskiDifferenceHull(a, b, frame);
      if (m.dimension < 3) continue;
      RefDifference d;
      for (const MinkowskiFacet& f : m.facets) {
        d.normals.push_back(frame.X_WP.linear() * f.normal);
        d.offsets.push_back(f.offset);
      }
      diffs.push_back(std::move(d));
    }
  }
  bool overlap = false;
  for (const RefDifference& d : diffs) overlap = overlap || d.strictlyInside(Vector3d::Zero(), ref.tol);
  if (!overlap) {
    ref.distance = std::max(minDistance, 0.0);
    return ref;
  }
  double R = std::numeric_limits<double>::infinity();
  for (int dir = 0; dir < 14; ++dir) {
    Vector3d u = dir < 6 ? Vector3d::Unit(dir / 2) * (dir % 2 ? -1.0 : 1.0)
                         : Vector3d((dir & 1) ? 1 : -1, (dir & 2) ? 1 : -1, (dir & 4) ? 1 : -1);
    R = std::min(R, rayLeaves(diffs, u.normalized(), ref.tol));
  }
  std::vector<Vector3d> n;
  std::vector<double> h;
  for (const RefDifference& d : diffs) {
    for (std::size_t f = 0; f < d.normals.size(); ++f) {
      if (std::abs(d.offsets[f]) <= R + ref.tol) {
        n.push_back(d.normals[f]);
        h.push_back(d.offsets[f]);
      }
    }
  }
  double best = R;
  Vector3d bestPoint = Vector3d::Zero();
  auto consider = [&](const Vector3d& x) {
    if (!x.allFinite() || x.norm() >= best) return;
    for (const RefDifference& d : diffs) {
      if (d.strictlyInside(x, ref.tol)) return;
    }
    best = x.norm();
    bestPoint = x;
  };
  const std::size_t P = n.size();
  for (std::size_t a = 0; a < P; ++a) {
    consider(h[a] * n[a]);
    for (std::size_t b = a + 1; b < P; ++b) {
      const double c = n[a].dot(n[b]);
      if (1.0 - c * c < 1e-18) continue;
      consider(((h[a] - c * h[b]) * n[a] + (h[b] - c * h[a]) * n[b]) / (1.0 - c * c));
      for (std::size_t e = b + 1; e < P; ++e) {
        Eigen::Matrix3d M;
        M.row(0) = n[a];
        M.row(1) = n[b];
        M.row(2) = n[e];
        if (std::abs(M.determinant()) < 1e-12) continue;
        consider(M.partialPivLu().solve(Vector3d(h[a], h[b], h[e])));
      }
    }
  }
  ref.distance = -best;
  ref.point = bestPoint;
  return ref;
}

/// Smallest pairwise signed distance of the bodies with B moved by t.
double minPairDistance(const Body& A, const Isometry3d& X_WA, const Body& B, Isometry3d X_WB, const Vector3d& t) {
  X_WB.translation() += t;
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < A.pieces.size(); ++i) {
    for (std::size_t j = 0; j < B.pieces.size(); ++j) {
      d = std::min(d, exactSignedDistance(*A.pieces[i].shape.core, pieceWorld(A, X_WA, i), *B.pieces[j].shape.core,
                                          pieceWorld(B, X_WB, j))
                          .distance);
    }
  }
  return d;
}

/// Checks the result against the reference and the contract; returns the reference.
Reference checkAgainstReference(const TestBody& A, const Isometry3d& X_WA, const TestBody& B, const Isometry3d& X_WB,
                                const std::string& what) {
  BOOST_TEST_CONTEXT(what) {
    const BodySignedDistanceResult r = bodySignedDistance(A.body, X_WA, B.body, X_WB);
    const Reference ref = referenceBodyDistance(A.body, X_WA, B.body, X_WB);
    const double scale = std::max(std::abs(ref.distance), 1e-3 * ref.L);
    BOOST_TEST(std::abs(r.distance - ref.distance) <= 1e-9 * scale,
               "sd " << r.distance << " reference " << ref.distance);
    BOOST_TEST(std::abs(r.normal.norm() - 1.0) <= 1e-12);
    BOOST_TEST((r.pointB - r.pointA - r.distance * r.normal).norm() <= 1e-9 * ref.L);
    BOOST_TEST(r.depthLower <= -r.distance + 1e-12 * ref.L);
    BOOST_TEST(r.depthUpper >= -r.distance - 1e-12 * ref.L);
    if (ref.distance < 0) {
      BOOST_TEST(r.certified);
      BOOST_TEST(std::string(toString(r.status)) == "certified");
      // The push-out separates, and a slightly shorter one does not.
      const double sep = 1e-10 * ref.L;
      BOOST_TEST(minPairDistance(A.body, X_WA, B.body, X_WB, -r.distance * r.normal) >= -sep);
      BOOST_TEST(minPairDistance(A.body, X_WA, B.body, X_WB, -0.999 * r.distance * r.normal) < 0);
    } else {
      BOOST_TEST(std::string(toString(r.status)) == "separated");
    }
    return ref;
  }
  return {};
}

/// A random union of n pieces (random hulls and boxes) around the body origin.
TestBody randomBody(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  TestBody b;
  for (int i = 0; i < n; ++i) {
    const Vector3d semi(0.15 + 0.3 * u(rng), 0.15 + 0.3 * u(rng), 0.1 + 0.3 * u(rng));
    const Isometry3d X = makePose(randomRotation(rng), 0.5 * randomUnit(rng) * u(rng));
    if (u(rng) < 0.3) b.add(ConvexPolytope::box(2.0 * semi), X);
    else b.add(ConvexPolytope::fromPoints(ellipsoidPoints(rng, 5 + static_cast<int>(u(rng) * 5), semi)), X);
  }
  return b;
}

/// A slab of two boxes touching along x = 0 (top at z = 0.1), and a box pressed into it across
/// the seam, penetrating 0.2 with half width 0.15: each pair's depth is sideways, the body's up.
struct SlabCase {
  TestBody box;
  TestBody slab;
  Isometry3d X_WA = translation(Vector3d(0.01, 0.0, 0.1 + 0.15 - 0.2));
  SlabCase() {
    box.addBox(Vector3d(0.3, 0.3, 0.3), Vector3d::Zero());
    slab.addBox(Vector3d(1.0, 1.0, 0.2), Vector3d(-0.5, 0.0, 0.0));
    slab.addBox(Vector3d(1.0, 1.0, 0.2), Vector3d(0.5, 0.0, 0.0));
  }
};

}  // namespace

BOOST_AUTO_TEST_SUITE(body_depth)

BOOST_AUTO_TEST_CASE(names) {
  BOOST_TEST(std::string(toString(BodyDepthStatus::Separated)) == "separated");
  BOOST_TEST(std::string(toString(BodyDepthStatus::Certified)) == "certified");
  BOOST_TEST(std::string(toString(BodyDepthStatus::FaceLimit)) == "face-limit");
  BOOST_TEST(std::string(toString(BodyDepthStatus::PairNotCertified)) == "pair-not-certified");
  BOOST_TEST(std::string(toString(BodyDepthStatus::BuildLimit)) == "build-limit");
}

BOOST_AUTO_TEST_CASE(random_unions_agree_with_the_reference) {
  std::mt19937 rng(20261129);
  std::uniform_int_distribution<int> pieces(2, 6);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int overlapping = 0;
  int separated = 0;
  int bodyDeeper = 0;  // cases where the body depth exceeds the deepest pair's
  for (int c = 0; c < 120; ++c) {
    // Fewer pieces on most cases keep the reference's cubic enumeration quick.
    const int nA = c % 4 == 0 ? pieces(rng) : 2 + c % 2;
    const int nB = c % 4 == 0 ? pieces(rng) : 2 + (c / 2) % 2;
    const TestBody A = randomBody(rng, nA);
    const TestBody B = randomBody(rng, nB);
    const Isometry3d X_WA = makePose(randomRotation(rng), randomUnit(rng) * u(rng));
    const Isometry3d X_WB = makePose(randomRotation(rng), X_WA.translation() + randomUnit(rng) * (0.3 + 1.4 * u(rng)));
    const Reference ref = checkAgainstReference(A, X_WA, B, X_WB, "case " + std::to_string(c));
    if (ref.distance < 0) {
      ++overlapping;
      const BodySignedDistanceResult r = bodySignedDistance(A.body, X_WA, B.body, X_WB);
      if (-r.distance > r.pairDepth * (1 + 1e-6)) ++bodyDeeper;
    } else {
      ++separated;
    }
  }
  BOOST_TEST(overlapping >= 40);
  BOOST_TEST(separated >= 10);
  BOOST_TEST(bodyDeeper >= 10);
}

BOOST_AUTO_TEST_CASE(large_pieces_agree_with_the_reference) {
  // Pieces of 16 to 30 vertices: their differences are built as hulls of all vertex differences,
  // not from their features (body_difference.cpp chooses by size).
  std::mt19937 rng(808);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int overlapping = 0;
  for (int c = 0; c < 12; ++c) {
    TestBody A, B;
    for (TestBody* b : {&A, &B}) {
      for (int i = 0; i < 2; ++i) {
        const Vector3d semi(0.2 + 0.3 * u(rng), 0.2 + 0.3 * u(rng), 0.15 + 0.3 * u(rng));
        b->add(ConvexPolytope::fromPoints(ellipsoidPoints(rng, 16 + static_cast<int>(u(rng) * 14), semi)),
               makePose(randomRotation(rng), 0.4 * randomUnit(rng)));
      }
    }
    const Isometry3d X_WB = makePose(randomRotation(rng), randomUnit(rng) * (0.2 + 0.6 * u(rng)));
    const Reference ref = checkAgainstReference(A, Isometry3d::Identity(), B, X_WB, "large " + std::to_string(c));
    overlapping += ref.distance < 0 ? 1 : 0;
  }
  BOOST_TEST(overlapping >= 6);
}

BOOST_AUTO_TEST_CASE(box_pressed_into_a_two_box_slab_is_pushed_up) {
  const SlabCase s;
  const BodySignedDistanceResult r = bodySignedDistance(s.box.body, s.X_WA, s.slab.body, Isometry3d::Identity());
  // The pairwise answer pushes sideways (into the other slab box); the body's pushes up.
  BOOST_TEST(std::abs(s.X_WA.translation().x() + 0.15 - r.pairDepth) <= 1e-12);
  BOOST_TEST(std::abs(r.pairNormal.x()) >= 1.0 - 1e-12);
  BOOST_TEST(std::abs(r.distance + 0.2) <= 1e-12);
  BOOST_TEST((r.normal - Vector3d(0, 0, -1)).norm() <= 1e-12);
  checkAgainstReference(s.box, s.X_WA, s.slab, Isometry3d::Identity(), "slab");
  // The same under a rigid motion of the whole scene.
  std::mt19937 rng(7);
  for (int i = 0; i < 5; ++i) {
    const Isometry3d X = makePose(randomRotation(rng), randomUnit(rng));
    const BodySignedDistanceResult m = bodySignedDistance(s.box.body, X * s.X_WA, s.slab.body, X);
    BOOST_TEST(std::abs(m.distance + 0.2) <= 1e-12);
    BOOST_TEST((m.normal - X.linear() * Vector3d(0, 0, -1)).norm() <= 1e-12);
  }
}

BOOST_AUTO_TEST_CASE(peg_in_a_u_shaped_hole) {
  TestBody hole;
  hole.addBox(Vector3d(1.0, 1.0, 0.2), Vector3d(0.0, 0.0, -0.1));
  hole.addBox(Vector3d(0.3, 1.0, 0.6), Vector3d(-0.4, 0.0, 0.3));
  hole.addBox(Vector3d(0.3, 1.0, 0.6), Vector3d(0.4, 0.0, 0.3));
  TestBody peg;
  peg.addBox(Vector3d(0.56, 0.4, 0.8), Vector3d::Zero());
  // The peg spans x in [-0.26, 0.30] across a gap [-0.25, 0.25] and sinks 0.05 into the floor:
  // it leaves only upwards, by the walls' height plus the sinking, 0.65.
  const Isometry3d X_WA = translation(Vector3d(0.02, 0.0, -0.05 + 0.4));
  const BodySignedDistanceResult r = bodySignedDistance(peg.body, X_WA, hole.body, Isometry3d::Identity());
  BOOST_TEST(std::abs(r.distance + 0.65) <= 1e-12);
  BOOST_TEST((r.normal - Vector3d(0, 0, -1)).norm() <= 1e-12);
  BOOST_TEST(r.pairDepth <= 0.05 + 1e-12);
  checkAgainstReference(peg, X_WA, hole, Isometry3d::Identity(), "peg");
}

BOOST_AUTO_TEST_CASE(identical_bodies_at_one_pose) {
  std::mt19937 rng(11);
  for (int c = 0; c < 6; ++c) {
    const TestBody A = randomBody(rng, 2 + c % 3);
    const Isometry3d X = makePose(randomRotation(rng), randomUnit(rng));
    const Reference ref = checkAgainstReference(A, X, A, X, "identical " + std::to_string(c));
    BOOST_TEST(ref.distance < 0);
  }
}

BOOST_AUTO_TEST_CASE(a_piece_inside_the_union_changes_nothing) {
  const SlabCase s;
  TestBody slab = s.slab;
  slab.add(ConvexPolytope::box(Vector3d(0.2, 0.3, 0.1)),
           makePose(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vector3d::UnitZ())), Vector3d(0.05, 0.1, 0.0)));
  const BodySignedDistanceResult with = bodySignedDistance(s.box.body, s.X_WA, slab.body, Isometry3d::Identity());
  BOOST_TEST(std::abs(with.distance + 0.2) <= 1e-12);
  checkAgainstReference(s.box, s.X_WA, slab, Isometry3d::Identity(), "inside");
}

BOOST_AUTO_TEST_CASE(touching_bodies_and_continuity_through_contact) {
  const SlabCase s;
  // The box resting on the slab across the seam: sd 0; sunk or lifted by delta: -delta or delta.
  for (const double delta : {0.0, 1e-9, -1e-9, 1e-6, -1e-6}) {
    const Isometry3d X = translation(Vector3d(0.01, 0.0, 0.1 + 0.15 + delta));
    const BodySignedDistanceResult r = bodySignedDistance(s.box.body, X, s.slab.body, Isometry3d::Identity());
    BOOST_TEST(std::abs(r.distance - delta) <= 1e-12, "delta " << delta << " sd " << r.distance);
  }
}

BOOST_AUTO_TEST_CASE(separated_bodies_give_the_smallest_pairwise_distance) {
  std::mt19937 rng(5);
  for (int c = 0; c < 10; ++c) {
    const TestBody A = randomBody(rng, 3);
    const TestBody B = randomBody(rng, 4);
    const Isometry3d X_WA = makePose(randomRotation(rng), Vector3d::Zero());
    const Isometry3d X_WB = makePose(randomRotation(rng), randomUnit(rng) * 3.0);
    const BodySignedDistanceResult r = bodySignedDistance(A.body, X_WA, B.body, X_WB);
    const double expected = minPairDistance(A.body, X_WA, B.body, X_WB, Vector3d::Zero());
    BOOST_TEST(expected > 0);
    BOOST_TEST(std::abs(r.distance - expected) <= 1e-12 * 3.0);
    BOOST_TEST(std::string(toString(r.status)) == "separated");
    BOOST_TEST(r.certified);
  }
}

BOOST_AUTO_TEST_CASE(far_tiny_and_huge) {
  // Far scenes are the near ones moved by an integer vector of length ~1e4, with translations
  // snapped to multiples of 2^-30 so that the move is exact: the far answer must equal the near.
  std::mt19937 rng(99);
  const SlabCase s;
  for (const double scale : {1e-4, 1.0, 1e3}) {
    const TestBody box = s.box.scaled(scale);
    const TestBody slab = s.slab.scaled(scale);
    const Eigen::Quaterniond q = randomRotation(rng);
    const Vector3d far = (randomUnit(rng) * 1e4).array().round().matrix();
    const Isometry3d X_WA = makePose(q, snap(q * (scale * s.X_WA.translation())));
    const Isometry3d X_WB = makePose(q, Vector3d::Zero());
    const BodySignedDistanceResult near = bodySignedDistance(box.body, X_WA, slab.body, X_WB);
    BOOST_TEST(std::abs(near.distance + 0.2 * scale) <= 1e-12 * scale + 4e-9, "scale " << scale);
    BOOST_TEST((near.normal - q * Vector3d(0, 0, -1)).norm() <= 1e-9);
    const BodySignedDistanceResult moved =
        bodySignedDistance(box.body, translation(far) * X_WA, slab.body, translation(far) * X_WB);
    BOOST_TEST(std::abs(moved.distance - near.distance) <= 1e-12 * scale);
    BOOST_TEST((moved.normal - near.normal).norm() <= 1e-12);
  }
  for (int c = 0; c < 12; ++c) {
    const double scale = c % 3 == 0 ? 1e-4 : c % 3 == 1 ? 1e3 : 1.0;
    const TestBody A = randomBody(rng, 2).scaled(scale);
    const TestBody B = randomBody(rng, 3).scaled(scale);
    const Isometry3d X_WA = makePose(randomRotation(rng), Vector3d::Zero());
    const Isometry3d X_WB = makePose(randomRotation(rng), snap(randomUnit(rng) * 0.4 * scale));
    const Reference ref = checkAgainstReference(A, X_WA, B, X_WB, "scaled " + std::to_string(c));
    const Vector3d far = (randomUnit(rng) * 1e4).array().round().matrix();
    const BodySignedDistanceResult moved =
        bodySignedDistance(A.body, translation(far) * X_WA, B.body, translation(far) * X_WB);
    BOOST_TEST(std::abs(moved.distance - ref.distance) <= 1e-9 * std::max(std::abs(ref.distance), 1e-3 * ref.L));
  }
}

BOOST_AUTO_TEST_CASE(flat_pieces) {
  std::mt19937 rng(3);
  const std::vector<Vector3d> square = {{-0.3, -0.3, 0}, {0.3, -0.3, 0}, {0.3, 0.3, 0}, {-0.3, 0.3, 0}};
  for (int c = 0; c < 10; ++c) {
    TestBody A = randomBody(rng, 2);
    A.add(ConvexPolytope::fromPoints(square), makePose(randomRotation(rng), randomUnit(rng) * 0.3));
    TestBody B;
    B.add(ConvexPolytope::fromPoints(square), Isometry3d::Identity());
    B.add(ConvexPolytope::fromPoints(square), makePose(randomRotation(rng), randomUnit(rng) * 0.3));
    B.addBox(Vector3d(0.3, 0.2, 0.25), randomUnit(rng) * 0.3);
    const Isometry3d X_WB = makePose(randomRotation(rng), randomUnit(rng) * 0.3);
    checkAgainstReference(A, Isometry3d::Identity(), B, X_WB, "flat " + std::to_string(c));
  }
  // Two coplanar squares: their difference is flat and never overlaps.
  TestBody P;
  P.add(ConvexPolytope::fromPoints(square), Isometry3d::Identity());
  const BodySignedDistanceResult r =
      bodySignedDistance(P.body, Isometry3d::Identity(), P.body, translation(Vector3d(0.1, 0, 0)));
  BOOST_TEST(std::abs(r.distance) <= 1e-12);
}

BOOST_AUTO_TEST_CASE(swapping_the_bodies_negates_the_normal) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int overlapping = 0;
  for (int c = 0; c < 30; ++c) {
    const TestBody A = randomBody(rng, 3);
    const TestBody B = randomBody(rng, 2);
    const Isometry3d X_WA = makePose(randomRotation(rng), Vector3d::Zero());
    const Isometry3d X_WB = makePose(randomRotation(rng), randomUnit(rng) * (0.3 + u(rng)));
    const BodySignedDistanceResult ab = bodySignedDistance(A.body, X_WA, B.body, X_WB);
    const BodySignedDistanceResult ba = bodySignedDistance(B.body, X_WB, A.body, X_WA);
    BOOST_TEST(std::abs(ab.distance - ba.distance) <= 1e-9 * std::max(std::abs(ab.distance), 1e-3));
    if (std::abs(ab.distance) > 1e-6) BOOST_TEST((ab.normal + ba.normal).norm() <= 1e-6);
    overlapping += ab.distance < 0 ? 1 : 0;
  }
  BOOST_TEST(overlapping >= 10);
}

BOOST_AUTO_TEST_CASE(the_face_cap_returns_a_separating_bracketed_answer) {
  const SlabCase s;
  BodyDepthOptions options;
  options.maxFaces = 1;
  const BodySignedDistanceResult r =
      bodySignedDistance(s.box.body, s.X_WA, s.slab.body, Isometry3d::Identity(), options);
  BOOST_TEST(std::string(toString(r.status)) == "face-limit");
  BOOST_TEST(!r.certified);
  // A verified push-out, at least the true depth 0.2; the bracket holds the true depth.
  BOOST_TEST(-r.distance >= 0.2 - 1e-12);
  BOOST_TEST(r.depthLower <= 0.2 + 1e-12);
  BOOST_TEST(r.depthUpper >= 0.2 - 1e-12);
  BOOST_TEST(minPairDistance(s.box.body, s.X_WA, s.slab.body, Isometry3d::Identity(), -r.distance * r.normal) >=
             -1e-12);
}

BOOST_AUTO_TEST_CASE(the_build_cap_returns_a_separating_bracketed_answer) {
  const SlabCase s;
  BodyDepthOptions options;
  options.maxBuildCost = 0.0;  // no difference can be built: the bounding boxes' separation
  const BodySignedDistanceResult r =
      bodySignedDistance(s.box.body, s.X_WA, s.slab.body, Isometry3d::Identity(), options);
  BOOST_TEST(std::string(toString(r.status)) == "build-limit");
  BOOST_TEST(!r.certified);
  BOOST_TEST(r.differences == 0);
  BOOST_TEST(-r.distance >= 0.2 - 1e-12);
  BOOST_TEST(r.depthLower <= 0.2 + 1e-12);
  BOOST_TEST(r.depthUpper >= 0.2 - 1e-12);
  BOOST_TEST(minPairDistance(s.box.body, s.X_WA, s.slab.body, Isometry3d::Identity(), -r.distance * r.normal) >=
             -1e-12);
  BOOST_TEST((r.pointB - r.pointA - r.distance * r.normal).norm() <= 1e-12);
}

// Random unions under random build caps, from none to more than they need: every answer is
// either the reference depth (certified) or, past the cap, a verified separating translation
// whose bracket holds the reference; and a larger cap never answers worse.
BOOST_AUTO_TEST_CASE(random_unions_under_build_caps_separate_and_bracket_the_reference) {
  std::mt19937 rng(4711);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int capped = 0;
  int exact = 0;
  for (int c = 0; c < 40; ++c) {
    const TestBody A = randomBody(rng, 2 + c % 2);
    const TestBody B = randomBody(rng, 2 + (c / 2) % 2);
    const Isometry3d X_WA = makePose(randomRotation(rng), randomUnit(rng) * u(rng));
    const Isometry3d X_WB = makePose(randomRotation(rng), X_WA.translation() + randomUnit(rng) * (0.3 + 0.6 * u(rng)));
    const Reference ref = referenceBodyDistance(A.body, X_WA, B.body, X_WB);
    if (!(ref.distance < 0)) continue;
    const double depth = -ref.distance;
    double previous = std::numeric_limits<double>::infinity();
    for (double cap : {0.0, 50.0 * u(rng), 200.0 + 400.0 * u(rng), std::numeric_limits<double>::infinity()}) {
      BOOST_TEST_CONTEXT("case " << c << " cap " << cap) {
        BodyDepthOptions options;
        options.maxBuildCost = cap;
        const BodySignedDistanceResult r = bodySignedDistance(A.body, X_WA, B.body, X_WB, options);
        const double tol = 1e-9 * std::max(depth, 1e-3 * ref.L);
        BOOST_TEST(r.depthLower <= depth + tol);
        BOOST_TEST(r.depthUpper >= depth - tol);
        BOOST_TEST(-r.distance >= depth - tol);
        BOOST_TEST(minPairDistance(A.body, X_WA, B.body, X_WB, -r.distance * r.normal) >= -1e-10 * ref.L);
        if (r.status == BodyDepthStatus::BuildLimit) {
          ++capped;
        } else {
          BOOST_TEST(r.certified);
          BOOST_TEST(std::abs(-r.distance - depth) <= tol);
          ++exact;
        }
        if (std::isinf(cap)) BOOST_TEST(std::string(toString(r.status)) == "certified");
        BOOST_TEST(-r.distance <= previous + tol);  // (each cap pays for at least what the smaller did)
        previous = std::min(previous, -r.distance);
      }
    }
  }
  BOOST_TEST(capped >= 10);
  BOOST_TEST(exact >= 20);
}

BOOST_AUTO_TEST_CASE(bad_input_is_rejected_with_a_message) {
  const SlabCase s;
  auto message = [&](const Body& A, const Body& B) {
    try {
      bodySignedDistance(A, Isometry3d::Identity(), B, Isometry3d::Identity());
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  BOOST_TEST(message(Body{}, s.slab.body).find("body A has no pieces") != std::string::npos);
  Body round = s.slab.body;
  round.pieces[1].shape.radius = 0.1;
  BOOST_TEST(message(s.box.body, round).find("body B piece 1 has radius 0.1") != std::string::npos);
  Body hollow = s.slab.body;
  hollow.pieces[0].shape.core = nullptr;
  BOOST_TEST(message(hollow, s.box.body).find("body A piece 0 has no core") != std::string::npos);
  for (double cap : {-1.0, std::numeric_limits<double>::quiet_NaN()}) {
    BodyDepthOptions options;
    options.maxBuildCost = cap;
    try {
      bodySignedDistance(s.box.body, s.X_WA, s.slab.body, Isometry3d::Identity(), options);
      BOOST_ERROR("a build cap of " << cap << " was accepted");
    } catch (const std::invalid_argument& e) {
      BOOST_TEST(std::string(e.what()).find("maxBuildCost must be >= 0") != std::string::npos);
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
