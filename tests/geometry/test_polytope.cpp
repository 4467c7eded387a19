// Tests of ConvexPolytope (hulls, kinds, adjacency conventions, support) and PairFrame.
//
// Hull correctness is checked against the input, not against stored numbers: every input point is
// inside the hull within its flatness tolerance, every hull vertex is an input point bit for bit,
// the hull's support value equals the input's in random directions, and hill-climbing support
// agrees with brute force from random hints.

#include "deepcheck/geometry/internal/polytope_access.h"
#include "deepcheck/geometry/pair_frame.h"
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
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

using deepcheck::geometry::ConvexPolytope;
using deepcheck::geometry::PairFrame;
using deepcheck::geometry::PolytopeKind;
using Eigen::Vector3d;
namespace shapes = deepcheck::geometry::testing;
namespace detail = deepcheck::geometry::detail;

namespace {

Vector3d gaussian(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Vector3d(g(rng), g(rng), g(rng));
}

Vector3d inBall(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (;;) {
    const Vector3d v(u(rng), u(rng), u(rng));
    if (v.squaredNorm() <= 1.0) return v;
  }
}

/// Points sampled on the six faces of the box [-e, e], plus its eight corners.
std::vector<Vector3d> boxSurfacePoints(const Vector3d& e, int perFace, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vector3d> pts;
  for (int axis = 0; axis < 3; ++axis) {
    for (double side : {-1.0, 1.0}) {
      for (int i = 0; i < perFace; ++i) {
        Vector3d p(u(rng) * e.x(), u(rng) * e.y(), u(rng) * e.z());
        p[axis] = side * e[axis];
        pts.push_back(p);
      }
    }
  }
  for (int i = 0; i < 8; ++i) {
    pts.emplace_back((i & 1) ? e.x() : -e.x(), (i & 2) ? e.y() : -e.y(), (i & 4) ? e.z() : -e.z());
  }
  return pts;
}

std::vector<Vector3d> transformed(const std::vector<Vector3d>& pts, const Eigen::Matrix3d& R, const Vector3d& t) {
  std::vector<Vector3d> out;
  for (const Vector3d& p : pts) out.push_back(R * p + t);
  return out;
}

/// The checks every hull must pass; `label` names the input in failure messages.
void checkHull(const ConvexPolytope& poly, const std::vector<Vector3d>& input, std::mt19937& rng,
               const std::string& label) {
  BOOST_TEST_CONTEXT(label << " (" << toString(poly.kind()) << ", " << poly.numVertices() << " vertices)") {
    BOOST_TEST(detail::validate(poly) == "");
    BOOST_TEST(poly.lengthScale() > 0.0);

    // Every hull vertex is one of the input points, exactly.
    std::set<std::array<double, 3>> given;
    for (const Vector3d& p : input) given.insert({p.x(), p.y(), p.z()});
    int foreign = 0;
    for (const Vector3d& v : poly.vertices()) foreign += given.count({v.x(), v.y(), v.z()}) == 0;
    BOOST_TEST(foreign == 0);

    const Vector3d& c = poly.center();
    const double tol = poly.hullTolerance() + 4.0 * std::numeric_limits<double>::epsilon() * poly.lengthScale();

    // Every input point inside every face plane (solids).
    if (poly.kind() == PolytopeKind::Polyhedron) {
      double worst = -std::numeric_limits<double>::infinity();
      for (int f = 0; f < poly.numFaces(); ++f) {
        const Vector3d& n = poly.faceNormal(f);
        const double localOffset = poly.faceOffset(f) - n.dot(c);
        for (const Vector3d& p : input) worst = std::max(worst, n.dot(p - c) - localOffset);
      }
      BOOST_TEST(worst <= tol);
    }

    // Support: hill climbing agrees with brute force, and the hull's support value is the
    // input's (no extreme point lost, none invented).
    std::uniform_int_distribution<int> hint(-2, poly.numVertices() + 2);
    int badClimb = 0;
    int badHull = 0;
    for (int k = 0; k < 1000; ++k) {
      const Vector3d dir = gaussian(rng);
      const int s = poly.support(dir, hint(rng));
      const int b = poly.supportBruteForce(dir);
      BOOST_REQUIRE(s >= 0 && s < poly.numVertices());
      const double hs = dir.dot(poly.vertex(s) - c);
      const double hb = dir.dot(poly.vertex(b) - c);
      if (std::abs(hs - hb) > tol * dir.norm()) ++badClimb;
      double hi = -std::numeric_limits<double>::infinity();
      for (const Vector3d& p : input) hi = std::max(hi, dir.dot(p - c));
      if (std::abs(hb - hi) > tol * dir.norm()) ++badHull;
    }
    BOOST_TEST(badClimb == 0);
    BOOST_TEST(badHull == 0);

    // Each face's stored support is as high along the face's normal as brute force finds.
    int badFace = 0;
    for (int f = 0; f < poly.numFaces(); ++f) {
      const Vector3d& n = poly.faceNormal(f);
      const double hs = n.dot(poly.localVertex(poly.faceSupport(f)));
      const double hb = n.dot(poly.localVertex(poly.supportBruteForce(n)));
      if (hs < hb - tol) ++badFace;
    }
    BOOST_TEST(badFace == 0);

    // Each probe direction's stored support is as high as brute force finds.
    int badProbe = 0;
    for (int i = 0; i < detail::kProbeDirections; ++i) {
      const Vector3d& d = detail::probeDirection(i);
      const double hs = d.dot(poly.localVertex(detail::probeSupport(poly, i)));
      const double hb = d.dot(poly.localVertex(poly.supportBruteForce(d)));
      if (hs < hb - tol) ++badProbe;
    }
    BOOST_TEST(badProbe == 0);

    // The inside radius: the centre's smallest distance to a face plane of a solid, else 0.
    double inside = poly.kind() == PolytopeKind::Polyhedron ? std::numeric_limits<double>::infinity() : 0.0;
    if (poly.kind() == PolytopeKind::Polyhedron)
      for (int f = 0; f < poly.numFaces(); ++f)
        inside = std::min(inside, poly.faceOffset(f) - poly.faceNormal(f).dot(c));
    BOOST_TEST(std::abs(poly.insideRadius() - inside) <= tol);
  }
}

bool messageHas(const std::exception& e, std::initializer_list<const char*> parts) {
  const std::string what = e.what();
  for (const char* p : parts) {
    if (what.find(p) == std::string::npos) {
      BOOST_TEST_MESSAGE("message '" << what << "' lacks '" << p << "'");
      return false;
    }
  }
  return true;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(polytope)

BOOST_AUTO_TEST_CASE(kind_names) {
  BOOST_TEST(std::string(toString(PolytopeKind::Point)) == "Point");
  BOOST_TEST(std::string(toString(PolytopeKind::Segment)) == "Segment");
  BOOST_TEST(std::string(toString(PolytopeKind::Polygon)) == "Polygon");
  BOOST_TEST(std::string(toString(PolytopeKind::Polyhedron)) == "Polyhedron");
}

BOOST_AUTO_TEST_CASE(bad_input_messages) {
  BOOST_CHECK_EXCEPTION(ConvexPolytope::fromPoints({}, "link3"), std::invalid_argument, [](const std::exception& e) {
    return messageHas(e, {"link3", "no points"});
  });
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<Vector3d> pts(5, Vector3d(1.0 / 3.0, 0.5, 0.25));
  pts[3].y() = nan;
  BOOST_CHECK_EXCEPTION(ConvexPolytope::fromPoints(pts, "gripper"), std::invalid_argument, [](const std::exception& e) {
    return messageHas(e, {"gripper", "point 3", "y", "nan"});
  });
  pts[3].y() = 0.5;
  pts[4].z() = -inf;
  BOOST_CHECK_EXCEPTION(ConvexPolytope::fromPoints(pts), std::invalid_argument, [](const std::exception& e) {
    return messageHas(e, {"points", "point 4", "z", "-inf"});
  });
  BOOST_CHECK_EXCEPTION(ConvexPolytope::box(Vector3d(1.0, -0.5, 1.0)), std::invalid_argument,
                        [](const std::exception& e) {
                          return messageHas(e, {"box", "y", "-0.5"});
                        });
  BOOST_CHECK_EXCEPTION(ConvexPolytope::box(Vector3d(1.0, 1.0, 0.0)), std::invalid_argument,
                        [](const std::exception& e) {
                          return messageHas(e, {"box", "z", "0"});
                        });
  BOOST_CHECK_EXCEPTION(ConvexPolytope::box(Vector3d(inf, 1.0, 1.0)), std::invalid_argument,
                        [](const std::exception& e) {
                          return messageHas(e, {"box", "x", "inf"});
                        });
}

BOOST_AUTO_TEST_CASE(point_kind) {
  std::mt19937 rng(11);
  const Vector3d p(1e4 / 3.0, -2.0 / 7.0, 0.1);
  for (int copies : {1, 5}) {
    const std::vector<Vector3d> pts(copies, p);
    const ConvexPolytope poly = ConvexPolytope::fromPoints(pts);
    BOOST_TEST(toString(poly.kind()) == "Point");
    BOOST_TEST(poly.numVertices() == 1);
    BOOST_TEST(poly.numFaces() == 0);
    BOOST_TEST(poly.numEdges() == 0);
    BOOST_TEST(poly.vertex(0) == p);
    BOOST_TEST(poly.boundingRadius() == 0.0);
    BOOST_TEST(poly.lengthScale() > 0.0);
    BOOST_TEST(poly.neighbors(0).size() == 0);
    BOOST_TEST(poly.vertexFaces(0).size() == 0);
    BOOST_TEST(poly.support(Vector3d(1, 2, 3), 7) == 0);
    checkHull(poly, pts, rng, "point");
  }
}

BOOST_AUTO_TEST_CASE(segment_kind) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double offset : {0.0, 1e4}) {
    const Vector3d dir = shapes::randomUnit(rng);
    const Vector3d base = offset * Vector3d(1.0, -1.0, 1.0) + Vector3d(0.3, 0.1, -0.2);
    std::vector<Vector3d> pts;
    for (int i = 0; i < 100; ++i) pts.push_back(base + (0.7 * u(rng)) * dir);
    pts.push_back(pts[3]);  // an exact duplicate
    const ConvexPolytope poly = ConvexPolytope::fromPoints(pts);
    BOOST_TEST_CONTEXT("offset " << offset) {
      BOOST_TEST(toString(poly.kind()) == "Segment");
      BOOST_TEST(poly.numVertices() == 2);
      BOOST_TEST(poly.numEdges() == 1);
      BOOST_TEST(poly.numFaces() == 0);
      BOOST_TEST(poly.neighbors(0).size() == 1);
      BOOST_TEST(poly.neighbors(0)[0] == 1);
      BOOST_TEST(poly.neighbors(1)[0] == 0);
      BOOST_TEST(poly.vertexFaces(1).size() == 0);
      // The two extreme input points along the line.
      auto along = [&](const Vector3d& p) { return dir.dot(p - base); };
      const auto [lo, hi] = std::minmax_element(
          pts.begin(), pts.end(), [&](const Vector3d& a, const Vector3d& b) { return along(a) < along(b); });
      const bool ordered = poly.vertex(0) == *lo && poly.vertex(1) == *hi;
      const bool swapped = poly.vertex(0) == *hi && poly.vertex(1) == *lo;
      BOOST_TEST((ordered || swapped));
      checkHull(poly, pts, rng, "segment");
    }
  }
}

