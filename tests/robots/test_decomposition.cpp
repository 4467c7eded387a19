// Convex decomposition (robots/decomposition.h) and its disk cache (decomposition_cache.h).
//
// Properties checked rather than stored numbers: the pieces cover the mesh (every vertex, and
// points sampled on every triangle, inside a piece), the reported concavity meets the target, a
// convex mesh stays one piece, the vertex budget holds, results are deterministic, the cache
// round-trips, recovers from corrupt files and rejects entries whose pieces miss the mesh, a
// missed target is warned about, duplicated faces are dropped, a budget above 32 pieces is used
// only by a mesh that needs it, and bad input is rejected with a message.

#include "deepcheck/deep/internal/polytope_access.h"
#include "deepcheck/robots/decomposition.h"
#include "deepcheck/robots/decomposition_cache.h"
#include "deepcheck/robots/mesh_loader.h"

#include "robots_test_util.h"

#include <boost/test/unit_test.hpp>

#include <sys/resource.h>

#include <csignal>

#include <algorithm>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <system_error>
#include <tuple>
#include <vector>

namespace deepcheck::robots {
namespace {

using Eigen::Vector3d;
using test::checkThrows;
using test::TempDir;

/// The boundary of a union of grid cells (cell size h, grid origin `origin`): two triangles per
/// cell face between a filled and an empty cell, wound counter-clockwise seen from outside. The
/// shapes used here have no cells touching along an edge only, so the mesh is closed and
/// manifold. Sizes and offsets are not exact in binary on purpose.
TriangleMesh voxelMesh(const std::vector<std::array<int, 3>>& cells, double h, const Vector3d& origin,
                       const std::string& name) {
  std::set<std::array<int, 3>> filled(cells.begin(), cells.end());
  TriangleMesh mesh;
  mesh.source = name;
  std::map<std::array<int, 3>, int> index;
  auto vertex = [&](const std::array<int, 3>& g) {
    auto [it, inserted] = index.emplace(g, static_cast<int>(mesh.vertices.size()));
    if (inserted) mesh.vertices.push_back(origin + h * Vector3d(g[0], g[1], g[2]));
    return it->second;
  };
  for (const auto& c : cells) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int side : {0, 1}) {
        std::array<int, 3> n = c;
        n[axis] += side == 1 ? 1 : -1;
        if (filled.count(n) != 0) continue;
        // The face at c[axis] + side, spanned by the two other axes (u, v) so that u x v points
        // along +axis; reversed for the lower face.
        const int u = (axis + 1) % 3;
        const int v = (axis + 2) % 3;
        std::array<int, 3> p0 = c;
        p0[axis] += side;
        std::array<int, 3> p1 = p0;
        p1[u] += 1;
        std::array<int, 3> p2 = p1;
        p2[v] += 1;
        std::array<int, 3> p3 = p0;
        p3[v] += 1;
        std::array<int, 4> q = {vertex(p0), vertex(p1), vertex(p2), vertex(p3)};
        if (side == 0) std::swap(q[1], q[3]);
        mesh.triangles.push_back({q[0], q[1], q[2]});
        mesh.triangles.push_back({q[0], q[2], q[3]});
      }
    }
  }
  return mesh;
}

/// An L: a 3x1 foot and a 1x2 stem on it (cells of 1/3), one cell thick.
TriangleMesh lShape() {
  return voxelMesh({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 2, 0}}, 1.0 / 3.0,
                   Vector3d(0.1, -0.2, 0.3), "L shape");
}

/// A U: a 3x1 base with two 1x2 arms.
TriangleMesh uShape() {
  return voxelMesh({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 2, 0}, {2, 1, 0}, {2, 2, 0}},
                   0.37, Vector3d(-0.41, 0.05, 0.0), "U shape");
}

/// A square ring (the torus of this grid): 3x3 cells around a missing centre.
TriangleMesh ring() {
  std::vector<std::array<int, 3>> cells;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i != 1 || j != 1) cells.push_back({i, j, 0});
    }
  }
  return voxelMesh(cells, 0.29, Vector3d(0.7, 0.7, -0.1), "ring");
}

/// A box of 3x2x1 cells: convex.
TriangleMesh box() {
  std::vector<std::array<int, 3>> cells;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 2; ++j) cells.push_back({i, j, 0});
  }
  return voxelMesh(cells, 0.23, Vector3d(0.01, 0.02, 0.03), "box");
}

