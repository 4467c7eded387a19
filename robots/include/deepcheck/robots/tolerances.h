#pragma once
// All numerical tolerances and defaults of deepcheck::robots, in one place.
//
// Lengths are in metres. Where a tolerance is relative it says what it is multiplied by.

namespace deepcheck::robots::tol {

/// A mesh triangle is degenerate (and dropped) when its height over its longest edge is at most
/// kDegenerateTriangleRelative times the mesh's bounding-box diagonal, or when two of its corners
/// are the same vertex. Collision meshes are mostly binary STL, whose float32 coordinates carry a
/// round-off of 6e-8 of their magnitude, so a triangle that is collinear in the author's tool may
/// come back with a height of that order; 1e-7 of the diagonal (0.1 um on a 1 m mesh) catches
/// those and nothing a collision checker could resolve.
constexpr double kDegenerateTriangleRelative = 1e-7;

/// A joint axis whose Euclidean norm is below this is "zero" (an error for a moving joint).
/// URDF axes are unit vectors written with a handful of digits; anything else is normalized.
constexpr double kMinAxisNorm = 1e-9;

/// A rotation R is accepted as orthonormal (base poses) when every entry of R^T R - I is at most
/// this in magnitude (dimensionless).
constexpr double kOrthonormality = 1e-9;

/// Default bound on how far the circumscribed prism of a URDF cylinder may stick out of the true
/// cylinder, metres (see collision_geometry.h).
constexpr double kCylinderMaxDeviation = 1e-3;

/// Bounds on the number of sides of a cylinder's prism: at least a hexagon, at most 128 sides
/// (above that the prism's deviation is r * (1 / cos(pi / 128) - 1) = 3.0e-4 r, which exceeds the
/// default 1 mm only for cylinders of radius over 3.3 m).
constexpr int kCylinderMinSides = 6;
constexpr int kCylinderMaxSides = 128;

}  // namespace deepcheck::robots::tol
