// `deepcheck plan`'s --goal-pose and its tolerances (goal_pose.h).

#include "goal_pose.h"

#include "common.h"

#include "deepcheck/robots/inverse_kinematics.h"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <iterator>

namespace deepcheck::tools {
namespace {

/// X_WT from x y z qx qy qz qw (MoveIt's quaternion order), the quaternion normalized; UsageError
/// for a quaternion of norm below kMinQuaternionNorm.
Eigen::Isometry3d poseOfValues(const std::vector<std::string>& words) {
  static const char* const names[7] = {"x", "y", "z", "qx", "qy", "qz", "qw"};
  double v[7];
  for (int k = 0; k < 7; ++k)
    v[k] = parseValue(words[static_cast<std::size_t>(k)], std::string("--goal-pose ") + names[k]);
  // stableNorm: the plain norm squares the components, which overflows to infinity from about
  // 1e154 and would make every component zero after the division.
  const double norm = Eigen::Vector4d(v[3], v[4], v[5], v[6]).stableNorm();
  if (!(norm >= kMinQuaternionNorm)) {
    char text[48];
    std::snprintf(text, sizeof text, "%.3g", norm);
    throw UsageError("--goal-pose: the quaternion qx qy qz qw = " + words[3] + " " + words[4] + " " + words[5] + " " +
                     words[6] + " is zero (norm " + text + "): it gives no orientation");
  }
  return robots::poseFromQuaternion(Eigen::Vector3d(v[0], v[1], v[2]), v[3] / norm, v[4] / norm, v[5] / norm,
                                    v[6] / norm);
}

/// A tolerance option: positive and finite; empty when absent.
std::optional<double> takeTolerance(std::vector<std::string>& args, const std::string& name, const char* unit) {
  const std::string text = takeSingleOption(args, name);
  if (text.empty()) return std::nullopt;
  const double value = parseValue(text, name);
  if (!(value > 0.0)) throw UsageError(name + " must be > 0 " + unit + ", got " + text);
  return value;
}

/// Removes `--position-box X Y Z` from `args`; empty when absent. Each edge length > 0 metres.
std::optional<Eigen::Vector3d> takePositionBox(std::vector<std::string>& args) {
  const auto at = std::find(args.begin(), args.end(), "--position-box");
  if (at == args.end()) return std::nullopt;
  Eigen::Vector3d box;
  const auto first = at + 1;
  const auto isOption = [](const std::string& word) { return word.compare(0, 2, "--") == 0; };
  if (args.end() - first < 3 || std::any_of(first, first + 3, isOption)) {
    throw UsageError("--position-box needs 3 edge lengths in metres: X Y Z");
  }
  for (int k = 0; k < 3; ++k) {
    const std::string& word = *(first + k);
    box[k] = parseValue(word, "--position-box");
    if (!(box[k] > 0.0)) throw UsageError("--position-box edge lengths must be > 0 m, got " + word);
  }
  args.erase(at, first + 3);
  if (std::find(args.begin(), args.end(), "--position-box") != args.end()) {
    throw UsageError("option --position-box given more than once");
  }
  return box;
}

}  // namespace

std::optional<GoalPoseArg> takeGoalPose(std::vector<std::string>& args) {
  std::optional<GoalPoseArg> pose;
  std::vector<std::string> rest;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] != "--goal-pose") {
      rest.push_back(args[i]);
      continue;
    }
    if (pose) throw UsageError("option --goal-pose given more than once");
    const auto isOption = [](const std::string& word) { return word.compare(0, 2, "--") == 0; };
    if (i + 8 >= args.size() || std::any_of(args.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                                            args.begin() + static_cast<std::ptrdiff_t>(i) + 9, isOption)) {
      throw UsageError("--goal-pose needs a link and 7 numbers: LINK x y z qx qy qz qw");
    }
    pose.emplace();
    pose->link = args[i + 1];
    pose->X_WT = poseOfValues(std::vector<std::string>(args.begin() + static_cast<std::ptrdiff_t>(i) + 2,
                                                       args.begin() + static_cast<std::ptrdiff_t>(i) + 9));
    i += 8;
  }
  args = std::move(rest);
  const std::optional<double> position = takeTolerance(args, "--position-tol", "m");
  const std::optional<double> orientation = takeTolerance(args, "--orientation-tol", "rad");
  const std::optional<Eigen::Vector3d> box = takePositionBox(args);
  if (!pose) {
    if (position || orientation || box) {
      throw UsageError("--position-tol, --position-box and --orientation-tol need --goal-pose");
    }
    return pose;
  }
  if (position && box) throw UsageError("--position-tol and --position-box exclude each other");
  pose->positionBox = box;
  if (position) pose->positionTolerance = *position;
  if (orientation) pose->orientationTolerance = *orientation;
  return pose;
}

}  // namespace deepcheck::tools
