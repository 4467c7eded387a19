// Convex polytopes: dimension classification, hulls, coplanar-face merging, adjacency, support.
// Conventions (vertex neighbours and face rings, polygon faces) are documented in polytope.h.
//
// fromPoints, step by step:
//  1. Validate the input; shift it to a local origin (the centre of its bounding box) so that the
//     geometric predicates below work on coordinates of the size of the set, not of its position.
//  2. Flatness tolerance h = max(kFlatRelative * D, kCoordinateRoundoff * max|x|), D the extent of
//     the set (distance of a farthest-point pair found by sweeps).
//  3. Drop points within h of an earlier kept point (a hash grid of cell size h).
//  4. Classify: the farthest-point pair spans a line, the point farthest from it a plane, the point
//     farthest from that plane a thickness. Each is compared with h: Point, Segment, Polygon,
//     Polyhedron. All four kinds are decided here, before Qhull, which fails on flat input.
//  5. Polygon: Andrew's monotone chain on plane coordinates, dropping vertices within h of the line
//     through their neighbours; the plane is refitted and must hold every point within h,
//     otherwise the set is treated as a solid after all.
//  6. Polyhedron (makeSolid): Qhull, merging facets within h itself (C-h) unless the set is thin,
//     then our own pass over its facets: adjacent faces coplanar within kCoplanarAngle and h are
//     merged (the union's boundary becomes the new loop), vertices left on two faces only (inside
//     an edge) are removed, normals are fitted (fitPlane), and vertex rings are built by walking
//     around each vertex: from ring face F, the next neighbour is F's predecessor of v, and the
//     next ring face is the face holding the half-edge from v to that neighbour. Vertices that
//     are not extreme within h (at a straight or reflex face corner) are pruned and the hull
//     rebuilt, and the result is checked against every input point; when Qhull's merging leaves
//     something unresolved, the hull is rebuilt without it (C-0).
// Output vertices are always input points, bit for bit.
//
// Why all this: within a tolerance, noise in the input leaves slivers (facets whose three vertices
// are nearly collinear: their normals are arbitrary) and faces that are convex only within the
// tolerance. Both break what DEEP and hill climbing rely on, a vertex whose neighbours are all
// lower is the maximum, by far more than the tolerance (a reflex corner hides a whole wedge of
// directions). Inputs with noise from round-off up to 1e-7 of their size, points on the edges or
// faces of boxes, near-duplicates, thin slabs and needles, far from the origin, were used to
// tune it; the tests keep a sample of them.

#include "deepcheck/deep/polytope.h"

#include "deepcheck/deep/input_range.h"
#include "deepcheck/deep/qhull_hull.h"
#include "deepcheck/deep/tolerances.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <iterator>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>


