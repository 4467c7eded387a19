#include "bvh.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace deepcheck::decomposition::detail {

using Eigen::Vector3d;

namespace {

constexpr int kLeafSize = 4;

/// Squared distance from p to the box [lo, hi] (0 inside).
double boxDistanceSquared(const Vector3d& p, const Vector3d& lo, const Vector3d& hi) {
  const Vector3d d = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
  return d.squaredNorm();
}

/// True when the whole box lies strictly outside `keep`.
bool boxOutside(const Vector3d& lo, const Vector3d& hi, const Halfspace& keep) {
  const Vector3d center = 0.5 * (lo + hi);
  const Vector3d half = 0.5 * (hi - lo);
  return keep.signedDistance(center) - keep.normal.cwiseAbs().dot(half) > 0.0;
}

}  // namespace

double rayTriangle(const Vector3d& origin, const Vector3d& dir, const Vector3d& a, const Vector3d& b,
                   const Vector3d& c) {
  const Vector3d e1 = b - a;
  const Vector3d e2 = c - a;
  const Vector3d h = dir.cross(e2);
  const double det = e1.dot(h);
  const double scale = e1.norm() * e2.norm();
  if (!(std::abs(det) > 1e-12 * scale)) return -1.0;
  const Vector3d s = origin - a;
  const double u = s.dot(h) / det;
  if (u < 0.0 || u > 1.0) return -1.0;
  const Vector3d q = s.cross(e1);
  const double v = dir.dot(q) / det;
  if (v < 0.0 || u + v > 1.0) return -1.0;
  return e2.dot(q) / det;
}

void clipPolygon(const std::vector<Vector3d>& in, const Halfspace& keep, std::vector<Vector3d>* out) {
  out->clear();
  const std::size_t n = in.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vector3d& p = in[i];
    const Vector3d& q = in[(i + 1) % n];
    const double sp = keep.signedDistance(p);
    const double sq = keep.signedDistance(q);
    if (sp <= 0.0) out->push_back(p);
    if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0)) {
      out->push_back(p + (sp / (sp - sq)) * (q - p));
    }
  }
}

TriangleBvh::TriangleBvh(std::vector<Triangle> triangles) : triangles_(std::move(triangles)) {
  if (triangles_.empty()) return;
  const int n = static_cast<int>(triangles_.size());
  std::vector<Vector3d> centers(n);
  for (int i = 0; i < n; ++i) centers[i] = (triangles_[i][0] + triangles_[i][1] + triangles_[i][2]) / 3.0;
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  nodes_.reserve(2 * n);
  nodes_.emplace_back();
  buildNode(0, 0, n, centers, order);
  std::vector<Triangle> sorted(n);
  for (int i = 0; i < n; ++i) sorted[i] = triangles_[order[i]];
  triangles_ = std::move(sorted);
}

void TriangleBvh::buildNode(int node, int first, int count, const std::vector<Vector3d>& centers,
                            std::vector<int>& order) {
  Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity());
  Vector3d hi = -lo;
  Vector3d clo = lo;
  Vector3d chi = hi;
  for (int i = first; i < first + count; ++i) {
    for (const Vector3d& v : triangles_[order[i]]) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    clo = clo.cwiseMin(centers[order[i]]);
    chi = chi.cwiseMax(centers[order[i]]);
  }
  nodes_[node].lo = lo;
  nodes_[node].hi = hi;
  if (count <= kLeafSize) {
    nodes_[node].first = first;
    nodes_[node].count = count;
    return;
  }
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(order.begin() + first, order.begin() + first + half, order.begin() + first + count,
                   [&](int a, int b) { return centers[a][axis] < centers[b][axis]; });
  const int left = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  nodes_.emplace_back();
  nodes_[node].first = left;
  nodes_[node].count = 0;
  buildNode(left, first, half, centers, order);
  buildNode(left + 1, first + half, count - half, centers, order);
}

double TriangleBvh::distance(const Vector3d& p, const Halfspace* keep, double stopBelow, Vector3d* closest) const {
  double best2 = std::numeric_limits<double>::infinity();
  if (nodes_.empty()) return best2;
  const double stop2 = stopBelow > 0.0 ? stopBelow * stopBelow : 0.0;
  std::pair<int, double> stack[128];
  int top = 0;
  stack[top++] = {0, boxDistanceSquared(p, nodes_[0].lo, nodes_[0].hi)};
  thread_local std::vector<Vector3d> polygon;  // scratch, reused across calls
  thread_local std::vector<Vector3d> clipped;
  auto consider = [&](const Vector3d& a, const Vector3d& b, const Vector3d& c) {
    const Vector3d q = closestPointOnTriangle(p, a, b, c);
    const double d2 = (q - p).squaredNorm();
    if (d2 < best2) {
      best2 = d2;
      if (closest != nullptr) *closest = q;
    }
  };
  while (top > 0) {
    const auto [index, lower2] = stack[--top];
    if (lower2 >= best2) continue;
    const Node& node = nodes_[index];
    if (keep != nullptr && boxOutside(node.lo, node.hi, *keep)) continue;
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const Triangle& t = triangles_[i];
        if (keep == nullptr) {
          consider(t[0], t[1], t[2]);
          continue;
        }
        const double s0 = keep->signedDistance(t[0]);
        const double s1 = keep->signedDistance(t[1]);
        const double s2 = keep->signedDistance(t[2]);
        if (s0 <= 0.0 && s1 <= 0.0 && s2 <= 0.0) {
          consider(t[0], t[1], t[2]);
        } else if (s0 > 0.0 && s1 > 0.0 && s2 > 0.0) {
          continue;
        } else {
          polygon.assign(t.begin(), t.end());
          clipPolygon(polygon, *keep, &clipped);
          for (std::size_t k = 1; k + 1 < clipped.size(); ++k) consider(clipped[0], clipped[k], clipped[k + 1]);
          if (clipped.size() == 1 || clipped.size() == 2) {
            consider(clipped[0], clipped.back(), clipped.back());
          }
        }
      }
      if (best2 <= stop2) return std::sqrt(best2);
      continue;
    }
    const int left = node.first;
    const double dl = boxDistanceSquared(p, nodes_[left].lo, nodes_[left].hi);
    const double dr = boxDistanceSquared(p, nodes_[left + 1].lo, nodes_[left + 1].hi);
    if (top + 2 > 128) continue;  // cannot happen: depth <= log2(n) + 1 with median splits
    if (dl <= dr) {
      stack[top++] = {left + 1, dr};
      stack[top++] = {left, dl};
    } else {
      stack[top++] = {left, dl};
      stack[top++] = {left + 1, dr};
    }
  }
  return std::sqrt(best2);
}

}  // namespace deepcheck::decomposition::detail
