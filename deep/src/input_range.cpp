// Checks of the supported numeric range (input_range.h).

#include "deepcheck/deep/input_range.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace deepcheck::deep::range {
namespace {

const char* axisLabel(int axis) { return axis == 0 ? "x" : (axis == 1 ? "y" : "z"); }

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string coordinateProblem(double x) {
  if (!std::isfinite(x)) return "non-finite";
  return "out-of-range (|value| > " + number(kMaxCoordinate) + ")";
}

}  // namespace

void checkPoints(const std::vector<Eigen::Vector3d>& points, const std::string& name) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double x = points[i][c];
      if (!(std::abs(x) <= kMaxCoordinate)) {
        throw std::invalid_argument(name + ": point " + std::to_string(i) + " has a " +
                                    coordinateProblem(x) + " coordinate " + axisLabel(c) + " = " +
                                    number(x));
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
    const double x = translation[c];
    if (!(std::abs(x) <= kMaxCoordinate)) {
      throw std::invalid_argument(what + ": pose has a " + coordinateProblem(x) + " translation " +
                                  axisLabel(c) + " = " + number(x));
    }
  }
}

}  // namespace deepcheck::deep::range
