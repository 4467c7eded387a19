// The Minkowski difference of two pieces from their features (body_depth_internal.h).
//
// M = B - A = B + (-A). Its facet normals are among: the face normals of B, the negated face
// normals of A, and the cross products (either sign) of an edge direction of A with one of B.
// For each candidate unit normal u the support value is h(u) = max u.b - min u.a over the
// vertices, and the face of M in u is the set of differences b - a of the vertices that reach it
// (b within eps of B's support plane, a within eps of A's): u names a facet when that set spans a
// polygon. Offsets are exact support values, so every point of M is inside every plane and the
// planes of all facets describe M exactly. The work grows as eA eB (vA + vB) (distinct edge
// directions, vertices): the cheaper method for the small pieces of a decomposition, where a
// general hull of all vA vB differences costs more (buildDifference chooses).

#include "body_depth_internal.h"

#include "deepcheck/geometry/tolerances.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepcheck::geometry::body {
namespace {

/// The largest u.x over the points (their support value in u), each u.x kept in `dots`.
double supportValue(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& u, std::vector<double>& dots) {
  double best = -std::numeric_limits<double>::infinity();
  dots.resize(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    dots[i] = u.dot(pts[i]);
    best = std::max(best, dots[i]);
  }
  return best;
}

/// The points within eps of the support value `best` (supportValue, with its `dots`).
void supportSet(const std::vector<Eigen::Vector3d>& pts, const std::vector<double>& dots, double best, double eps,
                std::vector<Eigen::Vector3d>& set) {
  set.clear();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (dots[i] >= best - eps) set.push_back(pts[i]);
  }
}

double cross2(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

/// The convex hull of points of the plane u.x = h, counter-clockwise about u (monotone chain in
/// a basis of the plane), points projected onto the plane. Fewer than three corners, or a hull
/// thinner than eps: empty (the set is not a polygon).
/// Scratch space of planeHull, reused across the candidates of one difference.
struct HullScratch {
  std::vector<Eigen::Vector2d> q;
  std::vector<Eigen::Vector2d> hull;
};

std::vector<Eigen::Vector3d> planeHull(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& u, double h,
                                       double eps, HullScratch& scratch) {
  if (pts.size() < 3) return {};
  const Eigen::Vector3d e1 = u.unitOrthogonal();
  const Eigen::Vector3d e2 = u.cross(e1);
  std::vector<Eigen::Vector2d>& q = scratch.q;
  q.clear();
  for (const Eigen::Vector3d& p : pts) q.emplace_back(e1.dot(p), e2.dot(p));
  std::sort(q.begin(), q.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  std::vector<Eigen::Vector2d>& hull = scratch.hull;
  hull.resize(2 * q.size() + 1);
  std::size_t k = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    while (k >= 2 && cross2(hull[k - 2], hull[k - 1], q[i]) <= 0) --k;
    hull[k++] = q[i];
  }
  for (std::size_t i = q.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross2(hull[k - 2], hull[k - 1], q[i]) <= 0) --k;
    hull[k++] = q[i];
  }
  hull.resize(k > 0 ? k - 1 : 0);
  if (hull.size() < 3) return {};
  // Thickness: twice the area over the longest chord-like extent.
  double area2 = 0.0;
  double extent = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    area2 += cross2(hull[0], hull[i], hull[(i + 1) % hull.size()]);
    extent = std::max(extent, (hull[i] - hull[0]).norm());
  }
  if (area2 <= eps * extent) return {};
  std::vector<Eigen::Vector3d> out;
  out.reserve(hull.size());
  for (const Eigen::Vector2d& p : hull) out.push_back(p.x() * e1 + p.y() * e2 + h * u);
  return out;
}

