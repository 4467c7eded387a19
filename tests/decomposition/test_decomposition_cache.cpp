// The on-disk cache of decompositions (decomposition/cache.h) and the coverage check it relies on:
// the cache round-trips, recovers from corrupt, unreadable or misplaced files and rejects entries
// whose pieces miss the mesh, says why a write failed, and a missed target is warned about also
// on a hit.

#include "deepcheck/decomposition/cache.h"
#include "deepcheck/decomposition/decomposition.h"

#include "decomposition_test_util.h"

#include <boost/test/unit_test.hpp>

#include <sys/resource.h>

#include <csignal>

#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <system_error>
#include <vector>

namespace deepcheck::decomposition::test {

BOOST_AUTO_TEST_SUITE(decomposition_cache)

BOOST_AUTO_TEST_CASE(cache_round_trip_reads_the_second_time) {
  TempDir dir;
  const DecompositionCache cache(dir.path().string());
  const TriangleMesh mesh = uShape();
  const ConvexDecomposition first = decomposeConvexCached(mesh, {}, cache);
  BOOST_CHECK(first.report.cache == CacheStatus::Stored);
  const std::string path = cache.pathFor(DecompositionCache::key(mesh, {}));
  BOOST_CHECK(std::filesystem::exists(path));
  const ConvexDecomposition second = decomposeConvexCached(mesh, {}, cache);
  BOOST_CHECK(second.report.cache == CacheStatus::Hit);
  BOOST_CHECK_EQUAL(second.report.source, mesh.source);
  BOOST_REQUIRE_EQUAL(second.pieces.size(), first.pieces.size());
  for (std::size_t i = 0; i < first.pieces.size(); ++i) {
    BOOST_CHECK(second.pieces[i].vertices == first.pieces[i].vertices);
    BOOST_CHECK(second.pieces[i].triangles == first.pieces[i].triangles);
    BOOST_CHECK_EQUAL(second.pieces[i].volume, first.pieces[i].volume);
  }
  BOOST_CHECK_EQUAL(second.report.concavity, first.report.concavity);
  BOOST_CHECK_EQUAL(second.report.numPieces, first.report.numPieces);
  BOOST_CHECK_EQUAL(second.report.decomposeMilliseconds, first.report.decomposeMilliseconds);
  // No temporary file is left behind.
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    (void)entry;
    ++files;
  }
  BOOST_CHECK_EQUAL(files, 1);
}

BOOST_AUTO_TEST_CASE(corrupt_or_truncated_cache_files_are_recomputed) {
  TempDir dir;
  const DecompositionCache cache(dir.path().string());
  const TriangleMesh mesh = lShape();
  const ConvexDecomposition reference = decomposeConvexCached(mesh, {}, cache);
  const std::string path = cache.pathFor(DecompositionCache::key(mesh, {}));
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  BOOST_REQUIRE_GT(bytes.size(), 64u);
  const std::vector<std::string> damaged = {
      bytes.substr(0, bytes.size() / 2),                           // truncated
      std::string(bytes).replace(bytes.size() / 2, 1, 1, '\x7f'),  // one byte flipped
      "not a cache file at all",                                   // garbage
      "",                                                          // empty
  };
  for (const std::string& content : damaged) {
    {
      std::ofstream out(path, std::ios::binary | std::ios::trunc);
      out << content;
    }
    std::string problem;
    BOOST_CHECK(!cache.load(DecompositionCache::key(mesh, {}), &problem));
    BOOST_CHECK(!problem.empty());
    const ConvexDecomposition again = decomposeConvexCached(mesh, {}, cache);
    BOOST_CHECK(again.report.cache == CacheStatus::Replaced);
    BOOST_CHECK(!again.report.cacheMessage.empty());
    BOOST_CHECK_EQUAL(again.pieces.size(), reference.pieces.size());
    BOOST_CHECK(decomposeConvexCached(mesh, {}, cache).report.cache == CacheStatus::Hit);
  }
}

BOOST_AUTO_TEST_CASE(a_directory_in_place_of_a_cache_file_is_decomposed_again) {
  TempDir dir;
  const DecompositionCache cache(dir.path().string());
  const TriangleMesh mesh = lShape();
  const ConvexDecomposition reference = decomposeConvex(mesh);
  const std::string key = DecompositionCache::key(mesh, {});
  std::filesystem::create_directories(std::filesystem::path(cache.pathFor(key)) / "inside");
  std::string problem;
  BOOST_CHECK(!cache.load(key, &problem));
  BOOST_CHECK_MESSAGE(problem.find("not a regular file") != std::string::npos, problem);
  BOOST_CHECK_MESSAGE(problem.find(cache.pathFor(key)) != std::string::npos, problem);
  // Decomposed again; the directory cannot be replaced (it is not ours to delete), which the
  // report says, and it is left as it was.
  const ConvexDecomposition again = decomposeConvexCached(mesh, {}, cache);
  BOOST_CHECK(again.report.cache == CacheStatus::StoreFailed);
  BOOST_CHECK_MESSAGE(again.report.cacheMessage.find(cache.pathFor(key)) != std::string::npos,
                      again.report.cacheMessage);
  BOOST_REQUIRE_EQUAL(again.pieces.size(), reference.pieces.size());
  for (std::size_t i = 0; i < reference.pieces.size(); ++i) {
    BOOST_CHECK(again.pieces[i].vertices == reference.pieces[i].vertices);
  }
  BOOST_CHECK(std::filesystem::is_directory(std::filesystem::path(cache.pathFor(key)) / "inside"));
}

