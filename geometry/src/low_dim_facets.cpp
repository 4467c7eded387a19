// Points and segments (sphere and capsule cores): M = X - S, S a point or a segment, has
// O(F + E) facets, enumerated directly; pairs whose M is flat have depth zero. Vocabulary in
// deep_walker.h.

#include "deep_walker.h"

namespace deepcheck::geometry::detail {
namespace {

/// Facets of M = X (+) (-S), X a polygon or polyhedron, S a point or segment given by its
/// vertices s0, s1 (equal for a point), all in frame P. `xVertex`/`xNormal` map X's vertex and
/// face normal into P. Returns the facet of smallest offset.
template <class VertexFn, class NormalFn>
Candidate lowDimFacets(const ConvexPolytope& X, VertexFn xVertex, NormalFn xNormal, const Vec3& s0, const Vec3& s1,
                       bool segment) {
  Candidate best;
  auto consider = [&](const Vec3& u, const Vec3& onX, WalkResult::FacetType type) {
    const Vec3 s = u.dot(s0) <= u.dot(s1) ? s0 : s1;  // support of S in -u
    const double d = u.dot(onX - s);
    if (d < best.d) {
      best.d = d;
      best.u = u;
      best.type = type;
      best.featuresKnown = false;
    }
  };
  for (int f = 0; f < X.numFaces(); ++f) consider(xNormal(f), xVertex(X.faceVertices(f)[0]), WalkResult::FacetType::VF);
  if (!segment) return best;
  const Vec3 sd = s1 - s0;
  for (int v = 0; v < X.numVertices(); ++v) {
    const IndexRange nbr = X.neighbors(v);
    const IndexRange ring = X.vertexFaces(v);
    for (int k = 0; k < nbr.size(); ++k) {
      const int w = nbr[k];
      if (w < v) continue;  // each edge once
      const Vec3 xv = xVertex(v);
      const Vec3 e = xVertex(w) - xv;
      Vec3 u = e.cross(sd);
      const double len = u.norm();
      if (len <= tol::kParallelSine * e.norm() * sd.norm()) continue;
      u /= len;
      // u must lie on the Gauss arc of edge (v, w): between the normals of its two faces.
      bool onArc = false;
      for (int sign = 0; sign < 2 && !onArc; ++sign) {
        if (sign) u = -u;
        if (X.kind() == PolytopeKind::Polyhedron) {
          const int m = nbr.size();
          const Vec3 n1 = xNormal(ring[(k + m - 1) % m]);
          const Vec3 n2 = xNormal(ring[k]);
          const Vec3 axis = n1.cross(n2);
          onArc = n1.cross(u).dot(axis) >= 0 && u.cross(n2).dot(axis) >= 0;
        } else {
          // Polygon: the arc of a boundary edge runs from +N to -N through the outward edge normal.
          const Vec3 N = xNormal(0);
          Vec3 m = N.cross(e);
          const Vec3 inner = xVertex(nbr[1 - k]) - xv;  // the other neighbour is inside the edge's half-plane
          if (m.dot(inner) > 0) m = -m;
          onArc = u.dot(m) >= 0;
        }
      }
      if (onArc) consider(u, xv, WalkResult::FacetType::EE);
    }
  }
  return best;
}

/// Lower-dimensional Minkowski differences (both shapes points or segments, a point and a polygon,
/// parallel polygons): no interior, the depth is zero.
bool isFlatPair(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame) {
  return (isLowDim(A) && isLowDim(B)) ||
         (isLowDim(A) && B.kind() == PolytopeKind::Polygon && A.kind() == PolytopeKind::Point) ||
         (isLowDim(B) && A.kind() == PolytopeKind::Polygon && B.kind() == PolytopeKind::Point) ||
         (A.kind() == PolytopeKind::Polygon && B.kind() == PolytopeKind::Polygon &&
          A.faceNormal(0).cross(frame.R * B.faceNormal(0)).norm() < tol::kParallelSine);
}

void flatPairAnswer(const Walker& w, const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                    WalkResult& result) {
  Vec3 u = Vec3::UnitZ();
  if (A.kind() == PolytopeKind::Polygon) u = A.faceNormal(0);
  else if (B.kind() == PolytopeKind::Polygon) u = frame.R * B.faceNormal(0);
  else if (A.kind() == PolytopeKind::Segment && B.kind() == PolytopeKind::Segment) {
    const Vec3 c = (w.va(1) - w.va(0)).cross(w.vb(1) - w.vb(0));
    if (c.norm() > 0) u = c.normalized();
  }
  result.status = WalkStatus::Converged;
  result.depth = 0;
  result.normal = -u;
  result.pointA = w.va(0);
  result.pointB = result.pointA;
}

}  // namespace

bool isLowDim(const ConvexPolytope& P) { return P.kind() == PolytopeKind::Point || P.kind() == PolytopeKind::Segment; }

bool lowDimPenetration(Walker& w, const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                       WalkResult& result) {
  if (isFlatPair(A, B, frame)) {
    flatPairAnswer(w, A, B, frame, result);
    return true;
  }
  if (!isLowDim(A) && !isLowDim(B)) return false;
  // One side is a point or segment, the other a polygon or polyhedron.
  Candidate c;
  if (isLowDim(A)) {
    const Vec3 s0 = w.va(0), s1 = w.va(A.numVertices() - 1);
    c = lowDimFacets(
        B, [&](int v) { return w.vb(v); }, [&](int f) { return w.nb(f); }, s0, s1, A.kind() == PolytopeKind::Segment);
  } else {
    // M = B - A = -(A - B): facets of A - B with normals negated.
    const Vec3 s0 = w.vb(0), s1 = w.vb(B.numVertices() - 1);
    c = lowDimFacets(
        A, [&](int v) { return w.va(v); }, [&](int f) { return w.na(f); }, s0, s1, B.kind() == PolytopeKind::Segment);
    c.u = -c.u;
  }
  result.status = WalkStatus::Converged;
  result.depth = c.d;
  result.normal = -c.u;
  result.type = c.type;
  // Witnesses: the supporting features of both shapes in direction u.
  int ia, ib;
  w.hubFor(c.u, ia, ib, 0, 0);
  c.hubA = ia;
  c.hubB = ib;
  int next[4];
  Vec3 pA, pB;
  if (w.footInFacet(c, pA, pB, next)) {
    result.pointA = pA;
    result.pointB = pB;
  } else {
    result.pointB = w.vb(ib);
    result.pointA = result.pointB + c.d * result.normal;
  }
  result.featureA = ia;
  result.featureB = ib;
  result.stats.starts = 1;
  return true;
}

}  // namespace deepcheck::geometry::detail
