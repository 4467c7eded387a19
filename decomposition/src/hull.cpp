// Convex hulls for the convex decomposition: Qhull (deep/qhull_hull.h) for the hull itself, our own
// greedy vertex reduction on top of it (decomposition.h describes the bound).

#include "hull.h"

#include "bvh.h"
#include "deepcheck/decomposition/tolerances.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <deepcheck/geometry/qhull_hull.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <tuple>
#include <unordered_map>
#include <utility>

namespace deepcheck::decomposition::detail {

using Eigen::Vector3d;

namespace {

/// Qhull's options here: Qhull's own start (no 'Qs') and merging, triangles when asked.
geometry::QhullOptions qhullOptions(bool triangulate) {
  geometry::QhullOptions options;
  options.triangulate = triangulate;
  options.searchAllPoints = false;
  return options;
}

/// Unit eigenvectors of the covariance of `points` (columns, largest variance first).
Eigen::Matrix3d principalAxes(const std::vector<Vector3d>& points, const Vector3d& center) {
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vector3d& p : points) cov += (p - center) * (p - center).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
  Eigen::Matrix3d axes;
  for (int i = 0; i < 3; ++i) axes.col(i) = solver.eigenvectors().col(2 - i);
  return axes;
}

Vector3d centroid(const std::vector<Vector3d>& points) {
  Vector3d c = Vector3d::Zero();
  for (const Vector3d& p : points) c += p;
  return c / static_cast<double>(std::max<std::size_t>(points.size(), 1));
}

/// Planar (or lower-dimensional) hull: the 2D hull of the points in their best-fit plane, fanned.
/// Vertices are input points, unprojected.
Hull flatHull(const std::vector<Vector3d>& points) {
  Hull hull;
  const Vector3d c = centroid(points);
  const Eigen::Matrix3d axes = principalAxes(points, c);
  const Vector3d u = axes.col(0);
  const Vector3d v = axes.col(1);
  const Vector3d n = u.cross(v).normalized();
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::vector<Eigen::Vector2d> q(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) q[i] = {u.dot(points[i] - c), v.dot(points[i] - c)};
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return q[a].x() < q[b].x() || (q[a].x() == q[b].x() && q[a].y() < q[b].y()); });
  auto cross = [&](int o, int a, int b) {
    return (q[a] - q[o]).x() * (q[b] - q[o]).y() - (q[a] - q[o]).y() * (q[b] - q[o]).x();
  };
  // Andrew's monotone chain, counter-clockwise about n.
  std::vector<int> chain(2 * order.size() + 1);
  int k = 0;
  for (int i : order) {
    while (k >= 2 && cross(chain[k - 2], chain[k - 1], i) <= 0) --k;
    chain[k++] = i;
  }
  for (int j = static_cast<int>(order.size()) - 2, lower = k + 1; j >= 0; --j) {
    const int i = order[j];
    while (k >= lower && cross(chain[k - 2], chain[k - 1], i) <= 0) --k;
    chain[k++] = i;
  }
  chain.resize(std::max(k - 1, 1));
  for (int i : chain) hull.vertices.push_back(points[i]);
  if (hull.vertices.size() < 3) {
    // Collinear: keep the two extremes (or the single point).
    if (points.size() >= 2) hull.vertices = {points[order.front()], points[order.back()]};
    return hull;
  }
  const double offset = n.dot(c);
  for (int i = 1; i + 1 < static_cast<int>(hull.vertices.size()); ++i) {
    hull.triangles.push_back({0, i, i + 1});
    hull.normals.push_back(n);
    hull.offsets.push_back(offset);
    hull.area += 0.5 * (hull.vertices[i] - hull.vertices[0]).cross(hull.vertices[i + 1] - hull.vertices[0]).norm();
  }
  return hull;
}