BOOST_AUTO_TEST_CASE(a_cache_directory_that_cannot_be_created_leaves_the_decomposition_uncached) {
  // A regular file where the cache directory should be: creating the directory fails (as root
  // too, unlike a permission).
  TempDir dir;
  const std::string notADirectory = dir.write("cache", "a file, not a directory");
  const DecompositionCache cache(notADirectory);
  const TriangleMesh mesh = uShape();
  const ConvexDecomposition d = decomposeConvexCached(mesh, {}, cache);
  BOOST_CHECK(d.report.cache == CacheStatus::StoreFailed);
  BOOST_CHECK_MESSAGE(d.report.cacheMessage.find(notADirectory) != std::string::npos, d.report.cacheMessage);
  BOOST_CHECK_EQUAL(d.pieces.size(), decomposeConvex(mesh).pieces.size());
  BOOST_CHECK(std::filesystem::is_regular_file(notADirectory));
  // And again: still no error, still decomposed.
  BOOST_CHECK(decomposeConvexCached(mesh, {}, cache).report.cache == CacheStatus::StoreFailed);
}

BOOST_AUTO_TEST_CASE(an_unreadable_cache_file_is_decomposed_again) {
  TempDir dir;
  const DecompositionCache cache(dir.path().string());
  const TriangleMesh mesh = lShape();
  const std::string key = DecompositionCache::key(mesh, {});
  BOOST_REQUIRE(decomposeConvexCached(mesh, {}, cache).report.cache == CacheStatus::Stored);
  std::filesystem::permissions(cache.pathFor(key), std::filesystem::perms::none);
  if (std::ifstream(cache.pathFor(key)).good()) {
    BOOST_TEST_MESSAGE("skipped the unreadable-file case: this user reads files without permission (root)");
    return;
  }
  const ConvexDecomposition again = decomposeConvexCached(mesh, {}, cache);
  BOOST_CHECK(again.report.cache == CacheStatus::Replaced);
  BOOST_CHECK_MESSAGE(again.report.cacheMessage.find("cannot be read") != std::string::npos, again.report.cacheMessage);
}

BOOST_AUTO_TEST_CASE(parameters_and_content_change_the_key) {
  const TriangleMesh mesh = lShape();
  const DecompositionParams base;
  const std::string key = DecompositionCache::key(mesh, base);
  BOOST_CHECK_EQUAL(key.size(), 32u);
  BOOST_CHECK_EQUAL(key, DecompositionCache::key(mesh, base));
  std::vector<DecompositionParams> changed(6, base);
  changed[0].maxConcavity = 0.02;
  changed[1].minConcavityAbs = 0.001;
  changed[2].maxPieces = 16;
  changed[3].maxVerticesPerPiece = 32;
  changed[4].mergePieces = false;
  changed[5].seed = base.seed + 1;
  std::set<std::string> keys = {key};
  for (const DecompositionParams& p : changed) keys.insert(DecompositionCache::key(mesh, p));
  BOOST_CHECK_EQUAL(keys.size(), changed.size() + 1);
  TriangleMesh moved = mesh;
  moved.vertices[0].x() += 1e-12;
  BOOST_CHECK_NE(DecompositionCache::key(moved, base), key);
  TriangleMesh renamed = mesh;
  renamed.source = "another file";
  BOOST_CHECK_EQUAL(DecompositionCache::key(renamed, base), key);  // the content is the key
}

BOOST_AUTO_TEST_CASE(a_forged_cache_entry_whose_pieces_miss_the_mesh_is_rebuilt) {
  // A well-formed entry (right key, right checksum) holding one 1 mm cube: the coverage check
  // rejects it, and the mesh is decomposed again.
  TempDir dir;
  const DecompositionCache cache(dir.path().string());
  const TriangleMesh mesh = lShape();
  const std::string key = DecompositionCache::key(mesh, {});
  const ConvexDecomposition reference = decomposeConvexCached(mesh, {}, cache);
  ConvexDecomposition forged = reference;
  const TriangleMesh tiny = voxelMesh({{0, 0, 0}}, 0.001, Vector3d(0.1, -0.2, 0.3), "tiny");
  forged.pieces = {{tiny.vertices, tiny.triangles, 1e-9, 0.0}};
  forged.report.numPieces = 1;
  BOOST_REQUIRE(cache.store(key, forged));
  BOOST_REQUIRE(cache.load(key));  // it reads as a valid file
  BOOST_CHECK_NE(coverageProblem(mesh, forged.pieces), "");
  const ConvexDecomposition again = decomposeConvexCached(mesh, {}, cache);
  BOOST_CHECK(again.report.cache == CacheStatus::Replaced);
  BOOST_CHECK_MESSAGE(again.report.cacheMessage.find("do not cover the mesh") != std::string::npos,
                      again.report.cacheMessage);
  BOOST_CHECK_MESSAGE(again.report.cacheMessage.find("outside every piece") != std::string::npos,
                      again.report.cacheMessage);
  BOOST_REQUIRE_EQUAL(again.pieces.size(), reference.pieces.size());
  checkDecomposition(mesh, again);
  BOOST_CHECK(decomposeConvexCached(mesh, {}, cache).report.cache == CacheStatus::Hit);
}

