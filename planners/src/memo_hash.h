#pragma once
// Internal to deepcheck::planners: the hash of configurations by their exact bits, for the memos
// of certified and refused motions.

#include <Eigen/Core>

#include <cstdint>
#include <cstring>

namespace deepcheck::planners::detail {

/// One step of a 64-bit mix (splitmix64's finaliser) over the running hash and one word.
inline std::uint64_t mix(std::uint64_t h, std::uint64_t word) {
  h ^= word + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ULL;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebULL;
  return h ^ (h >> 31);
}

inline std::uint64_t bitsOf(double x) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}

/// The hash of a configuration's exact bits after `seed` (never 0: it marks empty memo slots).
inline std::uint64_t hashOf(const Eigen::Ref<const Eigen::VectorXd>& point, std::uint64_t seed) {
  std::uint64_t h = mix(0, seed);
  for (Eigen::Index i = 0; i < point.size(); ++i) h = mix(h, bitsOf(point[i]));
  return h == 0 ? 1 : h;
}

}  // namespace deepcheck::planners::detail
