#pragma once
// Scratch space of DEEP's walk: the hub pairs evaluated in a query, the local Gauss map polygons
// and B's vertices and face normals transformed into the pair frame. Grown on demand and never
// shrunk, so a query given the caller's scratch allocates nothing.
//
// The caller owns it, one per thread, and shares it across pairs: through PairCache::walk for
// signedDistance, or deepPenetration's `scratch` argument. Without one a query makes a local one
// (allocating what that query uses: about 100 KB when it walks).

#include <memory>

namespace deepcheck::deep {

namespace detail {
struct WalkScratchData;
}

class WalkScratch {
 public:
  WalkScratch();
  ~WalkScratch();
  WalkScratch(WalkScratch&&) noexcept;
  WalkScratch& operator=(WalkScratch&&) noexcept;
  WalkScratch(const WalkScratch&) = delete;
  WalkScratch& operator=(const WalkScratch&) = delete;

  /// The data, for deep's own sources (deep_walker.h).
  detail::WalkScratchData& data() { return *data_; }

 private:
  std::unique_ptr<detail::WalkScratchData> data_;
};

}  // namespace deepcheck::deep
