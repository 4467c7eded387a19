// Warm start of the certified penetration depth (see CertifiedWarmStart in
// internal/certified_warm_start.h).

#include "deepcheck/geometry/internal/certified.h"

#include "deepcheck/geometry/tolerances.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepcheck::geometry::detail {

namespace {

using Vec3 = Eigen::Vector3d;
using W = CertifiedWarmStart;

/// Copies the live faces of `surface` with their corners (renumbered) into `warm`; false when
/// they do not fit or a face's offset is not positive.
bool copyFaces(const ExpansionSurface& surface, W& warm) {
  int map[ExpansionSurface::kMaxVertices];
  std::fill(map, map + surface.numVertices(), -1);
  int index[ExpansionSurface::kMaxFaces];  // face slot -> cached face
  for (int f = 0, n = 0; f < surface.numFaceSlots(); ++f) index[f] = surface.face(f).alive ? n++ : -1;
  warm.numVertices = warm.numFaces = 0;
  double nearest = std::numeric_limits<double>::infinity();
  for (int f = 0; f < surface.numFaceSlots(); ++f) {
    const ExpansionSurface::Face& face = surface.face(f);
    if (!face.alive) continue;
    double offset = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      int& m = map[face.v[k]];
      const ExpansionSurface::Vertex& v = surface.vertex(face.v[k]);
      if (m < 0) {
        if (warm.numVertices == W::kMaxVertices) return false;
        m = warm.numVertices++;
        warm.a[m] = v.a;
        warm.b[m] = v.b;
      }
      warm.face[warm.numFaces][k] = m;
      warm.adj[warm.numFaces][k] = 4 * index[face.adj[k] >> 2] + (face.adj[k] & 3);
      offset = std::min(offset, face.n.dot(v.p));
    }
    if (!(offset > 0)) return false;  // not enclosing: nothing to certify from
    // The certifying face of a cold query is its nearest one.
    if (face.d < nearest) {
      nearest = face.d;
      warm.last = warm.numFaces;
    }
    warm.normal[warm.numFaces] = face.n;
    warm.offset[warm.numFaces++] = offset;
  }
  return true;
}

}  // namespace

void saveWarmStart(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                   const ExpansionSurface& surface, const CertifiedResult& result, W& warm) {
  warm.valid = false;
  if (result.status != CertifiedStatus::Certified || surface.numLiveFaces() > W::kMaxFaces) return;
  if (!copyFaces(surface, warm)) return;
  warm.A = &A;
  warm.B = &B;
  warm.R0 = frame.R;
  warm.t0 = frame.t;
  warm.hintA = result.supportA;
  warm.hintB = result.supportB;
  warm.valid = true;
}

namespace {

/// The cached surface at the current pose: its corners, evaluated on first use, and the bound
/// on how far any vertex of M has moved since the reference.
class MovedSurface {
 public:
  MovedSurface(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, const W& w)
      : A_(A), B_(B), frame_(frame), w_(w) {
    shift = frame.t - w.t0;
    turn = (frame.R - w.R0).norm() * B.boundingRadius();
    motion = turn + shift.norm();
  }

  double motion;  ///< every vertex of M moved at most this far since the reference
  /// Each vertex's move is shift plus a turn of length at most `turn`: n.q >= n.p + n.shift - turn.
  Vec3 shift;
  double turn;

  /// A lower bound on n0.q over face f's moved corners from its reference offset and the motion's
  /// shift along its normal, without evaluating the corners.
  double shiftBound(int f) const { return w_.offset[f] + w_.normal[f].dot(shift) - turn; }

  /// Cached vertex i at the current pose.
  const Vec3& vertex(int i) {
    if (!done_[i]) {
      q_[i] = frame_.vertexB(B_, w_.b[i]) - A_.localVertex(w_.a[i]);
      done_[i] = true;
    }
    return q_[i];
  }
  const Vec3& corner(int f, int k) { return vertex(w_.face[f][k]); }

  /// min_k n0.q_k over face f's moved corners: a lower bound on their face's distance to the
  /// origin, and (when positive) proof that the face did not cross it.
  double normalBound(int f) {
    const Vec3& n0 = w_.normal[f];
    return std::min({n0.dot(corner(f, 0)), n0.dot(corner(f, 1)), n0.dot(corner(f, 2))});
  }

  /// Face f's plane through its moved corners (unit normal, offset); false when degenerate.
  bool plane(int f, Vec3& n, double& d) {
    return ExpansionSurface::planeThrough(corner(f, 0), corner(f, 1), corner(f, 2), n, d);
  }