BOOST_AUTO_TEST_CASE(polygon_kind_conventions) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double offset : {0.0, 1e4}) {
    for (int n : {5, 300, 2000}) {
      const Eigen::Matrix3d R = shapes::randomRotation(rng).toRotationMatrix();
      const Vector3d t = offset * Vector3d(-1.0, 1.0, 1.0) + Vector3d(0.25, 0.5, 1.0 / 3.0);
      std::vector<Vector3d> flat;
      for (int i = 0; i < n; ++i) {
        if (n == 2000) {  // a circle: every point is a vertex, support climbs
          const double a = 2.0 * M_PI * i / n;
          flat.emplace_back(std::cos(a), 0.5 * std::sin(a), 0.0);
        } else {
          flat.emplace_back(u(rng), 0.5 * u(rng), 0.0);
        }
      }
      flat.push_back(flat[1]);  // a duplicate
      const std::vector<Vector3d> pts = transformed(flat, R, t);
      const ConvexPolytope poly = ConvexPolytope::fromPoints(pts);
      BOOST_TEST_CONTEXT("offset " << offset << ", " << n << " points") {
        BOOST_REQUIRE(toString(poly.kind()) == std::string("Polygon"));
        const int k = poly.numVertices();
        BOOST_TEST(k >= 3);
        if (n == 2000) BOOST_TEST(k == n);
        BOOST_TEST(poly.numFaces() == 2);
        BOOST_TEST(poly.numEdges() == k);
        const Vector3d nrm = poly.faceNormal(0);
        BOOST_TEST((poly.faceNormal(1) + nrm).norm() < 1e-15);
        BOOST_TEST(std::abs(std::abs(nrm.dot(R.col(2))) - 1.0) < 1e-12);
        BOOST_TEST(poly.faceOffset(1) == -poly.faceOffset(0));
        for (int i = 0; i < k; ++i) {
          BOOST_TEST(poly.faceVertices(0)[i] == i);
          BOOST_TEST(poly.faceVertices(1)[i] == k - 1 - i);
          BOOST_TEST(poly.neighbors(i).size() == 2);
          BOOST_TEST(poly.neighbors(i)[0] == (i + 1) % k);
          BOOST_TEST(poly.neighbors(i)[1] == (i + k - 1) % k);
          BOOST_TEST(poly.vertexFaces(i).size() == 2);
          BOOST_TEST(poly.vertexFaces(i)[0] == 0);
          BOOST_TEST(poly.vertexFaces(i)[1] == 1);
          // Counter-clockwise about faceNormal(0): every corner turns left.
          const Vector3d a = poly.vertex(i) - poly.center();
          const Vector3d b = poly.vertex((i + 1) % k) - poly.center();
          const Vector3d c = poly.vertex((i + 2) % k) - poly.center();
          BOOST_TEST((b - a).cross(c - b).dot(nrm) > 0.0);
        }
        checkHull(poly, pts, rng, "polygon");
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(polygon_from_square_with_collinear_points) {
  std::mt19937 rng(14);
  // Points on the boundary of a rotated square, including its edges' interior points and
  // duplicates: only the four corners are vertices.
  const Eigen::Matrix3d R = shapes::randomRotation(rng).toRotationMatrix();
  std::vector<Vector3d> flat;
  for (int i = 0; i <= 10; ++i) {
    const double s = -1.0 + 0.2 * i;
    flat.emplace_back(s, -1.0, 0.0);
    flat.emplace_back(s, 1.0, 0.0);
    flat.emplace_back(-1.0, s, 0.0);
    flat.emplace_back(1.0, s, 0.0);
  }
  const std::vector<Vector3d> pts = transformed(flat, R, Vector3d(0.1, 0.2, 0.3));
  const ConvexPolytope poly = ConvexPolytope::fromPoints(pts);
  BOOST_TEST(toString(poly.kind()) == std::string("Polygon"));
  BOOST_TEST(poly.numVertices() == 4);
  checkHull(poly, pts, rng, "square");
}

BOOST_AUTO_TEST_CASE(tetrahedron) {
  std::mt19937 rng(15);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vector3d> pts;
    for (int i = 0; i < 4; ++i) pts.push_back(inBall(rng));
    const ConvexPolytope poly = ConvexPolytope::fromPoints(pts);
    BOOST_REQUIRE(toString(poly.kind()) == std::string("Polyhedron"));
    BOOST_TEST(poly.numVertices() == 4);
    BOOST_TEST(poly.numFaces() == 4);
    BOOST_TEST(poly.numEdges() == 6);
    checkHull(poly, pts, rng, "tetrahedron");
  }
}

BOOST_AUTO_TEST_CASE(box_and_cube_ring_order) {
  std::mt19937 rng(16);
  const Vector3d e(0.5, 1.0 / 3.0, 0.25);
  const ConvexPolytope box = ConvexPolytope::box(2.0 * e);  // half extents e
  BOOST_TEST(toString(box.kind()) == std::string("Polyhedron"));
  BOOST_TEST(box.numVertices() == 8);
  BOOST_TEST(box.numFaces() == 6);
  BOOST_TEST(box.numEdges() == 12);
  BOOST_TEST(box.center().norm() < 1e-16);
  BOOST_TEST(std::abs(box.boundingRadius() - e.norm()) < 1e-15);
  BOOST_TEST(box.lengthScale() == box.boundingRadius());
  BOOST_TEST(box.insideRadius() == 0.25);  // the smallest half extent
  for (int f = 0; f < 6; ++f) {
    BOOST_TEST(box.faceVertices(f).size() == 4);
    const Vector3d& n = box.faceNormal(f);
    int axis = 0;
    n.cwiseAbs().maxCoeff(&axis);
    BOOST_TEST(std::abs(n[axis]) == 1.0);
    BOOST_TEST(box.faceOffset(f) == e[axis]);
  }
  // Principal axes: largest extent first.
  const Eigen::Matrix3d& A = box.principalAxes();
  BOOST_TEST(std::abs(std::abs(A(0, 0)) - 1.0) < 1e-12);
  BOOST_TEST(std::abs(std::abs(A(1, 1)) - 1.0) < 1e-12);
  BOOST_TEST(std::abs(std::abs(A(2, 2)) - 1.0) < 1e-12);
  BOOST_TEST(std::abs(A.determinant() - 1.0) < 1e-12);

  // At every corner, the ring's face normals, in ring order, turn counter-clockwise seen from
  // outside (about the corner's direction), and neighbour j is the corner across the edge shared
  // by ring faces j-1 and j.
  for (int v = 0; v < 8; ++v) {
    const Vector3d out = box.vertex(v);
    const auto ring = box.vertexFaces(v);
    const auto nb = box.neighbors(v);
    BOOST_REQUIRE(ring.size() == 3);
    BOOST_REQUIRE(nb.size() == 3);
    for (int j = 0; j < 3; ++j) {
      const Vector3d& n0 = box.faceNormal(ring[j]);
      const Vector3d& n1 = box.faceNormal(ring[(j + 1) % 3]);
      BOOST_TEST(n0.cross(n1).dot(out) > 0.0);
      // The edge (v, nbr_j) lies in ring faces j-1 and j: its direction is orthogonal to both.
      const Vector3d edge = box.vertex(nb[j]) - box.vertex(v);
      BOOST_TEST(std::abs(edge.dot(box.faceNormal(ring[j]))) < 1e-15);
      BOOST_TEST(std::abs(edge.dot(box.faceNormal(ring[(j + 2) % 3]))) < 1e-15);
    }
  }
  checkHull(box, box.vertices(), rng, "box");
}

// The probe directions are the vertices of a regular icosahedron: unit, in opposite pairs, each
// with five nearest neighbours at the icosahedron's edge angle, atan(2).
BOOST_AUTO_TEST_CASE(probe_directions_are_an_icosahedron) {
  const int n = detail::kProbeDirections;
  BOOST_TEST(n == 12);
  const double edgeAngle = std::atan(2.0);
  for (int i = 0; i < n; ++i) {
    const Vector3d& d = detail::probeDirection(i);
    BOOST_TEST(std::abs(d.norm() - 1.0) < 1e-15);
    int opposite = 0, nearest = 0;
    for (int j = 0; j < n; ++j) {
      if (j == i) continue;
      const Vector3d& e = detail::probeDirection(j);
      const double angle = std::atan2(d.cross(e).norm(), d.dot(e));
      opposite += (d + e).norm() < 1e-15;
      nearest += std::abs(angle - edgeAngle) < 1e-12;
      BOOST_TEST(angle > edgeAngle - 1e-12, "directions " << i << " and " << j);
    }
    BOOST_TEST(opposite == 1, "direction " << i);
    BOOST_TEST(nearest == 5, "direction " << i);
  }
}

BOOST_AUTO_TEST_CASE(box_surface_samples_merge_into_six_faces) {
  std::mt19937 rng(17);
  const Vector3d e(0.5, 1.0 / 3.0, 0.2);
  const std::vector<Vector3d> surface = boxSurfacePoints(e, 300, rng);
  for (int rotated = 0; rotated < 2; ++rotated) {
    const Eigen::Matrix3d R = rotated ? shapes::randomRotation(rng).toRotationMatrix() : Eigen::Matrix3d::Identity();
    const std::vector<Vector3d> pts = transformed(surface, R, Vector3d(0.1, -0.7, 1.0 / 3.0));
    const ConvexPolytope poly = ConvexPolytope::fromPoints(pts);
    BOOST_TEST_CONTEXT("rotated " << rotated) {
      BOOST_TEST(poly.numVertices() == 8);
      BOOST_TEST(poly.numFaces() == 6);
      checkHull(poly, pts, rng, "box surface");
    }
  }
  // Points on edges and at face centres of a cube are not vertices (they lie on two or on one
  // face): the hull is the cube.
  std::vector<Vector3d> cube;
  for (int x = -1; x <= 1; ++x) {
    for (int y = -1; y <= 1; ++y) {
      for (int z = -1; z <= 1; ++z) cube.emplace_back(x, y, z);
    }
  }
  const ConvexPolytope poly = ConvexPolytope::fromPoints(cube);
  BOOST_TEST(poly.numVertices() == 8);
  BOOST_TEST(poly.numFaces() == 6);
  checkHull(poly, cube, rng, "cube lattice");
}

BOOST_AUTO_TEST_CASE(nearly_coplanar_noise_below_tolerance) {
  std::mt19937 rng(18);
  std::normal_distribution<double> noise(0.0, 1e-13);
  std::vector<Vector3d> pts = boxSurfacePoints(Vector3d(0.5, 0.4, 0.3), 200, rng);
  for (Vector3d& p : pts) p += Vector3d(noise(rng), noise(rng), noise(rng));
  const ConvexPolytope poly = ConvexPolytope::fromPoints(pts);
  BOOST_TEST(toString(poly.kind()) == std::string("Polyhedron"));
  checkHull(poly, pts, rng, "noisy box surface");
}

// Inputs that leave features at or near the flatness tolerance: noise on coplanar and collinear
// points, near-duplicates just above the tolerance, thin slabs and needles, float-rounded meshes,
// all rotated and far from the origin. Every hull must be valid and correct.
BOOST_AUTO_TEST_CASE(noisy_and_nearly_degenerate_inputs) {
  std::mt19937 rng(25);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int solids = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const double scale = trial % 2 ? 1e-3 : 10.0;
    const Vector3d t = (trial < 3 ? 1e4 : 1.0) * shapes::randomUnit(rng);
    const Eigen::Matrix3d R = shapes::randomRotation(rng).toRotationMatrix();
    auto place = [&](std::vector<Vector3d> pts) {
      for (Vector3d& p : pts) p = t + scale * (R * p);
      return pts;
    };
    for (double noise : {1e-13, 1e-11, 1e-9}) {
      std::vector<Vector3d> surface = boxSurfacePoints(Vector3d(1.0, 0.7, 0.4), 60, rng);
      for (Vector3d& p : surface) p += noise * gaussian(rng);
      std::vector<Vector3d> edges;
      for (int i = 0; i < 150; ++i) {
        Vector3d p(u(rng) > 0 ? 1.0 : -1.0, u(rng) > 0 ? 1.0 : -1.0, u(rng));
        std::swap(p[2], p[i % 3]);
        edges.push_back(p + noise * gaussian(rng));
      }
      std::vector<Vector3d> clusters;
      for (int i = 0; i < 60; ++i) {
        const Vector3d c = gaussian(rng);
        for (int k = 0; k < 3; ++k) clusters.push_back(c + 1e2 * noise * gaussian(rng));
      }
      for (const auto* set : {&surface, &edges, &clusters}) {
        const std::vector<Vector3d> pts = place(*set);
        const ConvexPolytope poly = ConvexPolytope::fromPoints(pts);
        solids += poly.kind() == PolytopeKind::Polyhedron;
        checkHull(poly, pts, rng, "noise " + std::to_string(noise));
      }
    }
    for (double thickness : {3e-10, 1e-8, 1e-6}) {
      std::vector<Vector3d> slab;
      std::vector<Vector3d> needle;
      for (int i = 0; i < 100; ++i) {
        slab.emplace_back(u(rng), u(rng), thickness * (u(rng) > 0 ? 1.0 : -1.0));
        needle.emplace_back(u(rng), thickness * u(rng), thickness * u(rng));
      }
      checkHull(ConvexPolytope::fromPoints(place(slab)), place(slab), rng, "slab");
      checkHull(ConvexPolytope::fromPoints(place(needle)), place(needle), rng, "needle");
    }
    std::vector<Vector3d> cylinder;  // a mesh stored in single precision, posed in double
    for (int i = 0; i < 48; ++i) {
      const double a = 2.0 * M_PI * i / 48.0;
      for (double z : {-1.0, -0.5, 0.0, 0.5, 1.0}) {
        cylinder.push_back(Vector3d(std::cos(a), std::sin(a), z).cast<float>().cast<double>());
      }
    }
    cylinder = place(cylinder);
    checkHull(ConvexPolytope::fromPoints(cylinder), cylinder, rng, "float cylinder");
  }
  BOOST_TEST(solids == 6 * 9);
}

BOOST_AUTO_TEST_CASE(duplicates_and_near_duplicates) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> jitter(-1e-14, 1e-14);
  std::vector<Vector3d> base;
  for (int i = 0; i < 200; ++i) base.push_back(inBall(rng));
  std::vector<Vector3d> pts;
  for (const Vector3d& p : base) {
    pts.push_back(p);
    pts.push_back(p);
    pts.push_back(p + Vector3d(jitter(rng), jitter(rng), jitter(rng)));
    pts.push_back(p + Vector3d(jitter(rng), jitter(rng), jitter(rng)));
  }
  std::shuffle(pts.begin(), pts.end(), rng);
  const ConvexPolytope poly = ConvexPolytope::fromPoints(pts, "dups");
  BOOST_TEST(toString(poly.kind()) == std::string("Polyhedron"));
  checkHull(poly, pts, rng, "near duplicates");
  // Same on a box's corners: still a box.
  std::vector<Vector3d> corners;
  const ConvexPolytope reference = ConvexPolytope::box(Vector3d(2, 4, 6));
  for (const Vector3d& c : reference.vertices()) {
    for (int k = 0; k < 4; ++k) corners.push_back(c + Vector3d(jitter(rng), jitter(rng), jitter(rng)));
  }
  const ConvexPolytope box = ConvexPolytope::fromPoints(corners);
  BOOST_TEST(box.numVertices() == 8);
  BOOST_TEST(box.numFaces() == 6);
  checkHull(box, corners, rng, "jittered box corners");
}

