#include "deepcheck/decomposition/cache.h"

#include "deepcheck/decomposition/cache_file.h"

#include "basics.h"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <mutex>
#include <set>

namespace deepcheck::decomposition {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'D', 'C', 'K', 'D', 'E', 'C', 'M', 'P'};
/// Bumped when the file layout changes (kDecompositionAlgorithmVersion covers the content).
constexpr std::uint32_t kFormatVersion = 3;
/// Sanity bounds on counts read from a file: a corrupt count must not make us allocate gigabytes.
constexpr std::uint32_t kMaxPiecesInFile = 1u << 20;
constexpr std::uint32_t kMaxVerticesInFile = 1u << 24;

// Little-endian encoding.
class Writer {
 public:
  void raw(const void* data, std::size_t size) { buffer_.append(static_cast<const char*>(data), size); }
  void u32(std::uint32_t x) {
    for (int i = 0; i < 4; ++i) buffer_.push_back(static_cast<char>(x >> (8 * i)));
  }
  void u64(std::uint64_t x) {
    for (int i = 0; i < 8; ++i) buffer_.push_back(static_cast<char>(x >> (8 * i)));
  }
  void f64(double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    u64(bits);
  }
  std::string& buffer() { return buffer_; }

 private:
  std::string buffer_;
};

class Reader {
 public:
  Reader(const std::string& data, std::size_t end) : data_(data), end_(end) {}
  bool raw(void* out, std::size_t size) {
    if (end_ - pos_ < size) return false;
    std::memcpy(out, data_.data() + pos_, size);
    pos_ += size;
    return true;
  }
  bool u32(std::uint32_t* x) {
    unsigned char b[4];
    if (!raw(b, 4)) return false;
    *x = 0;
    for (int i = 0; i < 4; ++i) *x |= static_cast<std::uint32_t>(b[i]) << (8 * i);
    return true;
  }
  bool u64(std::uint64_t* x) {
    unsigned char b[8];
    if (!raw(b, 8)) return false;
    *x = 0;
    for (int i = 0; i < 8; ++i) *x |= static_cast<std::uint64_t>(b[i]) << (8 * i);
    return true;
  }
  bool f64(double* x) {
    std::uint64_t bits;
    if (!u64(&bits)) return false;
    std::memcpy(x, &bits, sizeof bits);
    return true;
  }
  bool atEnd() const { return pos_ == end_; }

 private:
  const std::string& data_;
  std::size_t end_;
  std::size_t pos_ = 0;
};

/// The report fields that describe the result (not the call: source, times of this call, cache).
void writeReport(Writer& w, const DecompositionReport& r) {
  for (int x : {r.numTriangles, r.numVertices, r.numComponents, r.numPieces, r.maxPieceVertices, r.holesFilled,
                r.voidsRemoved, r.duplicatesRemoved}) {
    w.u32(static_cast<std::uint32_t>(x));
  }
  for (double x : {r.diagonal, r.targetConcavity, r.concavity, r.concavityRelative, r.hullConcavity, r.meshVolume,
                   r.piecesVolume, r.volumeRatio, r.decomposeMilliseconds}) {
    w.f64(x);
  }
  w.u32((r.targetMet ? 1u : 0u) | (r.alreadyConvex ? 2u : 0u) | (r.meshClosed ? 4u : 0u));
}

bool readReport(Reader& rd, DecompositionReport* r) {
  std::uint32_t counts[8];
  for (std::uint32_t& c : counts) {
    if (!rd.u32(&c)) return false;
  }
  r->numTriangles = static_cast<int>(counts[0]);
  r->numVertices = static_cast<int>(counts[1]);
  r->numComponents = static_cast<int>(counts[2]);
  r->numPieces = static_cast<int>(counts[3]);
  r->maxPieceVertices = static_cast<int>(counts[4]);
  r->holesFilled = static_cast<int>(counts[5]);
  r->voidsRemoved = static_cast<int>(counts[6]);
  r->duplicatesRemoved = static_cast<int>(counts[7]);
  for (double* x : {&r->diagonal, &r->targetConcavity, &r->concavity, &r->concavityRelative, &r->hullConcavity,
                    &r->meshVolume, &r->piecesVolume, &r->volumeRatio, &r->decomposeMilliseconds}) {
    if (!rd.f64(x)) return false;
  }
  std::uint32_t flags;
  if (!rd.u32(&flags)) return false;
  r->targetMet = (flags & 1u) != 0;
  r->alreadyConvex = (flags & 2u) != 0;
  r->meshClosed = (flags & 4u) != 0;
  return true;
}