namespace deepcheck::deep {

using Eigen::Vector3d;

const char* toString(PolytopeKind kind) {
  switch (kind) {
    case PolytopeKind::Point:
      return "Point";
    case PolytopeKind::Segment:
      return "Segment";
    case PolytopeKind::Polygon:
      return "Polygon";
    case PolytopeKind::Polyhedron:
      return "Polyhedron";
  }
  return "unknown";
}

namespace {

/// support() scans all vertices up to this count; hill climbing only pays off beyond.
constexpr int kBruteForceMaxVertices = 16;
/// support() searches plateaus of vertices within hullTolerance * |dir| of the best value (the
/// hull is convex within hullTolerance), up to kMaxPlateau vertices.
constexpr int kMaxPlateau = 64;

/// Classification factors, in units of the flatness tolerance h (not tolerances themselves):
/// sets measured up to kFlatRetryFactor * h thick against the plane through three extreme points
/// are tried as polygons (the refitted plane then has to hold them within h); solids thinner than
/// kQhullMergeMinThickness * h are built without Qhull's tolerance-sized facet merging.
constexpr double kFlatRetryFactor = 8.0;
constexpr double kQhullMergeMinThickness = 1000.0;
/// At most this many rounds of dropping redundant vertices and rebuilding (see makeSolid).
constexpr int kMaxPruneRounds = 8;

const char* axisName(int axis) { return axis == 0 ? "x" : (axis == 1 ? "y" : "z"); }

std::string formatDouble(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

std::uint64_t edgeKey(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

/// Newell's area vector of a closed loop: twice the vector area, along the normal for which the
/// loop is counter-clockwise. Computed relative to the first vertex to keep digits.
template <class Loop, class Coord>
Vector3d newellVector(const Loop& loop, const Coord& coord) {
  Vector3d sum = Vector3d::Zero();
  const int k = static_cast<int>(loop.size());
  if (k < 3) return sum;
  const Vector3d origin = coord(loop[0]);
  for (int i = 1; i + 1 < k; ++i) {
    sum += (coord(loop[i]) - origin).cross(coord(loop[i + 1]) - origin);
  }
  return sum;
}

/// Position i in verts of the point coord(verts[i]) farthest from `from` (the first on ties).
template <class Verts, class Coord>
int farthestFrom(const Verts& verts, const Coord& coord, const Vector3d& from) {
  int best = 0;
  double bestD = -1.0;
  const int k = static_cast<int>(verts.size());
  for (int i = 0; i < k; ++i) {
    const double d = (coord(verts[i]) - from).squaredNorm();
    if (d > bestD) {
      bestD = d;
      best = i;
    }
  }
  return best;
}

/// Andrew's monotone chain: the boundary of the 2-d convex hull of `sorted` (points sorted by x,
/// then y), counter-clockwise, each corner once. The chain keeps corner m between o and e when
/// keep(o, m, e) (a strict left turn, possibly by more than a tolerance).
template <class P, class Keep>
std::vector<P> monotoneChain(const std::vector<P>& sorted, const Keep& keep) {
  std::vector<P> hull;
  hull.reserve(2 * sorted.size());
  for (int pass = 0; pass < 2; ++pass) {  // lower chain, then upper chain
    const std::size_t base = hull.size();
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      const P& x = pass == 0 ? sorted[i] : sorted[sorted.size() - 1 - i];
      while (hull.size() >= base + 2 && !keep(hull[hull.size() - 2], hull.back(), x)) {
        hull.pop_back();
      }
      hull.push_back(x);
    }
    hull.pop_back();  // the next chain's first point
  }
  return hull;
}

/// A plane fitted to a set of points: unit normal, the thickness of the set along it (band) and
/// the width of the set (largest distance from its longest chord: a sliver has a small width).
struct PlaneFit {
  Vector3d normal = Vector3d::Zero();
  double band = std::numeric_limits<double>::infinity();
  double width = 0.0;
};

/// Plane of a (nearly) planar set, well conditioned on slivers, unlike Newell's vector, whose
/// round-off (eps * length^2) tilts a sliver's normal in any direction by eps * length / width:
/// here the frame comes from the set's longest chord u (two farthest-point sweeps) and the point
/// farthest from that chord, so the only poorly determined component is a rotation about u, which
/// moves the points by at most width * angle = eps * length. The plane is then refined by least
/// squares in that frame. The normal is oriented along `orient`; it is zero for collinear sets.
template <class Verts, class Coord>
PlaneFit fitPlane(const Verts& verts, const Coord& coord, const Vector3d& orient) {
  PlaneFit fit;
  const int k = static_cast<int>(verts.size());
  if (k < 3) return fit;
  const Vector3d a = coord(verts[farthestFrom(verts, coord, coord(verts[0]))]);
  const Vector3d chord = coord(verts[farthestFrom(verts, coord, a)]) - a;
  if (!(chord.norm() > 0.0)) return fit;
  const Vector3d u = chord.normalized();
  Vector3d across = Vector3d::Zero();
  for (int i = 0; i < k; ++i) {
    const Vector3d x = coord(verts[i]) - a;
    const Vector3d r = x - x.dot(u) * u;
    if (r.squaredNorm() > across.squaredNorm()) across = r;
  }
  fit.width = across.norm();
  if (!(fit.width > 0.0)) return fit;
  const Vector3d w = across / fit.width;
  Vector3d n = u.cross(w).normalized();
  // Least squares z = alpha * s + beta * t + gamma in the frame (u, w, n) about a.
  Vector3d mean = Vector3d::Zero();
  for (int i = 0; i < k; ++i) {
    const Vector3d x = coord(verts[i]) - a;
    mean += Vector3d(x.dot(u), x.dot(w), x.dot(n));
  }
  mean /= static_cast<double>(k);
  double ss = 0.0, st = 0.0, tt = 0.0, sz = 0.0, tz = 0.0;
  for (int i = 0; i < k; ++i) {
    const Vector3d x = coord(verts[i]) - a;
    const Vector3d y = Vector3d(x.dot(u), x.dot(w), x.dot(n)) - mean;
    ss += y.x() * y.x();
    st += y.x() * y.y();
    tt += y.y() * y.y();
    sz += y.x() * y.z();
    tz += y.y() * y.z();
  }
  const double det = ss * tt - st * st;
  if (det > 0.0) {
    const double alpha = (sz * tt - tz * st) / det;
    const double beta = (ss * tz - st * sz) / det;
    n = (n - alpha * u - beta * w).normalized();
  }
  if (orient.dot(n) < 0.0) n = -n;
  fit.normal = n;
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (int i = 0; i < k; ++i) {
    const double z = n.dot(coord(verts[i]) - a);
    lo = std::min(lo, z);
    hi = std::max(hi, z);
  }
  fit.band = hi - lo;
  return fit;
}

/// Normal of a face loop, counter-clockwise about it (see fitPlane).
template <class Loop, class Coord>
Vector3d fitNormal(const Loop& loop, const Coord& coord) {
  return fitPlane(loop, coord, newellVector(loop, coord)).normal;
}

struct Cell {
  std::int64_t x, y, z;
  bool operator==(const Cell& o) const { return x == o.x && y == o.y && z == o.z; }
};

struct CellHash {
  std::size_t operator()(const Cell& c) const {
    std::uint64_t h = static_cast<std::uint64_t>(c.x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(c.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(c.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h ^ (h >> 31));
  }
};

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(n) {
    for (int i = 0; i < n; ++i) parent_[i] = i;
  }
  int find(int i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }
  void unite(int root, int other) { parent_[other] = root; }

 private:
  std::vector<int> parent_;
};

}  // namespace

/// Builds polytopes; a friend of ConvexPolytope. One builder per fromPoints call.
class PolytopeBuilder {
 public:
  PolytopeBuilder(const std::vector<Vector3d>& points, const std::string& name)
      : points_(points), name_(name) {}

  ConvexPolytope build();

 private:
  ConvexPolytope makePoint(int i) const;
  ConvexPolytope makeSegment(int a, int b) const;
  bool makePolygon(const Vector3d& normal, ConvexPolytope* out) const;
  struct SolidAttempt {
    ConvexPolytope hull;
    bool covers = false;  // holds every input point within hullTolerance()
    bool clean = false;   // and has no redundant vertex left
  };
  ConvexPolytope makeSolid(double thickness) const;
  SolidAttempt pruneRounds(bool merge) const;
  ConvexPolytope makePolyhedron(const std::vector<int>& ids, double qhullMerge,
                                std::vector<int>* vertexIds, std::vector<int>* redundant) const;
  bool covers(const ConvexPolytope& p, const std::vector<int>& vertexIds) const;
  void dropNearDuplicates();
  [[noreturn]] void topologyError(const std::string& what) const {
    throw std::runtime_error(name_ + ": inconsistent hull topology (" + what + ")");
  }

  const std::vector<Vector3d>& points_;
  const std::string& name_;
  std::vector<Vector3d> q_;  // points relative to the local origin
  std::vector<int> ids_;     // kept points (near-duplicates dropped), indices into points_
  double h_ = 0.0;           // flatness tolerance (absolute)
  Vector3d lineDir_ = Vector3d::UnitX();
  Vector3d planeNormal_ = Vector3d::UnitZ();  // normal of the plane through three extreme points
};

ConvexPolytope PolytopeBuilder::build() {
  const int n = static_cast<int>(points_.size());
  Vector3d lo = points_[0];
  Vector3d hi = points_[0];
  double maxAbs = 0.0;
  for (const Vector3d& p : points_) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    maxAbs = std::max(maxAbs, p.cwiseAbs().maxCoeff());
  }
  const Vector3d origin = 0.5 * (lo + hi);
  q_.resize(n);
  for (int i = 0; i < n; ++i) q_[i] = points_[i] - origin;

  // Farthest-point sweeps: from point 0, then back from the point found, twice.
  auto self = [](const Vector3d& x) -> const Vector3d& { return x; };
  const int b0 = farthestFrom(q_, self, q_[0]);
  const int a = farthestFrom(q_, self, q_[b0]);
  const int b = farthestFrom(q_, self, q_[a]);
  const double extent = (q_[b] - q_[a]).norm();
  h_ = std::max(tol::kFlatRelative * extent, tol::kCoordinateRoundoff * maxAbs);
  if (!(extent > h_)) return makePoint(0);

  dropNearDuplicates();

  // Line through the farthest pair; the point farthest from it.
  lineDir_ = (q_[b] - q_[a]) / extent;
  int c = a;
  double lineDist = -1.0;
  for (int i : ids_) {
    const Vector3d r = q_[i] - q_[a];
    const double d = (r - r.dot(lineDir_) * lineDir_).norm();
    if (d > lineDist) {
      lineDist = d;
      c = i;
    }
  }
  if (lineDist <= h_) {
    int lo_i = ids_[0];
    int hi_i = ids_[0];
    for (int i : ids_) {
      if (q_[i].dot(lineDir_) < q_[lo_i].dot(lineDir_)) lo_i = i;
      if (q_[i].dot(lineDir_) > q_[hi_i].dot(lineDir_)) hi_i = i;
    }
    return makeSegment(lo_i, hi_i);
  }

  // Plane through a, b, c; the point farthest from it.
  const Vector3d normal = lineDir_.cross(q_[c] - q_[a]).normalized();
  planeNormal_ = normal;
  double planeDist = 0.0;
  for (int i : ids_) planeDist = std::max(planeDist, std::abs((q_[i] - q_[a]).dot(normal)));
  // The plane through a, b, c can be tilted against the best-fitting one by a few times the
  // thickness, so near-flat sets get the polygon test, whose refitted plane must hold every point
  // within h_ itself.
  if (planeDist <= kFlatRetryFactor * h_) {
    ConvexPolytope polygon;
    if (makePolygon(normal, &polygon)) return polygon;
    if (polygon.numVertices() == 2) return polygon;  // collinear within h_ after all
  }
  return makeSolid(planeDist);
}

void PolytopeBuilder::dropNearDuplicates() {
  // Two points within h_ are in the same or in adjacent cells of size h_; the first one seen is
  // kept. Cell coordinates stay below about 1e11 since h_ >= kFlatRelative * extent.
  std::unordered_map<Cell, std::vector<int>, CellHash> grid;
  const int n = static_cast<int>(q_.size());
  grid.reserve(2 * static_cast<std::size_t>(n));
  ids_.clear();
  const double h2 = h_ * h_;
  for (int i = 0; i < n; ++i) {
    const Cell cell{static_cast<std::int64_t>(std::floor(q_[i].x() / h_)),
                    static_cast<std::int64_t>(std::floor(q_[i].y() / h_)),
                    static_cast<std::int64_t>(std::floor(q_[i].z() / h_))};
    bool duplicate = false;
    for (int dx = -1; dx <= 1 && !duplicate; ++dx) {
      for (int dy = -1; dy <= 1 && !duplicate; ++dy) {
        for (int dz = -1; dz <= 1 && !duplicate; ++dz) {
          const auto it = grid.find(Cell{cell.x + dx, cell.y + dy, cell.z + dz});
          if (it == grid.end()) continue;
          for (int j : it->second) {
            if ((q_[i] - q_[j]).squaredNorm() <= h2) {
              duplicate = true;
              break;
            }
          }
        }
      }
    }
    if (!duplicate) {
      grid[cell].push_back(i);
      ids_.push_back(i);
    }
  }
}

ConvexPolytope PolytopeBuilder::makePoint(int i) const {
  ConvexPolytope p;
  p.kind_ = PolytopeKind::Point;
  p.vertices_ = {points_[i]};
  p.faceStart_ = {0};
  p.adjStart_ = {0, 0};
  p.flatTol_ = h_;
  p.finish();
  return p;
}

ConvexPolytope PolytopeBuilder::makeSegment(int a, int b) const {
  ConvexPolytope p;
  p.kind_ = PolytopeKind::Segment;
  p.vertices_ = {points_[a], points_[b]};
  p.faceStart_ = {0};
  p.adjStart_ = {0, 1, 2};
  p.adjVerts_ = {1, 0};
  p.flatTol_ = h_;
  p.finish();
  return p;
}

// Returns true with *out set to the polygon; false when the set is not flat within h_ after the
// refit (a solid), or, with *out set to a segment, when it is collinear within h_.
bool PolytopeBuilder::makePolygon(const Vector3d& normal, ConvexPolytope* out) const {
  // Plane coordinates (x, y) on the basis (e1, e2) with e1 x e2 = normal: counter-clockwise in
  // (x, y) is counter-clockwise about the normal.
  const Vector3d e1 = lineDir_;
  const Vector3d e2 = normal.cross(e1);
  struct P2 {
    double x, y;
    int id;
  };
  std::vector<P2> pts;
  pts.reserve(ids_.size());
  for (int i : ids_) pts.push_back({q_[i].dot(e1), q_[i].dot(e2), i});
  std::sort(pts.begin(), pts.end(), [](const P2& l, const P2& r) {
    return l.x < r.x || (l.x == r.x && (l.y < r.y || (l.y == r.y && l.id < r.id)));
  });
  // Is m strictly left of the line o -> e, by more than h_? (cross / |e - o| is the distance.)
  auto leftTurn = [&](const P2& o, const P2& m, const P2& e) {
    const double cross = (m.x - o.x) * (e.y - o.y) - (m.y - o.y) * (e.x - o.x);
    return cross > h_ * std::hypot(e.x - o.x, e.y - o.y);
  };
  std::vector<P2> hull = monotoneChain(pts, leftTurn);
  // The chain's end points are never tested; drop any vertex within h_ of its neighbours' line.
  for (bool changed = true; changed && hull.size() >= 3;) {
    changed = false;
    for (std::size_t i = 0; i < hull.size() && hull.size() >= 3; ++i) {
      const P2& prev = hull[(i + hull.size() - 1) % hull.size()];
      const P2& next = hull[(i + 1) % hull.size()];
      if (!leftTurn(prev, hull[i], next)) {
        hull.erase(hull.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
        break;
      }
    }
  }
  if (hull.size() < 3) {  // every point within h_ of a line: a segment between the extremes
    *out = makeSegment(pts.front().id, pts.back().id);
    return false;
  }

  std::vector<int> loop;
  for (const P2& p : hull) loop.push_back(p.id);
  const Vector3d n = fitNormal(loop, [&](int i) { return q_[i]; });
  if (!(n.dot(normal) > 0.0)) return false;
  double mean = 0.0;
  for (int i : loop) mean += n.dot(q_[i]);
  mean /= static_cast<double>(loop.size());
  for (int i : ids_) {
    if (std::abs(n.dot(q_[i]) - mean) > h_) return false;  // not flat after all: a solid
  }

  const int k = static_cast<int>(loop.size());
  ConvexPolytope& p = *out;
  p = ConvexPolytope();
  p.kind_ = PolytopeKind::Polygon;
  for (int i : loop) p.vertices_.push_back(points_[i]);
  p.faceNormals_ = {n, -n};
  p.faceStart_ = {0, k, 2 * k};
  for (int i = 0; i < k; ++i) p.faceVerts_.push_back(i);
  for (int i = k - 1; i >= 0; --i) p.faceVerts_.push_back(i);
  for (int i = 0; i < k; ++i) {
    p.adjStart_.push_back(2 * i);
    p.adjVerts_.push_back((i + 1) % k);
    p.adjVerts_.push_back((i + k - 1) % k);
    p.adjFaces_.push_back(0);
    p.adjFaces_.push_back(1);
  }
  p.adjStart_.push_back(2 * k);
  p.flatTol_ = h_;
  p.finish();
  return true;
}

// The solid hull, in rounds. Qhull merging facets within h_ gives clean faces on noisy coplanar
// input; on sets only tens of h_ thick its merge thresholds (several h_) reach across the whole
// thickness and it can fail or collapse the rim, so thin sets, and sets where the merged hull
// fails its check, are built with round-off-level merging (C-0) and our own merging only.
// Merging within a tolerance can leave a vertex that is not an extreme point (it sits at a face
// corner that is straight or reflex within h_: the remains of noise, or of a sliver along an
// edge). Hill climbing can stop at such a vertex far from the maximum, and a sliver's normal is
// arbitrary, so these vertices are dropped (an independent set at a time, so each one stays
// within h_ of the hull of its kept neighbours) and the hull is rebuilt from the remaining
// vertices, until none is left. The result is the last round's hull that holds all input points
// within hullTolerance() and is locally convex (see covers).
ConvexPolytope PolytopeBuilder::makeSolid(double thickness) const {
  const bool merge = thickness >= kQhullMergeMinThickness * h_;
  SolidAttempt attempt = pruneRounds(merge);
  if (attempt.clean || !merge) return std::move(attempt.hull);
  SolidAttempt conservative = pruneRounds(false);
  if (conservative.clean || !attempt.covers) return std::move(conservative.hull);
  return std::move(attempt.hull);
}

// Rounds of hull building and pruning, with or without Qhull's merging (see makeSolid). Clean
// when the hull returned holds all points (covers) and has no redundant vertex left.
PolytopeBuilder::SolidAttempt PolytopeBuilder::pruneRounds(bool merge) const {
  std::vector<int> ids = ids_;
  SolidAttempt best;  // the last hull that passed the check
  SolidAttempt last;
  for (int round = 0; round < kMaxPruneRounds; ++round) {
    std::vector<int> vertexIds;
    std::vector<int> redundant;
    try {
      last.hull = makePolyhedron(ids, merge ? h_ : 0.0, &vertexIds, &redundant);
      last.covers = covers(last.hull, vertexIds);
      last.clean = last.covers && redundant.empty() && last.hull.checkInvariants(false).empty();
    } catch (const std::runtime_error&) {
      if (round == 0 && !merge) throw;
      break;  // Qhull's merging failed, or pruned down to a degenerate set
    }
    if (last.covers) best = last;
    if (redundant.empty() || (merge && !last.covers)) break;
    std::sort(redundant.begin(), redundant.end());
    ids.clear();
    for (int i : vertexIds) {
      if (!std::binary_search(redundant.begin(), redundant.end(), i)) ids.push_back(i);
    }
  }
  return best.covers ? best : last;
}

// True when the hull is locally convex (every vertex's neighbours are inside its ring faces'
// planes) and every input point is inside every face plane, within hullTolerance(). A closed,
// locally convex surface is convex, so the hull's own vertices (vertexIds) need no plane test.
bool PolytopeBuilder::covers(const ConvexPolytope& p, const std::vector<int>& vertexIds) const {
  const double tol = p.hullTolerance();
  const int nf = p.numFaces();
  std::vector<double> localOffset(nf);
  double inRadius = std::numeric_limits<double>::infinity();
  for (int f = 0; f < nf; ++f) {
    localOffset[f] = p.faceOffset(f) - p.faceNormal(f).dot(p.center());
    inRadius = std::min(inRadius, localOffset[f]);
  }
  for (int v = 0; v < p.numVertices(); ++v) {
    for (int f : p.vertexFaces(v)) {
      for (int u : p.neighbors(v)) {
        if (p.faceNormal(f).dot(p.localVertex(u)) - localOffset[f] > tol) return false;
      }
    }
  }
  // Face planes of a thin hull are nearly parallel and cannot see a point missed in its plane:
  // every point must also be inside the hull's shadow on the plane of the classification (the
  // 2-d convex hull of the projected vertices), within tol.
  const Vector3d e0 = lineDir_;
  const Vector3d e1 = planeNormal_.cross(lineDir_);
  std::vector<Eigen::Vector2d> shadow;
  for (int v = 0; v < p.numVertices(); ++v) {
    shadow.emplace_back(e0.dot(p.localVertex(v)), e1.dot(p.localVertex(v)));
  }
  std::sort(shadow.begin(), shadow.end(), [](const Eigen::Vector2d& l, const Eigen::Vector2d& r) {
    return l.x() < r.x() || (l.x() == r.x() && l.y() < r.y());
  });
  auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  const std::vector<Eigen::Vector2d> outline = monotoneChain(
      shadow, [&](const auto& o, const auto& a, const auto& b) { return !(turn(o, a, b) <= 0.0); });
  for (const Vector3d& point : points_) {
    const Vector3d x = point - p.center();
    const Eigen::Vector2d y(e0.dot(x), e1.dot(x));
    for (std::size_t i = 0; i < outline.size(); ++i) {
      const Eigen::Vector2d& a = outline[i];
      const Eigen::Vector2d& b = outline[(i + 1) % outline.size()];
      if (turn(a, b, y) < -tol * (b - a).norm()) return false;
    }
  }
  std::vector<char> isVertex(points_.size(), 0);
  for (int i : vertexIds) isVertex[i] = 1;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Vector3d x = points_[i] - p.center();
    if (isVertex[i] || x.norm() <= inRadius - tol) continue;  // a vertex, or in the inscribed ball
    for (int f = 0; f < nf; ++f) {
      if (p.faceNormal(f).dot(x) - localOffset[f] > tol) return false;
    }
  }
  return true;
}

// The hull of the points `ids` (indices into points_); reports its vertices' indices and the
// vertices found redundant (see makeSolid).
ConvexPolytope PolytopeBuilder::makePolyhedron(const std::vector<int>& ids, double qhullMerge,
                                               std::vector<int>* vertexIds,
                                               std::vector<int>* redundant) const {
  // --- Qhull on the points; loops come back as indices into points_.
  std::vector<Vector3d> kept;
  kept.reserve(ids.size());
  for (int i : ids) kept.push_back(q_[i]);
  // Qs: search all points for the initial simplex (robust on thin sets). C-m: pre-merge facets
  // whose centrum is within m of a neighbour's plane, so coplanar triangles come out as one
  // polygonal facet and, with m our flatness tolerance, no sliver thinner than m survives (C-0,
  // Qhull's default, merges at round-off level only: noisy coplanar input then leaves facets
  // whose normals are set by the noise).
  QhullOptions options;
  options.mergeDistance = qhullMerge;
  QhullHull qf = qhullHull(kept, options, name_);
  auto coord = [&](int i) { return q_[i]; };
  std::vector<std::vector<int>>& loops = qf.loops;
  const int numFacets = static_cast<int>(loops.size());
  std::vector<Vector3d> area(numFacets);
  for (int f = 0; f < numFacets; ++f) {
    for (int& v : loops[f]) v = ids[v];
    area[f] = newellVector(loops[f], coord);  // loops are counter-clockwise (qhullHull)
  }

  // --- Half-edges: directed edge (a, b) of a counter-clockwise loop -> its facet.
  std::unordered_map<std::uint64_t, int> edgeFacet;
  edgeFacet.reserve(4 * static_cast<std::size_t>(numFacets));
  for (int f = 0; f < numFacets; ++f) {
    const auto& l = loops[f];
    for (std::size_t i = 0; i < l.size(); ++i) {
      if (!edgeFacet.emplace(edgeKey(l[i], l[(i + 1) % l.size()]), f).second) {
        topologyError("a directed edge is used twice");
      }
    }
  }
  auto twinFacet = [&](int a, int b) {
    const auto it = edgeFacet.find(edgeKey(b, a));
    if (it == edgeFacet.end()) topologyError("an edge has one face only");
    return it->second;
  };

  // --- Merge adjacent faces whose normals differ by less than kCoplanarAngle and whose union is
  // planar within h_ (Qhull's merging catches most; this enforces our own criterion on the
  // fitted planes). The merged normal must stay within kCoplanarAngle of every merged facet's,
  // so chains of merges cannot drift. Passes repeat until nothing merges.
  struct Group {
    std::vector<int> verts;  // sorted, unique
    std::vector<int> facets;
    Vector3d area = Vector3d::Zero();
    PlaneFit plane;
  };
  std::vector<Group> group(numFacets);
  for (int f = 0; f < numFacets; ++f) {
    group[f].facets = {f};
    group[f].verts = loops[f];
    std::sort(group[f].verts.begin(), group[f].verts.end());
    group[f].area = area[f];
    group[f].plane = fitPlane(group[f].verts, coord, area[f]);
  }
  auto angleBetween = [](const Vector3d& m, const Vector3d& n) {
    return std::atan2(m.cross(n).norm(), m.dot(n));
  };
  std::vector<Vector3d> facetNormal(numFacets);
  for (int f = 0; f < numFacets; ++f) facetNormal[f] = group[f].plane.normal;
  UnionFind groups(numFacets);
  for (bool merged = true; merged;) {
    merged = false;
    struct Candidate {
      double score;  // angle between the normals: most coplanar first
      int f, g;
    };
    std::vector<Candidate> candidates;
    for (const auto& [key, f] : edgeFacet) {
      const int a = static_cast<int>(key >> 32);
      const int b = static_cast<int>(key & 0xffffffffu);
      if (a > b) continue;  // each undirected edge once
      const int rf = groups.find(f);
      const int rg = groups.find(twinFacet(a, b));
      if (rf == rg) continue;
      const double angle = angleBetween(group[rf].plane.normal, group[rg].plane.normal);
      if (angle < tol::kCoplanarAngle) candidates.push_back({angle, rf, rg});
    }
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& l, const Candidate& r) {
      return l.score < r.score || (l.score == r.score && (l.f < r.f || (l.f == r.f && l.g < r.g)));
    });
    for (const Candidate& c : candidates) {
      const int rf = groups.find(c.f);
      const int rg = groups.find(c.g);
      if (rf == rg) continue;
      if (!(angleBetween(group[rf].plane.normal, group[rg].plane.normal) < tol::kCoplanarAngle)) {
        continue;
      }
      Group u;
      std::merge(group[rf].verts.begin(), group[rf].verts.end(), group[rg].verts.begin(),
                 group[rg].verts.end(), std::back_inserter(u.verts));
      u.verts.erase(std::unique(u.verts.begin(), u.verts.end()), u.verts.end());
      u.area = group[rf].area + group[rg].area;
      u.plane = fitPlane(u.verts, coord, u.area);
      if (!(u.plane.band <= h_)) continue;
      u.facets = group[rf].facets;
      u.facets.insert(u.facets.end(), group[rg].facets.begin(), group[rg].facets.end());
      bool drift = false;
      for (int f : u.facets) {
        drift = drift || !(angleBetween(facetNormal[f], u.plane.normal) < tol::kCoplanarAngle);
      }
      if (drift) continue;
      groups.unite(rf, rg);
      group[rf] = std::move(u);
      group[rg] = Group();
      merged = true;
    }
  }

