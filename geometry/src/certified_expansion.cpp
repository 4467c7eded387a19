#include "deepcheck/geometry/internal/certified.h"

#include "deepcheck/geometry/tolerances.h"

#include "probe_icosahedron.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepcheck::geometry::detail {

const char* toString(CertifiedStatus s) {
  switch (s) {
    case CertifiedStatus::Certified:
      return "certified";
    case CertifiedStatus::NotConverged:
      return "not-converged";
  }
  return "unknown";
}

namespace {

using Vec3 = Eigen::Vector3d;
using Vertex = ExpansionSurface::Vertex;

/// Support points of M = B - A in frame P, by hill climbing from a hint pair.
class Support {
 public:
  Support(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& F) : A_(A), B_(B), F_(F) {}
  Vertex point(int a, int b) const { return {F_.vertexB(B_, b) - A_.localVertex(a), a, b}; }
  Vertex operator()(const Vec3& u, int hintA, int hintB) const {
    return point(A_.support(-u, hintA), B_.support(F_.toB(u), hintB));
  }
  /// The support in the normal of face f of s. Each shape's climb starts from the face's corner
  /// whose vertex of that shape is highest along that shape's direction (A's along -n, B's along
  /// n): the corners lie near the support, but the corner highest in M need not be in either.
  Vertex inNormalOf(const ExpansionSurface& s, int f) const {
    const ExpansionSurface::Face& face = s.face(f);
    const Vec3 nB = F_.toB(face.n);
    int a = s.vertex(face.v[0]).a, b = s.vertex(face.v[0]).b;
    double va = -face.n.dot(A_.localVertex(a)), vb = nB.dot(B_.localVertex(b));
    for (int k = 1; k < 3; ++k) {
      const Vertex& c = s.vertex(face.v[k]);
      const double sa = -face.n.dot(A_.localVertex(c.a)), sb = nB.dot(B_.localVertex(c.b));
      if (sa > va) {
        va = sa;
        a = c.a;
      }
      if (sb > vb) {
        vb = sb;
        b = c.b;
      }
    }
    return point(A_.support(-face.n, a), B_.support(nB, b));
  }

