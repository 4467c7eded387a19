// Warm start of the certified penetration depth (see CertifiedWarmStart in certified.h).

#include "deepcheck/deep/certified.h"

#include "deepcheck/deep/tolerances.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepcheck::deep {

void saveWarmStart(const ConvexPolytope& A, const ConvexPolytope& B, const ExpansionSurface& surface,
                   const CertifiedResult& result, CertifiedWarmStart& warm) {
  using W = CertifiedWarmStart;
  warm.valid = false;
  if (result.status != CertifiedStatus::Certified || surface.numLiveFaces() > W::kMaxFaces) return;
  // Surface vertex -> cached vertex, for the vertices live faces use.
  int map[ExpansionSurface::kMaxVertices];
  std::fill(map, map + surface.numVertices(), -1);
  warm.numVertices = warm.numFaces = 0;
  for (int f = 0; f < surface.numFaceSlots(); ++f) {
    const ExpansionSurface::Face& face = surface.face(f);
    if (!face.alive) continue;
    if (face.d < 0) return;  // not enclosing: nothing to certify from
    for (int k = 0; k < 3; ++k) {
      int& m = map[face.v[k]];
      if (m < 0) {
        if (warm.numVertices == W::kMaxVertices) return;
        const ExpansionSurface::Vertex& v = surface.vertex(face.v[k]);
        m = warm.numVertices++;
        warm.a[m] = v.a;
        warm.b[m] = v.b;
        warm.p[m] = v.p;
      }
      warm.face[warm.numFaces][k] = m;
    }
    warm.offset[warm.numFaces++] = face.d;
  }
  warm.A = &A;
  warm.B = &B;
  warm.direction = result.direction;
  warm.hintA = result.supportA;
  warm.hintB = result.supportB;
  warm.valid = true;
}

namespace {

using Vec3 = Eigen::Vector3d;

/// The cached surface moved to the current pose: lower bounds on every face's distance to the
/// origin, refreshed lazily.
struct MovedSurface {
  Vec3 q[CertifiedWarmStart::kMaxVertices];
  double key[CertifiedWarmStart::kMaxFaces];
  Vec3 n[CertifiedWarmStart::kMaxFaces];
  double d[CertifiedWarmStart::kMaxFaces];
  bool fresh[CertifiedWarmStart::kMaxFaces];
};

/// Moves the vertices and bounds each face's distance by its reference offset minus its corners'
/// largest move; false when a face could have crossed the origin.
bool moveSurface(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                 const CertifiedWarmStart& w, MovedSurface& m) {
  double move[CertifiedWarmStart::kMaxVertices];
  for (int i = 0; i < w.numVertices; ++i) {
    m.q[i] = frame.vertexB(B, w.b[i]) - A.localVertex(w.a[i]);
    move[i] = (m.q[i] - w.p[i]).norm();
  }
  for (int f = 0; f < w.numFaces; ++f) {
    const int* c = w.face[f];
    m.key[f] = w.offset[f] - std::max({move[c[0]], move[c[1]], move[c[2]]});
    if (!(m.key[f] > 0)) return false;
    m.fresh[f] = false;
  }
  return true;
}

/// Recomputes face f's plane from its moved corners; the distance to a triangle is at least the
/// distance to its plane. False for a degenerate face.
bool refresh(const CertifiedWarmStart& w, MovedSurface& m, int f) {
  const Vec3& p0 = m.q[w.face[f][0]];
  const Vec3& p1 = m.q[w.face[f][1]];
  const Vec3& p2 = m.q[w.face[f][2]];
  const Vec3 n = (p1 - p0).cross(p2 - p0);
  const double len = n.norm();
  if (!(len > 0)) return false;
  m.n[f] = n / len;
  m.d[f] = m.n[f].dot(p0 + p1 + p2) / 3.0;
  m.key[f] = std::max(m.key[f], std::abs(m.d[f]));
  m.fresh[f] = true;
  return true;
}

void setFace(const CertifiedWarmStart& w, const MovedSurface& m, int f, CertifiedResult& r) {
  r.faceNormal = m.n[f];
  for (int k = 0; k < 3; ++k) {
    r.faceA[k] = w.a[w.face[f][k]];
    r.faceB[k] = w.b[w.face[f][k]];
  }
}

/// The warm queries' common start: the tolerance, and the cached surface moved to the current
/// pose. False when the surface is not this pair's or a face could have crossed the origin.
bool startWarm(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
               const CertifiedWarmStart& w, CertifiedResult& r, MovedSurface& m) {
  r.tau = tol::kCertifyRelative * (std::max(A.lengthScale(), B.lengthScale()) + frame.t.norm());
  return w.belongsTo(A, B) && moveSurface(A, B, frame, w, m);
}

/// Refreshes the nearest face while it is stale and below r.upper by more than tau; r.lower is
/// then its key. Returns that face, or -1 for a degenerate face. Each refresh makes one more face
/// fresh, so this ends.
int settleNearest(const CertifiedWarmStart& w, MovedSurface& m, CertifiedResult& r) {
  for (;;) {
    const int f = static_cast<int>(std::min_element(m.key, m.key + w.numFaces) - m.key);
    r.lower = m.key[f];
    if (r.upper - r.lower <= r.tau || m.fresh[f]) return f;
    if (!refresh(w, m, f)) return -1;
  }
}

}  // namespace

CertifiedResult certifiedWarm(const ConvexPolytope& A, const ConvexPolytope& B,
                              const PairFrame& frame, CertifiedWarmStart& w) {
  CertifiedResult r;
  r.upper = std::numeric_limits<double>::infinity();
  MovedSurface m;
  if (!startWarm(A, B, frame, w, r, m)) return r;
  auto supportIn = [&](const Vec3& u) {
    w.hintA = A.support(-u, w.hintA);
    w.hintB = B.support(frame.toB(u), w.hintB);
    const double h = u.dot(frame.vertexB(B, w.hintB) - A.localVertex(w.hintA));
    if (h < r.upper) {
      r.upper = h;
      r.direction = u;
      r.supportA = w.hintA;
      r.supportB = w.hintB;
    }
  };
  supportIn(w.direction);
  const int f = settleNearest(w, m, r);
  if (f < 0) return r;
  int named = -1;  // the face whose normal gave the upper bound
  if (r.upper - r.lower > r.tau) {
    // The nearest face is up to date and still below the upper bound: query its normal once.
    if (!(m.d[f] > 0)) return r;
    const double before = r.upper;
    supportIn(m.n[f]);
    if (r.upper < before) named = f;
    if (r.upper - r.lower > r.tau) return r;
  }
  r.status = CertifiedStatus::Certified;
  if (named >= 0) setFace(w, m, named, r);
  w.direction = r.direction;
  return r;
}

CertifiedResult certifyUpperBound(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                                  const CertifiedWarmStart& w, double upper) {
  CertifiedResult r;
  r.upper = upper;
  MovedSurface m;
  if (!std::isfinite(upper) || !startWarm(A, B, frame, w, r, m)) return r;
  // No support query: a fresh face still below the bound leaves the depth uncertified.
  if (settleNearest(w, m, r) >= 0 && r.upper - r.lower <= r.tau) r.status = CertifiedStatus::Certified;
  return r;
}

}  // namespace deepcheck::deep