/// Unit edge directions of a piece in P, parallel ones (either sense) kept once; computed on the
/// piece's first difference and kept with it (PosedPiece::edgeDirections).
const std::vector<Eigen::Vector3d>& edgeDirections(const PosedPiece& p) {
  std::vector<Eigen::Vector3d>& dirs = p.edgeDirections;
  if (p.hasEdgeDirections) return dirs;
  p.hasEdgeDirections = true;
  dirs.clear();
  const ConvexPolytope& core = *p.core;
  for (int v = 0; v < core.numVertices(); ++v) {
    for (const int w : core.neighbors(v)) {
      if (w <= v) continue;
      const Eigen::Vector3d e =
          (p.vertices[static_cast<std::size_t>(w)] - p.vertices[static_cast<std::size_t>(v)]).normalized();
      const bool known = std::any_of(dirs.begin(), dirs.end(), [&](const Eigen::Vector3d& d) {
        return d.cross(e).norm() < tol::kBodyParallelSine;
      });
      if (!known) dirs.push_back(e);
    }
  }
  return dirs;
}

}  // namespace

bool buildDifferenceFromFeatures(const PosedPiece& A, const PosedPiece& B, Difference& out, double keep) {
  const std::vector<Eigen::Vector3d>& vb = B.vertices;
  std::vector<Eigen::Vector3d> negA;
  negA.reserve(A.vertices.size());
  for (const Eigen::Vector3d& a : A.vertices) negA.push_back(-a);
  // A vertex within the pieces' own hull tolerance of a face plane belongs to that face.
  const double scale = std::max(A.core->lengthScale(), B.core->lengthScale());
  const double eps = std::max(A.core->hullTolerance(), B.core->hullTolerance()) + tol::kBodyMemberRelative * scale;

  std::vector<Eigen::Vector3d> candidates = B.faceNormals;
  for (const Eigen::Vector3d& n : A.faceNormals) candidates.push_back(-n);
  const std::vector<Eigen::Vector3d>& edgesB = edgeDirections(B);
  for (const Eigen::Vector3d& da : edgeDirections(A)) {
    for (const Eigen::Vector3d& db : edgesB) {
      const Eigen::Vector3d c = da.cross(db);
      const double length = c.norm();
      if (length < tol::kBodyParallelSine) continue;
      candidates.push_back(c / length);
      candidates.push_back(-c / length);
    }
  }

  std::vector<Eigen::Vector3d> sb, sa, diffs;
  std::vector<double> dotsB, dotsA;
  HullScratch scratch;
  bool skipped = false;  // some candidate was beyond `keep`
  // |n - u| < s for unit vectors is n.u > 1 - s^2 / 2.
  const double same = 1.0 - 0.5 * tol::kBodyParallelSine * tol::kBodyParallelSine;
  for (const Eigen::Vector3d& u : candidates) {
    const bool known =
        std::any_of(out.normals.begin(), out.normals.end(), [&](const Eigen::Vector3d& n) { return n.dot(u) > same; });
    if (known) continue;
    const double hb = supportValue(vb, u, dotsB);
    const double ha = supportValue(negA, u, dotsA);
    const double h = hb + ha;
    if (!(h < keep)) {
      skipped = true;
      continue;
    }
    supportSet(vb, dotsB, hb, eps, sb);
    supportSet(negA, dotsA, ha, eps, sa);
    diffs.clear();
    for (const Eigen::Vector3d& b : sb) {
      for (const Eigen::Vector3d& a : sa) diffs.push_back(b + a);  // sa holds -a
    }
    std::vector<Eigen::Vector3d> face = planeHull(diffs, u, h, eps, scratch);
    if (face.empty()) continue;
    addFace(out, u, h, std::move(face));
  }
  // A flat difference (coplanar polygons): two opposite facets at one offset; no interior. The
  // offsets are compared first: in a solid difference no two facets pass that test.
  for (std::size_t f = 0; f < out.normals.size(); ++f) {
    for (std::size_t g = f + 1; g < out.normals.size(); ++g) {
      if (out.offsets[f] + out.offsets[g] <= eps && (out.normals[f] + out.normals[g]).norm() < tol::kBodyParallelSine) {
        return false;
      }
    }
  }
  // Fewer than four facets kept: whether the difference is solid is decided on all of them.
  if (out.normals.size() < 4 && skipped) {
    out.normals.clear();
    out.offsets.clear();
    out.faces.clear();
    out.centres.clear();
    out.radii.clear();
    return buildDifferenceFromFeatures(A, B, out, std::numeric_limits<double>::infinity());
  }
  return out.normals.size() >= 4;
}

}  // namespace deepcheck::geometry::body
