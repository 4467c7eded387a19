#include "deepcheck/robots/inverse_kinematics.h"

#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/random_configuration.h"

#include <Eigen/Cholesky>

#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace deepcheck::robots {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Jacobian = Eigen::Matrix<double, 6, Eigen::Dynamic>;

bool hasBox(const IkOptions& options) { return (options.positionBox.array() > 0.0).all(); }

/// Origin of the box frame B, in B's target frame (see the file comment of the header).
Eigen::Vector3d boxOffset(const Eigen::Isometry3d& X_WL, const Eigen::Isometry3d& X_WT, const IkOptions& options) {
  const Eigen::Isometry3d X_WBtarget = X_WT * options.boxPose;
  return X_WBtarget.inverse() * (X_WL * options.boxPose.translation());
}

/// [rotation vector of R_WT R_WL^T; position error], in W: the angular rows first, as the spatial
/// Jacobian's. The position error is p_WT - p_WL, or with a box the step from B's origin to the
/// box scaled by tol::kIkBoxAimScale.
Vector6d errorVector(const Eigen::Isometry3d& X_WL, const Eigen::Isometry3d& X_WT, const IkOptions& options) {
  const Eigen::AngleAxisd rotation(X_WT.linear() * X_WL.linear().transpose());
  Vector6d e;
  e.head<3>() = rotation.angle() * rotation.axis();
  e.tail<3>() = X_WT.translation() - X_WL.translation();
  if (hasBox(options)) {
    const Eigen::Vector3d d = boxOffset(X_WL, X_WT, options);
    const Eigen::Vector3d aim = tol::kIkBoxAimScale * 0.5 * options.positionBox;
    const Eigen::Vector3d outside = d - d.cwiseMax(-aim).cwiseMin(aim);
    e.tail<3>() = (X_WT.linear() * options.boxPose.linear()) * -outside;
  }
  return e;
}

PoseError errorOf(const Eigen::Isometry3d& X_WL, const Eigen::Isometry3d& X_WT, const Vector6d& e,
                  const IkOptions& options) {
  PoseError error;
  error.orientation = e.head<3>().norm();
  error.position = (X_WT.translation() - X_WL.translation()).norm();
  const double positionPart =
      hasBox(options) ? boxOffset(X_WL, X_WT, options).cwiseAbs().cwiseQuotient(0.5 * options.positionBox).maxCoeff()
                      : error.position / options.positionTolerance;
  error.normalized = std::max(positionPart, error.orientation / options.orientationTolerance);
  return error;
}

bool isContinuous(const RobotModel& model, int v) {
  return model.joint(model.variableJoint(v)).type == JointType::Continuous;
}

/// Continuous joints wrapped into [-pi, pi], the others clamped into their limits.
void applyLimits(const RobotModel& model, Eigen::VectorXd& q) {
  for (int v = 0; v < q.size(); ++v) {
    if (isContinuous(model, v)) {
      q[v] = std::remainder(q[v], 2.0 * M_PI);
    } else {
      q[v] = std::min(std::max(q[v], model.lowerLimits()[v]), model.upperLimits()[v]);
    }
  }
}

/// The damped least-squares step with the joints that sit at a limit and would be pushed beyond
/// it frozen (their columns removed), scaled to at most maxJointStep per joint.
Eigen::VectorXd projectedStep(const RobotModel& model, Jacobian J, const Vector6d& e, const Eigen::VectorXd& q,
                              double lambda, double maxJointStep) {
  Eigen::VectorXd dq(q.size());
  for (int pass = 0; pass <= q.size(); ++pass) {
    Eigen::Matrix<double, 6, 6> A = J * J.transpose();
    A.diagonal().array() += lambda * lambda;
    dq.noalias() = J.transpose() * A.ldlt().solve(e);
    const double largest = dq.cwiseAbs().maxCoeff();
    if (largest > maxJointStep) dq *= maxJointStep / largest;
    bool froze = false;
    for (int v = 0; v < q.size(); ++v) {
      if (isContinuous(model, v) || J.col(v).isZero()) continue;
      const bool outwards =
          (q[v] <= model.lowerLimits()[v] && dq[v] < 0.0) || (q[v] >= model.upperLimits()[v] && dq[v] > 0.0);
      if (outwards) {
        J.col(v).setZero();
        froze = true;
      }
    }
    if (!froze) break;
  }
  return dq;
}