/// One line on stderr about the cache: the decomposition goes on without it, but the user should
/// know why every load recomputes. A write problem is reported once per directory and process
/// (it would repeat for every mesh).
void noteCacheProblem(const std::string& text, const std::string& directory, bool once) {
  static std::mutex mutex;
  static std::set<std::string> reported;
  const std::lock_guard<std::mutex> lock(mutex);
  if (once && !reported.insert(directory).second) return;
  std::fprintf(stderr, "deepcheck: decomposition cache: %s\n", text.c_str());
}

/// The report's warning, if any, as one line on stderr.
void printWarning(const DecompositionReport& report) {
  if (!report.warning.empty()) std::fprintf(stderr, "deepcheck: warning: %s\n", report.warning.c_str());
}

void setProblem(std::string* problem, const std::string& text) {
  if (problem != nullptr) *problem = text;
}

}  // namespace

DecompositionCache::DecompositionCache(std::string directory) : directory_(std::move(directory)) {
  if (directory_.empty()) directory_ = defaultDirectory();
  enabled_ = !directory_.empty();
}

DecompositionCache DecompositionCache::disabled() {
  DecompositionCache cache("-");
  cache.directory_.clear();
  cache.enabled_ = false;
  return cache;
}

std::string DecompositionCache::defaultDirectory() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg != nullptr && xdg[0] == '/') return (fs::path(xdg) / "deepcheck").string();
  const char* home = std::getenv("HOME");
  if (home != nullptr && home[0] != '\0') return (fs::path(home) / ".cache" / "deepcheck").string();
  return "";
}

std::string DecompositionCache::key(const TriangleMesh& mesh, const DecompositionParams& params) {
  ContentHasher h;
  static const char kTag[] = "deepcheck convex decomposition";
  h.bytes(kTag, sizeof kTag);
  h.u64(static_cast<std::uint64_t>(kDecompositionAlgorithmVersion));
  h.u64(mesh.vertices.size());
  for (const Eigen::Vector3d& v : mesh.vertices) {
    h.f64(v.x());
    h.f64(v.y());
    h.f64(v.z());
  }
  h.u64(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    for (int k : t) h.u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(k)));
  }
  h.f64(params.maxConcavity);
  h.f64(params.minConcavityAbs);
  h.u64(static_cast<std::uint64_t>(params.maxPieces));
  h.u64(static_cast<std::uint64_t>(params.maxVerticesPerPiece));
  h.u64(params.mergePieces ? 1 : 0);
  h.u64(params.seed);
  return h.hex();
}

std::string DecompositionCache::pathFor(const std::string& key) const {
  return (fs::path(directory_) / ("decomposition-" + key + ".bin")).string();
}

std::optional<ConvexDecomposition> DecompositionCache::load(const std::string& key, std::string* problem) const {
  setProblem(problem, "");
  if (!enabled_) return std::nullopt;
  const std::string path = pathFor(key);
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) return std::nullopt;
  auto bad = [&](const std::string& why) {
    setProblem(problem, path + ": " + why);
    return std::nullopt;
  };
  if (!fs::is_regular_file(status)) return bad("not a regular file");
  std::string data;
  if (const std::string why = readWholeFile(path, data); !why.empty()) return bad("cannot be read: " + why);
  if (data.size() < sizeof kMagic + 8) return bad("truncated");
  // Checksum first: it covers everything, so the fields below are read from intact bytes.
  const std::size_t body = data.size() - 8;
  std::uint64_t stored = 0;
  for (int i = 0; i < 8; ++i) {
    stored |= static_cast<std::uint64_t>(static_cast<unsigned char>(data[body + i])) << (8 * i);
  }
  if (fnv1a(data.data(), body) != stored) return bad("checksum mismatch (corrupt or truncated)");
  Reader rd(data, body);
  char magic[8];
  std::uint32_t format = 0;
  std::uint32_t algorithm = 0;
  unsigned char fileKey[16];
  unsigned char wantKey[16];
  if (!rd.raw(magic, 8) || std::memcmp(magic, kMagic, 8) != 0) return bad("not a decomposition cache file");
  if (!rd.u32(&format) || format != kFormatVersion) return bad("format version " + std::to_string(format));
  if (!rd.u32(&algorithm) || algorithm != static_cast<std::uint32_t>(kDecompositionAlgorithmVersion)) {
    return bad("algorithm version " + std::to_string(algorithm));
  }
  if (!rd.raw(fileKey, 16) || !cacheKeyBytes(key, wantKey) || std::memcmp(fileKey, wantKey, 16) != 0) {
    return bad("key mismatch");
  }
  ConvexDecomposition result;
  if (!readReport(rd, &result.report)) return bad("truncated report");
  std::uint32_t numPieces = 0;
  if (!rd.u32(&numPieces) || numPieces > kMaxPiecesInFile) return bad("bad piece count");
  result.pieces.resize(numPieces);
  for (ConvexPiece& piece : result.pieces) {
    std::uint32_t nv = 0;
    std::uint32_t nt = 0;
    if (!rd.u32(&nv) || !rd.u32(&nt) || nv > kMaxVerticesInFile || nt > 2 * kMaxVerticesInFile) {
      return bad("bad piece size");
    }
    piece.vertices.resize(nv);
    for (Eigen::Vector3d& v : piece.vertices) {
      for (int k = 0; k < 3; ++k) {
        if (!rd.f64(&v[k]) || !std::isfinite(v[k])) return bad("bad vertex");
      }
    }
    piece.triangles.resize(nt);
    for (auto& t : piece.triangles) {
      for (int& k : t) {
        std::uint32_t index = 0;
        if (!rd.u32(&index) || index >= nv) return bad("bad triangle index");
        k = static_cast<int>(index);
      }
    }
    if (!rd.f64(&piece.volume) || !(piece.volume >= 0.0)) return bad("bad volume");
    if (!rd.f64(&piece.concavity) || !(piece.concavity >= 0.0)) return bad("bad concavity");
  }
  if (!rd.atEnd()) return bad("trailing bytes");
  if (static_cast<std::uint32_t>(result.report.numPieces) != numPieces) return bad("piece count mismatch");
  return result;
}

