#pragma once
// On-disk cache of the self-pair grids (self_pair_grid.h), so that loading a robot a second time
// does not certify its grids' cells again (GJK per piece pair per cell plus forward kinematics:
// most of a warm load's time before it).
//
// Where: beside the decomposition cache (decomposition/cache.h), in the directory of
// WorldOptions::decompositionCacheDir or its default, and disabled with it. One file per grid,
// `<directory>/grid-<key>.bin`.
//
// Key: a 128-bit hash (decomposition::ContentHasher) of everything the cells' FREE flags depend
// on: both links' pieces (core vertices, radii, poses in their links), every joint from the lower
// link up to the upper one (type, origin, axis, limits, variable, multiplier, offset), the grid's
// layout (variables, lower limits, cell widths and counts, delta), every tolerance the
// certificate uses (tol::kCertifiedGapRelative, the layout's padding and budgets, the GJK
// tolerances of deep/tolerances.h) and kGridCacheFormatVersion, bumped whenever the certificate's
// code changes. Anything else changed gives another key: the grid is built again.
//
// File format (little-endian): magic "DCKGRID1", u32 format version, the 16-byte key, u32 cell
// count, one byte per cell (1 FREE, 0 not), then a u64 FNV-1a checksum of everything before it.
//
// Never trusted blindly, never an error. An absent entry, or one with another version or key,
// is built again silently; a corrupt one (truncated, bad checksum, bad magic, a flag other than
// 0 or 1, another cell count) is built again with one line on the progress stream. An entry that
// reads well is spot-checked before use (SelfPairGrid::build re-certifies
// tol::kGridCacheSpotChecks of its FREE cells) and rebuilt, with one line, if any fails. The
// spot check catches an entry wrong in a fair share of its cells, not a single flipped cell (the
// key and checksum guard against those). It runs GJK from other warm starts than the scan did,
// so a cell certified within GJK's accuracy of the threshold could in principle fail it: the
// entry is then rebuilt, which costs time, never an answer. Writes
// are atomic (decomposition::writeFileAtomically); a directory that cannot be created or written
// leaves the grids uncached, silently.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace deepcheck::checker {
struct WorldOptions;
}

namespace deepcheck::checker::detail {

struct RobotData;
struct LinkGeometry;

/// Bumped when the file layout or the certificate's code (self_pair_grid.cpp, GJK) changes.
constexpr std::uint32_t kGridCacheFormatVersion = 1;

/// Every tolerance the certificate and its layout use (tolerances.h, deep/tolerances.h), as the
/// key hashes them.
std::vector<double> gridCertificateTolerances();

/// The key of the grid of links `up` (geometry U) and `down` (geometry D, below U in the tree)
/// laid out as `layout` says (its variables, lower limits, cell widths, cell counts and delta, in
/// SelfPairGrid's order) and certified with `tolerances`: 32 hex digits.
std::string selfPairGridKey(const RobotData& robot, int up, int down, const LinkGeometry& U, const LinkGeometry& D,
                            const std::vector<double>& layout,
                            const std::vector<double>& tolerances = gridCertificateTolerances());

class SelfPairGridCache {
 public:
  /// A cache in `directory` (created on the first store); "" disables it.
  explicit SelfPairGridCache(std::string directory = "");
  /// The cache beside `options`' decomposition cache; disabled when that one is.
  static SelfPairGridCache besideDecompositionCache(const WorldOptions& options);

  bool enabled() const { return !directory_.empty(); }
  const std::string& directory() const { return directory_; }
  std::string pathFor(const std::string& key) const;

  /// The FREE flags (one per cell, 0 or 1) of the entry for `key`, or nullopt: disabled, absent,
  /// another version or key (`*problem` ""), or corrupt (`*problem` says why). Never throws.
  std::optional<std::vector<std::uint8_t>> load(const std::string& key, std::size_t numCells,
                                                std::string* problem) const;
  /// Writes the entry atomically; "" on success, else why not. Never throws.
  std::string store(const std::string& key, const std::vector<std::uint8_t>& flags) const;

 private:
  std::string directory_;
};

}  // namespace deepcheck::checker::detail