/// 34 separate cubes on a 17 x 2 grid, one cell apart: 34 convex components, and the hull of any
/// two of them spans a gap far above the target, so meeting it takes 34 pieces.
TriangleMesh cubeGrid() {
  std::vector<std::array<int, 3>> cells;
  for (int i = 0; i < 17; ++i) {
    for (int j = 0; j < 2; ++j) cells.push_back({2 * i, 2 * j, 0});
  }
  return voxelMesh(cells, 0.07, Vector3d(-0.3, 0.2, 0.05), "cube grid");
}

/// A closed cylinder (a convex mesh with many vertices) of radius r, height h, n sides.
TriangleMesh cylinder(int n, double r, double h) {
  TriangleMesh mesh;
  mesh.source = "cylinder";
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * k / n;
    mesh.vertices.emplace_back(r * std::cos(a), r * std::sin(a), 0.0);
    mesh.vertices.emplace_back(r * std::cos(a), r * std::sin(a), h);
  }
  const int bottom = static_cast<int>(mesh.vertices.size());
  mesh.vertices.emplace_back(0.0, 0.0, 0.0);
  mesh.vertices.emplace_back(0.0, 0.0, h);
  for (int k = 0; k < n; ++k) {
    const int a0 = 2 * k;
    const int a1 = 2 * k + 1;
    const int b0 = 2 * ((k + 1) % n);
    const int b1 = b0 + 1;
    mesh.triangles.push_back({a0, b0, b1});
    mesh.triangles.push_back({a0, b1, a1});
    mesh.triangles.push_back({bottom, b0, a0});
    mesh.triangles.push_back({bottom + 1, a1, b1});
  }
  return mesh;
}

/// A torus about the z axis (radii R and r, `around` x `across` quads): not convex, and its hull
/// has far more vertices than the default budget of 64.
TriangleMesh torus(int around, int across, double R, double r) {
  TriangleMesh mesh;
  mesh.source = "torus";
  for (int i = 0; i < around; ++i) {
    const double u = 2.0 * M_PI * i / around;
    for (int j = 0; j < across; ++j) {
      const double v = 2.0 * M_PI * j / across;
      mesh.vertices.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
                                 r * std::sin(v));
    }
  }
  for (int i = 0; i < around; ++i) {
    for (int j = 0; j < across; ++j) {
      const int a = i * across + j;
      const int b = ((i + 1) % around) * across + j;
      const int c = i * across + (j + 1) % across;
      const int d = ((i + 1) % around) * across + (j + 1) % across;
      mesh.triangles.push_back({a, b, d});
      mesh.triangles.push_back({a, d, c});
    }
  }
  return mesh;
}

double diagonalOf(const TriangleMesh& mesh) {
  Vector3d lo = mesh.vertices.front();
  Vector3d hi = lo;
  for (const Vector3d& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return (hi - lo).norm();
}

/// Coverage: every vertex, and `perTriangle` random points on every triangle, inside some piece
/// (within 1e-9 of the diagonal). Returns the number of points missed.
int uncoveredPoints(const TriangleMesh& mesh, const std::vector<ConvexPiece>& pieces, int perTriangle) {
  const double tolerance = 1e-9 * diagonalOf(mesh);
  auto covered = [&](const Vector3d& p) {
    for (const ConvexPiece& piece : pieces) {
      if (pieceContains(piece, p, tolerance)) return true;
    }
    return false;
  };
  int missed = 0;
  for (const Vector3d& v : mesh.vertices) missed += covered(v) ? 0 : 1;
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < perTriangle; ++k) {
      double a = unit(rng);
      double b = unit(rng);
      if (a + b > 1.0) {
        a = 1.0 - a;
        b = 1.0 - b;
      }
      const Vector3d& p0 = mesh.vertices[t[0]];
      missed += covered(p0 + a * (mesh.vertices[t[1]] - p0) + b * (mesh.vertices[t[2]] - p0)) ? 0 : 1;
    }
  }
  return missed;
}