  // --- Loops of merged faces: the boundary half-edges of the group, chained. A group whose
  // boundary is not one simple loop (possible only at tolerance level) is left unmerged.
  std::vector<std::vector<int>> members(numFacets);
  for (int f = 0; f < numFacets; ++f) members[groups.find(f)].push_back(f);
  std::vector<char> dissolved(numFacets, 0);
  auto groupLoop = [&](int r) {
    std::unordered_map<int, int> nextOf;
    bool simple = true;
    int start = std::numeric_limits<int>::max();
    for (int f : members[r]) {
      const auto& l = loops[f];
      for (std::size_t i = 0; i < l.size(); ++i) {
        const int a = l[i];
        const int b = l[(i + 1) % l.size()];
        if (groups.find(twinFacet(a, b)) == r) continue;  // interior edge
        if (!nextOf.emplace(a, b).second) simple = false;
        start = std::min(start, a);
      }
    }
    std::vector<int> loop;
    if (simple && !nextOf.empty()) {
      int v = start;
      do {
        loop.push_back(v);
        const auto it = nextOf.find(v);
        if (it == nextOf.end()) break;
        v = it->second;
      } while (v != start && loop.size() <= nextOf.size());
      simple = v == start && loop.size() == nextOf.size();
    }
    if (!(simple && loop.size() >= 3)) loop.clear();
    return loop;
  };
  const int numPoints = static_cast<int>(points_.size());
  std::vector<int> faceCount(numPoints, 0);
  std::vector<std::vector<int>> faces;
  auto countFaces = [&] {  // faceCount[v]: the faces listing v
    std::fill(faceCount.begin(), faceCount.end(), 0);
    for (const auto& l : faces) {
      for (int v : l) ++faceCount[v];
    }
  };
  std::vector<int> faceGroup;  // the merged group a face comes from, or -1
  // A vertex left on two faces only must lie on the straight edge between its loop neighbours
  // (within h_), else it is a real corner that a merge hid (thin sets): such merges are undone.
  for (bool redo = true; redo;) {
    redo = false;
    faces.clear();
    faceGroup.clear();
    for (int r = 0; r < numFacets; ++r) {
      if (members[r].empty()) continue;
      std::vector<int> loop;
      if (members[r].size() > 1 && !dissolved[r]) loop = groupLoop(r);
      if (!loop.empty()) {
        faces.push_back(std::move(loop));
        faceGroup.push_back(r);
      } else {
        for (int f : members[r]) {
          faces.push_back(loops[f]);
          faceGroup.push_back(-1);
        }
      }
    }
    countFaces();
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const auto& l = faces[f];
      const std::size_t k = l.size();
      for (std::size_t i = 0; i < k; ++i) {
        if (faceCount[l[i]] != 2) continue;
        const Vector3d a = q_[l[(i + k - 1) % k]];
        const Vector3d chord = q_[l[(i + 1) % k]] - a;
        const Vector3d x = q_[l[i]] - a;
        const double t = std::clamp(x.dot(chord) / chord.squaredNorm(), 0.0, 1.0);
        if ((x - t * chord).norm() <= h_) continue;
        for (std::size_t g = 0; g < faces.size(); ++g) {
          if (faceGroup[g] >= 0 &&
              std::find(faces[g].begin(), faces[g].end(), l[i]) != faces[g].end()) {
            dissolved[faceGroup[g]] = 1;
            redo = true;
          }
        }
      }
    }
  }

  // --- Remove vertices on only two faces (inside an edge: not extreme points); faces left with
  // fewer than three vertices vanish (their two half-edges' twins then pair up).
  for (bool changed = true; changed;) {
    changed = false;
    countFaces();
    for (auto& l : faces) {
      const std::size_t before = l.size();
      l.erase(std::remove_if(l.begin(), l.end(), [&](int v) { return faceCount[v] == 2; }),
              l.end());
      changed = changed || l.size() != before;
    }
    const std::size_t before = faces.size();
    faces.erase(std::remove_if(faces.begin(), faces.end(),
                               [](const std::vector<int>& l) { return l.size() < 3; }),
                faces.end());
    changed = changed || faces.size() != before;
  }

  // --- Final numbering: vertices in input order.
  std::vector<int> compact(numPoints, -1);
  for (const auto& l : faces) {
    for (int v : l) compact[v] = 0;
  }
  ConvexPolytope p;
  p.kind_ = PolytopeKind::Polyhedron;
  for (int i = 0; i < numPoints; ++i) {
    if (compact[i] < 0) continue;
    compact[i] = static_cast<int>(p.vertices_.size());
    p.vertices_.push_back(points_[i]);
    vertexIds->push_back(i);
  }
  const int numVerts = static_cast<int>(p.vertices_.size());
  const int numFaces = static_cast<int>(faces.size());
  if (numVerts < 4 || numFaces < 4) topologyError("fewer than four vertices or faces");
  p.faceStart_.push_back(0);
  for (const auto& l : faces) {
    const Vector3d n = fitNormal(l, coord);
    if (!(n.norm() > 0.0)) topologyError("a face has zero area");
    p.faceNormals_.push_back(n);
    for (int v : l) p.faceVerts_.push_back(compact[v]);
    p.faceStart_.push_back(static_cast<int>(p.faceVerts_.size()));
  }

  // --- Vertex rings. For ring face F_j: nbr_j = F_j's successor of v, nbr_{j+1} = F_j's
  // predecessor of v, and F_{j+1} is the face whose successor of v is nbr_{j+1}.
  struct Incidence {
    int face, next, prev;
  };
  std::vector<std::vector<Incidence>> around(numVerts);
  for (int f = 0; f < numFaces; ++f) {
    const int s = p.faceStart_[f];
    const int k = p.faceStart_[f + 1] - s;
    for (int i = 0; i < k; ++i) {
      around[p.faceVerts_[s + i]].push_back(
          {f, p.faceVerts_[s + (i + 1) % k], p.faceVerts_[s + (i + k - 1) % k]});
    }
  }
  p.adjStart_.push_back(0);
  for (int v = 0; v < numVerts; ++v) {
    const auto& inc = around[v];
    const int k = static_cast<int>(inc.size());
    if (k < 3) topologyError("a vertex on fewer than three faces");
    int cur = 0;
    for (int j = 0; j < k; ++j) {
      p.adjFaces_.push_back(inc[cur].face);
      p.adjVerts_.push_back(inc[cur].next);
      const int wanted = inc[cur].prev;
      int found = -1;
      for (int t = 0; t < k; ++t) {
        if (inc[t].next == wanted) found = t;
      }
      if (found < 0) topologyError("an open vertex ring");
      cur = found;
    }
    if (cur != 0) topologyError("a vertex ring that does not close");
    p.adjStart_.push_back(static_cast<int>(p.adjVerts_.size()));
  }

  // --- Redundant vertices: at a face corner that sticks out of the chord of its two neighbours
  // by no more than h_ (straight or reflex). Most redundant first, no two adjacent.
  std::vector<std::pair<double, int>> candidates;
  std::vector<double> stickOut(numVerts, std::numeric_limits<double>::infinity());
  for (int f = 0; f < numFaces; ++f) {
    const int s = p.faceStart_[f];
    const int k = p.faceStart_[f + 1] - s;
    const Vector3d& n = p.faceNormals_[f];
    for (int i = 0; i < k; ++i) {
      const int prev = p.faceVerts_[s + (i + k - 1) % k];
      const int v = p.faceVerts_[s + i];
      const int next = p.faceVerts_[s + (i + 1) % k];
      const Vector3d a = q_[vertexIds->at(prev)];
      const Vector3d chord = q_[vertexIds->at(next)] - a;
      const Vector3d x = q_[vertexIds->at(v)] - a;
      const double along = x.dot(chord) / chord.squaredNorm();
      const double out = chord.cross(n).dot(x) / chord.norm();
      // A corner within h_ of the chord line but beyond its ends is a spike (a sliver's end),
      // which is extreme; a clearly reflex corner is never extreme in its face.
      if (out >= -h_ && !(along >= 0.0 && along <= 1.0)) continue;
      stickOut[v] = std::min(stickOut[v], out);
    }
  }
  for (int v = 0; v < numVerts; ++v) {
    if (!(stickOut[v] > h_)) candidates.emplace_back(stickOut[v], v);
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<char> blocked(numVerts, 0);
  for (const auto& [out, v] : candidates) {
    if (blocked[v]) continue;
    redundant->push_back(vertexIds->at(v));
    blocked[v] = 1;
    for (int k = p.adjStart_[v]; k < p.adjStart_[v + 1]; ++k) blocked[p.adjVerts_[k]] = 1;
  }

  p.flatTol_ = h_;
  p.finish();
  return p;
}

