#pragma once
// Internal to deepcheck::checker, for its tests: a hook on a Context's narrow phase (which pairs
// reach it), and a world's robot data and self pairs. Not part of the public API: tests include
// it from checker/src.

#include "world_queries_internal.h"

#include "world_internal.h"

#include <functional>
#include <utility>
#include <vector>

namespace deepcheck::checker::detail {

struct ContextTestAccess {
  /// Calls `hook` before every narrow-phase call of queries with `context` (slows them); an empty
  /// function removes it.
  static void setNarrowPhaseHook(World::Context& context, std::function<void(const NarrowPhaseEvent&)> hook) {
    context.impl_->onNarrowPhase = std::move(hook);
  }
};

struct WorldTestAccess {
  /// The robot as the world built it (pieces grouped by link geometry).
  static std::shared_ptr<const RobotData> robot(const World& world) { return snapshot(world)->robot; }
  /// The world's self pairs, with their grids (null where a pair has none).
  static std::vector<SelfPair> selfPairs(const World& world) { return snapshot(world)->selfPairs; }

 private:
  static std::shared_ptr<const Snapshot> snapshot(const World& world) {
    const std::lock_guard<std::mutex> lock(world.state_->mutex);
    return world.state_->current;
  }
};

}  // namespace deepcheck::checker::detail