/// One attempt from q (within the limits): Levenberg-Marquardt iterations until the pose is
/// reached, the iterations run out or the damping exceeds its maximum. q becomes the attempt's
/// end; returns its error. `iterations` counts the Jacobians evaluated.
PoseError runAttempt(const RobotModel& model, int link, const Eigen::Isometry3d& X_WT, const IkOptions& options,
                     Eigen::VectorXd& q, int& iterations) {
  std::vector<Eigen::Isometry3d> X_WL = forwardKinematics(model, q);
  std::vector<Eigen::Isometry3d> X_WL_trial;
  Vector6d e = errorVector(X_WL[link], X_WT, options);
  const Eigen::Vector3d jacobianPoint =
      hasBox(options) ? Eigen::Vector3d(options.boxPose.translation()) : Eigen::Vector3d::Zero();
  double lambda = options.damping;
  Jacobian J;
  Eigen::VectorXd trial;
  for (int it = 0; it < options.maxIterations && !errorOf(X_WL[link], X_WT, e, options).within(); ++it) {
    ++iterations;
    spatialJacobian(model, X_WL, link, jacobianPoint, J);
    trial = q + projectedStep(model, J, e, q, lambda, options.maxJointStep);
    applyLimits(model, trial);
    forwardKinematics(model, trial, X_WL_trial);
    const Vector6d eTrial = errorVector(X_WL_trial[link], X_WT, options);
    if (eTrial.squaredNorm() < e.squaredNorm()) {
      q.swap(trial);
      X_WL.swap(X_WL_trial);
      e = eTrial;
      lambda = std::max(0.5 * lambda, tol::kIkMinDamping);
    } else {
      lambda *= 4.0;
      if (lambda > tol::kIkMaxDamping) break;  // stalled: a local minimum of the error
    }
  }
  return errorOf(X_WL[link], X_WT, e, options);
}

[[noreturn]] void badOption(const char* name, double value, const char* requirement) {
  std::ostringstream msg;
  msg << "inverse kinematics: option " << name << " is " << value << ", it must be " << requirement;
  throw std::invalid_argument(msg.str());
}

bool isRigid(const Eigen::Isometry3d& X) {
  const Eigen::Matrix3d R = X.linear();
  const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  return X.matrix().allFinite() && error <= tol::kOrthonormality && R.determinant() > 0.0;
}

void checkTarget(const RobotModel& model, const std::string& link, const Eigen::Isometry3d& X_WT) {
  if (!isRigid(X_WT)) {
    std::ostringstream msg;
    msg << "robot '" << model.name() << "': target pose of link '" << link << "' is not a finite rigid transform:\n"
        << X_WT.matrix();
    throw std::invalid_argument(msg.str());
  }
}

void checkBox(const IkOptions& options) {
  const Eigen::Vector3d& h = options.positionBox;
  if (!h.allFinite() || (h.array() < 0.0).any() || ((h.array() == 0.0).any() && (h.array() > 0.0).any())) {
    std::ostringstream msg;
    msg << "inverse kinematics: option positionBox (m) is (" << h.x() << ", " << h.y() << ", " << h.z()
        << "), its edge lengths must be all positive and finite, or all zero for the positionTolerance sphere";
    throw std::invalid_argument(msg.str());
  }
  if (!isRigid(options.boxPose)) {
    std::ostringstream msg;
    msg << "inverse kinematics: option boxPose is not a finite rigid transform:\n" << options.boxPose.matrix();
    throw std::invalid_argument(msg.str());
  }
}

void checkOptions(const RobotModel& model, const IkOptions& options) {
  const auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!positive(options.positionTolerance)) badOption("positionTolerance (m)", options.positionTolerance, "positive");
  if (!positive(options.orientationTolerance)) {
    badOption("orientationTolerance (rad)", options.orientationTolerance, "positive");
  }
  checkBox(options);
  if (!positive(options.damping)) badOption("damping", options.damping, "positive");
  if (!positive(options.maxJointStep)) badOption("maxJointStep", options.maxJointStep, "positive");
  if (options.maxIterations < 1) badOption("maxIterations", options.maxIterations, "at least 1");
  if (options.maxRestarts < 0) badOption("maxRestarts", options.maxRestarts, "at least 0");
  if (options.initial.size() > 0) checkConfiguration(model, options.initial);
}

}  // namespace