ConvexPolytope ConvexPolytope::fromPoints(const std::vector<Vector3d>& points,
                                          const std::string& name) {
  if (points.empty()) throw std::invalid_argument(name + ": no points");
  range::checkPoints(points, name);
  return PolytopeBuilder(points, name).build();
}

ConvexPolytope ConvexPolytope::box(const Vector3d& halfExtents) {
  for (int c = 0; c < 3; ++c) {
    if (!(std::isfinite(halfExtents[c]) && halfExtents[c] > 0.0)) {
      throw std::invalid_argument(std::string("box: half extent ") + std::to_string(c) + " (" +
                                  axisName(c) + ") = " + formatDouble(halfExtents[c]) +
                                  " must be positive and finite");
    }
  }
  std::vector<Vector3d> corners;
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back((i & 1) ? halfExtents.x() : -halfExtents.x(),
                         (i & 2) ? halfExtents.y() : -halfExtents.y(),
                         (i & 4) ? halfExtents.z() : -halfExtents.z());
  }
  return fromPoints(corners, "box");
}

int ConvexPolytope::numEdges() const {
  switch (kind_) {
    case PolytopeKind::Point:
      return 0;
    case PolytopeKind::Segment:
      return 1;
    default:
      return static_cast<int>(adjVerts_.size() / 2);
  }
}