BOOST_AUTO_TEST_CASE(coverage_names_the_first_vertex_outside_the_pieces) {
  const TriangleMesh mesh = uShape();
  ConvexDecomposition d = decomposeConvex(mesh);
  BOOST_CHECK_EQUAL(coverageProblem(mesh, d.pieces), "");
  // Every piece moved away along x by 1/7: some vertex is left outside.
  for (ConvexPiece& piece : d.pieces) {
    for (Vector3d& v : piece.vertices) v.x() += 1.0 / 7.0;
  }
  const std::string problem = coverageProblem(mesh, d.pieces);
  BOOST_CHECK_MESSAGE(problem.find("vertex ") != std::string::npos, problem);
  BOOST_CHECK_MESSAGE(problem.find("outside every piece") != std::string::npos, problem);
  BOOST_CHECK_EQUAL(coverageProblem(mesh, {}).find("no piece") != std::string::npos, true);
  TriangleMesh nan = mesh;
  nan.vertices[1].z() = std::numeric_limits<double>::quiet_NaN();
  checkThrows([&] { coverageProblem(nan, d.pieces); }, {"U shape", "vertex 1", "not finite"});
}

BOOST_AUTO_TEST_CASE(a_cache_write_failure_gives_the_system_reason) {
  // A file size limit of a few bytes makes the write fail (as root too): EFBIG, whose message
  // the problem must carry. SIGXFSZ would kill the process: ignored meanwhile.
  TempDir dir;
  const DecompositionCache cache(dir.path().string());
  const TriangleMesh mesh = lShape();
  const ConvexDecomposition d = decomposeConvex(mesh);
  rlimit saved{};
  BOOST_REQUIRE_EQUAL(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  rlimit tiny = saved;
  tiny.rlim_cur = 16;
  const auto previous = std::signal(SIGXFSZ, SIG_IGN);
  BOOST_REQUIRE_EQUAL(::setrlimit(RLIMIT_FSIZE, &tiny), 0);
  std::string problem;
  const bool stored = cache.store(DecompositionCache::key(mesh, {}), d, &problem);
  ::setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, previous);
  BOOST_CHECK(!stored);
  BOOST_CHECK_MESSAGE(problem.find("cannot write") != std::string::npos, problem);
  const std::string reason = std::error_code(EFBIG, std::generic_category()).message();
  BOOST_CHECK_MESSAGE(problem.find(reason) != std::string::npos, problem);
}

BOOST_AUTO_TEST_CASE(a_disabled_cache_neither_reads_nor_writes) {
  const DecompositionCache cache = DecompositionCache::disabled();
  BOOST_CHECK(!cache.enabled());
  const ConvexDecomposition d = decomposeConvexCached(box(), {}, cache);
  BOOST_CHECK(d.report.cache == CacheStatus::NotUsed);
  BOOST_CHECK_EQUAL(d.report.numPieces, 1);
}

BOOST_AUTO_TEST_CASE(a_missed_target_is_named_in_the_warning_also_from_the_cache) {
  // The ring in one piece: its hull spans the hole, far above the target.
  DecompositionParams one;
  one.maxPieces = 1;
  const TriangleMesh mesh = ring();
  const ConvexDecomposition d = decomposeConvex(mesh, one);
  BOOST_REQUIRE(!d.report.targetMet);
  for (const std::string& part : {std::string("'ring'"), std::string("misses its target"), std::string("1 of 1")}) {
    BOOST_CHECK_MESSAGE(d.report.warning.find(part) != std::string::npos, d.report.warning);
  }
  TempDir dir;
  const DecompositionCache cache(dir.path().string());
  BOOST_CHECK_EQUAL(decomposeConvexCached(mesh, one, cache).report.warning, d.report.warning);
  const ConvexDecomposition hit = decomposeConvexCached(mesh, one, cache);
  BOOST_CHECK(hit.report.cache == CacheStatus::Hit);
  BOOST_CHECK_EQUAL(hit.report.warning, d.report.warning);
  // Met: no warning.
  BOOST_CHECK_EQUAL(decomposeConvex(mesh).report.warning, "");
}

BOOST_AUTO_TEST_SUITE_END()

}  // namespace deepcheck::decomposition::test
