#pragma once
// Reference backend on FCL 0.7: the same world checked on the ORIGINAL geometry.
//
// Built from a World (a copy of its description at construction): the robot's links and every
// scene link (pieces the World dropped as unreachable included, so the reach filter is checked
// too) and the obstacles, each URDF collision element as FCL sees it:
//   mesh      fcl::BVHModel<fcl::OBBRSSd> of the triangles (not decomposed, not convexified);
//   box       fcl::Boxd;  sphere  fcl::Sphered;  cylinder  fcl::Cylinderd (exact, not a prism).
// World bodies live in a DynamicAABBTreeCollisionManager; robot elements are posed per query and
// run against it; self pairs are the World's allowedSelfPairs().
//
// Expected agreement. The World's pieces contain the original geometry (prisms contain the
// cylinders, decomposition pieces contain the meshes), so:
//   - FCL colliding implies World colliding (never the reverse miss);
//   - where the World reports a collision that FCL does not, FCL's distance is at most the sum of
//     the two bodies' excesses, so at most twice the World's geometry excess
//     (Summary::geometryExcess) — with one exception FCL cannot see: a mesh entirely inside
//     another body has no intersecting triangles, and FCL calls it free;
//   - on free configurations the World's distance is at most FCL's, and at least FCL's minus
//     twice the geometry excess.
//
// Not thread-safe: the robot's FCL objects are posed in place. Use one FclWorld per thread.

#include "deepcheck/checker/world.h"

#include <Eigen/Core>

#include <limits>
#include <memory>
#include <string>

namespace deepcheck::fcl_reference {

struct FclDistanceResult {
  /// Some allowed pair collides (FCL's boolean test); `distance` is then 0 and no pair is given.
  bool colliding = false;
  /// Minimum distance over allowed pairs when not colliding (infinity when there is no pair).
  double distance = std::numeric_limits<double>::infinity();
  std::string nameA;  ///< robot link of the closest pair
  std::string nameB;  ///< robot link, "scene/<link>" or "obstacle/<name>"
};

class FclWorld {
 public:
  /// Loads the original meshes of every body of `world` (robot, scenes, obstacles as they are
  /// now). Throws std::invalid_argument naming the body when a mesh cannot be loaded.
  explicit FclWorld(const checker::World& world);
  ~FclWorld();
  FclWorld(FclWorld&&) noexcept;
  FclWorld& operator=(FclWorld&&) noexcept;

  /// True when no allowed pair collides.
  bool isFree(const Eigen::Ref<const Eigen::VectorXd>& q);
  /// FCL's boolean test, then (when free) the minimum distance.
  FclDistanceResult distance(const Eigen::Ref<const Eigen::VectorXd>& q);

  int numRobotObjects() const;
  int numWorldObjects() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace deepcheck::fcl_reference