IndexRange ConvexPolytope::faceVertices(int f) const {
  const int* base = faceVerts_.data();
  return {base + faceStart_[f], base + faceStart_[f + 1]};
}

IndexRange ConvexPolytope::neighbors(int v) const {
  const int* base = adjVerts_.data();
  return {base + adjStart_[v], base + adjStart_[v + 1]};
}

IndexRange ConvexPolytope::vertexFaces(int v) const {
  if (adjFaces_.empty()) return {};  // points and segments have no faces
  const int* base = adjFaces_.data();
  return {base + adjStart_[v], base + adjStart_[v + 1]};
}

void ConvexPolytope::finish() {
  const int n = numVertices();
  // Centroid as base + mean offset: the offsets are small, so no digits are lost far from 0.
  Vector3d sum = Vector3d::Zero();
  for (const Vector3d& v : vertices_) sum += v - vertices_[0];
  center_ = vertices_[0] + sum / static_cast<double>(n);
  local_.resize(n);
  radius_ = 0.0;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int v = 0; v < n; ++v) {
    local_[v] = vertices_[v] - center_;
    radius_ = std::max(radius_, local_[v].norm());
    cov += local_[v] * local_[v].transpose();
  }
  // Never zero, so that tolerances scaled by it are well defined; for a Point it is the smallest
  // normal double, which makes every relative tolerance of the point alone exact (zero in effect):
  // a pair's tolerances take their size from the other shape and the distance.
  lengthScale_ = std::max(radius_, std::numeric_limits<double>::min());

  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov / static_cast<double>(n));
  const Eigen::Matrix3d& ev = eig.eigenvectors();  // ascending eigenvalues
  for (int c = 0; c < 2; ++c) {
    Vector3d axis = ev.col(2 - c);
    int big = 0;
    axis.cwiseAbs().maxCoeff(&big);
    if (axis[big] < 0.0) axis = -axis;
    axes_.col(c) = axis.normalized();
  }
  axes_.col(2) = axes_.col(0).cross(axes_.col(1)).normalized();

  faceOffsets_.resize(faceNormals_.size());
  for (int f = 0; f < numFaces(); ++f) {
    const Vector3d& nrm = faceNormals_[f];
    double mean = 0.0;
    for (int v : faceVertices(f)) mean += nrm.dot(local_[v]);
    mean /= static_cast<double>(faceVertices(f).size());
    faceOffsets_[f] = nrm.dot(center_) + mean;
  }
  buildDirectionIndex();
}