bool DecompositionCache::store(const std::string& key, const ConvexDecomposition& result, std::string* problem) const {
  setProblem(problem, "");
  if (!enabled_) {
    setProblem(problem, "cache disabled");
    return false;
  }
  unsigned char keyBin[16];
  if (!cacheKeyBytes(key, keyBin)) {
    setProblem(problem, "malformed key '" + key + "'");
    return false;
  }
  Writer w;
  w.raw(kMagic, 8);
  w.u32(kFormatVersion);
  w.u32(static_cast<std::uint32_t>(kDecompositionAlgorithmVersion));
  w.raw(keyBin, 16);
  writeReport(w, result.report);
  w.u32(static_cast<std::uint32_t>(result.pieces.size()));
  for (const ConvexPiece& piece : result.pieces) {
    w.u32(static_cast<std::uint32_t>(piece.vertices.size()));
    w.u32(static_cast<std::uint32_t>(piece.triangles.size()));
    for (const Eigen::Vector3d& v : piece.vertices) {
      w.f64(v.x());
      w.f64(v.y());
      w.f64(v.z());
    }
    for (const auto& t : piece.triangles) {
      for (int k : t) w.u32(static_cast<std::uint32_t>(k));
    }
    w.f64(piece.volume);
    w.f64(piece.concavity);
  }
  w.u64(fnv1a(w.buffer().data(), w.buffer().size()));

  if (const std::string why = writeFileAtomically(directory_, pathFor(key), w.buffer()); !why.empty()) {
    setProblem(problem, why);
    return false;
  }
  return true;
}

ConvexDecomposition decomposeConvexCached(const TriangleMesh& mesh, const DecompositionParams& params,
                                          const DecompositionCache& cache) {
  const auto start = std::chrono::steady_clock::now();
  params.validate();
  if (!cache.enabled()) {
    ConvexDecomposition result = decomposeConvex(mesh, params);
    printWarning(result.report);
    return result;
  }
  const std::string key = DecompositionCache::key(mesh, params);
  std::string problem;
  std::optional<ConvexDecomposition> hit = cache.load(key, &problem);
  auto elapsed = [&] {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  };
  if (hit) {
    // The entry is checked against the mesh before use: a checksum only says the file is as
    // written, not that what was written covers this mesh.
    const std::string gap = coverageProblem(mesh, hit->pieces);
    if (gap.empty()) {
      hit->report.source = mesh.source;
      hit->report.cache = CacheStatus::Hit;
      hit->report.warning = targetWarning(hit->report, hit->pieces);
      printWarning(hit->report);
      hit->report.milliseconds = elapsed();
      return std::move(*hit);
    }
    problem = cache.pathFor(key) + ": its pieces do not cover the mesh: " + gap;
  }
  if (!problem.empty()) {
    noteCacheProblem(problem + "; decomposing " + detail::meshName(mesh) + " again", cache.directory(), false);
  }
  ConvexDecomposition result = decomposeConvex(mesh, params);
  result.report.cache = problem.empty() ? CacheStatus::Stored : CacheStatus::Replaced;
  result.report.cacheMessage = problem;
  std::string storeProblem;
  if (!cache.store(key, result, &storeProblem)) {
    noteCacheProblem(storeProblem + "; continuing without storing decompositions there", cache.directory(), true);
    result.report.cache = CacheStatus::StoreFailed;
    result.report.cacheMessage = storeProblem;
  }
  result.report.milliseconds = elapsed();
  printWarning(result.report);
  return result;
}

}  // namespace deepcheck::decomposition
