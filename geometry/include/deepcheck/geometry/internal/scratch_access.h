#pragma once
// The parts of a PenetrationScratch (signed_distance.h), for deep's own sources and tests.

#include "deepcheck/geometry/internal/expansion_surface.h"
#include "deepcheck/geometry/internal/walk_scratch.h"
#include "deepcheck/geometry/signed_distance.h"

namespace deepcheck::geometry::detail {

struct ScratchAccess {
  static ExpansionSurface& surface(PenetrationScratch& s) { return *s.surface_; }
  static WalkScratch& walk(PenetrationScratch& s) { return *s.walk_; }
};

/// The cache's scratch surface, or null when it has no scratch (or there is no cache).
inline ExpansionSurface* scratchSurface(PairCache* cache) {
  return cache && cache->scratch ? &ScratchAccess::surface(*cache->scratch) : nullptr;
}

/// The cache's walk scratch, or null when it has no scratch (or there is no cache).
inline WalkScratch* scratchWalk(PairCache* cache) {
  return cache && cache->scratch ? &ScratchAccess::walk(*cache->scratch) : nullptr;
}

}  // namespace deepcheck::geometry::detail