BOOST_AUTO_TEST_CASE(sphere_points) {
  std::mt19937 rng(20);
  std::vector<Vector3d> pts;
  for (int i = 0; i < 2000; ++i) pts.push_back(shapes::randomUnit(rng));
  const ConvexPolytope poly = ConvexPolytope::fromPoints(pts);
  BOOST_TEST(poly.numVertices() == 2000);
  BOOST_TEST(poly.numEdges() == 3 * 2000 - 6);  // a triangulation: all points are vertices
  checkHull(poly, pts, rng, "sphere 2000");
}

BOOST_AUTO_TEST_CASE(scales_and_offsets) {
  std::mt19937 rng(21);
  struct Case {
    double scale;
    double offset;
  };
  for (const Case& c : {Case{1e-3, 0.0}, Case{1e3, 0.0}, Case{1.0, 1e4}, Case{1e-3, 1e4}, Case{1e3, 1e4}}) {
    const Vector3d t = c.offset * Vector3d(1.0, -1.0, 1.0) + Vector3d(1.0 / 3.0, 0.2, 0.1) * c.scale;
    const Eigen::Matrix3d R = shapes::randomRotation(rng).toRotationMatrix();
    std::vector<Vector3d> pts;
    for (int i = 0; i < 300; ++i) pts.push_back(t + c.scale * inBall(rng));
    for (int i = 0; i < 300; ++i) pts.push_back(t + c.scale * shapes::randomUnit(rng));
    for (const Vector3d& p : boxSurfacePoints(Vector3d(0.5, 0.3, 0.2), 50, rng)) {
      pts.push_back(t + c.scale * (R * p));
    }
    const ConvexPolytope poly = ConvexPolytope::fromPoints(pts);
    BOOST_TEST_CONTEXT("scale " << c.scale << " offset " << c.offset) {
      BOOST_TEST(toString(poly.kind()) == std::string("Polyhedron"));
      BOOST_TEST(std::abs(poly.boundingRadius() / c.scale - 1.0) < 0.5);
      checkHull(poly, pts, rng, "scaled");
    }
  }
}

