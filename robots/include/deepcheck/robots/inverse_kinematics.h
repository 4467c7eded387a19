#pragma once
// Inverse kinematics of one link of a RobotModel: a configuration q, within the joint limits, that
// puts the link's frame L at a target pose X_WT (frames as in robot_model.h and kinematics.h).
//
//   const robots::IkResult r = robots::solveInverseKinematics(model, "flange", X_WT, options);
//   if (r.converged()) use(r.q); else report(r.error);  // r.q is then the best attempt, not a solution
//
// Method: damped least squares (Levenberg-Marquardt) on the 6-D pose error, with the robot's own
// spatial Jacobian (kinematics.h) at the link origin. The error, in W, is
//   e = [ log(R_WT R_WL^T) ; p_WT - p_WL ]   (rotation vector, radians; position, metres),
// the step dq = J^T (J J^T + lambda^2 I)^-1 e, scaled down so that no joint moves more than
// IkOptions::maxJointStep. Joint limits: after each step a limited joint is clamped into
// [lower, upper]; a joint at a limit that the step pushes outwards is frozen (its Jacobian column
// removed) and the step recomputed, so the other joints do the work (projection on the box).
// Continuous joints are wrapped into the model's [-pi, pi] instead of clamped; fixed and mimic
// joints are not variables (a mimic joint's motion is in its variable's Jacobian column).
// Attempts: the first starts from IkOptions::initial (a random configuration when empty), each of
// the maxRestarts further ones from a configuration drawn uniformly within the limits by a
// std::mt19937_64 seeded with IkOptions::seed, so the result is a function of the inputs and the
// seed. An attempt ends when the pose is reached, after maxIterations, or when it stalls.
//
// Position tolerance: a sphere of radius IkOptions::positionTolerance around p_WT, or, when
// IkOptions::positionBox is set, a box region (MoveIt's and MotionBenchMaker's): the frame B
// attached to the link at X_LB = IkOptions::boxPose must have its origin within the box of those
// edge lengths along the axes of B's target X_WT X_LB, centred on that target's origin. With
// boxPose the identity, the link origin within a box along T's axes. With the box, the position
// rows of e are the gap from B's origin to the box (zero inside it), and the Jacobian is taken at
// B's origin, so an unreachable centre does not stop a reachable corner.
//
// Result: converged() only when the final q, within the limits, reaches the pose within both
// tolerances (and, when an acceptance test is given, passes it: a collision test, say); otherwise
// the status says why and q is the end of the attempt with the smallest normalized error (for
// Rejected, a configuration that reaches the pose but fails the acceptance test).
//
// Errors: std::invalid_argument naming the value: an unknown link (the message lists the links), a
// non-finite or non-rigid target pose, a tolerance, iteration count or damping that is not
// positive and finite, a position box with a negative, non-finite or (among positive ones) zero
// edge length or a boxPose that is not a finite rigid transform, an initial configuration of the wrong size or with a
// non-finite value.

#include "deepcheck/robots/robot_model.h"
#include "deepcheck/robots/tolerances.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <functional>
#include <string>

namespace deepcheck::robots {

struct IkOptions {
  double positionTolerance = tol::kIkPositionTolerance;        ///< metres
  double orientationTolerance = tol::kIkOrientationTolerance;  ///< radians
  /// Edge lengths of a position box along T's axes, metres (the full widths, as every box of the
  /// API and MoveIt's box constraint region; B's origin may be up to half of each from the
  /// target); all zero (the default): the sphere of radius positionTolerance instead. Either all
  /// zero or all positive.
  Eigen::Vector3d positionBox = Eigen::Vector3d::Zero();
  /// X_LB: where on the link the box applies, and the box's axes (see the file comment).
  Eigen::Isometry3d boxPose = Eigen::Isometry3d::Identity();
  int maxIterations = tol::kIkMaxIterations;   ///< per attempt
  int maxRestarts = tol::kIkMaxRestarts;       ///< attempts after the first
  double damping = tol::kIkDamping;            ///< initial lambda
  double maxJointStep = tol::kIkMaxJointStep;  ///< rad (m for prismatic)
  std::uint64_t seed = 0;                      ///< of the restarts
  /// Start of the first attempt (numVariables() values; clamped into the limits); empty: random.
  Eigen::VectorXd initial;
};

/// How far the link's pose is from the target.
struct PoseError {
  double position = 0.0;     ///< |p_WT - p_WL|, metres
  double orientation = 0.0;  ///< angle of R_WT R_WL^T, radians in [0, pi]
  /// max(position part, orientation / orientationTolerance): at most 1 exactly when the pose is
  /// reached. The position part is position / positionTolerance, or with a box max_i |d_i| / h_i
  /// (d = B's origin in its target's frame, h = positionBox / 2). Dimensionless; what "best" means between attempts.
  double normalized = 0.0;
  bool within() const { return normalized <= 1.0; }
};

enum class IkStatus {
  Converged,     ///< q reaches the pose within the tolerances (and passes the acceptance test)
  NotConverged,  ///< no attempt reached the pose; q is the best one
  Rejected,      ///< attempts reached the pose, the acceptance test rejected every one
};
const char* toString(IkStatus status);

struct IkResult {
  IkStatus status = IkStatus::NotConverged;
  Eigen::VectorXd q;   ///< the solution, or the best configuration found (see status)
  PoseError error;     ///< of q
  int attempts = 0;    ///< started (1 + restarts used)
  int iterations = 0;  ///< over all attempts
  int rejected = 0;    ///< solutions the acceptance test rejected
  bool converged() const { return status == IkStatus::Converged; }
};

/// A test a solution must also pass (true: accept), e.g. "collision free".
using IkAcceptFn = std::function<bool(const Eigen::VectorXd& q)>;

/// Index of link `name`; throws std::invalid_argument naming it and listing the links when the
/// robot has none of that name.
int requireLink(const RobotModel& model, const std::string& name);

/// X_WT from a position and a quaternion (x y z w, MoveIt's order). Throws std::invalid_argument
/// naming the value for a non-finite entry or a quaternion whose norm differs from 1 by more than
/// tol::kQuaternionUnitNorm; normalizes it otherwise.
Eigen::Isometry3d poseFromQuaternion(const Eigen::Vector3d& p_WT, double qx, double qy, double qz, double qw);

/// Checks a problem before solving: `link` names a link (requireLink), X_WT is finite and rigid
/// (rotation orthonormal within tol::kOrthonormality, right-handed), every option is usable
/// (tolerances, damping and step positive and finite, maxIterations >= 1, maxRestarts >= 0) and
/// `initial` is empty or a finite configuration of `model`. Throws std::invalid_argument naming
/// the value; returns the link's index.
int checkIkProblem(const RobotModel& model, const std::string& link, const Eigen::Isometry3d& X_WT,
                   const IkOptions& options);

/// The error of link `link` at q against X_WT (tolerances from `options` for `normalized`).
PoseError poseError(const RobotModel& model, int link, const Eigen::Ref<const Eigen::VectorXd>& q,
                    const Eigen::Isometry3d& X_WT, const IkOptions& options = {});

/// Solves for link `link` reaching X_WT. See the file comment.
IkResult solveInverseKinematics(const RobotModel& model, const std::string& link, const Eigen::Isometry3d& X_WT,
                                const IkOptions& options = {}, const IkAcceptFn& accept = {});

}  // namespace deepcheck::robots
