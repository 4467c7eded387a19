// `deepcheck decompose MESH`: approximate convex decomposition of one collision mesh (see
// deepcheck/decomposition/decomposition.h), written as OBJ, with its quality report.
// `--report` takes several meshes and prints one table row per mesh, then times reading them all
// back from the cache (what loading a robot a second time costs).
//
// Output of a single mesh (stdout):
//   mesh <file>
//   triangles <n> vertices <n> components <n> holes-filled <n> voids-removed <n>
//   pieces <n> (at most <n> vertices each)
//   concavity <metres> = <percent>% of the bounding-box diagonal <metres>; target <metres>: met|NOT met
//   hull of the whole mesh: concavity <metres>; already convex: yes|no
//   volume: mesh <m^3> pieces <m^3> ratio <r>      (or "mesh not closed")
//   time <ms> ms (cache <status>; decomposition <ms> ms)
// Units: metres (the mesh's own units for OBJ and STL files), milliseconds.

#include "common.h"
#include "subcommands.h"

#include "deepcheck/decomposition/cache.h"
#include "deepcheck/decomposition/decomposition.h"
#include "deepcheck/robots/mesh_loader.h"
#include "deepcheck/robots/package_path.h"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::tools {
namespace {

constexpr const char* kDecomposeUsage =
    "usage: deepcheck decompose MESH [--out PIECES.obj] [--max-concavity F]\n"
    "                           [--min-concavity-abs M] [--max-pieces N] [--max-vertices N]\n"
    "                           [--max-triangles N]\n"
    "                           [--cache DIR | --no-cache] [--package-path DIR]...\n"
    "       deepcheck decompose --report MESH... [same options, no --out]\n"
    "\n"
    "Approximate convex decomposition of a collision mesh (STL, OBJ, DAE; package:// URIs are\n"
    "resolved): pieces whose hulls stay within the concavity target of the mesh and cover it.\n"
    "Prints the quality report; --out writes the pieces as OBJ, one object 'piece_<i>' each.\n"
    "--report prints one row per mesh, then the time to read them all back from the cache.\n"
    "\n"
    "options:\n"
    "  --out FILE              write the pieces as Wavefront OBJ\n"
    "  --max-concavity F       target as a fraction of the bounding-box diagonal (default 0.01)\n"
    "  --min-concavity-abs M   floor of the target in metres (default 0.002):\n"
    "                          target = max(F * diagonal, M)\n"
    "  --max-pieces N          at most N pieces (default 64; more than 32 only when the\n"
    "                          target is missed with 32)\n"
    "  --max-vertices N        at most N vertices per piece (default 64; the pieces still\n"
    "                          contain the mesh)\n"
    "  --max-triangles N       refuse a mesh of more than N triangles (default 200000; about\n"
    "                          0.25-0.5 s per 1000 triangles; progress is printed past 1 s)\n"
    "  --cache DIR             cache folder (default $XDG_CACHE_HOME/deepcheck or\n"
    "                          ~/.cache/deepcheck)\n"
    "  --no-cache              neither read nor write the cache\n"
    "  --package-path DIR      a root to search for package:// URIs (repeatable; ROS_PACKAGE_PATH\n"
    "                          is also read)\n";

/// Largest value of --max-pieces and --max-vertices.
constexpr std::uint64_t kMaxCount = 1000000;

std::string baseName(const std::string& path) { return std::filesystem::path(path).filename().string(); }

void printReport(const decomposition::DecompositionReport& r) {
  std::printf("mesh %s\n", r.source.c_str());
  std::printf("triangles %d vertices %d components %d holes-filled %d voids-removed %d\n", r.numTriangles,
              r.numVertices, r.numComponents, r.holesFilled, r.voidsRemoved);
  std::printf("pieces %d (at most %d vertices each)\n", r.numPieces, r.maxPieceVertices);
  std::printf("concavity %.6g = %.3f%% of the bounding-box diagonal %.6g; target %.6g: %s\n", r.concavity,
              100.0 * r.concavityRelative, r.diagonal, r.targetConcavity, r.targetMet ? "met" : "NOT met");
  std::printf("hull of the whole mesh: concavity %.6g; already convex: %s\n", r.hullConcavity,
              r.alreadyConvex ? "yes" : "no");
  if (r.meshClosed) {
    std::printf("volume: mesh %.6g pieces %.6g ratio %.4f\n", r.meshVolume, r.piecesVolume, r.volumeRatio);
  } else {
    std::printf("volume: mesh not closed; pieces %.6g\n", r.piecesVolume);
  }
  std::printf("time %.1f ms (cache %s; decomposition %.1f ms)\n", r.milliseconds, decomposition::toString(r.cache),
              r.decomposeMilliseconds);
  if (!r.cacheMessage.empty()) std::printf("cache note: %s\n", r.cacheMessage.c_str());
}

/// The command line of `deepcheck decompose`.
struct DecomposeArgs {
  bool report = false;
  bool noCache = false;
  std::string out;
  std::string cacheDir;
  decomposition::DecompositionParams params;
  PackageRoots packages;
  std::vector<std::string> meshes;
};

/// The decomposition parameters given (--max-concavity, --min-concavity-abs, --max-pieces,
/// --max-vertices, --max-triangles); UsageError for a value they do not accept.
decomposition::DecompositionParams takeParams(std::vector<std::string>& args) {
  decomposition::DecompositionParams params;
  if (const std::string v = takeSingleOption(args, "--max-concavity"); !v.empty()) {
    params.maxConcavity = parseValue(v, "option --max-concavity");
  }
  if (const std::string v = takeSingleOption(args, "--min-concavity-abs"); !v.empty()) {
    params.minConcavityAbs = parseValue(v, "option --min-concavity-abs");
  }
  if (const std::string v = takeSingleOption(args, "--max-pieces"); !v.empty()) {
    params.maxPieces = static_cast<int>(parseCount(v, "--max-pieces", 1, kMaxCount));
  }
  if (const std::string v = takeSingleOption(args, "--max-vertices"); !v.empty()) {
    params.maxVerticesPerPiece = static_cast<int>(parseCount(v, "--max-vertices", 1, kMaxCount));
  }
  if (const std::string v = takeSingleOption(args, "--max-triangles"); !v.empty()) {
    params.maxTriangles = static_cast<int>(parseCount(v, "--max-triangles", 1, std::numeric_limits<int>::max()));
  }
  return params;
}

DecomposeArgs takeDecomposeArgs(std::vector<std::string>& args) {
  DecomposeArgs a;
  a.report = takeFlag(args, "--report");
  a.noCache = takeFlag(args, "--no-cache");
  a.out = takeSingleOption(args, "--out");
  a.cacheDir = takeSingleOption(args, "--cache");
  a.params = takeParams(args);
  a.packages = takePackageRoots(args);
  rejectUnknownOptions(args);
  if (a.noCache && !a.cacheDir.empty()) throw UsageError("--cache and --no-cache exclude each other");
  if (args.empty()) throw UsageError("no mesh given");
  if (!a.report && args.size() > 1) throw UsageError("one mesh at a time (or --report for several)");
  if (a.report && !a.out.empty()) throw UsageError("--out writes one mesh: not with --report");
  try {
    a.params.validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  a.meshes = std::move(args);
  return a;
}

/// `--report`: one table line per mesh, a summary, and the time to read them all back from the
/// cache.
void printReportTable(const std::vector<robots::TriangleMesh>& meshes, const decomposition::DecompositionParams& params,
                      const decomposition::DecompositionCache& cache) {
  std::printf("%-24s %9s %6s %10s %7s %10s %4s %8s %9s %7s\n", "mesh", "triangles", "pieces", "concavity", "%diag",
              "target", "met", "vol.ratio", "ms", "cache");
  bool allMet = true;
  double totalMs = 0.0;
  for (const robots::TriangleMesh& mesh : meshes) {
    const decomposition::ConvexDecomposition d = decomposition::decomposeConvexCached(mesh, params, cache);
    const decomposition::DecompositionReport& r = d.report;
    allMet = allMet && r.targetMet;
    totalMs += r.milliseconds;
    std::printf("%-24s %9d %6d %10.5f %7.3f %10.5f %4s %8.3f %9.1f %7s\n", baseName(r.source).c_str(), r.numTriangles,
                r.numPieces, r.concavity, 100.0 * r.concavityRelative, r.targetConcavity, r.targetMet ? "yes" : "NO",
                r.volumeRatio, r.decomposeMilliseconds, decomposition::toString(r.cache));
  }
  std::printf("meshes %zu, target met by all: %s, this run %.1f ms\n", meshes.size(), allMet ? "yes" : "no", totalMs);
  if (!cache.enabled()) return;
  // Reading everything back, as a second load of the same robot does (meshes already parsed).
  const auto start = std::chrono::steady_clock::now();
  int hits = 0;
  for (const robots::TriangleMesh& mesh : meshes) {
    hits += decomposition::decomposeConvexCached(mesh, params, cache).report.cache == decomposition::CacheStatus::Hit;
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("cached load: %d of %zu meshes from the cache in %.2f ms\n", hits, meshes.size(), ms);
}

int runDecompose(std::vector<std::string> args) {
  const DecomposeArgs a = takeDecomposeArgs(args);
  const decomposition::DecompositionCache cache =
      a.noCache ? decomposition::DecompositionCache::disabled() : decomposition::DecompositionCache(a.cacheDir);
  const std::vector<std::string> roots = robots::packageRoots(a.packages.commandLine);
  std::vector<robots::TriangleMesh> meshes;
  for (const std::string& arg : a.meshes) {
    const std::string path = robots::resolveUriOrThrow(arg, roots, "", "mesh argument");
    meshes.push_back(robots::loadMesh(path));
  }
  if (a.report) {
    printReportTable(meshes, a.params, cache);
    return 0;
  }
  const decomposition::ConvexDecomposition d = decomposition::decomposeConvexCached(meshes[0], a.params, cache);
  if (!a.out.empty()) decomposition::writePiecesObj(a.out, d.pieces);
  printReport(d.report);
  if (!a.out.empty()) std::printf("wrote %s\n", a.out.c_str());
  return 0;
}

}  // namespace

const Subcommand kDecomposeCommand = {"decompose", "convex decomposition of a mesh: OBJ pieces and a quality report",
                                      kDecomposeUsage, runDecompose};

}  // namespace deepcheck::tools
