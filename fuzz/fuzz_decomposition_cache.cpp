// Fuzz harness: a decomposition cache entry (decomposition/cache.h) read by
// DecompositionCache::load. The first byte picks how the rest becomes the entry's file:
//   even: the rest is the entry up to its checksum; the harness writes the current header (the
//         magic and the format and algorithm versions, as store() writes them) over bytes 0..15
//         and the requested key over bytes 16..31, and appends the FNV-1a checksum, so that
//         mutations reach the fields behind those checks, and the corpus stays valid when a
//         version is bumped;
//   odd:  the rest is the whole file, as is (the checks themselves).
// load must never throw; an entry it accepts must hold finite vertices, triangle indices within
// their piece, and convex pieces that become polytopes.

#include "harness_support.h"

#include "deepcheck/decomposition/cache.h"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace {

namespace decomposition = deepcheck::decomposition;

constexpr char kKey[] = "00112233445566778899aabbccddeeff";
constexpr std::size_t kHeaderSize = 16;  ///< "DCKDECMP", the format and the algorithm version
constexpr std::size_t kKeyOffset = kHeaderSize;

std::uint64_t fnv1a(const std::string& bytes) {
  std::uint64_t h = 1469598103934665603ULL;
  for (const char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ULL;
  return h;
}

const decomposition::DecompositionCache& cache() {
  static const decomposition::DecompositionCache c(
      (std::filesystem::temp_directory_path() / ("deepcheck_fuzz_cache_" + std::to_string(::getpid()))).string());
  return c;
}

/// The first kHeaderSize bytes of an entry as this build's store() writes it.
const std::string& currentHeader() {
  static const std::string header = [] {
    std::filesystem::create_directories(cache().directory());
    std::string problem;
    if (!cache().store(kKey, decomposition::ConvexDecomposition{}, &problem)) {
      throw std::runtime_error("fuzz_decomposition_cache: cannot write a reference entry: " + problem);
    }
    const std::string path = cache().pathFor(kKey);
    std::string bytes(kHeaderSize, '\0');
    std::ifstream in(path, std::ios::binary);
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    std::filesystem::remove(path);
    if (in.gcount() != static_cast<std::streamsize>(kHeaderSize)) {
      throw std::runtime_error("fuzz_decomposition_cache: the reference entry is shorter than its header");
    }
    return bytes;
  }();
  return header;
}

void require(bool ok, const char* what) {
  deepcheck::fuzz::require(ok, "DecompositionCache::load accepted an entry with", what);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  std::string entry(reinterpret_cast<const char*>(data + 1), size - 1);
  if (data[0] % 2 == 0) {
    if (entry.size() < kKeyOffset + 16) entry.resize(kKeyOffset + 16, '\0');
    entry.replace(0, kHeaderSize, currentHeader());
    for (std::size_t i = 0; i < 16; ++i) {
      entry[kKeyOffset + i] = static_cast<char>(std::stoi(std::string(kKey + 2 * i, 2), nullptr, 16));
    }
    const std::uint64_t checksum = fnv1a(entry);
    for (int i = 0; i < 8; ++i) entry.push_back(static_cast<char>((checksum >> (8 * i)) & 0xff));
  }
  const std::string path = cache().pathFor(kKey);
  std::filesystem::create_directories(cache().directory());
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(entry.data(), static_cast<std::streamsize>(entry.size()));
  }
  std::string problem;
  const auto hit = cache().load(kKey, &problem);
  std::filesystem::remove(path);
  if (!hit) return 0;
  require(static_cast<std::size_t>(hit->report.numPieces) == hit->pieces.size(), "a piece count unlike its pieces");
  for (const decomposition::ConvexPiece& piece : hit->pieces) {
    for (const Eigen::Vector3d& v : piece.vertices) require(v.allFinite(), "a non-finite vertex");
    for (const auto& t : piece.triangles) {
      for (const int k : t) {
        require(k >= 0 && static_cast<std::size_t>(k) < piece.vertices.size(), "a triangle index out of range");
      }
    }
  }
  try {
    hit->polytopes();
  } catch (const std::invalid_argument&) {
    // Pieces that are no polytope (too few or coincident vertices): the caller's error.
  }
  return 0;
}
