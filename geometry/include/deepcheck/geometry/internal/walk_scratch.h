#pragma once
// Scratch space of the Gauss-map walk: the hub pairs evaluated in a query, the local Gauss map
// polygons and B's vertices and face normals transformed into the pair frame. Grown on demand and
// never shrunk, so a query given the caller's scratch allocates nothing.
//
// Callers of signedDistance hold it inside a PenetrationScratch (signed_distance.h), one per
// thread shared across pairs. Without one a query makes a local one (allocating what that query
// uses: about 100 KB when it walks).

#include <memory>

namespace deepcheck::geometry::detail {

struct WalkScratchData;

class WalkScratch {
 public:
  WalkScratch();
  ~WalkScratch();
  WalkScratch(WalkScratch&&) noexcept;
  WalkScratch& operator=(WalkScratch&&) noexcept;
  WalkScratch(const WalkScratch&) = delete;
  WalkScratch& operator=(const WalkScratch&) = delete;

  /// The data, for the walk's sources (deep_walker.h).
  WalkScratchData& data() { return *data_; }

 private:
  std::unique_ptr<WalkScratchData> data_;
};

}  // namespace deepcheck::geometry::detail
