// Convex decomposition (decomposition/decomposition.h).
//
// Properties checked rather than stored numbers: the pieces cover the mesh (every vertex, and
// points sampled on every triangle, inside a piece), the reported concavity meets the target, a
// convex mesh stays one piece, the vertex budget holds, results are deterministic, duplicated
// faces are dropped, a budget above 32 pieces is used only by a mesh that needs it, and bad input
// is rejected with a message.

#include "deepcheck/geometry/internal/polytope_access.h"
#include "deepcheck/decomposition/cache.h"
#include "deepcheck/decomposition/decomposition.h"

#include "decomposition_test_util.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::decomposition::test {

BOOST_AUTO_TEST_SUITE(convex_decomposition)

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
  const std::vector<geometry::ConvexPolytope> polytopes = d.polytopes();
  BOOST_REQUIRE_EQUAL(polytopes.size(), d.pieces.size());
  for (const geometry::ConvexPolytope& p : polytopes) {
    BOOST_CHECK(p.kind() == geometry::PolytopeKind::Polyhedron);
    BOOST_CHECK_EQUAL(geometry::detail::validate(p), "");
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
  TriangleMesh repeated = mesh;  // every face twice
  TriangleMesh twoSided = mesh;  // every face also wound the other way
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
  checkThrows([&] { decomposeConvexCached(mesh, p, DecompositionCache::disabled()); }, {"maxVerticesPerPiece"});
}

BOOST_AUTO_TEST_SUITE_END()

}  // namespace deepcheck::decomposition::test
