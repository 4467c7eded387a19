#pragma once
// Random and named shapes for the deep test suites (pinned seeds everywhere).

#include "deepcheck/geometry/polytope.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace deepcheck::geometry::testing {

inline Eigen::Vector3d randomUnit(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Vector3d v;
  do {
    v = Eigen::Vector3d(g(rng), g(rng), g(rng));
  } while (v.norm() < 1e-6);
  return v.normalized();
}

inline Eigen::Quaterniond randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  q.normalize();
  return q;
}

inline Eigen::Isometry3d makePose(const Eigen::Quaterniond& q, const Eigen::Vector3d& t) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = t;
  return X;
}

/// n points on the surface of an ellipsoid with the given semi-axes (all hull vertices).
inline std::vector<Eigen::Vector3d> ellipsoidPoints(std::mt19937& rng, int n, const Eigen::Vector3d& semi) {
  std::vector<Eigen::Vector3d> pts;
  pts.reserve(n);
  for (int i = 0; i < n; ++i) pts.push_back(randomUnit(rng).cwiseProduct(semi));
  return pts;
}

/// Points of an axis-aligned box surface grid (many coplanar points) with half extents h.
inline std::vector<Eigen::Vector3d> boxCorners(const Eigen::Vector3d& h) {
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 8; ++i)
    pts.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  return pts;
}

/// A prism approximating a cylinder of the given radius and length along z, with `sides` sides.
inline std::vector<Eigen::Vector3d> prismPoints(double radius, double length, int sides) {
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < sides; ++i) {
    const double a = 2 * M_PI * i / sides;
    for (int s = -1; s <= 1; s += 2) pts.emplace_back(radius * std::cos(a), radius * std::sin(a), s * length / 2);
  }
  return pts;
}

/// Length scale of the depth error measure: the larger bounding radius of the two shapes.
inline double depthScale(const ConvexPolytope& A, const ConvexPolytope& B) {
  return std::max(A.boundingRadius(), B.boundingRadius());
}

/// Error of a signed distance against the exact one: relative to the depth, except that depths
/// below a thousandth of the shapes' size L are compared in absolute terms at that scale.
inline double depthError(double sd, double exact, double L) {
  return std::abs(sd - exact) / std::max(std::abs(exact), 1e-3 * L);
}

}  // namespace deepcheck::geometry::testing