/// Vertices of the intersection of the half-spaces {x : n_i.x <= d_i}, which must contain
/// `interior` strictly and be bounded: the facets of the hull of the polar points
/// n_i / (d_i - n_i.interior) are the vertices. Empty on failure.
std::vector<Vector3d> halfspaceIntersection(const std::vector<Vector3d>& normals, const std::vector<double>& offsets,
                                            const Vector3d& interior) {
  std::vector<Vector3d> dual(normals.size());
  for (std::size_t i = 0; i < normals.size(); ++i) {
    const double h = offsets[i] - normals[i].dot(interior);
    if (!(h > 0.0)) return {};
    dual[i] = normals[i] / h;
  }
  geometry::QhullHull polar;
  try {
    polar = geometry::qhullHull(dual, qhullOptions(false), "halfspace intersection");
  } catch (const geometry::QhullError&) {
    return {};
  }
  std::vector<Vector3d> corners;
  for (std::size_t f = 0; f < polar.normals.size(); ++f) {
    const double b = polar.offsets[f];  // facet plane: a.q = b, b > 0 when the polar set is bounded
    if (!(b > 0.0)) return {};
    corners.push_back(interior + polar.normals[f] / b);
  }
  return corners;
}

}  // namespace

Hull convexHull(const std::vector<Vector3d>& points) {
  if (points.size() < static_cast<std::size_t>(geometry::kQhullMinPoints)) return flatHull(points);
  geometry::QhullHull q;
  try {
    q = geometry::qhullHull(points, qhullOptions(true), "convex decomposition hull");
  } catch (const geometry::QhullError&) {
    return flatHull(points);  // flat or collinear part: its planar hull
  }
  Hull hull;
  std::vector<int> index(points.size(), -1);
  for (int id : q.vertices) {
    index[id] = static_cast<int>(hull.vertices.size());
    hull.vertices.push_back(points[id]);
  }
  for (std::size_t f = 0; f < q.loops.size(); ++f) {
    if (q.loops[f].size() != 3) continue;  // "Qt" triangulates every facet
    const std::array<int, 3> tri{index[q.loops[f][0]], index[q.loops[f][1]], index[q.loops[f][2]]};
    const Vector3d& a = hull.vertices[tri[0]];
    hull.triangles.push_back(tri);  // counter-clockwise seen from outside (qhullHull)
    hull.normals.push_back(q.normals[f]);
    hull.offsets.push_back(q.offsets[f]);
    hull.area += 0.5 * (hull.vertices[tri[1]] - a).cross(hull.vertices[tri[2]] - a).norm();
  }
  const Vector3d c = centroid(hull.vertices);
  for (const auto& t : hull.triangles) {
    hull.volume += (hull.vertices[t[0]] - c).dot((hull.vertices[t[1]] - c).cross(hull.vertices[t[2]] - c)) / 6.0;
  }
  if (!(hull.volume > 0.0)) return flatHull(points);
  return hull;
}

