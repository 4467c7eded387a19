// Best-first search for the nearest point of the complement of a union of convex polytopes'
// interiors (body_depth.h, step 4).
//
// Every face f of every difference, in order of its plane's distance |offset| to the origin (no
// point of the face is nearer), is asked for its nearest point outside the other differences'
// interiors. Within the face's plane that set is the face polygon minus convex regions, bounded by
// pieces of the polygon's edge lines and of the traces of the other differences' planes; its
// point nearest to the origin's projection p0 is p0 itself, the foot of p0 on one of those lines,
// or the intersection of two of them. The candidates are sorted by distance and tested exactly,
// nearest first; the first that passes is the face's answer.

#include "body_depth_internal.h"

#include "deepcheck/deep/tolerances.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <utility>

namespace deepcheck::deep::body {
namespace {

/// A line of the face plane: the points q + s d, d unit.
struct Line {
  Eigen::Vector3d q;
  Eigen::Vector3d d;
};

/// The lines bounding the face's candidate regions: its edge lines, and the traces of the other
/// differences' planes that cross the face polygon.
std::vector<Line> faceLines(const std::vector<Difference>& diffs, int k, int f, double tol) {
  const Difference& own = diffs[static_cast<std::size_t>(k)];
  const std::vector<Eigen::Vector3d>& poly = own.faces[static_cast<std::size_t>(f)];
  const Eigen::Vector3d& n = own.normals[static_cast<std::size_t>(f)];
  const double h = own.offsets[static_cast<std::size_t>(f)];
  std::vector<Line> lines;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector3d e = poly[(i + 1) % poly.size()] - poly[i];
    if (e.norm() > tol) lines.push_back({poly[i], e.normalized()});
  }
  for (std::size_t l = 0; l < diffs.size(); ++l) {
    if (static_cast<int>(l) == k) continue;
    const Difference& other = diffs[l];
    for (std::size_t g = 0; g < other.normals.size(); ++g) {
      const Eigen::Vector3d& m = other.normals[g];
      const double e = other.offsets[g];
      double lo = std::numeric_limits<double>::infinity();
      double hi = -lo;
      for (const Eigen::Vector3d& v : poly) {
        const double s = m.dot(v) - e;
        lo = std::min(lo, s);
        hi = std::max(hi, s);
      }
      if (lo > tol || hi < -tol) continue;  // the plane misses the face: no boundary on it
      const Eigen::Vector3d d = n.cross(m);
      const double sine = d.norm();
      if (sine < tol::kBodyParallelSine) continue;  // parallel to the face: no trace
      // The trace's point nearest the origin: a n + b m on both planes.
      const double c = n.dot(m);
      const double det = 1.0 - c * c;
      const double a = (h - c * e) / det;
      const double b = (e - c * h) / det;
      lines.push_back({a * n + b * m, d / sine});
    }
  }
  return lines;
}

/// Candidates of a face, nearer than `bound`: p0, the feet of p0 on the lines, the lines'
/// pairwise intersections. Returned as (squared norm, point).
std::vector<std::pair<double, Eigen::Vector3d>> faceCandidates(const Eigen::Vector3d& p0,
                                                               const std::vector<Line>& lines,
                                                               double bound) {
  std::vector<std::pair<double, Eigen::Vector3d>> out;
  const double bound2 = bound * bound;
  auto add = [&](const Eigen::Vector3d& x) {
    const double r2 = x.squaredNorm();
    if (r2 < bound2) out.emplace_back(r2, x);
  };
  add(p0);
  for (const Line& L : lines) add(L.q + L.d.dot(p0 - L.q) * L.d);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    for (std::size_t j = i + 1; j < lines.size(); ++j) {
      const Eigen::Vector3d cr = lines[i].d.cross(lines[j].d);
      const double c2 = cr.squaredNorm();
      if (c2 < tol::kBodyParallelSine * tol::kBodyParallelSine) continue;
      const double s = (lines[j].q - lines[i].q).cross(lines[j].d).dot(cr) / c2;
      add(lines[i].q + s * lines[i].d);
    }
  }
  std::sort(out.begin(), out.end(),
            [](const auto& x, const auto& y) { return x.first < y.first; });
  return out;
}

/// True when x lies on difference k's face (inside all of k's planes within tol).
bool onDifference(const Difference& d, const Eigen::Vector3d& x, double tol) {
  return planeExcess(d, x) <= tol;
}

}  // namespace

SearchResult searchNearestBoundary(const std::vector<Difference>& diffs,
                                   const Eigen::Vector3d& start, int maxFaces, double tol) {
  SearchResult r;
  r.point = start;
  double best = start.norm();
  // Min-heap of (plane distance, difference, face).
  using Entry = std::pair<double, std::pair<int, int>>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (std::size_t k = 0; k < diffs.size(); ++k) {
    for (std::size_t f = 0; f < diffs[k].normals.size(); ++f) {
      const double dist = std::abs(diffs[k].offsets[f]);
      if (dist < best) queue.push({dist, {static_cast<int>(k), static_cast<int>(f)}});
    }
  }
  while (!queue.empty() && queue.top().first < best) {
    if (r.facesSearched >= maxFaces) {
      r.lowerBound = queue.top().first;
      return r;
    }
    const auto [k, f] = queue.top().second;
    queue.pop();
    ++r.facesSearched;
    const Difference& d = diffs[static_cast<std::size_t>(k)];
    const Eigen::Vector3d p0 = d.offsets[static_cast<std::size_t>(f)] * d.normals[static_cast<std::size_t>(f)];
    const std::vector<Line> lines = faceLines(diffs, k, f, tol);
    for (const auto& [r2, x] : faceCandidates(p0, lines, best)) {
      if (!onDifference(d, x, tol) || insideAnother(diffs, k, x, tol)) continue;
      best = std::sqrt(r2);
      r.point = x;
      r.difference = k;
      break;
    }
  }
  r.finished = true;
  r.lowerBound = best;
  return r;
}

}  // namespace deepcheck::deep::body
