#pragma once
// Closest point on a triangle: the one geometric primitive shared by the exact reference
// (exact.cpp, distance from the origin to a facet of the Minkowski difference) and the convex
// decomposition's point-to-mesh distances (robots).

#include <Eigen/Core>

namespace deepcheck::geometry {

/// Closest point to `p` on the triangle (a, b, c), of any shape: degenerate (collinear or
/// coincident) corners give the closest point of the three edges. Voronoi regions of the
/// triangle's features (vertices, edges, interior) are tested in that order with dot products of
/// edge vectors, so no division happens until the region is known.
Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c);

}  // namespace deepcheck::geometry
