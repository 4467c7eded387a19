#pragma once
// The numeric range deepcheck::geometry supports, and the checks that reject input outside it.
//
// Every algorithm works in plain double precision on differences of coordinates and forms
// products of up to six lengths (squared norms of cross products, determinants of edge vectors,
// squared distances of them). Such a product stays a normal, finite double when every length
// involved lies between kMinExtent and kMaxCoordinate (1e-50^6 = 1e-300 > DBL_MIN ~ 2.2e-308;
// (2 * 1e50)^6 ~ 6.4e301 < DBL_MAX ~ 1.8e308). Within the range results are those of a scene
// scaled to unit size (all tolerances are relative, see tolerances.h); outside it squares
// overflow to infinity or underflow to zero, so the input is rejected instead of answered.
//
// Lengths are in the caller's unit (metres for robots): the range does not depend on it.

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace deepcheck::geometry::range {

/// Largest accepted magnitude of a coordinate: each vertex coordinate given to
/// ConvexPolytope::fromPoints (in the polytope's frame) and each pose translation component given
/// to signedDistance / exactSignedDistance (in the world frame). Same unit as the input.
constexpr double kMaxCoordinate = 1e50;

/// Smallest accepted extent (largest coordinate-wise spread, max over axes of max - min) of a
/// point set given to ConvexPolytope::fromPoints, unless the extent is exactly zero (a single
/// point, which is accepted). Same unit as the input.
constexpr double kMinExtent = 1e-50;

/// Throws std::invalid_argument "<what> = <x> is non-finite" or "... is out of range (|value| >
/// 1e+50)" unless x is finite with magnitude at most kMaxCoordinate.
void checkCoordinate(double x, const std::string& what);

/// Throws std::invalid_argument unless every coordinate of `points` is finite with magnitude at
/// most kMaxCoordinate and their extent is zero or at least kMinExtent. The message starts with
/// `name` and names the offending point index, axis and value (or the extent).
void checkPoints(const std::vector<Eigen::Vector3d>& points, const std::string& name);

/// Throws std::invalid_argument unless every component of `translation` has magnitude at most
/// kMaxCoordinate (non-finite ones included). The message starts with `what` and names the value.
void checkTranslation(const Eigen::Vector3d& translation, const std::string& what);

}  // namespace deepcheck::geometry::range
