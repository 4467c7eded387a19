// The supported numeric range (input_range.h): its boundaries (just inside accepted and answered
// correctly, just outside rejected with a message naming the value), and correct answers for
// tiny, huge and far-from-origin shapes inside it, by DEEP/GJK and by the exact reference.
//
// Oracle: two axis-aligned cubes of half size s, B centred at (g, 0, 0) from A, optionally turned
// by 45 degrees about z. Apart, sd = g - 2s (turned: g - s - s*sqrt(2)); overlapping, the depth
// is the smaller overlap along x (the faces there are the closest pair), so sd = g - 2s too.

#include "deepcheck/geometry/exact.h"
#include "deepcheck/geometry/input_range.h"
#include "deepcheck/geometry/signed_distance.h"

#include <boost/test/unit_test.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

using namespace deepcheck::geometry;

namespace {

/// Relative accuracy demanded at any scale: the answers carry round-off of a few ulps of the
/// pair's length scale, as at unit scale.
constexpr double kRelative = 1e-12;

Eigen::Isometry3d at(const Eigen::Vector3d& t, double yaw = 0.0) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = t;
  return X;
}

/// The corners of the cube of half size s centred at c (in the polytope's own frame).
std::vector<Eigen::Vector3d> cube(double s, const Eigen::Vector3d& c = Eigen::Vector3d::Zero()) {
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 8; ++i) {
    pts.push_back(c + s * Eigen::Vector3d((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1));
  }
  return pts;
}

/// Checks DEEP/GJK and the exact reference on A at X_WA, B at X_WB against `expected` (normal +x
/// of the world), to kRelative of `scale`.
void checkPair(const ConvexPolytope& A, const Eigen::Isometry3d& X_WA, const ConvexPolytope& B,
               const Eigen::Isometry3d& X_WB, double expected, double scale) {
  const SignedDistanceResult r = signedDistance(A, X_WA, B, X_WB);
  BOOST_TEST(std::abs(r.distance - expected) <= kRelative * scale,
             "DEEP/GJK sd " << r.distance << ", expected " << expected << " (scale " << scale << ")");
  BOOST_TEST((r.normal - Eigen::Vector3d::UnitX()).norm() <= 1e-9, "normal " << r.normal.transpose());
  const ExactResult e = exactSignedDistance(A, X_WA, B, X_WB);
  BOOST_TEST(std::abs(e.distance - expected) <= kRelative * scale,
             "exact sd " << e.distance << ", expected " << expected << " (scale " << scale << ")");
  BOOST_TEST((e.normal - Eigen::Vector3d::UnitX()).norm() <= 1e-9, "normal " << e.normal.transpose());
}

/// The cube pair at scale s: apart (gap 3s), overlapping (gap 1.5s) and B turned by 45 degrees,
/// with A at `offset` (a pose translation) and the cubes' points given about `local` (in their
/// own frames), so that the same geometry is tried with large pose and large vertex coordinates.
void checkCubesAtScale(double s, const Eigen::Vector3d& offset = Eigen::Vector3d::Zero(),
                       const Eigen::Vector3d& local = Eigen::Vector3d::Zero()) {
  BOOST_TEST_CONTEXT("scale " << s << ", offset " << offset.transpose() << ", local " << local.transpose()) {
    const ConvexPolytope A = ConvexPolytope::fromPoints(cube(s, local));
    const ConvexPolytope B = ConvexPolytope::fromPoints(cube(s, local));
    // Round-off of the positions themselves: far from the origin, only the digits below the
    // position's magnitude carry the geometry.
    const double scale = s + 1e-3 * (offset.norm() + local.norm());
    const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
    const Eigen::Isometry3d X_WA = at(offset - local);
    checkPair(A, X_WA, B, at(offset - local + 3 * s * x), s, scale);
    checkPair(A, X_WA, B, at(offset - local + 1.5 * s * x), -0.5 * s, scale);
    if (local.isZero()) {
      checkPair(A, X_WA, B, at(offset + 3 * s * x, M_PI / 4), (2 - std::sqrt(2.0)) * s, scale);
    }
  }
}

