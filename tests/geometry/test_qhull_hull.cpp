// Tests of the Qhull wrapper (qhull_hull.h), the one Qhull entry point of the project: solid
// input gives a closed hull with counter-clockwise loops that holds every input point; flat,
// collinear, coincident and too-few-point input throws QhullError naming the point set; bad
// coordinates throw std::invalid_argument; tiny, huge and far-off sets give the same hull as a
// unit one.

#include "deepcheck/geometry/qhull_hull.h"

#include "shapes.h"

#include <boost/test/unit_test.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using deepcheck::geometry::QhullError;
using deepcheck::geometry::QhullHull;
using deepcheck::geometry::qhullHull;
using deepcheck::geometry::QhullOptions;
using Eigen::Vector3d;
namespace shapes = deepcheck::geometry::testing;

namespace {

/// The 8 corners of the box [-s, s]^3 around `center`, in a fixed order.
std::vector<Vector3d> boxCorners(double s, const Vector3d& center) {
  std::vector<Vector3d> corners;
  for (int i = 0; i < 8; ++i) {
    corners.push_back(center + s * Vector3d((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1));
  }
  return corners;
}

/// Checks what qhullHull promises: unit outward normals, loops counter-clockwise about them with
/// their vertices on the plane, every directed edge used once with its twin (a closed surface),
/// every point inside every plane; `tol` is absolute.
void checkHull(const QhullHull& h, const std::vector<Vector3d>& points, double tol) {
  BOOST_TEST_REQUIRE(h.loops.size() == h.normals.size());
  BOOST_TEST_REQUIRE(h.loops.size() == h.offsets.size());
  std::set<std::pair<int, int>> edges;
  for (std::size_t f = 0; f < h.loops.size(); ++f) {
    const std::vector<int>& loop = h.loops[f];
    const Vector3d& n = h.normals[f];
    BOOST_TEST_REQUIRE(loop.size() >= 3u);
    BOOST_TEST(std::abs(n.norm() - 1.0) < 1e-12);
    Vector3d area = Vector3d::Zero();
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vector3d& p = points[loop[i]];
      const Vector3d& q = points[loop[(i + 1) % loop.size()]];
      area += (p - points[loop[0]]).cross(q - points[loop[0]]);
      BOOST_TEST(std::abs(n.dot(p) - h.offsets[f]) <= tol);
      BOOST_TEST(edges.insert({loop[i], loop[(i + 1) % loop.size()]}).second);
    }
    BOOST_TEST(area.dot(n) > 0.0);
    for (const Vector3d& p : points) BOOST_TEST(n.dot(p) - h.offsets[f] <= tol);
  }
  for (const auto& [a, b] : edges) BOOST_TEST(edges.count({b, a}) == 1u);
  const std::size_t v = h.vertices.size();
  BOOST_TEST(v - edges.size() / 2 + h.loops.size() == 2u);  // Euler: V - E + F = 2
}

/// Runs qhullHull and returns the message of the QhullError it must throw.
std::string qhullErrorOf(const std::vector<Vector3d>& points, const std::string& name) {
  try {
    qhullHull(points, QhullOptions{}, name);
  } catch (const QhullError& e) {
    return e.what();
  }
  BOOST_ERROR("no QhullError for " << name);
  return {};
}

}  // namespace

BOOST_AUTO_TEST_SUITE(qhull_hull)

BOOST_AUTO_TEST_CASE(cube_with_duplicates_and_interior_points) {
  std::vector<Vector3d> points = boxCorners(1.0, Vector3d::Zero());
  const std::vector<Vector3d> corners = points;
  for (const Vector3d& c : corners) points.push_back(c);  // every corner twice
  std::mt19937 rng(31);
  for (int i = 0; i < 50; ++i) points.push_back(0.9 * shapes::randomUnit(rng));
  const QhullHull merged = qhullHull(points, QhullOptions{}, "cube");
  BOOST_TEST(merged.vertices.size() == 8u);
  BOOST_TEST(merged.loops.size() == 6u);  // coplanar triangles merged into squares
  checkHull(merged, points, 1e-14);
  QhullOptions triangles;
  triangles.triangulate = true;
  const QhullHull split = qhullHull(points, triangles, "cube");
  BOOST_TEST(split.loops.size() == 12u);
  checkHull(split, points, 1e-14);
}

