#pragma once
// FCL's DynamicAABBTreeCollisionManager as a World's broad phase, over the boxes of the world
// pieces, with the same queries as the checker's own AABB tree, so the two can be compared on one
// world (tests/checker, bench/checker_bench.cpp). The checker itself does not depend on FCL: this
// library supplies the broad phase through the checker's extension point
// (deepcheck/checker/broad_phase.h).
//
//   checker::WorldOptions options;
//   options.externalBroadPhase = deepcheck::fcl_reference::fclBroadPhase();

#include "deepcheck/checker/broad_phase.h"

#include <memory>

namespace deepcheck::fcl_reference {

/// The factory of FCL's dynamic AABB tree for WorldOptions::externalBroadPhase (one shared
/// instance; World::summary() names it "fcl-dynamic-aabb-tree"). Thread-safe.
std::shared_ptr<const checker::PieceTreeFactory> fclBroadPhase();

}  // namespace deepcheck::fcl_reference
