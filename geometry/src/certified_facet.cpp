// Naming the facet of M = B - A under the certified expansion's final face (see certified.h).
//
// The face's three corners are vertices b - a of M on (within tau of) the facet of smallest
// offset. Their index pairs say which facet it is, in DEEP's terms (Kim, Lin, Manocha 2002): all
// corners share A's vertex (VF: that vertex against a face of B), or B's (FV), or they use two
// vertices of each (EE: an edge of each). The facet's normal is then computed from those features
// alone (a face normal, or the cross product of the edges), exactly as DEEP computes it, and its
// offset is one support query in that normal, so the answer is a support value: a valid
// separating translation, never below the true depth.

#include "deepcheck/geometry/internal/certified.h"

#include "deepcheck/geometry/tolerances.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace deepcheck::geometry::detail {
namespace {

using Vec3 = Eigen::Vector3d;

/// The distinct values of idx[0..2] in out; returns their count.
int distinct(const int* idx, int* out) {
  int m = 0;
  for (int i = 0; i < 3; ++i)
    if (std::find(out, out + m, idx[i]) == out + m) out[m++] = idx[i];
  return m;
}

bool adjacent(const ConvexPolytope& P, int v, int w) {
  for (int x : P.neighbors(v))
    if (x == w) return true;
  return false;
}

/// Face of P in vertex v's ring whose normal (P's own frame) is closest to `dir` (same frame);
/// -1 if none agrees to tol::kSameNormalCosine (the corners do not lie on one face).
int ringFaceAlong(const ConvexPolytope& P, int v, const Vec3& dir) {
  int best = -1;
  double bestDot = tol::kSameNormalCosine;
  for (int f : P.vertexFaces(v)) {
    const double d = P.faceNormal(f).dot(dir);
    if (d > bestDot) {
      bestDot = d;
      best = f;
    }
  }
  return best;
}

/// Witness on A for the facet named in `out` with normal u and offset h: A's vertex (VF), B's
/// vertex moved back by h u (FV), or the point of A's edge on the common perpendicular of the two
/// edges' lines (EE).
Vec3 witnessOnA(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& F, const WalkResult& out,
                const Vec3& u, double h) {
  switch (out.type) {
    case WalkResult::FacetType::VF:
      return A.localVertex(out.featureA);
    case WalkResult::FacetType::FV:
      return F.vertexB(B, out.featureB) - h * u;
    case WalkResult::FacetType::EE:
      break;
  }
  const Vec3 a0 = A.localVertex(out.featureA), ea = A.localVertex(out.featureA2) - a0;
  const Vec3 b0 = F.vertexB(B, out.featureB), eb = F.vertexB(B, out.featureB2) - b0;
  // Closest points of the lines a0 + s ea and b0 + t eb (skew: the edges are not parallel).
  const Vec3 d = a0 - b0;
  const double aa = ea.dot(ea), ab = ea.dot(eb), bb = eb.dot(eb), ad = ea.dot(d), bd = eb.dot(d);
  const double det = aa * bb - ab * ab;
  const double s = std::clamp((ab * bd - bb * ad) / det, 0.0, 1.0);
  return a0 + s * ea;
}

/// The facet's type, features and normal u from the corners' index pairs of a face with unit
/// normal `normal`; false if they name none.
bool facetOfCorners(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& F, const int* faceA,
                    const int* faceB, const Vec3& normal, NamedFacet& out) {
  int ia[3], ib[3];
  const int nA = distinct(faceA, ia), nB = distinct(faceB, ib);
  if (nA == 1 && nB == 3) {
    out.type = WalkResult::FacetType::VF;
    out.featureA = ia[0];
    // B's outward face normal is M's outward normal there (in B's frame).
    out.featureB = ringFaceAlong(B, ib[0], F.toB(normal));
    if (out.featureB >= 0) out.u = F.fromB(B.faceNormal(out.featureB));
    return out.featureB >= 0;
  }
  if (nB == 1 && nA == 3) {
    out.type = WalkResult::FacetType::FV;
    out.featureB = ib[0];
    // A's outward face normal is the opposite of M's.
    out.featureA = ringFaceAlong(A, ia[0], -normal);
    if (out.featureA >= 0) out.u = -A.faceNormal(out.featureA);
    return out.featureA >= 0;
  }
  if (nA == 2 && nB == 2 && adjacent(A, ia[0], ia[1]) && adjacent(B, ib[0], ib[1])) {
    const Vec3 ea = A.localVertex(ia[1]) - A.localVertex(ia[0]);
    const Vec3 eb = F.vertexB(B, ib[1]) - F.vertexB(B, ib[0]);
    Vec3 u = ea.cross(eb);
    const double len = u.norm();
    if (!(len > tol::kParallelSine * ea.norm() * eb.norm())) return false;
    u /= len;
    if (u.dot(normal) < 0) u = -u;
    if (u.dot(normal) < tol::kSameNormalCosine) return false;
    out.type = WalkResult::FacetType::EE;
    out.featureA = ia[0];
    out.featureA2 = ia[1];
    out.featureB = ib[0];
    out.featureB2 = ib[1];
    out.u = u;
    return true;
  }
  return false;
}

/// Writes a named facet's type and features into `out`, as WalkResult holds them.
void setFeatures(const NamedFacet& facet, WalkResult& out) {
  out.type = facet.type;
  out.featureA = facet.featureA;
  out.featureB = facet.featureB;
  if (facet.type != WalkResult::FacetType::EE) return;
  out.featureA2 = facet.featureA2;
  out.featureB2 = facet.featureB2;
}

}  // namespace

