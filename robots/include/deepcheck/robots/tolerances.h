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

/// Inverse kinematics (inverse_kinematics.h). A pose is reached when the link origin is within
/// kIkPositionTolerance metres of the target position AND the rotation from the link's orientation
/// to the target's is at most kIkOrientationTolerance radians. 0.1 mm and 1 mrad (0.057 deg) are
/// far below what a collision checker with a 1 mm decomposition resolves; the damped least
/// squares converge quadratically near a solution, so tighter values cost few iterations.
constexpr double kIkPositionTolerance = 1e-4;
constexpr double kIkOrientationTolerance = 1e-3;
/// Damped least-squares iterations per attempt, and random restarts after the first attempt.
constexpr int kIkMaxIterations = 100;
constexpr int kIkMaxRestarts = 50;
/// Initial damping lambda of the damped least squares, in the units of the pose error (metres and
/// radians weighted alike): dq = J^T (J J^T + lambda^2 I)^-1 e. Halved after a step that lowers
/// the error, multiplied by 4 after one that does not (Levenberg-Marquardt), kept within
/// [kIkMinDamping, kIkMaxDamping]; an attempt whose damping would exceed the maximum has stalled.
constexpr double kIkDamping = 1e-2;
constexpr double kIkMinDamping = 1e-6;
constexpr double kIkMaxDamping = 1e3;
/// Largest change of one joint in one iteration, radians (metres for a prismatic joint): the
/// linearization holds over a fraction of a radian, and a larger step overshoots.
constexpr double kIkMaxJointStep = 0.5;
/// With a position box (IkOptions::positionBox), the iterations aim at the box scaled by this
/// factor (dimensionless): converging from outside onto the box's own face would approach the
/// acceptance boundary without ever passing it, 1 % inside is passed in one more step.
constexpr double kIkBoxAimScale = 0.99;
/// A quaternion given for a pose (poseFromQuaternion) must have |norm - 1| at most this: values
/// typed with four significant digits (0.7071 for sqrt(1/2): norm 0.99999) are accepted, a
/// forgotten or mistyped component is not. The quaternion is then normalized.
constexpr double kQuaternionUnitNorm = 1e-4;

}  // namespace deepcheck::robots::tol