namespace {

/// Fallback reduction: the intersection of supporting half-spaces of the hull, starting from a
/// box (or a tetrahedron) along its principal axes and adding, while the vertex budget allows, the
/// facet plane of the hull that the worst corner violates most. An intersection of k half-spaces
/// has at most 2k - 4 vertices, so this always fits the budget, but it is coarse (about k = V/2
/// planes for V vertices).
Hull circumscribedReduction(const Hull& hull, int maxVertices) {
  const std::vector<Vector3d>& V = hull.vertices;
  const Vector3d center = centroid(V);
  const Eigen::Matrix3d axes = principalAxes(V, center);
  std::vector<int> facetOf;  // one triangle per distinct facet plane
  {
    std::vector<int> order(hull.triangles.size());
    std::iota(order.begin(), order.end(), 0);
    auto key = [&](int t) {
      return std::make_tuple(hull.normals[t].x(), hull.normals[t].y(), hull.normals[t].z(), hull.offsets[t]);
    };
    std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
    for (std::size_t k = 0; k < order.size(); ++k) {
      if (k == 0 || key(order[k]) != key(order[k - 1])) facetOf.push_back(order[k]);
    }
  }
  auto support = [&](const Vector3d& dir) {
    double best = -std::numeric_limits<double>::infinity();
    for (const Vector3d& v : V) best = std::max(best, dir.dot(v));
    return best;
  };
  std::vector<Vector3d> normals;
  std::vector<double> offsets;
  if (maxVertices >= 8) {
    for (int i = 0; i < 3; ++i) {
      for (const Vector3d& d : {Vector3d(axes.col(i)), Vector3d(-axes.col(i))}) {
        normals.push_back(d);
        offsets.push_back(support(d));
      }
    }
  } else {
    const double s = 1.0 / std::sqrt(3.0);
    for (const Vector3d& d : {Vector3d(1, 1, 1), Vector3d(1, -1, -1), Vector3d(-1, 1, -1), Vector3d(-1, -1, 1)}) {
      normals.push_back(axes * (s * d));
      offsets.push_back(support(normals.back()));
    }
  }
  std::vector<Vector3d> corners = halfspaceIntersection(normals, offsets, center);
  if (corners.empty()) return hull;
  std::vector<char> used(facetOf.size(), 0);
  for (;;) {
    std::vector<std::pair<double, int>> worst(corners.size(), {0.0, -1});
    for (std::size_t i = 0; i < corners.size(); ++i) {
      for (std::size_t f = 0; f < facetOf.size(); ++f) {
        const int t = facetOf[f];
        const double excess = hull.normals[t].dot(corners[i]) - hull.offsets[t];
        if (excess > worst[i].first) worst[i] = {excess, static_cast<int>(f)};
      }
    }
    std::sort(worst.begin(), worst.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    bool added = false;
    constexpr int kTries = 8;  // planes tried per round (cutting the worst corners first)
    for (int k = 0; k < std::min<int>(kTries, static_cast<int>(worst.size())); ++k) {
      const int f = worst[k].second;
      if (f < 0 || used[f]) continue;
      used[f] = 1;  // tried once: accepted now, or over the budget and not tried again
      const int t = facetOf[f];
      normals.push_back(hull.normals[t]);
      offsets.push_back(hull.offsets[t]);
      std::vector<Vector3d> trial = halfspaceIntersection(normals, offsets, center);
      if (!trial.empty() && static_cast<int>(trial.size()) <= maxVertices) {
        corners = std::move(trial);
        added = true;
        break;
      }
      normals.pop_back();
      offsets.pop_back();
    }
    if (!added) break;
  }
  Hull reduced = convexHull(corners);
  if (static_cast<int>(reduced.vertices.size()) > maxVertices || !(reduced.volume > 0.0)) return hull;
  return reduced;
}

/// Progressive hull (after Sander et al., "Silhouette clipping", SIGGRAPH 2000): collapse hull
/// edges (u, v) into one new vertex p placed on or outside the plane of every face around u and v
/// (so the new hull contains the old one), p minimizing the added volume (a 3-variable linear
/// program, solved by enumerating the vertices of its feasible region). The collapses whose p is
/// nearest to the original hull go first. Candidates are cached per edge and recomputed when the
/// neighbourhood of either end changes. Collapses are made in batches of edges whose
/// neighbourhoods (the vertices of the faces around both ends) do not overlap, so that one hull
/// computation serves a whole batch: the cost grows with the hull's size times the number of
/// batches (about the logarithm of the reduction), where one collapse at a time made it quadratic.
/// Each collapse is checked: u and v must be inside the new hull.
class ProgressiveHull {
 public:
  explicit ProgressiveHull(const Hull& original) : hull_(original), scale_(diagonalOf(original)) {
    // p lies on the original hull's surface or outside it: its distance is a surface distance.
    std::vector<Triangle> surface;
    for (const auto& t : original.triangles) {
      surface.push_back({original.vertices[t[0]], original.vertices[t[1]], original.vertices[t[2]]});
    }
    bvh_ = TriangleBvh(std::move(surface));
  }

  /// Collapses edges until the hull has at most `maxVertices` vertices; false when no edge of a
  /// larger hull can be collapsed.
  bool reduce(int maxVertices) {
    for (int n = static_cast<int>(hull_.vertices.size()); n > maxVertices;
         n = static_cast<int>(hull_.vertices.size())) {
      const Neighbourhoods around = neighbourhoods();
      if (!collapseBatch(rankEdges(around), around, batchSize(n, maxVertices))) return false;
    }
    return true;
  }

  Hull& hull() { return hull_; }

 private:
  /// A batch removes at most 1/kBatchDivisor of the vertices left to remove: its later
  /// collapses are ranked on the hull before the batch, so larger batches cost quality (1/2 left
  /// twice the excess on a finely tessellated sphere; 1/32 matches one collapse at a time).
  static constexpr int kBatchDivisor = 32;
  /// A batch takes at least kMinBatch collapses (fewer only when fewer vertices are left to
  /// remove): its collapses do not overlap, and one at a time the last few dozen vertices took a
  /// batch, a hull and a ranking each (a 150-vertex hull took 0.2 s to reduce to 64). Two keep
  /// the Panda's collision hulls within their targets as one at a time does; four did not (two
  /// of them ended 2 % above).
  static constexpr int kMinBatch = 2;

  /// Larger batches for a hull of thousands of vertices cost more than they save: a batch with
  /// one collapse that fails is redone without it, and a quarter of the vertices per batch made
  /// a 100,000-triangle mesh's merges 4x slower.
  static int batchSize(int n, int maxVertices) {
    return std::min(n - maxVertices, std::max(kMinBatch, (n - maxVertices) / kBatchDivisor));
  }
  static constexpr int kMaxConstraints = 24;  ///< planes around an edge; more (a fan apex) is skipped
  /// A collapse point may violate a face plane by this much, relative to the hull's diagonal
  /// (round-off of the plane intersection).
  static constexpr double kSlackRelative = 1e-12;

  struct Candidate {
    std::uint64_t signature;  ///< neighbourhoods of both ends when computed
    bool valid;
    double key;  ///< distance of p to the original hull
    Vector3d p;
  };
  /// The current hull's vertices: stable ids (by position), the faces around each, and a
  /// signature of each one's neighbourhood (its id and its neighbours' ids).
  struct Neighbourhoods {
    std::vector<int> id;
    std::vector<std::vector<int>> faces;
    std::vector<std::uint64_t> signature;
  };
  struct Choice {
    int u, v;
    std::uint64_t cacheKey;
  };

  static double diagonalOf(const Hull& hull) {
    Eigen::AlignedBox3d box;
    for (const Vector3d& v : hull.vertices) box.extend(v);
    return box.diagonal().norm();
  }

  int idOf(const Vector3d& p) { return ids_.emplace(positionKey(p), static_cast<int>(ids_.size())).first->second; }

  Neighbourhoods neighbourhoods() {
    const int n = static_cast<int>(hull_.vertices.size());
    Neighbourhoods out;
    out.id.resize(n);
    for (int i = 0; i < n; ++i) out.id[i] = idOf(hull_.vertices[i]);
    out.faces.resize(n);
    std::vector<std::vector<int>> neighbours(n);
    for (int t = 0; t < static_cast<int>(hull_.triangles.size()); ++t) {
      for (int e = 0; e < 3; ++e) {
        out.faces[hull_.triangles[t][e]].push_back(t);
        neighbours[hull_.triangles[t][e]].push_back(out.id[hull_.triangles[t][(e + 1) % 3]]);
      }
    }
    out.signature.resize(n);
    for (int i = 0; i < n; ++i) {
      std::sort(neighbours[i].begin(), neighbours[i].end());
      std::uint64_t h = 0xcbf29ce484222325ULL ^ static_cast<std::uint64_t>(out.id[i]);
      for (int k : neighbours[i]) h = (h ^ static_cast<std::uint64_t>(k)) * 0x100000001b3ULL;
      out.signature[i] = h;
    }
    return out;
  }

  /// The collapse point of edge (u, v): the vertex of the region outside every face plane around
  /// u and v that adds the least volume.
  Candidate solve(int u, int v, const Neighbourhoods& around) const {
    Candidate c{0, false, std::numeric_limits<double>::infinity(), Vector3d::Zero()};
    std::vector<std::pair<Vector3d, double>> planes;
    Vector3d objective = Vector3d::Zero();  // area vector of the faces around the edge
    for (int w : {u, v}) {
      for (int f : around.faces[w]) {
        const auto& t = hull_.triangles[f];
        objective += (hull_.vertices[t[1]] - hull_.vertices[t[0]]).cross(hull_.vertices[t[2]] - hull_.vertices[t[0]]);
        bool repeated = false;
        for (const auto& q : planes)
          repeated = repeated || (q.first == hull_.normals[f] && q.second == hull_.offsets[f]);
        if (!repeated) planes.emplace_back(hull_.normals[f], hull_.offsets[f]);
      }
    }
    const int m = static_cast<int>(planes.size());
    if (m < 3 || m > kMaxConstraints) return c;
    const double slack = kSlackRelative * scale_;
    double bestValue = std::numeric_limits<double>::infinity();
    for (int a = 0; a < m; ++a) {
      for (int b = a + 1; b < m; ++b) {
        for (int d = b + 1; d < m; ++d) {
          Eigen::Matrix3d A;
          A.row(0) = planes[a].first;
          A.row(1) = planes[b].first;
          A.row(2) = planes[d].first;
          if (std::abs(A.determinant()) < tol::kSingularPlanes) continue;
          const Vector3d p = A.inverse() * Vector3d(planes[a].second, planes[b].second, planes[d].second);
          // The objective first: only a point that would improve on the best needs the
          // feasibility test, which costs a pass over the planes.
          const double value = objective.dot(p);
          if (!(value < bestValue)) continue;
          bool feasible = true;
          for (const auto& q : planes) feasible = feasible && q.first.dot(p) >= q.second - slack;
          if (!feasible) continue;
          bestValue = value;
          c.p = p;
          c.valid = true;
        }
      }
    }
    if (c.valid) c.key = bvh_.distance(c.p, nullptr, 0.0);
    return c;
  }

  /// Every edge with a valid collapse, nearest collapse point first (cached or computed).
  std::vector<std::pair<double, Choice>> rankEdges(const Neighbourhoods& around) {
    const std::vector<int>& id = around.id;
    std::vector<std::pair<double, Choice>> ranked;
    for (const auto& t : hull_.triangles) {
      for (int e = 0; e < 3; ++e) {
        int u = t[e];
        int v = t[(e + 1) % 3];
        if (id[u] > id[v]) continue;  // each undirected edge once
        const std::uint64_t cacheKey = static_cast<std::uint64_t>(id[u]) << 32 | static_cast<std::uint32_t>(id[v]);
        const std::uint64_t sig = around.signature[u] * 31 + around.signature[v];
        auto it = cache_.find(cacheKey);
        if (it == cache_.end() || it->second.signature != sig) {
          Candidate c = solve(u, v, around);
          c.signature = sig;
          it = cache_.insert_or_assign(cacheKey, c).first;
        }
        if (it->second.valid) ranked.push_back({it->second.key, {u, v, cacheKey}});
      }
    }
    std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    return ranked;
  }

  /// The cheapest collapses of `ranked`, at most `count`, whose neighbourhoods do not overlap.
  std::vector<Choice> independentBatch(const std::vector<std::pair<double, Choice>>& ranked,
                                       const Neighbourhoods& around, int count) const {
    std::vector<char> taken(hull_.vertices.size(), 0);
    std::vector<int> ring;
    std::vector<Choice> batch;
    for (const auto& entry : ranked) {
      if (static_cast<int>(batch.size()) >= count) break;
      const Choice& choice = entry.second;
      ring.clear();
      for (int w : {choice.u, choice.v}) {
        for (int f : around.faces[w]) ring.insert(ring.end(), hull_.triangles[f].begin(), hull_.triangles[f].end());
      }
      if (std::any_of(ring.begin(), ring.end(), [&](int x) { return taken[x] != 0; })) continue;
      for (int x : ring) taken[x] = 1;
      batch.push_back(choice);
    }
    return batch;
  }

  /// Applies a batch of collapses (independentBatch) on one new hull when every collapsed u and v
  /// lies inside it; otherwise marks the failing ones invalid in the cache and leaves the hull as
  /// it was, for the next batch to do without them. False when there is nothing left to try.
  bool collapseBatch(const std::vector<std::pair<double, Choice>>& ranked, const Neighbourhoods& around, int count) {
    const std::vector<Choice> batch = independentBatch(ranked, around, count);
    if (batch.empty()) return false;
    const int n = static_cast<int>(hull_.vertices.size());
    std::vector<char> removed(n, 0);
    for (const Choice& choice : batch) removed[choice.u] = removed[choice.v] = 1;
    std::vector<Vector3d> points;
    points.reserve(n);
    for (int i = 0; i < n; ++i) {
      if (!removed[i]) points.push_back(hull_.vertices[i]);
    }
    for (const Choice& choice : batch) points.push_back(cache_[choice.cacheKey].p);
    Hull collapsed = convexHull(points);
    const bool solid = collapsed.volume > 0.0 && static_cast<int>(collapsed.vertices.size()) < n;
    auto inside = [&](const Vector3d& x) {
      for (std::size_t f = 0; f < collapsed.triangles.size(); ++f) {
        if (collapsed.normals[f].dot(x) - collapsed.offsets[f] > kSlackRelative * scale_) return false;
      }
      return true;
    };
    bool failed = false;
    for (const Choice& choice : batch) {
      if (solid && inside(hull_.vertices[choice.u]) && inside(hull_.vertices[choice.v])) continue;
      cache_[choice.cacheKey].valid = false;
      failed = true;
    }
    if (!failed) hull_ = std::move(collapsed);
    return true;
  }

  Hull hull_;
  const double scale_;
  TriangleBvh bvh_;
  std::unordered_map<PositionKey, int, PositionKeyHash> ids_;
  std::unordered_map<std::uint64_t, Candidate> cache_;
};

/// The progressive hull of `original` within `maxVertices`; false when it could not reach the
/// budget.
bool progressiveReduction(const Hull& original, int maxVertices, Hull* out) {
  ProgressiveHull progressive(original);
  if (!progressive.reduce(maxVertices)) return false;
  *out = std::move(progressive.hull());
  return true;
}

/// Largest distance from a vertex of `reduced` to `hull` (0 for vertices inside it).
double excessOver(const Hull& reduced, const Hull& hull) {
  double worst = 0.0;
  for (const Vector3d& v : reduced.vertices) {
    bool inside = true;
    for (std::size_t f = 0; inside && f < hull.triangles.size(); ++f) {
      inside = hull.normals[f].dot(v) - hull.offsets[f] <= 0.0;
    }
    if (inside) continue;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& t : hull.triangles) {
      const Vector3d q = closestPointOnTriangle(v, hull.vertices[t[0]], hull.vertices[t[1]], hull.vertices[t[2]]);
      best = std::min(best, (q - v).norm());
    }
    worst = std::max(worst, best);
  }
  return worst;
}

}  // namespace

Hull reduceHullVertices(const Hull& hull, int maxVertices, double* excess) {
  if (excess != nullptr) *excess = 0.0;
  if (static_cast<int>(hull.vertices.size()) <= maxVertices || !(hull.volume > 0.0)) return hull;
  Hull reduced;
  if (!progressiveReduction(hull, maxVertices, &reduced)) reduced = circumscribedReduction(hull, maxVertices);
  if (excess != nullptr) *excess = excessOver(reduced, hull);
  return reduced;
}

}  // namespace deepcheck::decomposition::detail