 private:
  const ConvexPolytope& A_;
  const ConvexPolytope& B_;
  const PairFrame& F_;
};

/// Four directions of a regular tetrahedron in the probes' generic orientation.
const Vec3* tetrahedronDirections() {
  static const Vec3* dirs = [] {
    static Vec3 d[4];
    const Eigen::Matrix3d& R = probe::genericOrientation();
    const double k = 1.0 / std::sqrt(3.0);
    d[0] = R * Vec3(k, k, k);
    d[1] = R * Vec3(k, -k, -k);
    d[2] = R * Vec3(-k, k, -k);
    d[3] = R * Vec3(-k, -k, k);
    return d;
  }();
  return dirs;
}

/// A unit vector orthogonal to unit-or-not v (v non-zero).
Vec3 orthogonal(const Vec3& v) {
  const Vec3 axis = std::abs(v.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
  return v.cross(axis).normalized();
}

/// Keeps the affinely independent points of `in` (greedily, a point counting when it lies farther
/// than `eps` from the span of those kept), then adds supports normal to the span until there are
/// four. Returns false when M is flat within eps.
bool completeTetrahedron(const Support& support, const Vertex* in, int n, double eps, Vertex* out) {
  int k = 0;
  auto offSpan = [&](const Vec3& p) {
    if (k == 0) return std::numeric_limits<double>::infinity();
    const Vec3 r = p - out[0].p;
    if (k == 1) return r.norm();
    if (k == 2) {
      const Vec3 e = (out[1].p - out[0].p).normalized();
      return (r - r.dot(e) * e).norm();
    }
    const Vec3 nrm = (out[1].p - out[0].p).cross(out[2].p - out[0].p).normalized();
    return std::abs(r.dot(nrm));
  };
  for (int i = 0; i < n && k < 4; ++i)
    if (offSpan(in[i].p) > eps) out[k++] = in[i];
  while (k < 4) {
    Vec3 dir;
    if (k == 1) dir = orthogonal(out[0].p.squaredNorm() > 0 ? out[0].p : Vec3::UnitZ());
    else if (k == 2) dir = orthogonal(out[1].p - out[0].p);
    else dir = (out[1].p - out[0].p).cross(out[2].p - out[0].p).normalized();
    const Vertex plus = support(dir, out[0].a, out[0].b);
    const Vertex minus = support(-dir, out[0].a, out[0].b);
    const Vertex& far = offSpan(plus.p) >= offSpan(minus.p) ? plus : minus;
    if (!(offSpan(far.p) > eps)) return false;
    out[k++] = far;
  }
  return true;
}

/// The starting tetrahedron: GJK's (when given) when it encloses the origin with every face at
/// positive distance, else supports in generic directions, completed.
bool startSurface(const Support& support, const GjkResult* gjk, double eps, ExpansionSurface& s) {
  Vertex pts[4];
  if (gjk && gjk->status == GjkStatus::Overlapping && gjk->simplexSize == 4) {
    for (int i = 0; i < 4; ++i) pts[i] = support.point(gjk->simplexA[i], gjk->simplexB[i]);
    bool encloses = s.startTetrahedron(pts);
    for (int f = 0; encloses && f < 4; ++f) encloses = s.face(f).d > eps;
    if (encloses) return true;
  }
  Vertex probes[4];
  for (int i = 0; i < 4; ++i) probes[i] = support(tetrahedronDirections()[i], 0, 0);
  return completeTetrahedron(support, probes, 4, eps, pts) && s.startTetrahedron(pts);
}

/// A result with an empty bracket [0, inf) and the tolerance of a pair of length scale L.
CertifiedResult emptyBracket(double L) {
  CertifiedResult r;
  r.tau = tol::kCertifyRelative * L;
  r.upper = std::numeric_limits<double>::infinity();
  return r;
}

/// The best-first expansion of a started surface: pops the nearest face, queries the support in
/// its normal, and stops when the bounds meet, the cap is hit or the surface cannot grow.
void expandBestFirst(const Support& support, ExpansionSurface& surface, const CertifiedOptions& options,
                     CertifiedResult& r) {
  while (true) {
    const int f = surface.bestFace();
    if (f < 0) break;
    const ExpansionSurface::Face& face = surface.face(f);
    r.lower = std::max(r.lower, face.d);
    const Vertex w = support.inNormalOf(surface, f);
    const double h = face.n.dot(w.p);
    if (h < r.upper) {
      r.upper = h;
      r.direction = face.n;
      r.supportA = w.a;
      r.supportB = w.b;
      surface.setQueueLimit(r.upper - r.tau);  // faces beyond it are never expanded
    }
    if (face.d >= 0 && r.upper - face.d <= r.tau) {
      r.status = CertifiedStatus::Certified;
      r.faceNormal = face.n;
      for (int k = 0; k < 3; ++k) {
        r.faceA[k] = surface.vertex(face.v[k]).a;
        r.faceB[k] = surface.vertex(face.v[k]).b;
      }
      break;
    }
    // A support already on the face cannot raise it (round-off on a sliver); the cap bounds work.
    if (r.expansions == options.maxExpansions || surface.isCorner(f, w)) break;
    if (!surface.expand(f, w)) break;
    ++r.expansions;
  }
  r.faces = surface.numLiveFaces();
  r.lower = std::min(r.lower, r.upper);
}

/// The expansion from startSurface (GJK's simplex when `gjk` is given).
CertifiedResult startAndExpand(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                               const GjkResult* gjk, ExpansionSurface& surface, const CertifiedOptions& options) {
  const double L = pairLengthScale(A, B, frame);
  CertifiedResult r = emptyBracket(L);
  const Support support(A, B, frame);
  if (!startSurface(support, gjk, tol::kFlatRelative * L, surface)) return r;
  expandBestFirst(support, surface, options, r);
  return r;
}

}  // namespace

CertifiedResult certifiedPenetration(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                                     const GjkResult& gjk, ExpansionSurface& surface, const CertifiedOptions& options) {
  return startAndExpand(A, B, frame, &gjk, surface, options);
}

CertifiedResult certifiedWithoutGjk(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                                    ExpansionSurface& surface, const CertifiedOptions& options) {
  return startAndExpand(A, B, frame, nullptr, surface, options);
}

CertifiedResult certifiedFromSurface(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                                     ExpansionSurface& surface, const CertifiedOptions& options) {
  CertifiedResult r = emptyBracket(pairLengthScale(A, B, frame));
  expandBestFirst(Support(A, B, frame), surface, options, r);
  return r;
}

}  // namespace deepcheck::geometry::detail
