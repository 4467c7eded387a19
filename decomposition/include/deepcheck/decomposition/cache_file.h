#pragma once
// What the on-disk caches (cache.h, the checker's self-pair grid cache) share: a
// 128-bit content hash for their keys, the FNV-1a checksum of their files, and whole-file reads
// and atomic writes.
//
// Keys: ContentHasher feeds one byte stream to two independent 64-bit hashes (FNV-1a and a
// multiply-xorshift of 8-byte words, whose collisions are unrelated) and writes them as 32
// lowercase hex digits. Numbers are hashed as their bytes (f64: the bit pattern), so two inputs
// share a key only when they are bit-identical (or in a hash collision).
//
// Writes go to a temporary file in the same directory, renamed over the final name (atomic on
// POSIX): a concurrent reader sees the old file or the new one, never a partial one.

#include <cstddef>
#include <cstdint>
#include <string>

namespace deepcheck::decomposition {

/// FNV-1a, 64 bits, of `size` bytes, continuing from `h`.
std::uint64_t fnv1a(const void* data, std::size_t size, std::uint64_t h = 1469598103934665603ULL);

class ContentHasher {
 public:
  void bytes(const void* data, std::size_t size);
  void u64(std::uint64_t x);
  void f64(double x);
  /// The 128-bit hash of everything fed so far: 32 lowercase hex digits.
  std::string hex();

 private:
  void flush();
  std::uint64_t a_ = 1469598103934665603ULL;
  std::uint64_t b_ = 0x243f6a8885a308d3ULL;
  std::uint64_t word_ = 0;
  int filled_ = 0;
};

/// The 16 bytes of a 32-hex-digit key; false when `key` is not one.
bool cacheKeyBytes(const std::string& key, unsigned char out[16]);

/// The system's message for errno value `error`.
std::string systemReason(int error);

/// Reads the whole file at `path` into `data`; "" on success, else the system's reason.
std::string readWholeFile(const std::string& path, std::string& data);

/// Writes `data` to `path` through a temporary file in the same directory (created if missing)
/// renamed over it; "" on success, else what failed and why (the temporary file is removed).
std::string writeFileAtomically(const std::string& directory, const std::string& path, const std::string& data);

}  // namespace deepcheck::decomposition
