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

#include "deepcheck/geometry/tolerances.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <utility>

namespace deepcheck::geometry::body {
namespace {

/// A line of the face plane: the points q + s d, d unit.
struct Line {
  Eigen::Vector3d q;
  Eigen::Vector3d d;
};

/// A line of faceCandidates that can hold a candidate, with its parameter interval in the polygon.
struct NearLine {
  std::size_t line;
  double lo, hi;
};

/// Per-face working space of the search, kept across faces so that each face allocates nothing.
struct FaceScratch {
  std::vector<Line> lines;
  std::vector<NearLine> near;
  std::vector<std::pair<double, Eigen::Vector3d>> candidates;
};

/// The range of n.x - h over the points.
std::pair<double, double> planeRange(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& n, double h) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const Eigen::Vector3d& v : pts) {
    const double s = n.dot(v) - h;
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  return {lo, hi};
}

/// True when points within `radius` of `centre` can lie on both sides of the plane n.x = h
/// (within tol), and then when the points themselves do.
bool straddles(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& centre, double radius,
               const Eigen::Vector3d& n, double h, double tol) {
  const double at = n.dot(centre) - h;
  if (at - radius > tol || at + radius < -tol) return false;
  const auto [lo, hi] = planeRange(pts, n, h);
  return lo <= tol && hi >= -tol;
}

/// How the face polygon `poly` (in the ball of `radius` about `centre`) meets difference d: Disjoint (some plane of d
/// has the whole polygon outside it), Covered (every vertex strictly inside d: the whole face is inside d's interior)
/// or Crossing.
enum class Meets { Disjoint, Covered, Crossing };

/// meets() also appends, per plane of d, whether the polygon straddles it (straddles(), which
/// faceLines needs for the planes of a crossing difference: the same tests, made once).
Meets meets(const Difference& d, const std::vector<Eigen::Vector3d>& poly, const Eigen::Vector3d& centre, double radius,
            double tol, std::vector<char>& straddling) {
  bool covered = true;
  const std::size_t first = straddling.size();
  for (std::size_t g = 0; g < d.normals.size(); ++g) {
    const double at = d.normals[g].dot(centre) - d.offsets[g];
    // The polygon's ball outside the plane: disjoint. Else, for straddles(), its first test
    // (at - radius > tol) fails too.
    if (at - radius >= -tol) {
      straddling.resize(first);
      return Meets::Disjoint;
    }
    if (at + radius < -tol) {  // ... or strictly inside it: not straddling
      straddling.push_back(0);
      continue;
    }
    const auto [lo, hi] = planeRange(poly, d.normals[g], d.offsets[g]);
    if (lo >= -tol) {  // interiors cannot meet across this plane
      straddling.resize(first);
      return Meets::Disjoint;
    }
    straddling.push_back(lo <= tol && hi >= -tol ? 1 : 0);
    covered = covered && hi < -tol;
  }
  if (covered) straddling.resize(first);
  return covered ? Meets::Covered : Meets::Crossing;
}

/// Number of edges of a face polygon longer than tol (the edge lines faceLines puts first).
std::size_t edgeCount(const std::vector<Eigen::Vector3d>& poly, double tol) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) n += (poly[(i + 1) % poly.size()] - poly[i]).norm() > tol ? 1 : 0;
  return n;
}

