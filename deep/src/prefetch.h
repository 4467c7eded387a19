#pragma once
// Requests for memory the caller will read soon: each brings one cache line towards the
// processor's caches without waiting for it. On data out of cache, loads that would otherwise
// wait on each other in turn then overlap. A request never faults and changes no result.

#include <cstddef>

namespace deepcheck::deep {

/// Bytes of a cache line, the step between requests.
constexpr std::size_t kCacheLineBytes = 64;

/// Requests every cache line of the `bytes` bytes from `p` on.
inline void prefetchBytes(const void* p, std::size_t bytes) {
  const char* c = static_cast<const char*>(p);
  for (std::size_t offset = 0; offset < bytes; offset += kCacheLineBytes) __builtin_prefetch(c + offset);
}

}  // namespace deepcheck::deep
