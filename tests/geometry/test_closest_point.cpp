// closestPointOnTriangle (closest_point.h): each Voronoi region with a known answer, degenerate
// triangles, and random triangles against the optimality conditions of a projection onto a
// convex set: q lies in the triangle and (p - q).(v - q) <= 0 for each corner v.

#include "deepcheck/geometry/closest_point.h"

#include <boost/test/unit_test.hpp>

#include <Eigen/Dense>

#include <random>

using deepcheck::geometry::closestPointOnTriangle;
using Eigen::Vector3d;

namespace {

// Round-off of the projection, relative to the squared size of the configuration.
constexpr double kRoundoff = 1e-12;

void requireNear(const Vector3d& got, const Vector3d& want) {
  BOOST_TEST_CONTEXT("got " << got.transpose() << ", want " << want.transpose()) {
    BOOST_TEST((got - want).norm() <= 1e-15 * (1.0 + want.norm()));
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(closest_point)

BOOST_AUTO_TEST_CASE(every_region_of_a_right_triangle) {
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  requireNear(closestPointOnTriangle(Vector3d(-1, -1, 2), a, b, c), a);                         // vertex a
  requireNear(closestPointOnTriangle(Vector3d(2, -1, -3), a, b, c), b);                         // vertex b
  requireNear(closestPointOnTriangle(Vector3d(-1, 2, 1), a, b, c), c);                          // vertex c
  requireNear(closestPointOnTriangle(Vector3d(0.25, -1, 1), a, b, c), Vector3d(0.25, 0, 0));    // ab
  requireNear(closestPointOnTriangle(Vector3d(-1, 0.75, 0), a, b, c), Vector3d(0, 0.75, 0));    // ac
  requireNear(closestPointOnTriangle(Vector3d(1, 1, 5), a, b, c), Vector3d(0.5, 0.5, 0));       // bc
  requireNear(closestPointOnTriangle(Vector3d(0.2, 0.3, -4), a, b, c), Vector3d(0.2, 0.3, 0));  // face
}

BOOST_AUTO_TEST_CASE(degenerate_triangles) {
  // Collinear corners, c between a and b: the segment [a, b].
  const Vector3d a(0, 0, 0), b(2, 0, 0), c(1, 0, 0);
  requireNear(closestPointOnTriangle(Vector3d(1.5, 1, 0), a, b, c), Vector3d(1.5, 0, 0));
  requireNear(closestPointOnTriangle(Vector3d(3, 1, 1), a, b, c), b);
  requireNear(closestPointOnTriangle(Vector3d(-1, 0, 1), a, b, c), a);
  // Two coincident corners, in each position: a segment; all three coincident: a point.
  requireNear(closestPointOnTriangle(Vector3d(0.5, 0, 1), a, b, b), Vector3d(0.5, 0, 0));
  requireNear(closestPointOnTriangle(Vector3d(0.5, 0, 1), a, a, b), Vector3d(0.5, 0, 0));
  requireNear(closestPointOnTriangle(Vector3d(0.5, 0, 1), a, b, a), Vector3d(0.5, 0, 0));
  requireNear(closestPointOnTriangle(Vector3d(0.5, 1, 0), b, b, a), Vector3d(0.5, 0, 0));
  requireNear(closestPointOnTriangle(Vector3d(4, 5, 6), c, c, c), c);
}

BOOST_AUTO_TEST_CASE(random_triangles_satisfy_the_projection_conditions) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  auto random = [&] { return Vector3d(g(rng), g(rng), g(rng)); };
  for (int trial = 0; trial < 2000; ++trial) {
    const Vector3d a = random(), b = random(), c = random();
    const Vector3d p = 2.0 * random();
    const Vector3d q = closestPointOnTriangle(p, a, b, c);
    const double scale2 = 1.0 + (p - a).squaredNorm() + (b - a).squaredNorm() + (c - a).squaredNorm();
    BOOST_TEST_CONTEXT("trial " << trial) {
      // q in the triangle: barycentric coordinates in [0, 1] and no offset from its plane.
      Eigen::Matrix<double, 3, 2> E;
      E << b - a, c - a;
      const Eigen::Vector2d st = E.colPivHouseholderQr().solve(q - a);
      BOOST_TEST(st[0] >= -1e-9);
      BOOST_TEST(st[1] >= -1e-9);
      BOOST_TEST(st[0] + st[1] <= 1.0 + 1e-9);
      BOOST_TEST((a + E * st - q).norm() <= 1e-9 * std::sqrt(scale2));
      // q is the projection: no corner lies further along p - q than q itself.
      for (const Vector3d& v : {a, b, c}) BOOST_TEST((p - q).dot(v - q) <= kRoundoff * scale2);
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