void checkDecomposition(const TriangleMesh& mesh, const ConvexDecomposition& d) {
  const DecompositionReport& r = d.report;
  BOOST_CHECK_EQUAL(r.numPieces, static_cast<int>(d.pieces.size()));
  BOOST_CHECK(r.targetMet);
  BOOST_CHECK_LE(r.concavity, r.targetConcavity);
  // The report's concavity is the worst piece's: not a separate, possibly smaller, estimate.
  double worst = 0.0;
  for (const ConvexPiece& piece : d.pieces) worst = std::max(worst, piece.concavity);
  BOOST_CHECK_EQUAL(r.concavity, worst);
  BOOST_CHECK_EQUAL(uncoveredPoints(mesh, d.pieces, 4), 0);
  if (r.meshClosed) {
    // The pieces cover the solid: their volumes add up to at least the mesh's.
    BOOST_CHECK_GE(r.volumeRatio, 1.0 - 1e-9);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(robots_decomposition)

BOOST_AUTO_TEST_CASE(l_u_and_ring_shapes_get_several_pieces_that_cover_them) {
  // Each shape with its volume (cells times cell volume).
  const std::vector<std::pair<TriangleMesh, double>> shapes = {
      {lShape(), 5 * std::pow(1.0 / 3.0, 3)}, {uShape(), 7 * std::pow(0.37, 3)}, {ring(), 8 * std::pow(0.29, 3)}};
  for (const auto& [mesh, volume] : shapes) {
    const ConvexDecomposition d = decomposeConvex(mesh);
    BOOST_CHECK_GE(d.report.numPieces, 2);
    BOOST_CHECK(!d.report.alreadyConvex);
    BOOST_CHECK(d.report.meshClosed);
    BOOST_CHECK_CLOSE(d.report.meshVolume, volume, 1e-9);
    checkDecomposition(mesh, d);
  }
}

BOOST_AUTO_TEST_CASE(a_convex_mesh_is_one_piece_without_decomposition) {
  const TriangleMesh mesh = box();
  const ConvexDecomposition d = decomposeConvex(mesh);
  BOOST_CHECK_EQUAL(d.report.numPieces, 1);
  BOOST_CHECK(d.report.alreadyConvex);
  BOOST_CHECK_SMALL(d.report.concavity, 1e-12);
  BOOST_CHECK_CLOSE(d.report.volumeRatio, 1.0, 1e-9);
  checkDecomposition(mesh, d);
}

BOOST_AUTO_TEST_CASE(pieces_become_valid_polytopes) {
  const ConvexDecomposition d = decomposeConvex(uShape());
  const std::vector<deep::ConvexPolytope> polytopes = d.polytopes();
  BOOST_REQUIRE_EQUAL(polytopes.size(), d.pieces.size());
  for (const deep::ConvexPolytope& p : polytopes) {
    BOOST_CHECK(p.kind() == deep::PolytopeKind::Polyhedron);
    BOOST_CHECK_EQUAL(deep::detail::validate(p), "");
  }
}

BOOST_AUTO_TEST_CASE(results_are_deterministic) {
  const TriangleMesh mesh = ring();
  const ConvexDecomposition a = decomposeConvex(mesh);
  const ConvexDecomposition b = decomposeConvex(mesh);
  BOOST_REQUIRE_EQUAL(a.pieces.size(), b.pieces.size());
  for (std::size_t i = 0; i < a.pieces.size(); ++i) {
    BOOST_CHECK(a.pieces[i].vertices == b.pieces[i].vertices);
    BOOST_CHECK(a.pieces[i].triangles == b.pieces[i].triangles);
  }
  BOOST_CHECK_EQUAL(a.report.concavity, b.report.concavity);
}

BOOST_AUTO_TEST_CASE(a_mesh_meeting_the_target_within_32_pieces_ignores_a_larger_budget) {
  const TriangleMesh mesh = ring();
  DecompositionParams small;
  small.maxPieces = 32;
  const ConvexDecomposition a = decomposeConvex(mesh, small);
  const ConvexDecomposition b = decomposeConvex(mesh);  // default budget, larger
  BOOST_REQUIRE(a.report.targetMet);
  BOOST_REQUIRE_EQUAL(a.pieces.size(), b.pieces.size());
  for (std::size_t i = 0; i < a.pieces.size(); ++i) {
    BOOST_CHECK(a.pieces[i].vertices == b.pieces[i].vertices);
    BOOST_CHECK(a.pieces[i].triangles == b.pieces[i].triangles);
  }
}

BOOST_AUTO_TEST_CASE(the_budget_grows_past_32_while_the_target_is_missed) {
  // 34 cubes: the first stage (32 pieces) forces merges across the gaps and misses the target;
  // the second (64) undoes them: one piece per cube. (maxPieces = 32 would stop after the first.)
  const TriangleMesh mesh = cubeGrid();
  const ConvexDecomposition d = decomposeConvex(mesh);
  BOOST_CHECK_EQUAL(d.report.numPieces, 34);
  checkDecomposition(mesh, d);
}

BOOST_AUTO_TEST_CASE(a_missing_quad_is_filled) {
  // The L with one face (two triangles) removed: the hole is closed before decomposing.
  TriangleMesh mesh = lShape();
  mesh.triangles.pop_back();
  mesh.triangles.pop_back();
  const ConvexDecomposition d = decomposeConvex(mesh);
  BOOST_CHECK_EQUAL(d.report.holesFilled, 1);
  BOOST_CHECK(d.report.meshClosed);
  checkDecomposition(mesh, d);
}

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
      bytes.substr(0, bytes.size() / 2),                          // truncated
      std::string(bytes).replace(bytes.size() / 2, 1, 1, '\x7f'),  // one byte flipped
      "not a cache file at all",                                  // garbage
      "",                                                         // empty
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
  BOOST_CHECK_MESSAGE(again.report.cacheMessage.find("cannot be read") != std::string::npos,
                      again.report.cacheMessage);
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

BOOST_AUTO_TEST_CASE(a_convex_mesh_with_many_vertices_stays_one_piece_within_the_vertex_budget) {
  // 96 sides: 194 hull vertices. Its hull meets any target; reduced to 16 vertices it may not,
  // which the warning would say, but it is not cut.
  const TriangleMesh mesh = cylinder(96, 0.31, 0.47);
  for (double maxConcavity : {0.05, 0.001}) {
    DecompositionParams params;
    params.maxVerticesPerPiece = 16;
    params.maxConcavity = maxConcavity;
    params.minConcavityAbs = 0.0;
    const ConvexDecomposition d = decomposeConvex(mesh, params);
    BOOST_CHECK_EQUAL(d.report.numPieces, 1);
    BOOST_CHECK(d.report.alreadyConvex);
    BOOST_CHECK_LE(d.report.maxPieceVertices, 16);
    BOOST_CHECK_EQUAL(d.report.warning.empty(), d.report.targetMet);
    BOOST_CHECK_EQUAL(uncoveredPoints(mesh, d.pieces, 2), 0);
  }
}

BOOST_AUTO_TEST_CASE(the_vertex_budget_holds_when_the_target_is_missed) {
  // A torus in one piece: the part misses the target and is never cut, yet its hull (576
  // vertices) is reduced to the budget.
  const TriangleMesh mesh = torus(48, 12, 0.1, 0.03);
  DecompositionParams params;
  params.maxPieces = 1;
  const ConvexDecomposition d = decomposeConvex(mesh, params);
  BOOST_REQUIRE_EQUAL(d.report.numPieces, 1);
  BOOST_CHECK(!d.report.targetMet);
  BOOST_CHECK_LE(d.report.maxPieceVertices, params.maxVerticesPerPiece);
  BOOST_CHECK_EQUAL(uncoveredPoints(mesh, d.pieces, 1), 0);
}

BOOST_AUTO_TEST_CASE(a_finely_tessellated_torus_is_covered_and_meets_the_target) {
  // 96 x 32 quads, 3,072 vertices: the pieces cover every vertex and random points of every
  // triangle, and meet the target and the vertex budget.
  const TriangleMesh mesh = torus(96, 32, 0.1, 0.03);
  const ConvexDecomposition d = decomposeConvex(mesh);
  BOOST_CHECK_GE(d.report.numPieces, 4);
  BOOST_CHECK(d.report.targetMet);
  BOOST_CHECK_EQUAL(coverageProblem(mesh, d.pieces), "");
  checkDecomposition(mesh, d);
}

BOOST_AUTO_TEST_CASE(duplicated_faces_are_dropped_and_the_volume_ratio_stays_right) {
  const TriangleMesh mesh = lShape();
  const ConvexDecomposition reference = decomposeConvex(mesh);
  BOOST_REQUIRE_GE(reference.report.volumeRatio, 1.0 - 1e-9);
  TriangleMesh repeated = mesh;   // every face twice
  TriangleMesh twoSided = mesh;   // every face also wound the other way
  for (const auto& t : mesh.triangles) {
    repeated.triangles.push_back(t);
    twoSided.triangles.push_back({t[0], t[2], t[1]});
  }
  for (const TriangleMesh& doubled : {repeated, twoSided}) {
    const ConvexDecomposition d = decomposeConvex(doubled);
    BOOST_CHECK_EQUAL(d.report.duplicatesRemoved, static_cast<int>(mesh.triangles.size()));
    BOOST_CHECK_EQUAL(d.report.numTriangles, reference.report.numTriangles);
    BOOST_CHECK_CLOSE(d.report.meshVolume, reference.report.meshVolume, 1e-9);
    BOOST_CHECK_CLOSE(d.report.volumeRatio, reference.report.volumeRatio, 1e-9);
    checkDecomposition(doubled, d);
  }
}

BOOST_AUTO_TEST_CASE(bad_input_is_rejected_with_a_message) {
  TriangleMesh empty;
  empty.source = "empty.stl";
  checkThrows([&] { decomposeConvex(empty); }, {"empty.stl", "no triangles"});

  TriangleMesh nan = lShape();
  nan.vertices[3].y() = std::numeric_limits<double>::quiet_NaN();
  checkThrows([&] { decomposeConvex(nan); }, {"L shape", "vertex 3", "not finite"});

  TriangleMesh index = lShape();
  index.triangles[2][1] = static_cast<int>(index.vertices.size());
  checkThrows([&] { decomposeConvex(index); }, {"triangle 2", "out of range"});

  TriangleMesh flat;
  flat.vertices = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(2, 0, 0)};
  flat.triangles = {{0, 1, 2}};
  checkThrows([&] { decomposeConvex(flat); }, {"degenerate"});

  const TriangleMesh mesh = box();
  DecompositionParams p;
  p.maxConcavity = 0.0;
  checkThrows([&] { decomposeConvex(mesh, p); }, {"maxConcavity", "0"});
  p = {};
  p.maxConcavity = 1.5;
  checkThrows([&] { decomposeConvex(mesh, p); }, {"maxConcavity", "1.5"});
  p = {};
  p.minConcavityAbs = -1.0;
  checkThrows([&] { decomposeConvex(mesh, p); }, {"minConcavityAbs", "-1"});
  p = {};
  p.minConcavityAbs = std::numeric_limits<double>::infinity();
  checkThrows([&] { decomposeConvex(mesh, p); }, {"minConcavityAbs"});
  p = {};
  p.maxPieces = 0;
  checkThrows([&] { decomposeConvex(mesh, p); }, {"maxPieces", "0"});
  p = {};
  p.maxTriangles = 0;
  checkThrows([&] { decomposeConvex(mesh, p); }, {"maxTriangles", "0"});
  // A mesh above the triangle limit: refused with its name, its count and the option.
  p = {};
  p.maxTriangles = 11;
  checkThrows([&] { decomposeConvex(mesh, p); }, {"'box'", "has 44 triangles", "maxTriangles (11)", "--max-triangles"});
  p.maxTriangles = 44;
  BOOST_CHECK_EQUAL(decomposeConvex(mesh, p).report.numPieces, 1);
  p = {};
  p.maxVerticesPerPiece = 3;
  checkThrows([&] { decomposeConvex(mesh, p); }, {"maxVerticesPerPiece", "3"});
  // The cached entry point validates the parameters before looking at the cache.
  checkThrows([&] { decomposeConvexCached(mesh, p, DecompositionCache::disabled()); },
              {"maxVerticesPerPiece"});
}

BOOST_AUTO_TEST_CASE(panda_links_are_covered_and_meet_the_target) {
  if (!test::haveShared("the Panda decomposition test")) return;
  const std::string folder = test::sharedDir() + "/robots/panda/moveit_resources_panda_description/meshes/collision/";
  for (const char* name : {"link0.stl", "hand.stl"}) {
    const TriangleMesh mesh = loadMesh(folder + name);
    const ConvexDecomposition d = decomposeConvex(mesh);
    checkDecomposition(mesh, d);
    for (const ConvexPiece& piece : d.pieces) BOOST_CHECK_LE(static_cast<int>(piece.vertices.size()), 64);
  }
}

BOOST_AUTO_TEST_SUITE_END()

}  // namespace deepcheck::robots
