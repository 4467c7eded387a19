#pragma once
// BroadPhase::FclTree: FCL's DynamicAABBTreeCollisionManager over the boxes of the world pieces,
// with the same two queries as AabbTree (aabb_tree.h), so the two can be compared on one world.
// Thread-safe: the manager is only read after construction; each query makes its own query object.

#include "aabb_tree.h"

#include <functional>
#include <memory>
#include <vector>

namespace deepcheck::checker::detail {

class FclPieceTree {
 public:
  explicit FclPieceTree(const std::vector<Aabb>& boxes);
  ~FclPieceTree();
  FclPieceTree(const FclPieceTree&) = delete;
  FclPieceTree& operator=(const FclPieceTree&) = delete;

  /// visit(item) for items whose box overlaps `query`, until it returns true; true when stopped.
  bool visitOverlapping(const Aabb& query, const std::function<bool(int)>& visit) const;
  /// visit(item, lowerBound) for items whose box is within bound() of the box of the sphere (c, r).
  void visitNear(const Eigen::Vector3d& c, double r, const std::function<double()>& bound,
                 const std::function<void(int, double)>& visit) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace deepcheck::checker::detail
