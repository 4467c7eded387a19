#pragma once
// Helpers of the decomposition tests: meshes built from grid cells and other shapes, and the
// checks every decomposition must pass (its pieces cover the mesh and meet the target).

#include "common/check_throws.h"
#include "common/temp_dir.h"

#include "deepcheck/decomposition/decomposition.h"

#include <boost/test/unit_test.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace deepcheck::decomposition::test {

using deepcheck::test::checkThrows;
using deepcheck::test::TempDir;
using Eigen::Vector3d;

/// The boundary of a union of grid cells (cell size h, grid origin `origin`): two triangles per
/// cell face between a filled and an empty cell, wound counter-clockwise seen from outside. The
/// shapes used here have no cells touching along an edge only, so the mesh is closed and
/// manifold. Sizes and offsets are not exact in binary on purpose.
inline TriangleMesh voxelMesh(const std::vector<std::array<int, 3>>& cells, double h, const Vector3d& origin,
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
inline TriangleMesh lShape() {
  return voxelMesh({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 2, 0}}, 1.0 / 3.0, Vector3d(0.1, -0.2, 0.3),
                   "L shape");
}

/// A U: a 3x1 base with two 1x2 arms.
inline TriangleMesh uShape() {
  return voxelMesh({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 2, 0}, {2, 1, 0}, {2, 2, 0}}, 0.37,
                   Vector3d(-0.41, 0.05, 0.0), "U shape");
}

/// A square ring (the torus of this grid): 3x3 cells around a missing centre.
inline TriangleMesh ring() {
  std::vector<std::array<int, 3>> cells;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i != 1 || j != 1) cells.push_back({i, j, 0});
    }
  }
  return voxelMesh(cells, 0.29, Vector3d(0.7, 0.7, -0.1), "ring");
}

/// A box of 3x2x1 cells: convex.
inline TriangleMesh box() {
  std::vector<std::array<int, 3>> cells;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 2; ++j) cells.push_back({i, j, 0});
  }
  return voxelMesh(cells, 0.23, Vector3d(0.01, 0.02, 0.03), "box");
}

/// 34 separate cubes on a 17 x 2 grid, one cell apart: 34 convex components, and the hull of any
/// two of them spans a gap far above the target, so meeting it takes 34 pieces.
inline TriangleMesh cubeGrid() {
  std::vector<std::array<int, 3>> cells;
  for (int i = 0; i < 17; ++i) {
    for (int j = 0; j < 2; ++j) cells.push_back({2 * i, 2 * j, 0});
  }
  return voxelMesh(cells, 0.07, Vector3d(-0.3, 0.2, 0.05), "cube grid");
}

/// A closed cylinder (a convex mesh with many vertices) of radius r, height h, n sides.
inline TriangleMesh cylinder(int n, double r, double h) {
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
inline TriangleMesh torus(int around, int across, double R, double r) {
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

inline double diagonalOf(const TriangleMesh& mesh) {
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
inline int uncoveredPoints(const TriangleMesh& mesh, const std::vector<ConvexPiece>& pieces, int perTriangle) {
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

inline void checkDecomposition(const TriangleMesh& mesh, const ConvexDecomposition& d) {
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

}  // namespace deepcheck::decomposition::test