const char* toString(IkStatus status) {
  switch (status) {
    case IkStatus::Converged:
      return "converged";
    case IkStatus::NotConverged:
      return "not converged";
    case IkStatus::Rejected:
      return "every solution rejected";
  }
  return "?";
}

int requireLink(const RobotModel& model, const std::string& name) {
  const int link = model.linkIndex(name);
  if (link >= 0) return link;
  std::ostringstream msg;
  msg << "robot '" << model.name() << "': no link named '" << name << "' (links:";
  for (const Link& l : model.links()) msg << " " << l.name;
  msg << ")";
  throw std::invalid_argument(msg.str());
}

Eigen::Isometry3d poseFromQuaternion(const Eigen::Vector3d& p_WT, double qx, double qy, double qz, double qw) {
  const Eigen::Quaterniond quaternion(qw, qx, qy, qz);
  const double norm = quaternion.norm();
  if (!p_WT.allFinite() || !quaternion.coeffs().allFinite() || !(std::abs(norm - 1.0) <= tol::kQuaternionUnitNorm)) {
    std::ostringstream msg;
    msg << "pose: position (" << p_WT.transpose() << "), quaternion (x y z w) (" << qx << " " << qy << " " << qz << " "
        << qw << ")";
    if (!p_WT.allFinite() || !quaternion.coeffs().allFinite()) {
      msg << " has a value that is not finite";
    } else {
      msg << " is not a unit quaternion: its norm is " << norm;
    }
    throw std::invalid_argument(msg.str());
  }
  Eigen::Isometry3d X_WT = Eigen::Isometry3d::Identity();
  X_WT.linear() = quaternion.normalized().toRotationMatrix();
  X_WT.translation() = p_WT;
  return X_WT;
}

int checkIkProblem(const RobotModel& model, const std::string& link, const Eigen::Isometry3d& X_WT,
                   const IkOptions& options) {
  const int index = requireLink(model, link);
  checkTarget(model, link, X_WT);
  checkOptions(model, options);
  return index;
}

PoseError poseError(const RobotModel& model, int link, const Eigen::Ref<const Eigen::VectorXd>& q,
                    const Eigen::Isometry3d& X_WT, const IkOptions& options) {
  if (link < 0 || link >= model.numLinks()) {
    std::ostringstream msg;
    msg << "robot '" << model.name() << "': link index " << link << " out of range [0, " << model.numLinks() << ")";
    throw std::invalid_argument(msg.str());
  }
  const std::vector<Eigen::Isometry3d> X_WL = forwardKinematics(model, q);
  return errorOf(X_WL[link], X_WT, errorVector(X_WL[link], X_WT, options), options);
}

IkResult solveInverseKinematics(const RobotModel& model, const std::string& linkName, const Eigen::Isometry3d& X_WT,
                                const IkOptions& options, const IkAcceptFn& accept) {
  const int link = checkIkProblem(model, linkName, X_WT, options);
  std::mt19937_64 rng(options.seed);
  IkResult result;
  for (int attempt = 0; attempt <= options.maxRestarts; ++attempt) {
    Eigen::VectorXd q = attempt == 0 && options.initial.size() > 0 ? options.initial : randomConfiguration(model, rng);
    applyLimits(model, q);
    ++result.attempts;
    const PoseError error = runAttempt(model, link, X_WT, options, q, result.iterations);
    if (error.within()) {
      if (!accept || accept(q)) {
        result.status = IkStatus::Converged;
        result.q = q;
        result.error = error;
        return result;
      }
      ++result.rejected;
      result.status = IkStatus::Rejected;
    }
    if (result.q.size() == 0 || error.normalized < result.error.normalized) {
      result.q = q;
      result.error = error;
    }
  }
  return result;
}

}  // namespace deepcheck::robots