int ConvexPolytope::supportBruteForce(const Vector3d& dir) const {
  int best = 0;
  double bestValue = dir.dot(local_[0]);
  const int n = numVertices();
  for (int v = 1; v < n; ++v) {
    const double s = dir.dot(local_[v]);
    if (s > bestValue) {
      bestValue = s;
      best = v;
    }
  }
  return best;
}

namespace {

/// Cell of the cube map (6 faces of `grid` x `grid` cells) that direction d points into, or -1
/// for a zero or non-finite d. Face 2k + (d_k < 0) is the one of the largest |d_k|; the cell
/// coordinates are the other two components divided by |d_k|, each in [-1, 1].
inline int cubeCell(const Vector3d& d, int grid) {
  const double ax = std::abs(d.x()), ay = std::abs(d.y()), az = std::abs(d.z());
  int face;
  double m, u, w;
  if (ax >= ay && ax >= az) {
    m = ax;
    face = d.x() < 0.0 ? 1 : 0;
    u = d.y();
    w = d.z();
  } else if (ay >= az) {
    m = ay;
    face = d.y() < 0.0 ? 3 : 2;
    u = d.x();
    w = d.z();
  } else {
    m = az;
    face = d.z() < 0.0 ? 5 : 4;
    u = d.x();
    w = d.y();
  }
  if (!(m > 0.0 && m <= std::numeric_limits<double>::max())) return -1;
  const double half = 0.5 * grid;
  const double s = half / m;
  const int iu = std::min(grid - 1, std::max(0, static_cast<int>(u * s + half)));
  const int iw = std::min(grid - 1, std::max(0, static_cast<int>(w * s + half)));
  return (face * grid + iu) * grid + iw;
}

}  // namespace