/// The lines bounding the face's candidate regions: its edge lines, and the traces of the planes
/// of the differences in `crossing` that cross the face polygon. `straddling`: per plane of each
/// crossing difference in turn, whether the face polygon straddles it (from meets()).
void faceLines(const std::vector<Difference>& diffs, const std::vector<int>& crossing,
               const std::vector<char>& straddling, int k, int f, double tol, std::vector<Line>& lines) {
  const Difference& own = diffs[static_cast<std::size_t>(k)];
  const std::vector<Eigen::Vector3d>& poly = own.faces[static_cast<std::size_t>(f)];
  const Eigen::Vector3d& n = own.normals[static_cast<std::size_t>(f)];
  const double h = own.offsets[static_cast<std::size_t>(f)];
  lines.clear();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector3d e = poly[(i + 1) % poly.size()] - poly[i];
    if (e.norm() > tol) lines.push_back({poly[i], e.normalized()});
  }
  // (edgeCount(poly, tol) lines so far: the polygon's edges, which faceCandidates tests against.)
  std::size_t flag = 0;
  for (const int l : crossing) {
    const Difference& other = diffs[static_cast<std::size_t>(l)];
    for (std::size_t g = 0; g < other.normals.size(); ++g) {
      const Eigen::Vector3d& m = other.normals[g];
      const double e = other.offsets[g];
      // The plane must cross the face, and (M_l's section by the face plane being bounded only
      // by the traces of the facets that cross that plane) its facet must cross the face plane.
      if (!straddling[flag++] || !straddles(other.faces[g], other.centres[g], other.radii[g], n, h, tol)) {
        continue;
      }
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
}

/// True when x (in the face plane, normal n) is inside the face polygon whose edges are the first
/// `edges` lines (counter-clockwise about n: the inside is on the left of each).
bool inPolygon(const Eigen::Vector3d& x, const std::vector<Line>& lines, std::size_t edges, const Eigen::Vector3d& n,
               double tol) {
  for (std::size_t i = 0; i < edges; ++i) {
    if (n.cross(lines[i].d).dot(x - lines[i].q) < -tol) return false;
  }
  return true;
}

/// The parameter interval [lo, hi] of line L inside the face polygon (edges: the first `edges`
/// lines), widened by tol; empty (lo > hi) when the line misses it.
std::pair<double, double> polygonInterval(const Line& L, const std::vector<Line>& lines, std::size_t edges,
                                          const Eigen::Vector3d& n, double tol) {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < edges && lo <= hi; ++i) {
    const Eigen::Vector3d w = n.cross(lines[i].d);  // inward, in the plane
    const double rate = w.dot(L.d);
    const double at = w.dot(L.q - lines[i].q) + tol;  // >= 0 where the line is inside this edge
    if (std::abs(rate) < tol::kBodyParallelSine) {
      if (at < 0) hi = -lo - 1.0;  // parallel and outside: empty
      continue;
    }
    const double s = -at / rate;
    if (rate > 0) lo = std::max(lo, s);
    else hi = std::min(hi, s);
  }
  return {lo, hi};
}

/// Candidates of a face inside its polygon and nearer than `bound`: p0, the feet of p0 on the
/// lines, the lines' pairwise intersections; sorted by distance, as (squared norm, point). The
/// first `edges` lines are the polygon's edges. Lines no nearer than the bound, or missing the
/// polygon, hold no candidate (a line's points are no nearer than its foot) and are dropped
/// before the pairs are formed; a pair's intersection counts only inside both lines' intervals.
/// The candidates go to scratch.candidates (scratch.lines holds the lines).
void faceCandidates(const Eigen::Vector3d& p0, std::size_t edges, const Eigen::Vector3d& n, double bound, double tol,
                    FaceScratch& scratch) {
  const std::vector<Line>& lines = scratch.lines;
  std::vector<std::pair<double, Eigen::Vector3d>>& out = scratch.candidates;
  out.clear();
  const double bound2 = bound * bound;
  auto add = [&](const Eigen::Vector3d& x) {
    const double r2 = x.squaredNorm();
    if (r2 < bound2 && inPolygon(x, lines, edges, n, tol)) out.emplace_back(r2, x);
  };
  add(p0);
  std::vector<NearLine>& near = scratch.near;
  near.clear();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const Line& L = lines[i];
    const Eigen::Vector3d foot = L.q + L.d.dot(p0 - L.q) * L.d;
    if (foot.squaredNorm() >= bound2) continue;
    add(foot);
    const auto [lo, hi] = polygonInterval(L, lines, edges, n, tol);
    if (lo <= hi) near.push_back({i, lo, hi});
  }
  for (std::size_t a = 0; a < near.size(); ++a) {
    const Line& Li = lines[near[a].line];
    for (std::size_t b = a + 1; b < near.size(); ++b) {
      const Line& Lj = lines[near[b].line];
      const Eigen::Vector3d cr = Li.d.cross(Lj.d);
      const double c2 = cr.squaredNorm();
      if (c2 < tol::kBodyParallelSine * tol::kBodyParallelSine) continue;
      const double si = (Lj.q - Li.q).cross(Lj.d).dot(cr) / c2;
      if (si < near[a].lo || si > near[a].hi) continue;
      const Eigen::Vector3d x = Li.q + si * Li.d;
      const double sj = Lj.d.dot(x - Lj.q);
      if (sj < near[b].lo || sj > near[b].hi) continue;
      add(x);
    }
  }
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
}

