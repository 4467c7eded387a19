#pragma once
// checker::BroadPhase::FclTree: FCL's DynamicAABBTreeCollisionManager over the boxes of the world
// pieces, with the same queries as the checker's own AABB tree, so the two can be compared on one
// world (tests/checker, bench/checker_bench.cpp). The checker itself does not depend on FCL: this
// library supplies the broad phase.
//
//   deepcheck::fcl_reference::enableFclBroadPhase();
//   checker::WorldOptions options;
//   options.broadPhase = checker::BroadPhase::FclTree;
//
// A World asked for FclTree before enableFclBroadPhase() throws std::invalid_argument.

namespace deepcheck::fcl_reference {

/// Makes checker::BroadPhase::FclTree available to the Worlds built afterwards. Thread-safe,
/// idempotent.
void enableFclBroadPhase();

}  // namespace deepcheck::fcl_reference