void ConvexPolytope::buildDirectionIndex() {
  directionIndex_.clear();
  if (numVertices() <= kBruteForceMaxVertices) return;
  constexpr int g = kDirectionGrid;
  std::vector<int> index(6 * g * g, 0);
  int previous = 0;
  for (int face = 0; face < 6; ++face) {
    for (int iu = 0; iu < g; ++iu) {
      for (int iw = 0; iw < g; ++iw) {
        // The cell's centre direction; consecutive cells are neighbours, so each climb is short.
        const double u = -1.0 + (2.0 * iu + 1.0) / g;
        const double w = -1.0 + (2.0 * iw + 1.0) / g;
        const double sign = face % 2 == 0 ? 1.0 : -1.0;
        Vector3d d;
        if (face / 2 == 0) d = Vector3d(sign, u, w);
        else if (face / 2 == 1) d = Vector3d(u, sign, w);
        else d = Vector3d(u, w, sign);
        previous = support(d, previous);  // the index is still empty: a plain climb
        index[(face * g + iu) * g + iw] = previous;
      }
    }
  }
  directionIndex_ = std::move(index);
}

int ConvexPolytope::supportStart(const Vector3d& dir) const {
  if (directionIndex_.empty()) return -1;
  const int cell = cubeCell(dir, kDirectionGrid);
  return cell < 0 ? -1 : directionIndex_[cell];
}

int ConvexPolytope::support(const Vector3d& dir, int hint) const {
  const int n = numVertices();
  if (n <= kBruteForceMaxVertices) return supportBruteForce(dir);
  // Steepest ascent over the vertex graph. On a convex polytope a vertex no neighbour of which
  // is higher is a global maximum. Hulls are convex within a tolerance only, and at a very short
  // edge that is enough to stop the climb far from the maximum (the edge's direction is set by
  // the tolerance, not by the shape). So when neighbours are lower by less than the slack, the
  // plateau they form is searched for a higher vertex before stopping. Every move raises the
  // value strictly, so ties cannot cycle. The slack (a square root) is computed only where the
  // climb stops: its test needs just the highest neighbour, and only when none is higher.
  int v = (hint >= 0 && hint < n) ? hint : 0;
  double value = dir.dot(local_[v]);
  // Start from the direction index's vertex when it is higher than the hint: it lies near the
  // support, while a hint (the last support of a pair) may be far when the direction swung.
  if (const int start = supportStart(dir); start >= 0) {
    const double startValue = dir.dot(local_[start]);
    if (startValue > value) {
      v = start;
      value = startValue;
    }
  }
  for (;;) {
    int best = v;
    double bestValue = value;
    double highestLower = -std::numeric_limits<double>::infinity();  // neighbours not higher
    for (int k = adjStart_[v]; k < adjStart_[v + 1]; ++k) {
      const double s = dir.dot(local_[adjVerts_[k]]);
      if (s > bestValue) {
        bestValue = s;
        best = adjVerts_[k];
      } else {
        highestLower = std::max(highestLower, s);
      }
    }
    if (best == v) {
      // No neighbour is higher (bestValue == value throughout, so every one went to the else).
      const double slack = hullTolerance() * dir.norm();
      if (!(highestLower >= value - slack)) return v;
      std::array<int, kMaxPlateau> plateau;
      int count = 0;
      plateau[count++] = v;
      for (int i = 0; i < count && best == v; ++i) {
        for (int k = adjStart_[plateau[i]]; k < adjStart_[plateau[i] + 1]; ++k) {
          const int u = adjVerts_[k];
          const double s = dir.dot(local_[u]);
          if (s > bestValue) {
            bestValue = s;
            best = u;
          } else if (s >= value - slack && count < kMaxPlateau &&
                     std::find(plateau.begin(), plateau.begin() + count, u) ==
                         plateau.begin() + count) {
            plateau[count++] = u;
          }
        }
      }
      if (best == v) return v;
    }
    v = best;
    value = bestValue;
  }
}

std::string ConvexPolytope::validate() const { return checkInvariants(true); }