BOOST_AUTO_TEST_CASE(large_inputs) {
  std::mt19937 rng(22);
  std::vector<Vector3d> ball;
  for (int i = 0; i < 10000; ++i) ball.push_back(inBall(rng));
  checkHull(ConvexPolytope::fromPoints(ball), ball, rng, "ball 10000");
  std::vector<Vector3d> sphere;
  for (int i = 0; i < 10000; ++i) sphere.push_back(Vector3d(2.0, 1.0, 0.5).cwiseProduct(shapes::randomUnit(rng)));
  const ConvexPolytope ellipsoid = ConvexPolytope::fromPoints(sphere);
  BOOST_TEST(ellipsoid.numVertices() == 10000);
  // The principal axes of an axis-aligned ellipsoid's samples are close to x, y, z.
  BOOST_TEST(std::abs(ellipsoid.principalAxes()(0, 0)) > 0.99);
  BOOST_TEST(std::abs(ellipsoid.principalAxes()(1, 1)) > 0.99);
  checkHull(ellipsoid, sphere, rng, "ellipsoid 10000");
}

BOOST_AUTO_TEST_CASE(flat_sets_are_classified_before_qhull) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> tiny(-1e-12, 1e-12);  // below kFlatRelative * L
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Matrix3d R = shapes::randomRotation(rng).toRotationMatrix();
    const Vector3d t = (trial % 2 ? 1e4 : 1.0) * shapes::randomUnit(rng);
    std::vector<Vector3d> flat;
    std::vector<Vector3d> line;
    for (int i = 0; i < 200; ++i) {
      flat.push_back(t + R * Vector3d(u(rng), u(rng), tiny(rng)));
      line.push_back(t + R * Vector3d(u(rng), tiny(rng), tiny(rng)));
    }
    BOOST_TEST(toString(ConvexPolytope::fromPoints(flat).kind()) == std::string("Polygon"));
    BOOST_TEST(toString(ConvexPolytope::fromPoints(line).kind()) == std::string("Segment"));
    checkHull(ConvexPolytope::fromPoints(flat), flat, rng, "thin flat set");
    checkHull(ConvexPolytope::fromPoints(line), line, rng, "thin line");
  }
}