 private:
  const ConvexPolytope& A_;
  const ConvexPolytope& B_;
  const PairFrame& frame_;
  const W& w_;
  Vec3 q_[W::kMaxVertices];
  bool done_[W::kMaxVertices] = {};
};

/// The moved surface's lower bound on the depth, and its nearest face when that is below the
/// target: a fresh face (plane through its moved corners).
struct Bound {
  double lower = std::numeric_limits<double>::infinity();
  int nearest = -1;  ///< the nearest face below the target, or -1
  Vec3 n = Vec3::UnitZ();
  double d = 0.0;
};

/// The faces whose reference offset minus the motion is below `target` (they need work) into
/// `near`, their count returned; `farLower` is the smallest bound of the others. One pass without
/// branches or a long dependency chain: most faces are far, and this scan is most of a warm query.
int nearFaces(const W& w, double motion, double target, int* near, double& farLower) {
  const double limit = target + motion;
  const double inf = std::numeric_limits<double>::infinity();
  double far0 = inf, far1 = inf;
  int k = 0;
  for (int f = 0; f + 1 < w.numFaces; f += 2) {
    const double o0 = w.offset[f], o1 = w.offset[f + 1];
    near[k] = f;
    k += o0 < limit;
    near[k] = f + 1;
    k += o1 < limit;
    far0 = std::min(far0, o0 < limit ? inf : o0);
    far1 = std::min(far1, o1 < limit ? inf : o1);
  }
  if (w.numFaces % 2 != 0) {
    const int f = w.numFaces - 1;
    near[k] = f;
    k += w.offset[f] < limit;
    far0 = std::min(far0, w.offset[f] < limit ? inf : w.offset[f]);
  }
  farLower = std::min(far0, far1) - motion;
  return k;
}

/// Bounds every face's distance to the origin, working only on faces whose reference offset
/// minus the motion is below `target` (the others already reach it). False when a face could
/// have crossed the origin or is degenerate: the surface then certifies nothing.
bool boundFaces(const W& w, MovedSurface& m, double target, Bound& out) {
  int near[W::kMaxFaces];
  const int count = nearFaces(w, m.motion, target, near, out.lower);
  for (int i = 0; i < count; ++i) {
    const int f = near[i];
    double key = m.shiftBound(f);
    if (key >= target) {
      out.lower = std::min(out.lower, key);
      continue;
    }
    key = m.normalBound(f);
    if (!(key > 0)) return false;
    if (key < target) {
      Vec3 n;
      double d;
      if (!m.plane(f, n, d)) return false;
      key = std::max(key, std::abs(d));
      if (key < target && key < out.lower) {
        out.nearest = f;
        out.n = n;
        out.d = d;
      }
    }
    out.lower = std::min(out.lower, key);
  }
  return true;
}

double tauOf(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame) {
  return tol::kCertifyRelative * pairLengthScale(A, B, frame);
}

/// Face f's corners as index pairs.
void cornerPairs(const W& w, int f, int* faceA, int* faceB) {
  for (int k = 0; k < 3; ++k) {
    faceA[k] = w.a[w.face[f][k]];
    faceB[k] = w.b[w.face[f][k]];
  }
}

/// The facet of M that face f's corners name, with moved normal n: a warm query supports in its
/// exact normal (certifiedFacet then need not query it again), else in n.
NamedFacet facetOf(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, const W& w, int f,
                   const Vec3& n) {
  int faceA[3], faceB[3];
  cornerPairs(w, f, faceA, faceB);
  return facetOfFace(A, B, frame, faceA, faceB, n);
}

}  // namespace

CertifiedResult certifiedWarm(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, W& w) {
  CertifiedResult r;
  r.upper = std::numeric_limits<double>::infinity();
  r.tau = tauOf(A, B, frame);
  if (!w.belongsTo(A, B)) return r;
  MovedSurface m(A, B, frame, w);
  int named = -1;  // the face whose normal gave the upper bound
  auto supportIn = [&](int f, const Vec3& n) {
    const NamedFacet facet = facetOf(A, B, frame, w, f, n);
    const bool isNamed = facet.state == NamedFacet::State::Named;
    const Vec3& u = isNamed ? facet.u : n;
    if (isNamed) {
      facetSupports(A, B, frame, facet, w.hintA, w.hintB);
    } else {
      w.hintA = A.support(-u, w.hintA);
      w.hintB = B.support(frame.toB(u), w.hintB);
    }
    const double h = u.dot(frame.vertexB(B, w.hintB) - A.localVertex(w.hintA));
    if (h < r.upper) {
      r.upper = h;
      r.direction = u;
      r.supportA = w.hintA;
      r.supportB = w.hintB;
      r.facet = facet;
      named = f;
    }
  };
  Vec3 n;
  double d;
  if (!m.plane(w.last, n, d)) return r;
  supportIn(w.last, n);
  Bound bound;
  if (!boundFaces(w, m, r.upper - r.tau, bound)) return r;
  r.lower = std::min(bound.lower, r.upper);
  if (r.upper - r.lower > r.tau) {
    // The nearest face is fresh and below the upper bound: query its normal once.
    if (bound.nearest == w.last || !(bound.d > 0)) return r;
    supportIn(bound.nearest, bound.n);
    r.lower = std::min(bound.lower, r.upper);
    if (r.upper - r.lower > r.tau) return r;
  }
  r.status = CertifiedStatus::Certified;
  r.faceNormal = named == w.last ? n : bound.n;
  cornerPairs(w, named, r.faceA, r.faceB);
  w.last = named;
  return r;
}

CertifiedResult expandWarm(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, W& w,
                           ExpansionSurface& surface, const CertifiedOptions& options) {
  CertifiedResult r;
  r.upper = std::numeric_limits<double>::infinity();
  r.tau = tauOf(A, B, frame);
  if (!w.belongsTo(A, B)) return r;
  MovedSurface m(A, B, frame, w);
  for (int f = 0; f < w.numFaces; ++f)
    if (!(w.offset[f] - m.motion > 0) && !(m.normalBound(f) > 0)) return r;  // could have crossed
  ExpansionSurface::Vertex moved[W::kMaxVertices];
  for (int i = 0; i < w.numVertices; ++i) moved[i] = {m.vertex(i), w.a[i], w.b[i]};
  if (!surface.load(moved, w.numVertices, w.face, w.adj, w.numFaces)) return r;
  r = certifiedFromSurface(A, B, frame, surface, options);
  if (r.status == CertifiedStatus::Certified) saveWarmStart(A, B, frame, surface, r, w);
  return r;
}

}  // namespace deepcheck::geometry::detail
