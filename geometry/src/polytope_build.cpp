// ConvexPolytope::fromPoints, first steps (polytope_internal.h lists them all): the local origin,
// the flatness tolerance, near-duplicates, the classification into point, segment, polygon or
// solid, and the lower-dimensional kinds built directly.

#include "polytope_internal.h"

#include "deepcheck/geometry/input_range.h"
#include "deepcheck/geometry/tolerances.h"

#include <sstream>
#include <unordered_map>

namespace deepcheck::geometry {

using namespace detail;

namespace {

/// Classification factor, in units of the flatness tolerance h (not a tolerance itself): sets
/// measured up to kFlatRetryFactor * h thick against the plane through three extreme points are
/// tried as polygons (the refitted plane then has to hold them within h).
constexpr double kFlatRetryFactor = 8.0;

const char* axisName(int axis) { return axis == 0 ? "x" : (axis == 1 ? "y" : "z"); }

std::string formatDouble(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
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

}  // namespace

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

ConvexPolytope ConvexPolytope::fromPoints(const std::vector<Vector3d>& points, const std::string& name) {
  if (points.empty()) throw std::invalid_argument(name + ": no points");
  range::checkPoints(points, name);
  return PolytopeBuilder(points, name).build();
}

ConvexPolytope ConvexPolytope::box(const Vector3d& size) {
  for (int c = 0; c < 3; ++c) {
    if (!(std::isfinite(size[c]) && size[c] > 0.0)) {
      throw std::invalid_argument(std::string("box: size ") + std::to_string(c) + " (" + axisName(c) +
                                  ") = " + formatDouble(size[c]) + " must be positive and finite");
    }
  }
  const Vector3d halfExtents = 0.5 * size;
  std::vector<Vector3d> corners;
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back((i & 1) ? halfExtents.x() : -halfExtents.x(), (i & 2) ? halfExtents.y() : -halfExtents.y(),
                         (i & 4) ? halfExtents.z() : -halfExtents.z());
  }
  return fromPoints(corners, "box");
}

}  // namespace deepcheck::geometry