BOOST_AUTO_TEST_CASE(pair_frame_maps_vertices) {
  std::mt19937 rng(24);
  for (double offset : {0.0, 1e4}) {
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<Vector3d> pa;
      std::vector<Vector3d> pb;
      for (int i = 0; i < 30; ++i) {
        pa.push_back(Vector3d(0.3, -0.2, 0.5) + inBall(rng));
        pb.push_back(Vector3d(-1.0 / 3.0, 0.7, 0.1) + 0.5 * inBall(rng));
      }
      const ConvexPolytope A = ConvexPolytope::fromPoints(pa);
      const ConvexPolytope B = ConvexPolytope::fromPoints(pb);
      const Vector3d o = offset * Vector3d(1.0, -1.0, 1.0);
      Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
      Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
      X_WA.linear() = shapes::randomRotation(rng).toRotationMatrix();
      X_WB.linear() = shapes::randomRotation(rng).toRotationMatrix();
      const Vector3d a = inBall(rng);
      const Vector3d b = inBall(rng);
      X_WA.translation() = o + a;
      X_WB.translation() = o + b;
      const PairFrame frame = PairFrame::make(A, X_WA, B, X_WB);

      // The same relative pose at the origin gives the same frame, up to the digits the world
      // positions o + a and o + b carry.
      Eigen::Isometry3d X0_WA = X_WA;
      Eigen::Isometry3d X0_WB = X_WB;
      X0_WA.translation() = X_WA.translation() - o;
      X0_WB.translation() = X_WB.translation() - o;
      const PairFrame near = PairFrame::make(A, X0_WA, B, X0_WB);
      BOOST_TEST((frame.R - near.R).norm() == 0.0);
      BOOST_TEST((frame.t - near.t).norm() <= 1e-14);

      // Direct world transforms agree (they lose digits far from the origin: 1e-11 there).
      const double tolWorld = offset > 0 ? 1e-11 : 1e-14;
      double worstWorld = 0.0;
      double worstLocal = 0.0;
      for (int v = 0; v < B.numVertices(); ++v) {
        const Vector3d direct = X_WB * B.vertex(v);
        worstWorld = std::max(worstWorld, (direct - frame.X_WP * frame.vertexB(B, v)).norm());
        // Mapped into P through the world near the origin: no large numbers on that route.
        const Vector3d inP = near.X_WP.inverse() * (X0_WB * B.vertex(v));
        worstLocal = std::max(worstLocal, (inP - frame.vertexB(B, v)).norm());
      }
      for (int v = 0; v < A.numVertices(); ++v) {
        const Vector3d direct = X_WA * A.vertex(v);
        worstWorld = std::max(worstWorld, (direct - frame.X_WP * PairFrame::vertexA(A, v)).norm());
      }
      BOOST_TEST(worstWorld <= tolWorld);
      BOOST_TEST(worstLocal <= 1e-14);
      const Vector3d d = shapes::randomUnit(rng);
      BOOST_TEST((frame.fromB(frame.toB(d)) - d).norm() < 1e-14);
      BOOST_TEST((frame.toB(d) - X_WB.linear().transpose() * (X_WA.linear() * d)).norm() < 1e-14);
    }
  }
}