template <typename F>
void checkRejected(F f, const std::string& mention) {
  try {
    f();
    BOOST_ERROR("accepted; expected an error mentioning '" << mention << "'");
  } catch (const std::invalid_argument& e) {
    BOOST_TEST(std::string(e.what()).find(mention) != std::string::npos,
               "message '" << e.what() << "' should mention '" << mention << "'");
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(input_range)

BOOST_AUTO_TEST_CASE(coordinate_limit_is_inclusive) {
  const double max = range::kMaxCoordinate;
  const double beyond = std::nextafter(max, std::numeric_limits<double>::infinity());
  const ConvexPolytope ok = ConvexPolytope::fromPoints({{0, 0, 0}, {0, -max, 0}, {max, 0, 0}});
  BOOST_TEST(ok.numVertices() == 3);
  checkRejected(
      [&] {
        ConvexPolytope::fromPoints({{0, 0, 0}, {0, -beyond, 0}}, "shape 'a'");
      },
      "shape 'a': point 1 coordinate y = -1.0000000000000003e+50 is out of range (|value| > 1e+50)");
  checkRejected([&] { ConvexPolytope::fromPoints({{0, 0, 0}, {0, 0, 1e300}}); }, "coordinate z = 1e+300");
  checkRejected([&] { ConvexPolytope::fromPoints({{0, 0, std::nan("")}}); }, "coordinate z = nan is non-finite");
}

BOOST_AUTO_TEST_CASE(extent_limit_is_inclusive_and_a_single_point_is_accepted) {
  const double min = range::kMinExtent;
  const ConvexPolytope ok = ConvexPolytope::fromPoints({{0, 0, 0}, {min, 0, 0}, {0, min, 0}, {0, 0, min}});
  BOOST_TEST(ok.numVertices() == 4);
  const ConvexPolytope point = ConvexPolytope::fromPoints({{1e-300, 0, 0}, {1e-300, 0, 0}});
  BOOST_TEST(point.numVertices() == 1);
  const double below = std::nextafter(min, 0.0);
  checkRejected(
      [&] {
        ConvexPolytope::fromPoints({{0, 0, 0}, {0, 0, below}}, "shape 't'");
      },
      "shape 't': the points span only 9.999999999999999e-51 (largest coordinate spread), below the "
      "smallest supported extent 1e-50");
  checkRejected(
      [&] {
        ConvexPolytope::fromPoints({{0, 0, 0}, {1e-300, 0, 0}, {0, 1e-300, 0}, {0, 0, 1e-300}});
      },
      "span only 1e-300");
}

BOOST_AUTO_TEST_CASE(pose_translation_limit_is_inclusive) {
  const ConvexPolytope A = ConvexPolytope::fromPoints(cube(1.0));
  const double max = range::kMaxCoordinate;
  const double beyond = std::nextafter(max, std::numeric_limits<double>::infinity());
  const SignedDistanceResult r = signedDistance(A, at({0, 0, -max}), A, at({0, 0, max}));
  BOOST_TEST(std::isfinite(r.distance));
  BOOST_TEST(r.distance == 2 * max, boost::test_tools::tolerance(1e-12));
  checkRejected(
      [&] {
        signedDistance(A, at({0, 0, 0}), A, at({beyond, 0, 0}));
      },
      "X_WB: pose translation x = 1.0000000000000003e+50 is out of range");
  checkRejected(
      [&] {
        exactSignedDistance(A, at({0, -beyond, 0}), A, at({0, 0, 0}));
      },
      "X_WA: pose translation y = -1.0000000000000003e+50 is out of range");
}

BOOST_AUTO_TEST_CASE(tiny_to_huge_shapes_are_answered_correctly) {
  // The smallest cube spans exactly kMinExtent; the largest is placed so that its farthest pose
  // translation (3s) is 0.75 kMaxCoordinate.
  for (double s : {0.5 * range::kMinExtent, 1e-40, 1e-20, 1e-6, 1.0, 1e6, 1e20, 1e40, range::kMaxCoordinate / 4}) {
    checkCubesAtScale(s);
  }
}

BOOST_AUTO_TEST_CASE(far_from_origin_shapes_are_answered_correctly) {
  // Unit cubes 1e4 .. 1e8 from the origin, placed by their pose or by their own coordinates, and
  // a millimetre cube 1e4 m away; irrational positions so that no digit is exact.
  for (double d : {1e4, 1e6, 1e8}) {
    const Eigen::Vector3d far = d * Eigen::Vector3d(M_PI / 4, -M_E / 3, std::sqrt(0.5));
    checkCubesAtScale(1.0, far);
    checkCubesAtScale(1.0, Eigen::Vector3d::Zero(), far);
  }
  checkCubesAtScale(1e-3, 1e4 * Eigen::Vector3d(M_PI, 1, 0));
  checkCubesAtScale(1e-3, Eigen::Vector3d::Zero(), 1e4 * Eigen::Vector3d(M_PI, 1, 0));
}

BOOST_AUTO_TEST_SUITE_END()
