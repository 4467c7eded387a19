// Minkowski differences of piece pairs as explicit polytopes, for the body depth (body_depth.h).
//
// M = B - A = B + (-A). Its facet normals are among: the face normals of B, the negated face
// normals of A, and the cross products (either sign) of an edge direction of A with one of B.
// For each candidate unit normal u the support value is h(u) = max u.b - min u.a over the
// vertices, and the face of M in u is the set of differences b - a of the vertices that reach it
// (b within eps of B's support plane, a within eps of A's): u names a facet when that set spans a
// polygon. Offsets are exact support values, so every point of M is inside every plane and the
// planes of all facets describe M exactly. No hull is built: the work is a few dot products per
// vertex and candidate, which for the small pieces of a convex decomposition is far cheaper than
// a general hull of all nA * nB differences.

#include "body_depth_internal.h"

#include "deepcheck/deep/tolerances.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepcheck::deep::body {
namespace {

/// Points of `pts` within eps of the largest u.x, and that largest value.
double supportSet(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& u, double eps,
                  std::vector<Eigen::Vector3d>& set) {
  double best = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : pts) best = std::max(best, u.dot(p));
  set.clear();
  for (const Eigen::Vector3d& p : pts) {
    if (u.dot(p) >= best - eps) set.push_back(p);
  }
  return best;
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

std::vector<Eigen::Vector3d> planeHull(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& u,
                                       double h, double eps, HullScratch& scratch) {
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

}  // namespace

PosedPiece posePiece(const ConvexPolytope& core, const Eigen::Isometry3d& X_PP) {
  PosedPiece p;
  p.core = &core;
  p.X_PP = X_PP;
  p.vertices.reserve(static_cast<std::size_t>(core.numVertices()));
  for (const Eigen::Vector3d& v : core.vertices()) p.vertices.push_back(X_PP * v);
  for (int f = 0; f < core.numFaces(); ++f) p.faceNormals.push_back(X_PP.linear() * core.faceNormal(f));
  for (int v = 0; v < core.numVertices(); ++v) {
    for (const int w : core.neighbors(v)) {
      if (w <= v) continue;
      const Eigen::Vector3d e =
          (p.vertices[static_cast<std::size_t>(w)] - p.vertices[static_cast<std::size_t>(v)]).normalized();
      const bool known = std::any_of(p.edgeDirections.begin(), p.edgeDirections.end(),
                                     [&](const Eigen::Vector3d& d) { return d.cross(e).norm() < tol::kBodyParallelSine; });
      if (!known) p.edgeDirections.push_back(e);
    }
  }
  return p;
}

bool buildDifference(const PosedPiece& A, const PosedPiece& B, Difference& out) {
  const std::vector<Eigen::Vector3d>& vb = B.vertices;
  std::vector<Eigen::Vector3d> negA;
  negA.reserve(A.vertices.size());
  for (const Eigen::Vector3d& a : A.vertices) negA.push_back(-a);
  // A vertex within the pieces' own hull tolerance of a face plane belongs to that face.
  const double scale = std::max(A.core->lengthScale(), B.core->lengthScale());
  const double eps = std::max(A.core->hullTolerance(), B.core->hullTolerance()) +
                     tol::kBodyMemberRelative * scale;

  std::vector<Eigen::Vector3d> candidates = B.faceNormals;
  for (const Eigen::Vector3d& n : A.faceNormals) candidates.push_back(-n);
  for (const Eigen::Vector3d& da : A.edgeDirections) {
    for (const Eigen::Vector3d& db : B.edgeDirections) {
      const Eigen::Vector3d c = da.cross(db);
      const double length = c.norm();
      if (length < tol::kBodyParallelSine) continue;
      candidates.push_back(c / length);
      candidates.push_back(-c / length);
    }
  }

  out.normals.clear();
  out.offsets.clear();
  out.faces.clear();
  out.centres.clear();
  out.radii.clear();
  std::vector<Eigen::Vector3d> sb, sa, diffs;
  HullScratch scratch;
  // |n - u| < s for unit vectors is n.u > 1 - s^2 / 2.
  const double same = 1.0 - 0.5 * tol::kBodyParallelSine * tol::kBodyParallelSine;
  for (const Eigen::Vector3d& u : candidates) {
    const bool known = std::any_of(out.normals.begin(), out.normals.end(),
                                   [&](const Eigen::Vector3d& n) { return n.dot(u) > same; });
    if (known) continue;
    const double h = supportSet(vb, u, eps, sb) + supportSet(negA, u, eps, sa);
    diffs.clear();
    for (const Eigen::Vector3d& b : sb) {
      for (const Eigen::Vector3d& a : sa) diffs.push_back(b + a);  // sa holds -a
    }
    std::vector<Eigen::Vector3d> face = planeHull(diffs, u, h, eps, scratch);
    if (face.empty()) continue;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : face) centre += p;
    centre /= static_cast<double>(face.size());
    double radius = 0.0;
    for (const Eigen::Vector3d& p : face) radius = std::max(radius, (p - centre).norm());
    out.normals.push_back(u);
    out.offsets.push_back(h);
    out.faces.push_back(std::move(face));
    out.centres.push_back(centre);
    out.radii.push_back(radius);
  }
  // A flat difference (coplanar polygons): two opposite facets at one offset; no interior.
  for (std::size_t f = 0; f < out.normals.size(); ++f) {
    for (std::size_t g = f + 1; g < out.normals.size(); ++g) {
      if ((out.normals[f] + out.normals[g]).norm() < tol::kBodyParallelSine &&
          out.offsets[f] + out.offsets[g] <= eps) {
        return false;
      }
    }
  }
  return out.normals.size() >= 4;
}

double planeExcess(const Difference& d, const Eigen::Vector3d& x) {
  double worst = -std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < d.normals.size(); ++f) worst = std::max(worst, d.normals[f].dot(x) - d.offsets[f]);
  return worst;
}

double rayExit(const Difference& d, const Eigen::Vector3d& u) {
  double exit = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < d.normals.size(); ++f) {
    const double rate = d.normals[f].dot(u);
    if (rate > 0) exit = std::min(exit, d.offsets[f] / rate);
  }
  return exit;
}

}  // namespace deepcheck::deep::body
