// Oriented bounding boxes: they contain their pieces, and the separating-axis test never calls
// overlapping boxes separated (checked against GJK on the boxes as polytopes), whether it tests
// all axes, one axis alone, or a remembered axis first.

#include "obb.h"
#include "deepcheck/geometry/signed_distance.h"

#include <boost/test/unit_test.hpp>

#include <random>

using namespace deepcheck;
using namespace deepcheck::checker;

namespace {

Eigen::Matrix3d randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized().toRotationMatrix();
}

/// The 8 corners of the box, as a polytope in the box's frame F.
geometry::ConvexPolytope cornersOf(const Obb& b) {
  std::vector<Eigen::Vector3d> corners;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d s((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1);
    corners.push_back(b.center + b.R * s.cwiseProduct(b.half));
  }
  return geometry::ConvexPolytope::fromPoints(corners, "obb");
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_obb)

BOOST_AUTO_TEST_CASE(box_contains_its_piece) {
  std::mt19937 rng(51);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 50; ++k) {
    // An elongated random point cloud, rotated and offset.
    std::vector<Eigen::Vector3d> points;
    const Eigen::Matrix3d R = randomRotation(rng);
    for (int i = 0; i < 30; ++i)
      points.push_back(R * Eigen::Vector3d(3 * u(rng), u(rng), 0.2 * u(rng)) + Eigen::Vector3d(5, -2, 1));
    const geometry::ConvexPolytope core = geometry::ConvexPolytope::fromPoints(points);
    const double radius = k % 2 ? 0.1 : 0.0;
    const Obb b = Obb::ofPiece(core, radius);
    for (const Eigen::Vector3d& v : core.vertices()) {
      const Eigen::Vector3d local = b.R.transpose() * (v - b.center);
      BOOST_TEST(((local.cwiseAbs() - b.half).array() <= -radius + 1e-12).all());
    }
    BOOST_TEST(std::abs(b.R.determinant() - 1.0) < 1e-12);
  }
}

BOOST_AUTO_TEST_CASE(separated_boxes_never_overlap) {
  std::mt19937 rng(52);
  std::uniform_real_distribution<double> size(0.05, 1.0);
  std::uniform_real_distribution<double> offset(-1.5, 1.5);
  int separatedCount = 0;
  int overlapping = 0;
  for (int k = 0; k < 3000; ++k) {
    Obb a, b;
    a.R = randomRotation(rng);
    b.R = k % 5 == 0 ? a.R : randomRotation(rng);  // parallel axes too
    a.half = Eigen::Vector3d(size(rng), size(rng), size(rng));
    b.half = Eigen::Vector3d(size(rng), size(rng), size(rng));
    a.center = Eigen::Vector3d(offset(rng), offset(rng), offset(rng));
    b.center = Eigen::Vector3d(offset(rng), offset(rng), offset(rng));
    const geometry::ConvexPolytope pa = cornersOf(a);
    const geometry::ConvexPolytope pb = cornersOf(b);
    const bool overlap =
        geometry::overlaps({&pa, 0.0}, Eigen::Isometry3d::Identity(), {&pb, 0.0}, Eigen::Isometry3d::Identity());
    const bool sep = separated(a, b);
    BOOST_TEST(!(overlap && sep), "overlapping boxes reported separated (case " << k << ")");
    separatedCount += sep;
    overlapping += overlap;
    // The test is exact up to its padding: boxes clearly apart are found separated.
    if (!overlap) {
      const geometry::SignedDistanceResult d =
          geometry::signedDistance(pa, Eigen::Isometry3d::Identity(), pb, Eigen::Isometry3d::Identity());
      if (d.distance > 1e-6) BOOST_TEST(sep, "boxes " << d.distance << " apart not separated (case " << k << ")");
    }
    // Symmetric.
    BOOST_TEST(separated(b, a) == sep);
    // One axis alone never separates overlapping boxes, the axis found separates by itself, and
    // the test with a remembered axis gives the same answer whatever axis it remembers.
    const int found = separatingAxis(a, b);
    BOOST_TEST((found >= 0) == sep);
    if (found >= 0) BOOST_TEST(separatedAlong(a, b, found), "axis " << found << " (case " << k << ")");
    for (int axis = 0; axis < kObbAxes; ++axis) {
      if (overlap) BOOST_TEST(!separatedAlong(a, b, axis), "axis " << axis << " (case " << k << ")");
      std::uint8_t hint = static_cast<std::uint8_t>(axis);
      BOOST_TEST(separated(a, b, hint) == sep, "remembered axis " << axis << " (case " << k << ")");
      if (sep) BOOST_TEST(separatedAlong(a, b, hint));
    }
  }
  BOOST_TEST(separatedCount > 300);
  BOOST_TEST(overlapping > 300);
}

BOOST_AUTO_TEST_SUITE_END()
