#pragma once
// Internal to deepcheck::checker, for its tests: a hook on a Context's narrow phase (which pairs
// reach it). Not part of the public API: tests include it from checker/src.

#include "world_queries_internal.h"

#include <functional>
#include <utility>

namespace deepcheck::checker::detail {

struct ContextTestAccess {
  /// Calls `hook` before every narrow-phase call of queries with `context` (slows them); an empty
  /// function removes it.
  static void setNarrowPhaseHook(World::Context& context, std::function<void(const NarrowPhaseEvent&)> hook) {
    context.impl_->onNarrowPhase = std::move(hook);
  }
};

}  // namespace deepcheck::checker::detail
