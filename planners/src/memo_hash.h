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
/// Each value is scrambled by itself, with its position, and the sum of them mixed once: the
/// values' multiplications do not wait for each other (every motion a planner checks hashes its
/// ends several times).
inline std::uint64_t hashOf(const Eigen::Ref<const Eigen::VectorXd>& point, std::uint64_t seed) {
  std::uint64_t sum = 0;
  for (Eigen::Index i = 0; i < point.size(); ++i) {
    std::uint64_t w = bitsOf(point[i]) + static_cast<std::uint64_t>(i + 1) * 0x9e3779b97f4a7c15ULL;
    w ^= w >> 32;
    w *= 0xd6e8feb86659fd93ULL;
    sum += w ^ (w >> 29);
  }
  const std::uint64_t h = mix(sum, seed);
  return h == 0 ? 1 : h;
}

}  // namespace deepcheck::planners::detail
