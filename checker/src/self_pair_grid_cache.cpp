// On-disk cache of the self-pair grids (see self_pair_grid_cache.h).

#include "self_pair_grid_cache.h"

#include "world_internal.h"

#include "deepcheck/checker/tolerances.h"
#include "deepcheck/geometry/tolerances.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/decomposition/cache.h"
#include "deepcheck/decomposition/cache_file.h"

#include <cstring>
#include <filesystem>
#include <system_error>

namespace deepcheck::checker::detail {

namespace {

constexpr char kMagic[8] = {'D', 'C', 'K', 'G', 'R', 'I', 'D', '1'};
constexpr std::size_t kHeaderBytes = sizeof kMagic + 4 + 16 + 4;
constexpr std::size_t kChecksumBytes = 8;

std::uint64_t readLittleEndian(const std::string& data, std::size_t at, int bytes) {
  std::uint64_t x = 0;
  for (int i = 0; i < bytes; ++i) x |= static_cast<std::uint64_t>(static_cast<unsigned char>(data[at + i])) << (8 * i);
  return x;
}

void appendLittleEndian(std::string& data, std::uint64_t x, int bytes) {
  for (int i = 0; i < bytes; ++i) data.push_back(static_cast<char>(x >> (8 * i)));
}

void hashPose(decomposition::ContentHasher& h, const Eigen::Isometry3d& X) {
  for (int k = 0; k < 16; ++k) h.f64(X.matrix().data()[k]);
}

void hashPieces(decomposition::ContentHasher& h, const RobotData& robot, const LinkGeometry& g) {
  h.u64(static_cast<std::uint64_t>(g.numPieces));
  for (int j = g.firstPiece; j < g.firstPiece + g.numPieces; ++j) {
    const RobotPiece& piece = robot.pieces[j];
    hashPose(h, piece.X_LP);
    h.f64(piece.radius);
    h.u64(static_cast<std::uint64_t>(piece.core->numVertices()));
    for (const Eigen::Vector3d& v : piece.core->vertices()) {
      for (int k = 0; k < 3; ++k) h.f64(v[k]);
    }
  }
}

/// Every joint from `down` up to `up`, and the limits of the variables that move them.
void hashJoints(decomposition::ContentHasher& h, const robots::RobotModel& model, int up, int down) {
  for (int l = down; l != up; l = model.link(l).parentLink) {
    const robots::Joint& joint = model.joint(model.link(l).parentJoint);
    h.u64(static_cast<std::uint64_t>(joint.type));
    hashPose(h, joint.X_PJ);
    for (int k = 0; k < 3; ++k) h.f64(joint.axis[k]);
    for (double x : {joint.lower, joint.upper, joint.multiplier, joint.offset}) h.f64(x);
    h.u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(joint.variable)));
    if (joint.variable >= 0) {
      h.f64(model.lowerLimits()[joint.variable]);
      h.f64(model.upperLimits()[joint.variable]);
    }
  }
}

}  // namespace

std::vector<double> gridCertificateTolerances() {
  return {tol::kCertifiedGapRelative,
          tol::kGridCellPaddingRelative,
          tol::kGridCellPaddingAbsolute,
          static_cast<double>(tol::kGridMaxCells),
          static_cast<double>(tol::kGridMaxPiecePairTests),
          geometry::tol::kGjkRelative,
          geometry::tol::kContactRelative,
          geometry::tol::kCertifyRelative,
          geometry::tol::kCoordinateRoundoff};
}

std::string selfPairGridKey(const RobotData& robot, int up, int down, const LinkGeometry& U, const LinkGeometry& D,
                            const std::vector<double>& layout, const std::vector<double>& tolerances) {
  decomposition::ContentHasher h;
  static const char kTag[] = "deepcheck self-pair grid";
  h.bytes(kTag, sizeof kTag);
  h.u64(kGridCacheFormatVersion);
  hashPieces(h, robot, U);
  hashPieces(h, robot, D);
  hashJoints(h, robot.model, up, down);
  h.u64(layout.size());
  for (double x : layout) h.f64(x);
  h.u64(tolerances.size());
  for (double x : tolerances) h.f64(x);
  return h.hex();
}

SelfPairGridCache::SelfPairGridCache(std::string directory) : directory_(std::move(directory)) {}

SelfPairGridCache SelfPairGridCache::besideDecompositionCache(const WorldOptions& options) {
  const decomposition::DecompositionCache decompositions(options.decompositionCacheDir);
  return SelfPairGridCache(decompositions.enabled() ? decompositions.directory() : "");
}

std::string SelfPairGridCache::pathFor(const std::string& key) const {
  return (std::filesystem::path(directory_) / ("grid-" + key + ".bin")).string();
}

std::optional<std::vector<std::uint8_t>> SelfPairGridCache::load(const std::string& key, std::size_t numCells,
                                                                 std::string* problem) const {
  problem->clear();
  unsigned char wantKey[16];
  if (!enabled() || !decomposition::cacheKeyBytes(key, wantKey)) return std::nullopt;
  const std::string path = pathFor(key);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  auto bad = [&](const std::string& why) {
    *problem = path + ": " + why;
    return std::nullopt;
  };
  std::string data;
  if (const std::string why = decomposition::readWholeFile(path, data); !why.empty())
    return bad("cannot be read: " + why);
  if (data.size() < kHeaderBytes + kChecksumBytes) return bad("truncated");
  // Checksum first: it covers everything, so the fields below are read from intact bytes.
  const std::size_t body = data.size() - kChecksumBytes;
  if (decomposition::fnv1a(data.data(), body) != readLittleEndian(data, body, 8)) return bad("checksum mismatch");
  if (std::memcmp(data.data(), kMagic, sizeof kMagic) != 0) return bad("not a grid cache file");
  // Another version or key: an entry of another build or grid, not a corrupt one.
  if (readLittleEndian(data, sizeof kMagic, 4) != kGridCacheFormatVersion) return std::nullopt;
  if (std::memcmp(data.data() + sizeof kMagic + 4, wantKey, 16) != 0) return std::nullopt;
  if (readLittleEndian(data, sizeof kMagic + 20, 4) != numCells || body - kHeaderBytes != numCells) {
    return bad("wrong cell count");
  }
  std::vector<std::uint8_t> flags(data.begin() + kHeaderBytes, data.begin() + body);
  for (std::uint8_t f : flags) {
    if (f > 1) return bad("bad cell flag");
  }
  return flags;
}

std::string SelfPairGridCache::store(const std::string& key, const std::vector<std::uint8_t>& flags) const {
  unsigned char keyBytes[16];
  if (!enabled()) return "cache disabled";
  if (!decomposition::cacheKeyBytes(key, keyBytes)) return "malformed key '" + key + "'";
  std::string data(kMagic, sizeof kMagic);
  appendLittleEndian(data, kGridCacheFormatVersion, 4);
  data.append(reinterpret_cast<const char*>(keyBytes), 16);
  appendLittleEndian(data, flags.size(), 4);
  data.append(flags.begin(), flags.end());
  appendLittleEndian(data, decomposition::fnv1a(data.data(), data.size()), 8);
  try {
    return decomposition::writeFileAtomically(directory_, pathFor(key), data);
  } catch (const std::exception& e) {  // std::bad_alloc, or a filesystem error of the path
    return e.what();
  }
}

}  // namespace deepcheck::checker::detail