BOOST_AUTO_TEST_CASE(pair_frame_rejects_bad_poses) {
  const ConvexPolytope A = ConvexPolytope::box(Vector3d(1, 1, 1));
  Eigen::Isometry3d good = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d bad = Eigen::Isometry3d::Identity();
  bad.translation().y() = std::numeric_limits<double>::quiet_NaN();
  BOOST_CHECK_EXCEPTION(PairFrame::make(A, bad, A, good), std::invalid_argument, [](const std::exception& e) {
    return messageHas(e, {"X_WA", "nan"});
  });
  bad = Eigen::Isometry3d::Identity();
  bad.linear()(0, 1) = std::numeric_limits<double>::infinity();
  BOOST_CHECK_EXCEPTION(PairFrame::make(A, good, A, bad), std::invalid_argument, [](const std::exception& e) {
    return messageHas(e, {"X_WB", "inf"});
  });
  bad = Eigen::Isometry3d::Identity();
  bad.linear() *= 1.001;
  BOOST_CHECK_EXCEPTION(PairFrame::make(A, good, A, bad), std::invalid_argument, [](const std::exception& e) {
    return messageHas(e, {"X_WB", "orthonormal", "0.002"});
  });
  bad = Eigen::Isometry3d::Identity();
  bad.linear()(2, 2) = -1.0;
  BOOST_CHECK_EXCEPTION(deepcheck::geometry::checkPose(bad, "link pose"), std::invalid_argument,
                        [](const std::exception& e) {
                          return messageHas(e, {"link pose", "reflection"});
                        });
  Eigen::Isometry3d slightly = Eigen::Isometry3d::Identity();
  slightly.linear() *= 1.0 + 1e-9;
  BOOST_CHECK_NO_THROW(deepcheck::geometry::checkPose(slightly, "almost"));
  // Around the tolerance on R^T R - I (1e-6): 8e-7 off is accepted, 1.2e-6 off is not.
  Eigen::Isometry3d near = Eigen::Isometry3d::Identity();
  near.linear() *= 1.0 + 4e-7;
  BOOST_CHECK_NO_THROW(deepcheck::geometry::checkPose(near, "near"));
  near.linear() = Eigen::Matrix3d::Identity() * (1.0 + 6e-7);
  BOOST_CHECK_EXCEPTION(deepcheck::geometry::checkPose(near, "near"), std::invalid_argument,
                        [](const std::exception& e) {
                          return messageHas(e, {"near", "orthonormal"});
                        });
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation().x() = 1e51;
  BOOST_CHECK_THROW(deepcheck::geometry::checkPose(far, "far"), std::invalid_argument);
}

BOOST_AUTO_TEST_SUITE_END()