NamedFacet facetOfFace(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, const int* faceA,
                       const int* faceB, const Vec3& normal) {
  NamedFacet facet;
  facet.state =
      facetOfCorners(A, B, frame, faceA, faceB, normal, facet) ? NamedFacet::State::Named : NamedFacet::State::None;
  return facet;
}

void facetSupports(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& F, const NamedFacet& facet,
                   int& a, int& b) {
  const bool vf = facet.type == WalkResult::FacetType::VF, fv = facet.type == WalkResult::FacetType::FV;
  a = fv ? A.faceSupport(facet.featureA) : A.support(-facet.u, a);
  b = vf ? B.faceSupport(facet.featureB) : B.support(F.toB(facet.u), b);
}

bool certifiedFacet(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& F, const CertifiedResult& c,
                    WalkResult& out) {
  if (c.status != CertifiedStatus::Certified) return false;
  const NamedFacet facet =
      c.facet.state == NamedFacet::State::Unknown ? facetOfFace(A, B, F, c.faceA, c.faceB, c.faceNormal) : c.facet;
  if (facet.state != NamedFacet::State::Named) return false;
  setFeatures(facet, out);
  const Vec3& u = facet.u;
  // The offset: one support in u (a support value, hence a valid depth), unless the bracket's
  // upper bound already is that support (a warm query supports in u). facetSupports reads the
  // face side from the hull's table and climbs the other side from the bracket's support pair, as
  // the pair's next warm query does: on a facet whose vertices tie along u to round-off, cold and
  // warm then reach the same vertices and the same depth.
  int sa = c.supportA, sb = c.supportB;
  if (u != c.direction) facetSupports(A, B, F, facet, sa, sb);
  const double h = u.dot(F.vertexB(B, sb) - A.localVertex(sa));
  const double onFacet = u.dot(F.vertexB(B, c.faceB[0]) - A.localVertex(c.faceA[0]));
  const double L = pairLengthScale(A, B, F);
  // The corners must support u (else the features are not the facet's) and the offset must lie
  // in the bracket.
  if (h - onFacet > tol::kFeatureRelative * L || h > c.upper + c.tau || h < c.lower - c.tau) return false;
  out.status = WalkStatus::Converged;
  out.depth = h;
  out.normal = -u;
  out.pointA = witnessOnA(A, B, F, out, u, h);
  out.pointB = out.pointA + h * u;
  return true;
}

}  // namespace deepcheck::geometry::detail