std::string ConvexPolytope::checkInvariants(bool globalConvexity) const {
  std::ostringstream out;
  auto fail = [&out](const auto&... parts) {
    (out << ... << parts);
    return out.str();
  };
  const int nv = numVertices();
  const int nf = numFaces();
  if (nv < 1) return fail("no vertices");
  if (static_cast<int>(local_.size()) != nv || static_cast<int>(adjStart_.size()) != nv + 1 ||
      static_cast<int>(faceStart_.size()) != nf + 1 ||
      static_cast<int>(faceOffsets_.size()) != nf) {
    return fail("array sizes do not match the counts");
  }
  if (adjStart_[nv] != static_cast<int>(adjVerts_.size())) return fail("adjacency size");
  if (!adjFaces_.empty() && adjFaces_.size() != adjVerts_.size()) return fail("ring size");
  for (int v = 0; v < nv; ++v) {
    if (!vertices_[v].allFinite()) return fail("vertex ", v, " is not finite");
  }
  if (!(lengthScale_ > 0.0)) return fail("lengthScale is not positive");

  switch (kind_) {
    case PolytopeKind::Point:
      if (nv != 1 || nf != 0 || !adjVerts_.empty()) return fail("a Point has 1 vertex, no faces");
      return "";
    case PolytopeKind::Segment:
      if (nv != 2 || nf != 0) return fail("a Segment has 2 vertices, no faces");
      if (vertices_[0] == vertices_[1]) return fail("Segment vertices coincide");
      if (neighbors(0).size() != 1 || neighbors(0)[0] != 1 || neighbors(1).size() != 1 ||
          neighbors(1)[0] != 0) {
        return fail("Segment vertices must be each other's only neighbour");
      }
      return "";
    case PolytopeKind::Polygon:
      if (nv < 3 || nf != 2) return fail("a Polygon has >= 3 vertices and 2 faces");
      if ((faceNormals_[0] + faceNormals_[1]).norm() > 1e-12) {
        return fail("Polygon face normals are not opposite");
      }
      for (int i = 0; i < nv; ++i) {
        if (faceVertices(0)[i] != i || faceVertices(1)[i] != nv - 1 - i) {
          return fail("Polygon faces must list 0..k-1 and k-1..0");
        }
      }
      break;
    case PolytopeKind::Polyhedron:
      if (nv < 4 || nf < 4) return fail("a Polyhedron has >= 4 vertices and faces");
      break;
  }

  const double tol = hullTolerance();
  const bool solid = kind_ == PolytopeKind::Polyhedron;
  // Faces: size, unit normal, planarity, counter-clockwise loops, directed edges used once.
  std::vector<double> localOffset(nf);
  std::vector<double> normalUncertainty(nf);
  const double roundoff = 16.0 * std::numeric_limits<double>::epsilon() * radius_;
  std::unordered_map<std::uint64_t, int> edgeFace;  // directed edge -> face
  std::unordered_map<std::uint64_t, int> facePos;   // (face, vertex) -> position in its loop
  for (int f = 0; f < nf; ++f) {
    const IndexRange fv = faceVertices(f);
    const Vector3d& n = faceNormals_[f];
    if (fv.size() < 3) return fail("face ", f, " has ", fv.size(), " vertices");
    if (std::abs(n.norm() - 1.0) > 1e-12) return fail("face ", f, " normal is not unit");
    localOffset[f] = faceOffsets_[f] - n.dot(center_);
    for (int i = 0; i < fv.size(); ++i) {
      const int v = fv[i];
      if (v < 0 || v >= nv) return fail("face ", f, " has vertex index ", v, " out of range");
      if (!facePos.emplace(edgeKey(f, v), i).second) {
        return fail("face ", f, " lists vertex ", v, " twice");
      }
      const double off = n.dot(local_[v]) - localOffset[f];
      if (std::abs(off) > tol) {
        return fail("face ", f, " is not planar: vertex ", v, " is ", off, " off its plane");
      }
      if (!edgeFace.emplace(edgeKey(v, fv[(i + 1) % fv.size()]), f).second) {
        return fail("directed edge (", v, ", ", fv[(i + 1) % fv.size()], ") is used twice");
      }
    }
    const Vector3d area = newellVector(fv, [&](int v) { return local_[v]; });
    if (!(area.dot(n) > 0.0)) return fail("face ", f, " is not counter-clockwise about its normal");
    for (int i = 0; i < fv.size(); ++i) {  // a convex polygon: every corner turns left
      const Vector3d& a = local_[fv[i]];
      const Vector3d& b = local_[fv[(i + 1) % fv.size()]];
      const Vector3d& c = local_[fv[(i + 2) % fv.size()]];
      if (!((b - a).cross(c - b).dot(n) > 0.0)) {
        return fail("face ", f, " is not convex at vertex ", fv[(i + 1) % fv.size()]);
      }
    }
    // How far the normal can turn with its vertices moving by no more than their band, the
    // flatness tolerance and round-off: (band + flatTolerance + round-off) / width, width the
    // face's extent across its longest chord; plus kCoplanarAngle, by which the facets merged
    // into one face may disagree. Rings may turn the wrong way by that much at nearly flat
    // vertices (where merging and vertex removal within the tolerance decide the last digits).
    const PlaneFit fit = fitPlane(
        fv, [&](int v) { return local_[v]; }, n);
    normalUncertainty[f] = fit.width > 0.0
                               ? (fit.band + flatTol_ + roundoff) / fit.width + tol::kCoplanarAngle
                               : std::numeric_limits<double>::infinity();
  }
  for (const auto& [key, face] : edgeFace) {
    const int a = static_cast<int>(key >> 32);
    const int b = static_cast<int>(key & 0xffffffffu);
    if (edgeFace.count(edgeKey(b, a)) == 0) {
      return fail("edge (", a, ", ", b, ") of face ", face, " has no twin");
    }
  }
  const int ne = static_cast<int>(edgeFace.size() / 2);
  if (ne != numEdges()) return fail("numEdges() = ", numEdges(), " but faces have ", ne, " edges");
  if (nv - ne + nf != 2) return fail("Euler characteristic V - E + F = ", nv - ne + nf);

  // Convexity: every vertex inside every face plane (solids; O(V F), only when asked), or
  // inside every edge of the polygon.
  if (solid) {
    for (int f = 0; f < nf && globalConvexity; ++f) {
      for (int v = 0; v < nv; ++v) {
        const double off = faceNormals_[f].dot(local_[v]) - localOffset[f];
        if (off > tol) return fail("vertex ", v, " is ", off, " outside face ", f);
      }
    }
  } else {
    // Face 0 lists the vertices in order, so the face loop above has checked every left turn.
    const Vector3d& n = faceNormals_[0];
    for (int i = 0; i < nv; ++i) {
      const Vector3d& a = local_[i];
      const Vector3d& b = local_[(i + 1) % nv];
      const Vector3d out = (b - a).cross(n).normalized();
      for (int v = 0; v < nv; ++v) {
        if (out.dot(local_[v] - a) > tol) {
          return fail("vertex ", v, " is outside edge (", i, ", ", (i + 1) % nv, ")");
        }
      }
    }
  }

  // Rings: ring face j holds the edges (v, nbr_j) and (v, nbr_{j+1}), with v's successor nbr_j
  // and predecessor nbr_{j+1} in that face's counter-clockwise loop.
  auto posIn = [&](int f, int v) {
    const auto it = facePos.find(edgeKey(f, v));
    return it == facePos.end() ? -1 : it->second;
  };
  for (int v = 0; v < nv; ++v) {
    const IndexRange nb = neighbors(v);
    const IndexRange ring = vertexFaces(v);
    const int k = nb.size();
    if (ring.size() != k)
      return fail("vertex ", v, " has ", k, " neighbours but ", ring.size(), " ring faces");
    if (k < (solid ? 3 : 2)) return fail("vertex ", v, " has only ", k, " neighbours");
    for (int j = 0; j < k; ++j) {
      const int u = nb[j];
      if (u < 0 || u >= nv || u == v) return fail("vertex ", v, " has a bad neighbour ", u);
      const IndexRange back = neighbors(u);
      if (std::find(back.begin(), back.end(), v) == back.end()) {
        return fail("neighbours are not symmetric: ", u, " of ", v);
      }
      const int f = ring[j];
      if (f < 0 || f >= nf) return fail("vertex ", v, " has a bad ring face ", f);
      const int i = posIn(f, v);
      if (i < 0) return fail("ring face ", f, " of vertex ", v, " does not contain it");
      const IndexRange fv = faceVertices(f);
      const int m = fv.size();
      if (fv[(i + 1) % m] != nb[j] || fv[(i + m - 1) % m] != nb[(j + 1) % k]) {
        return fail("ring of vertex ", v, ": face ", f, " is not between neighbours ", nb[j],
                    " and ", nb[(j + 1) % k]);
      }
      if (solid) {
        for (int t = 0; t < j; ++t) {
          if (ring[t] == f) return fail("vertex ", v, " has face ", f, " twice in its ring");
          if (nb[t] == u) return fail("vertex ", v, " has neighbour ", u, " twice");
        }
        // The Gauss image of edge (v, nbr_j) runs from ring normal j-1 to ring normal j, counter-
        // clockwise seen from outside, so n_{j-1} x n_j points along v - nbr_j. Allowed the
        // other way by no more than the two normals' uncertainty.
        const int prev = ring[(j + k - 1) % k];
        const Vector3d turn = faceNormals_[prev].cross(faceNormals_[f]);
        const Vector3d edge = (local_[u] - local_[v]).normalized();
        if (!(turn.dot(edge) < normalUncertainty[prev] + normalUncertainty[f])) {
          return fail("ring normals of vertex ", v, " are not counter-clockwise at edge to ", u,
                      " (by ", turn.dot(edge), " rad)");
        }
      }
    }
  }
  return "";
}

}  // namespace deepcheck::deep
