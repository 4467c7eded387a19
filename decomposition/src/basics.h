#pragma once
// Internal to deepcheck::decomposition: small helpers the decomposer's files share (constants,
// how messages name meshes and numbers, plane and polygon arithmetic, a portable random source).

#include "deepcheck/decomposition/mesh.h"
#include "deepcheck/decomposition/tolerances.h"

#include "bvh.h"

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace deepcheck::decomposition::detail {

using Eigen::Vector3d;

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kPi = 3.141592653589793;

/// A mesh as messages name it: its source in quotes, or "(generated mesh)".
inline std::string meshName(const std::string& source) {
  return source.empty() ? std::string("(generated mesh)") : "'" + source + "'";
}
inline std::string meshName(const TriangleMesh& mesh) { return meshName(mesh.source); }

/// A number for an error message: 17 significant digits (%.17g), so the message names the value
/// the caller gave rather than a rounding of it.
inline std::string formatNumber(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

/// A length or ratio for a message read by a person: 3 significant digits.
inline std::string roundedNumber(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", v);
  return buffer;
}

/// Twice the vector area of a convex polygon given by its corners in order (the sum of the cross
/// products of its fan triangles): its normal, times twice its area.
inline Vector3d doubleVectorArea(const std::vector<Vector3d>& corners) {
  Vector3d area = Vector3d::Zero();
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
    area += (corners[k] - corners[0]).cross(corners[k + 1] - corners[0]);
  }
  return area;
}

/// The point where the planes of three half-spaces meet; false when two of them are (nearly)
/// parallel (see kSingularPlanes) or the point is not finite.
inline bool planesMeet(const Halfspace& a, const Halfspace& b, const Halfspace& c, Vector3d* point) {
  Eigen::Matrix3d A;
  A.row(0) = a.normal;
  A.row(1) = b.normal;
  A.row(2) = c.normal;
  if (std::abs(A.determinant()) < tol::kSingularPlanes) return false;
  *point = A.inverse() * Vector3d(a.offset, b.offset, c.offset);
  return point->allFinite();
}

/// The smallest and largest of d.p over `points`.
struct Extent {
  double lo, hi;
};
inline Extent extentAlong(const std::vector<Vector3d>& points, const Vector3d& d) {
  Extent e{kInf, -kInf};
  for (const Vector3d& p : points) {
    e.lo = std::min(e.lo, d.dot(p));
    e.hi = std::max(e.hi, d.dot(p));
  }
  return e;
}

// Deterministic random numbers (splitmix64): the same on every platform, unlike std distributions.

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t state_;
};

}  // namespace deepcheck::decomposition::detail
