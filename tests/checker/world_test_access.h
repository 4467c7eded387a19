#pragma once
// The checker's internals as its tests reach them, through the library's internal headers
// (checker/src, on the test target's include path): which pairs reach the narrow phase, a world's
// robot data and self pairs, and the query shortcuts that never change an answer, turned off to
// find the same answers the long way.

#include "world_internal.h"
#include "world_queries_internal.h"

#include "deepcheck/checker/world.h"

#include <functional>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace deepcheck::checker::test {

using detail::NarrowPhaseEvent;

/// Calls `hook` before every narrow-phase call of the queries on `world` (slows them); an empty
/// function removes it. Not while queries run.
inline void setNarrowPhaseHook(const World& world, std::function<void(const NarrowPhaseEvent&)> hook) {
  world.internalState()->onNarrowPhase = std::move(hook);
}

/// A query context of `world` as World::makeContext makes one, reached from inside (the
/// queries' internal steps take it).
inline std::unique_ptr<detail::Impl> contextImplOf(const World& world) {
  auto impl = std::make_unique<detail::Impl>();
  impl->state = world.internalState().get();
  impl->worldUid = impl->state->uid;
  return impl;
}

/// The world's current snapshot.
inline std::shared_ptr<const detail::Snapshot> snapshotOf(const World& world) {
  return world.internalState()->snapshot();
}

/// The robot as the world built it (pieces grouped by link geometry).
inline std::shared_ptr<const detail::RobotData> robotOf(const World& world) { return snapshotOf(world)->robot; }

/// The world's self pairs, with their grids (null where a pair has none).
inline std::vector<detail::SelfPair> selfPairsOf(const World& world) { return snapshotOf(world)->selfPairs; }

/// Turns the self-pair grids off: the world's self pairs are made again without them.
inline void disableSelfPairGrids(World& world) {
  detail::WorldState& st = *world.internalState();
  const std::lock_guard<std::mutex> lock(st.mutex);
  auto snap = std::make_shared<detail::Snapshot>(*st.current);
  snap->shortcuts.selfPairGrids = false;
  snap->selfPairs.clear();  // no grid is kept
  detail::rebuildSelfPairs(*snap, st.options);
  detail::publish(st, snap);
}

/// Turns isFree's centroid test off. Not while queries run.
inline void disableCentroidTest(World& world) {
  detail::WorldState& st = *world.internalState();
  const std::lock_guard<std::mutex> lock(st.mutex);
  auto snap = std::make_shared<detail::Snapshot>(*st.current);
  snap->shortcuts.centroidTest = false;
  detail::publish(st, snap);
}

/// isFreeBatch's bound stage and batch kinematics in their baseline build (true) or in AVX2
/// where the processor has it (false, the default).
inline void forceBatchBaseline(const World& world, bool on) { world.internalState()->batchBaseline = on; }

}  // namespace deepcheck::checker::test
