#pragma once
// What several fuzz harnesses share: the bundled arm, the rigid-pose check, and the failure of a
// property (an abort, which libFuzzer reports as a crash with the input).

#include "deepcheck/robots/robot_model.h"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace deepcheck::fuzz {

/// The bundled arm (robots/data), loaded once; ROS_PACKAGE_PATH is not read.
inline const robots::RobotModel& bundledArm() {
  static const robots::RobotModel model = [] {
    robots::LoadOptions options;
    options.packageRoots = {DEEPCHECK_SOURCE_DIR "/robots/data"};
    options.useRosPackagePath = false;
    return robots::RobotModel::fromUrdfFile(DEEPCHECK_SOURCE_DIR "/robots/data/deepcheck_arm/urdf/deepcheck_arm.urdf",
                                            options);
  }();
  return model;
}

/// Finite, with a rotation part that is a proper rotation (to 1e-9).
inline bool rigid(const Eigen::Isometry3d& X) {
  const Eigen::Matrix3d R = X.linear();
  return X.matrix().allFinite() && (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-9 &&
         std::abs(R.determinant() - 1.0) < 1e-9;
}

/// Aborts, saying `what` about `subject`, unless `ok`.
inline void require(bool ok, const char* subject, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "%s: %s\n", subject, what);
  std::abort();
}

}  // namespace deepcheck::fuzz
