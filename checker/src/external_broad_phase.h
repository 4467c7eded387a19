#pragma once
// Broad phases the checker does not implement itself, supplied at run time by another library of
// this project, so that the checker needs no third-party collision library:
//   BroadPhase::FclTree  FCL's DynamicAABBTreeCollisionManager, from deepcheck::fcl_reference
//                        (fcl_reference/fcl_broad_phase.h: enableFclBroadPhase()).
// A World built with such a broad phase before its provider was installed throws
// std::invalid_argument naming the provider.

#include "aabb_tree.h"
#include "deepcheck/checker/world.h"

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <vector>

namespace deepcheck::checker::detail {

/// The same two queries as AabbTree (aabb_tree.h), over the boxes it was built from.
/// Implementations are read-only after construction and thread-safe.
class ExternalPieceTree {
 public:
  virtual ~ExternalPieceTree() = default;
  /// visit(item) for items whose box overlaps `query`, until it returns true; true when stopped.
  virtual bool visitOverlapping(const Aabb& query, const std::function<bool(int)>& visit) const = 0;
  /// visit(item, lowerBound) for items whose box is within bound() of the box of the sphere (c, r).
  virtual void visitNear(const Eigen::Vector3d& c, double r, const std::function<double()>& bound,
                         const std::function<void(int, double)>& visit) const = 0;
};

/// Builds the tree over items 0 .. boxes.size() - 1 (boxes is not empty).
using ExternalPieceTreeFactory = std::shared_ptr<const ExternalPieceTree> (*)(const std::vector<Aabb>& boxes);

/// Installs the factory of `broadPhase` (BroadPhase::FclTree; std::invalid_argument for the
/// broad phases the checker implements). Thread-safe; Worlds built afterwards use it.
void setExternalBroadPhase(BroadPhase broadPhase, ExternalPieceTreeFactory factory);

/// The tree of `broadPhase` over `boxes` (nullptr for no boxes). Throws std::invalid_argument
/// naming the library to link when no factory was installed.
std::shared_ptr<const ExternalPieceTree> makeExternalPieceTree(BroadPhase broadPhase, const std::vector<Aabb>& boxes);

}  // namespace deepcheck::checker::detail
