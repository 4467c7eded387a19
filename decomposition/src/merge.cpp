// Merging pieces whose union still meets the concavity target (decomposer.h).

#include "decomposer.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace deepcheck::decomposition::detail {

Hull Decomposer::pieceHull(const Piece& a, const Piece* b) const {
  std::vector<Vector3d> points = a.hull.vertices;
  if (b != nullptr) points.insert(points.end(), b->hull.vertices.begin(), b->hull.vertices.end());
  return detail::convexHull(points);
}

Target Decomposer::pieceTarget(const Piece& a, const Piece* b) const {
  Target target;
  target.mesh = &meshBvh_;
  std::vector<int> planes;
  for (const Piece* piece : {&a, b}) {
    if (piece == nullptr) continue;
    for (int p : piece->parts) {
      for (const CellSide& side : parts_[p].cell) planes.push_back(side.plane);
    }
  }
  std::sort(planes.begin(), planes.end());
  planes.erase(std::unique(planes.begin(), planes.end()), planes.end());
  for (int p : planes) target.caps.push_back({planes_[p]->normal, planes_[p]->offset, &planes_[p]->section});
  return target;
}

double Decomposer::mergeCost(const Piece& a, const Piece& b, double abortAbove, Piece* merged) {
  for (int x : a.parts) {
    for (int y : b.parts) {
      if (forbidden_.count({x, y}) != 0) return kInf;  // merged once, failed the final check
    }
  }
  Hull hull = pieceHull(a, &b);
  const Target target = pieceTarget(a, &b);
  Concavity c = measureConcavity(hull, target, tol::kPartSamples, Extra::Dense, nextSeed(), abortAbove, diagonal_);
  if (c.aborted) return kInf;
  Hull reduced = hull;
  if (static_cast<int>(hull.vertices.size()) > params_.maxVerticesPerPiece) {
    reduced = detail::reduceHullVertices(hull, params_.maxVerticesPerPiece);
    c = measureConcavity(reduced, target, tol::kPartSamples, Extra::Dense, nextSeed(), abortAbove, diagonal_);
    if (c.aborted) return kInf;
  }
  // The merged piece, kept for when this merge is made: its hulls are not computed twice.
  merged->parts = a.parts;
  merged->parts.insert(merged->parts.end(), b.parts.begin(), b.parts.end());
  merged->hull = std::move(hull);
  merged->finalHull = std::move(reduced);
  merged->concavity = c.value;
  return c.value;
}

std::vector<Piece> Decomposer::merge(std::vector<Piece> pieces, bool forced) {
  // Not forced: neighbours whose merged hull meets the target, cheapest first. Forced: the
  // cheapest pair of all while there are more than maxPieces pieces.
  auto boxOf = [&](const Piece& p) {
    Eigen::AlignedBox3d box;
    for (const Vector3d& v : p.hull.vertices) box.extend(v);
    return box;
  };
  if (forced && static_cast<int>(pieces.size()) <= budget_) return pieces;
  const double bound = forced ? kInf : target_;
  const int n = static_cast<int>(pieces.size());
  std::vector<std::vector<double>> cost(n, std::vector<double>(n, kInf));
  std::vector<std::vector<Piece>> candidate(n, std::vector<Piece>(n));  // the merged pieces
  std::vector<Eigen::AlignedBox3d> boxes(n);
  for (int i = 0; i < n; ++i) boxes[i] = boxOf(pieces[i]);
  const double grow = tol::kNeighbourFraction * target_;
  auto neighbours = [&](int i, int j) {
    if (forced) return true;
    Eigen::AlignedBox3d a = boxes[i];
    a.min().array() -= grow;
    a.max().array() += grow;
    return a.intersects(boxes[j]);
  };
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (neighbours(i, j)) cost[i][j] = mergeCost(pieces[i], pieces[j], bound, &candidate[i][j]);
    }
  }
  std::vector<char> alive(n, 1);
  int count = n;
  for (;;) {
    if (forced && count <= budget_) break;
    int bi = -1;
    int bj = -1;
    for (int i = 0; i < n; ++i) {
      for (int j = i + 1; j < n; ++j) {
        if (alive[i] && alive[j] && cost[i][j] < kInf && (bi < 0 || cost[i][j] < cost[bi][bj])) {
          bi = i;
          bj = j;
        }
      }
    }
    if (bi < 0 || (!forced && cost[bi][bj] > target_)) break;
    pieces[bi] = std::move(candidate[bi][bj]);
    boxes[bi] = boxOf(pieces[bi]);
    alive[bj] = 0;
    --count;
    for (int k = 0; k < n; ++k) {
      if (!alive[k] || k == bi) continue;
      const int i = std::min(k, bi);
      const int j = std::max(k, bi);
      cost[i][j] = neighbours(i, j) ? mergeCost(pieces[i], pieces[j], bound, &candidate[i][j]) : kInf;
    }
  }
  std::vector<Piece> kept;
  for (int i = 0; i < n; ++i) {
    if (alive[i]) kept.push_back(std::move(pieces[i]));
  }
  return kept;
}

}  // namespace deepcheck::decomposition::detail
