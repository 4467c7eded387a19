#pragma once
// Wrap-around variables: the angles of continuous joints, taken modulo 2 pi.
//
// A variable WRAPS when turning it by 2 pi gives the same robot pose: its own joint is continuous
// (robot_model.h), and every joint it drives (mimic joints included) is continuous with a
// non-zero integer multiplier (a mimic with multiplier 1/2 or a revolute mimic with limits turns
// a different amount, or leaves its limits, after 2 pi; such a variable keeps the bounded
// [-pi, pi] of robot_model.h). Locked joints are fixed joints and drive nothing.
//
// The values of wrapping variables are normalized to (-pi, pi] wherever they enter deepcheck:
// planners' state spaces (an SO2 subspace per wrapping variable, planners/state_space.h),
// setStartAndGoal, the problem files, and the `check` and `plan` command lines. A value of
// 4.0 rad is then 4.0 - 2 pi = -2.283 rad, the same angle; it is not refused as outside the
// [-pi, pi] the model reports as its limits.
//
// Units: radians.

#include "deepcheck/robots/robot_model.h"

#include <Eigen/Core>

#include <vector>

namespace deepcheck::robots {

/// x modulo 2 pi in (-pi, pi] (pi = M_PI, the double nearest pi): -pi maps to pi, 3 pi to pi.
/// Exact: the result is x - 2 pi k for the integer k nearest x / (2 pi), computed without rounding
/// (std::remainder), so normalizing an already normalized value returns it unchanged. NaN and
/// infinities are returned as NaN.
double normalizeAngle(double x);

/// True when variable v of `model` wraps (see the header comment); throws std::invalid_argument
/// for a variable index out of range.
bool isWrappingVariable(const RobotModel& model, int v);

/// isWrappingVariable for every variable, in variable order.
std::vector<bool> wrappingVariables(const RobotModel& model);

/// Normalizes the wrapping variables of q (one value per variable of `model`) to (-pi, pi], in
/// place; the others are left as they are. Throws std::invalid_argument for a q of another size.
void normalizeWrappingVariables(const RobotModel& model, Eigen::Ref<Eigen::VectorXd> q);

}  // namespace deepcheck::robots
