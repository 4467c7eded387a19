#pragma once
// On-disk cache of convex decompositions, so that loading a robot a second time does not
// decompose its meshes again.
//
// Key: a 128-bit hash of the mesh content (vertex coordinates as bytes, triangle indices), of
// every DecompositionParams field, and of kDecompositionAlgorithmVersion; written as 32 hex
// digits. The file `<directory>/decomposition-<key>.bin` holds the pieces (vertices and hull
// faces) and the report fields that describe the result.
//
// File format (little-endian): magic "DCKDECMP", u32 format version, u32 algorithm version, the
// 16-byte key, the report's numbers, u32 piece count, then per piece u32 vertex count, u32
// triangle count, the vertices (3 x f64 each), the triangles (3 x u32 each), f64 volume, f64
// concavity; then a u64 checksum (FNV-1a) of everything before it.
//
// The cache is never trusted and never an error. An entry that is not a regular file (a directory
// in its place), cannot be read, is truncated, has a wrong magic, version, key or checksum, or
// holds an out-of-range index or a non-finite number is treated as absent: the mesh is decomposed
// again and the file replaced when possible. An entry that reads well is still checked against
// the mesh before use (coverageProblem: every vertex inside some piece, within
// tol::kCoverageToleranceRelative of the diagonal), so a stale or forged entry whose pieces miss
// part of the mesh is rebuilt too. A directory that cannot be created or written leaves the
// decomposition uncached. decomposeConvexCached says so in one line on stderr
// ("deepcheck: decomposition cache: <file or directory>: <why>; ...", naming the mesh when it is
// decomposed again, with the system's reason for a failed read or write; a write problem once
// per directory and process) and in the report (CacheStatus, cacheMessage). Reading never throws.
//
// decomposeConvexCached also prints the report's warning (a piece missing the target), on a hit
// too: "deepcheck: warning: decomposition of '<mesh>' misses its target: ...".
//
// Writes go to a temporary file in the same directory that is then renamed over the final name
// (atomic on POSIX), so concurrent processes never see a partial file; at worst two of them both
// compute and write the same result.

#include "deepcheck/decomposition/decomposition.h"
#include "deepcheck/decomposition/mesh.h"

#include <optional>
#include <string>

namespace deepcheck::decomposition {

class DecompositionCache {
 public:
  /// A cache in `directory`, created on the first store. An empty `directory` means
  /// defaultDirectory(); if that is empty too (no XDG_CACHE_HOME nor HOME), the cache is disabled.
  explicit DecompositionCache(std::string directory = "");

  /// A cache that never reads nor writes.
  static DecompositionCache disabled();

  /// `$XDG_CACHE_HOME/deepcheck` when XDG_CACHE_HOME is set and absolute, else
  /// `$HOME/.cache/deepcheck`, else "".
  static std::string defaultDirectory();

  bool enabled() const { return enabled_; }
  const std::string& directory() const { return directory_; }

  /// The key of (mesh, params): 32 lowercase hex digits.
  static std::string key(const TriangleMesh& mesh, const DecompositionParams& params);
  /// Where the entry for `key` lives.
  std::string pathFor(const std::string& key) const;

  /// Reads the entry for `key`. Returns nullopt when caching is disabled, the file is absent, or
  /// it is unreadable; in the last case `*problem` (if given) says why. Never throws.
  std::optional<ConvexDecomposition> load(const std::string& key, std::string* problem = nullptr) const;

  /// Writes the entry atomically. Returns false (with `*problem` saying why) when it could not be
  /// written; never throws.
  bool store(const std::string& key, const ConvexDecomposition& result, std::string* problem = nullptr) const;

 private:
  std::string directory_;
  bool enabled_ = true;
};

/// decomposeConvex through `cache`: a hit is a file read and the coverage check
/// (report.cache == CacheStatus::Hit, report.milliseconds the time of both,
/// report.decomposeMilliseconds the original time); a miss decomposes and stores. Prints the
/// report's warning, if any, on stderr. Same exceptions as decomposeConvex (the input is
/// validated on hits too).
ConvexDecomposition decomposeConvexCached(const TriangleMesh& mesh, const DecompositionParams& params,
                                          const DecompositionCache& cache);

}  // namespace deepcheck::decomposition
