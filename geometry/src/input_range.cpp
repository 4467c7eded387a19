// Checks of the supported numeric range (input_range.h).

#include "deepcheck/geometry/input_range.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace deepcheck::geometry::range {
namespace {

const char* axisLabel(int axis) { return axis == 0 ? "x" : (axis == 1 ? "y" : "z"); }

/// The shortest text that reads back as x (1e+50, not 1.0000000000000001e+50).
std::string number(double x) {
  char buf[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, x);
    if (std::strtod(buf, nullptr) == x) break;
  }
  return buf;
}

}  // namespace

void checkCoordinate(double x, const std::string& what) {
  if (std::abs(x) <= kMaxCoordinate) return;
  throw std::invalid_argument(
      what + " = " + number(x) + " is " +
      (std::isfinite(x) ? "out of range (|value| > " + number(kMaxCoordinate) + ")" : std::string("non-finite")));
}

void checkPoints(const std::vector<Eigen::Vector3d>& points, const std::string& name) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      // The message is built only for a bad value: this runs on every point of every hull.
      if (!(std::abs(points[i][c]) <= kMaxCoordinate)) {
        checkCoordinate(points[i][c], name + ": point " + std::to_string(i) + " coordinate " + axisLabel(c));
      }
    }
  }
  if (points.empty()) return;
  Eigen::Vector3d lo = points[0];
  Eigen::Vector3d hi = points[0];
  for (const Eigen::Vector3d& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double extent = (hi - lo).maxCoeff();
  if (extent > 0.0 && extent < kMinExtent) {
    throw std::invalid_argument(name + ": the points span only " + number(extent) +
                                " (largest coordinate spread), below the smallest supported extent " +
                                number(kMinExtent) + " (use a larger length unit)");
  }
}

void checkTranslation(const Eigen::Vector3d& translation, const std::string& what) {
  for (int c = 0; c < 3; ++c) {
    if (!(std::abs(translation[c]) <= kMaxCoordinate)) {
      checkCoordinate(translation[c], what + ": pose translation " + axisLabel(c));
    }
  }
}

}  // namespace deepcheck::geometry::range