BOOST_AUTO_TEST_CASE(random_sets_with_and_without_merging) {
  std::mt19937 rng(32);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vector3d> points;
    for (int i = 0; i < 200; ++i) points.push_back(shapes::randomUnit(rng));
    for (double merge : {-1.0, 0.0, 1e-6}) {
      QhullOptions options;
      options.mergeDistance = merge;
      options.searchAllPoints = trial % 2 == 0;
      // Merging within m moves facet planes by a few m at most.
      checkHull(qhullHull(points, options, "sphere"), points, 1e-12 + 8.0 * std::max(merge, 0.0));
    }
  }
}

BOOST_AUTO_TEST_CASE(flat_collinear_coincident_and_too_few_points_throw) {
  std::mt19937 rng(33);
  const Eigen::Matrix3d R = shapes::randomRotation(rng).toRotationMatrix();
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vector3d> flat;
  std::vector<Vector3d> line;
  for (int i = 0; i < 100; ++i) {
    flat.push_back(R * Vector3d(u(rng), u(rng), 0.0));
    line.push_back(R * Vector3d(u(rng), 0.0, 0.0));
  }
  const std::vector<Vector3d> same(10, Vector3d(0.25, -3.0, 7.0));
  const std::vector<Vector3d> three = {Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY()};
  for (const auto& [points, name] :
       {std::pair{flat, "flat set"}, std::pair{line, "collinear set"}, std::pair{same, "one point ten times"}}) {
    const std::string message = qhullErrorOf(points, name);
    BOOST_TEST(message.rfind(name, 0) == 0u, message);
    BOOST_TEST(message.find("Qhull failed") != std::string::npos, message);
  }
  const std::string few = qhullErrorOf(three, "triangle");
  BOOST_TEST(few == "triangle: a 3-d hull needs at least 4 points, got 3");
  BOOST_TEST(qhullErrorOf({}, "nothing").find("got 0") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(bad_coordinates_throw_invalid_argument_naming_the_point) {
  std::vector<Vector3d> points = boxCorners(1.0, Vector3d::Zero());
  points[5].y() = std::numeric_limits<double>::quiet_NaN();
  BOOST_CHECK_EXCEPTION(
      qhullHull(points, QhullOptions{}, "box"), std::invalid_argument,
      [](const std::invalid_argument& e) { return std::string(e.what()).rfind("box: point 5 coordinate y", 0) == 0; });
  points[5].y() = 1e101;
  BOOST_CHECK_THROW(qhullHull(points, QhullOptions{}, "box"), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(tiny_huge_and_far_sets_give_the_unit_hull) {
  // A cube with points near its faces and inside: the hull is the cube at every scale and offset.
  std::mt19937 rng(34);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vector3d> unit = boxCorners(1.0, Vector3d::Zero());
  for (int i = 0; i < 60; ++i) {
    Vector3d p(u(rng), u(rng), u(rng));
    if (i % 2 == 0) p[i % 3] = (i % 4 == 0) ? 1.0 : -1.0;  // near a face
    unit.push_back(0.999 * p);
  }
  for (const auto& [scale, offset] : {std::pair{1e-60, 0.0}, std::pair{1e-9, 0.0}, std::pair{1e9, 0.0},
                                      std::pair{1e60, 0.0}, std::pair{1.0, 1e6}, std::pair{1e-3, 1e3}}) {
    std::vector<Vector3d> points;
    for (const Vector3d& p : unit) points.push_back(scale * p + Vector3d::Constant(offset));
    const QhullHull h = qhullHull(points, QhullOptions{}, "scaled cube");
    std::set<int> vertices(h.vertices.begin(), h.vertices.end());
    BOOST_TEST(vertices == (std::set<int>{0, 1, 2, 3, 4, 5, 6, 7}), "scale " << scale << " offset " << offset);
    BOOST_TEST(h.loops.size() == 6u);
    // Round-off of the coordinates: a few ulps of the largest one.
    const double roundoff = 64.0 * std::numeric_limits<double>::epsilon() * (scale + offset);
    checkHull(h, points, roundoff);
  }
}

BOOST_AUTO_TEST_SUITE_END()
