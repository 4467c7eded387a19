#include "reach.h"

#include "aabb_tree.h"
#include "deepcheck/robots/kinematics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace deepcheck::checker {
namespace {

/// Largest |value| of a prismatic joint over its variable's limits (0 for other joints).
double prismaticTravel(const robots::RobotModel& model, const robots::Joint& joint) {
  if (joint.type != robots::JointType::Prismatic) return 0.0;
  if (joint.variable < 0) return std::abs(joint.offset);
  const double lo = model.lowerLimits()[joint.variable];
  const double hi = model.upperLimits()[joint.variable];
  return std::max(std::abs(joint.multiplier * lo + joint.offset), std::abs(joint.multiplier * hi + joint.offset));
}

}  // namespace

std::vector<ReachSphere> linkReachSpheres(const robots::RobotModel& model,
                                          const std::vector<std::vector<robots::CollisionPiece>>& pieces) {
  if (static_cast<int>(pieces.size()) != model.numLinks()) {
    throw std::invalid_argument("linkReachSpheres: robot '" + model.name() + "' has " +
                                std::to_string(model.numLinks()) + " links but " + std::to_string(pieces.size()) +
                                " piece lists were given");
  }
  // Poses at the default configuration: only the poses of rigid parts (above the first moving
  // joint of each path) are used, and those do not depend on q.
  const std::vector<Eigen::Isometry3d> X_WL = robots::forwardKinematics(model, model.defaultConfiguration());
  std::vector<ReachSphere> out(model.numLinks());
  for (int l = 0; l < model.numLinks(); ++l) {
    if (pieces[l].empty()) continue;
    ReachSphere& s = out[l];
    s.valid = true;
    // Path from the root: walk up, remembering the topmost moving joint and summing the
    // offsets below it.
    double chain = 0.0;           // sum of |t_k| + travel_k of joints below the topmost moving one
    double pendingOffsets = 0.0;  // sum since the last moving joint met while walking up
    int topMoving = -1;
    for (int link = l; model.link(link).parentJoint >= 0; link = model.link(link).parentLink) {
      const robots::Joint& joint = model.joint(model.link(link).parentJoint);
      pendingOffsets += prismaticTravel(model, joint);
      s.withinLimitsOnly = s.withinLimitsOnly || (joint.type == robots::JointType::Prismatic && joint.variable >= 0);
      if (joint.moves()) {
        topMoving = model.link(link).parentJoint;
        chain += pendingOffsets;
        pendingOffsets = 0.0;
      }
      // The joint's own <origin> offset is above its motion: it counts only if a moving joint
      // sits higher on the path; it is added to the pending sum and committed when one is met.
      pendingOffsets += joint.X_PJ.translation().norm();
    }
    if (topMoving < 0) {
      // Rigidly attached to the root: the bounding sphere of the pieces at their fixed pose.
      s.fixed = true;
      Aabb box;
      for (const robots::CollisionPiece& p : pieces[l]) {
        const Eigen::Vector3d c = X_WL[l] * (p.X_LP * p.core->center());
        box.extend(Aabb::ofSphere(c, p.core->boundingRadius() + p.radius));
      }
      s.center_W = box.center();
      double radius = 0.0;
      for (const robots::CollisionPiece& p : pieces[l]) {
        const Eigen::Vector3d c = X_WL[l] * (p.X_LP * p.core->center());
        radius = std::max(radius, (c - s.center_W).norm() + p.core->boundingRadius() + p.radius);
      }
      s.radius = radius;
      continue;
    }
    double extent = 0.0;  // max |p_L| over the pieces
    for (const robots::CollisionPiece& p : pieces[l]) {
      extent = std::max(extent, (p.X_LP * p.core->center()).norm() + p.core->boundingRadius() + p.radius);
    }
    const robots::Joint& j0 = model.joint(topMoving);
    s.center_W = (X_WL[j0.parentLink] * j0.X_PJ).translation();
    s.radius = chain + extent;
  }
  return out;
}

std::vector<std::pair<int, int>> pairsWithinReach(const std::vector<ReachSphere>& spheres,
                                                  const std::vector<int>& links, double margin) {
  const int n = static_cast<int>(links.size());
  std::vector<Aabb> boxes;
  std::vector<int> unbounded;  // positions in `links` of the spheres that hold within the limits only
  boxes.reserve(links.size());
  for (int i = 0; i < n; ++i) {
    const ReachSphere& s = spheres[links[i]];
    boxes.push_back(Aabb::ofSphere(s.center_W, s.radius));
    if (s.withinLimitsOnly) unbounded.push_back(i);
  }
  const AabbTree tree(boxes);
  std::vector<std::pair<int, int>> out;
  for (int i = 0; i < n; ++i) {
    const ReachSphere& a = spheres[links[i]];
    if (a.withinLimitsOnly) continue;
    tree.visitOverlapping(Aabb::ofSphere(a.center_W, a.radius + margin), [&](int j) {
      const ReachSphere& b = spheres[links[j]];
      if (j > i && !b.withinLimitsOnly && (a.center_W - b.center_W).norm() - a.radius - b.radius <= margin) {
        out.emplace_back(i, j);
      }
      return false;
    });
  }
  for (int i : unbounded) {
    for (int j = 0; j < n; ++j) {
      if (j != i && (j > i || !spheres[links[j]].withinLimitsOnly)) out.emplace_back(std::min(i, j), std::max(i, j));
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace deepcheck::checker