/// Distance from the origin to the face polygon `poly` (plane n.x = h): |h| when the origin's
/// projection is inside it, else the distance to the nearest edge segment.
double polygonDistance(const std::vector<Eigen::Vector3d>& poly, const Eigen::Vector3d& n, double h, double tol) {
  const Eigen::Vector3d p0 = h * n;
  double nearest = std::numeric_limits<double>::infinity();
  bool inside = true;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector3d& a = poly[i];
    const Eigen::Vector3d e = poly[(i + 1) % poly.size()] - a;
    const double len2 = e.squaredNorm();
    if (len2 <= tol * tol) continue;
    inside = inside && n.cross(e).dot(p0 - a) >= -tol * std::sqrt(len2);
    const double s = std::clamp(e.dot(-a) / len2, 0.0, 1.0);
    nearest = std::min(nearest, (a + s * e).norm());
  }
  return inside ? std::abs(h) : nearest;
}

/// True when x is strictly inside one of the differences listed.
bool insideAny(const std::vector<Difference>& diffs, const std::vector<int>& which, const Eigen::Vector3d& x,
               double tol) {
  for (const int l : which) {
    if (planeExcess(diffs[static_cast<std::size_t>(l)], x) < -tol) return true;
  }
  return false;
}

/// True when x lies on difference k's face (inside all of k's planes within tol).
bool onDifference(const Difference& d, const Eigen::Vector3d& x, double tol) { return planeExcess(d, x) <= tol; }

}  // namespace

SearchResult searchNearestBoundary(const std::vector<Difference>& diffs, const Eigen::Vector3d& start, double reach,
                                   int maxFaces, double tol) {
  SearchResult r;
  r.point = start;
  double best = std::max(reach, start.norm());
  // Min-heap of (bound, (difference, face)); a face enters with its plane's distance and, when
  // first popped, is put back with the polygon's distance (never smaller) before it is searched.
  using Entry = std::pair<double, std::pair<int, int>>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  std::vector<std::vector<char>> refined(diffs.size());
  std::vector<int> crossing;     // per searched face: the differences crossing it
  std::vector<char> straddling;  // ... and per plane of each, whether the face straddles it
  FaceScratch scratch;
  for (std::size_t k = 0; k < diffs.size(); ++k) {
    refined[k].assign(diffs[k].normals.size(), 0);
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
    const Difference& d = diffs[static_cast<std::size_t>(k)];
    const std::vector<Eigen::Vector3d>& poly = d.faces[static_cast<std::size_t>(f)];
    const Eigen::Vector3d& n = d.normals[static_cast<std::size_t>(f)];
    char& seen = refined[static_cast<std::size_t>(k)][static_cast<std::size_t>(f)];
    if (!seen) {
      seen = 1;
      const double dist = polygonDistance(poly, n, d.offsets[static_cast<std::size_t>(f)], tol);
      if (dist < best) queue.push({dist, {k, f}});
      continue;
    }
    ++r.facesSearched;
    // Only the differences whose interiors reach the face bound or cover parts of it.
    crossing.clear();
    straddling.clear();
    bool covered = false;
    for (int l = 0; l < static_cast<int>(diffs.size()) && !covered; ++l) {
      if (l == k) continue;
      const Meets m = meets(diffs[static_cast<std::size_t>(l)], poly, d.centres[static_cast<std::size_t>(f)],
                            d.radii[static_cast<std::size_t>(f)], tol, straddling);
      covered = m == Meets::Covered;
      if (m == Meets::Crossing) crossing.push_back(l);
    }
    if (covered) continue;
    const Eigen::Vector3d p0 = d.offsets[static_cast<std::size_t>(f)] * n;
    faceLines(diffs, crossing, straddling, k, f, tol, scratch.lines);
    faceCandidates(p0, edgeCount(poly, tol), n, best, tol, scratch);
    for (const auto& [r2, x] : scratch.candidates) {
      if (!onDifference(d, x, tol) || insideAny(diffs, crossing, x, tol)) continue;
      best = std::sqrt(r2);
      r.point = x;
      r.difference = k;
      break;
    }
  }
  r.finished = true;
  r.lowerBound = std::min(best, r.point.norm());
  return r;
}

}  // namespace deepcheck::geometry::body
