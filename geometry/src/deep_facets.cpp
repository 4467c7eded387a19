// DEEP's facets: the overlay of the local Gauss maps of a hub pair (the Gauss region of B's
// vertex clipped by the planes of A's edges), the candidate facets of M at its corners (VF, FV,
// EE), their supporting features, and the test whether a facet contains the origin's foot point.
// Vocabulary in deep_walker.h.

#include "deep_walker.h"

namespace deepcheck::geometry::detail {

// The Gauss region of B's vertex ib as a polygon of directions in frame P, with arc labels.
// Polyhedron: corners are the ring's face normals; the arc leaving corner j is the Gauss image of
// edge (ib, nbr_{j+1}). Polygon: the region is a lune between the planes orthogonal to the two
// boundary edges, through +N and -N; it is written with four corners (+N, m_next, -N, m_prev),
// m being the in-plane outward edge normals, so that no arc reaches 180 degrees.
int Walker::gaussPolygonB(int ib, const Vec3& b, Corner* poly) {
  const IndexRange nbr = B_.neighbors(ib);
  if (B_.kind() == PolytopeKind::Polyhedron) {
    const IndexRange ring = B_.vertexFaces(ib);
    const int m = ring.size();
    for (int j = 0; j < m; ++j) poly[j] = {nb(ring[j]), labelB(j + 1 == m ? 0 : j + 1)};
    return m;
  }
  // Polygon.
  const Vec3 N = nb(0);
  const Vec3 q = vb(nbr[0]) - b;
  const Vec3 p = vb(nbr[1]) - b;
  Vec3 mq = N.cross(q).normalized();
  if (mq.dot(p) > 0) mq = -mq;
  Vec3 mp = N.cross(p).normalized();
  if (mp.dot(q) > 0) mp = -mp;
  poly[0] = {N, labelB(0)};
  poly[1] = {mq, labelB(0)};
  poly[2] = {-N, labelB(1)};
  poly[3] = {mp, labelB(1)};
  return 4;
}

// Sutherland-Hodgman clipping of the direction polygon by the half-space u.h >= 0. Interpolating
// two directions linearly and renormalizing follows the great arc between them (central
// projection), so the polygon stays exact on the sphere as long as every arc is below 180 degrees.
// Writes at most n + 1 corners to `out`; returns their number.
int Walker::clip(const Corner* in, int n, Corner* out, double* side, const Vec3& h, int label) {
  // Corners are unit directions. Those within tol::kOnPlaneSine of the plane count as on it: keeps
  // boundary corners of degenerate overlays (parallel faces) instead of letting round-off decide.
  const double onPlane = -tol::kOnPlaneSine * h.norm();
  bool allIn = true;
  for (int i = 0; i < n; ++i) {
    side[i] = in[i].u.dot(h);
    allIn = allIn && side[i] >= onPlane;
  }
  if (allIn) return -1;  // nothing to cut: the caller keeps `in`
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const int j = i + 1 == n ? 0 : i + 1;
    const Corner& P = in[i];
    const Corner& Q = in[j];
    const double sP = side[i], sQ = side[j];
    const bool inP = sP >= onPlane;
    const bool inQ = sQ >= onPlane;
    if (inP) {
      out[m++] = P;
      if (!inQ) {
        const double t = std::clamp(sP / (sP - sQ), 0.0, 1.0);
        out[m++] = {(P.u + t * (Q.u - P.u)).normalized(), label};
      }
    } else if (inQ) {
      const double t = std::clamp(sP / (sP - sQ), 0.0, 1.0);
      out[m++] = {(P.u + t * (Q.u - P.u)).normalized(), P.out};
    }
  }
  return m;
}

// The Gauss region of hub pair (ia, ib): B's region of ib clipped by the planes of A's edges at
// ia. Returns its corners' count (< 3: no region) and sets *poly to them (in the scratch space).
inline int Walker::overlayRegion(int ia, int ib, const Corner** poly) {
  const Vec3 a = va(ia);
  const IndexRange nbrA = A_.neighbors(ia);
  // Room for the ring plus one corner per clipping plane, in two buffers used alternately.
  const std::size_t cap = B_.neighbors(ib).size() + nbrA.size() + 4;
  if (s_.poly.size() < cap) {
    s_.poly.resize(cap);
    s_.clipped.resize(cap);
    s_.side.resize(cap);
  }
  Corner* cur = s_.poly.data();
  Corner* spare = s_.clipped.data();
  int n = gaussPolygonB(ib, vb(ib), cur);
  for (int k = 0; k < nbrA.size() && n > 0; ++k) {
    const int m = clip(cur, n, spare, s_.side.data(), va(nbrA[k]) - a, labelA(k));
    if (m < 0) continue;
    std::swap(cur, spare);
    n = m;
  }
  *poly = cur;
  return n;
}

// Every corner of the overlay where two arcs meet is a facet of M through b - a: a face normal of
// B inside -N_A(a) (VF), minus a face normal of A inside N_B(b) (FV), or the crossing of an edge
// arc of each (EE). The best (smallest offset) goes to `best`.
bool Walker::evaluateHub(int ia, int ib, Candidate& best) {
  const Corner* poly = nullptr;
  const int n = overlayRegion(ia, ib, &poly);
  if (n < 3) return false;
  const Vec3 a = va(ia);
  const Vec3 b = vb(ib);
  const Vec3 ba = b - a;
  const IndexRange nbrA = A_.neighbors(ia);
  const IndexRange nbrB = B_.neighbors(ib);
  const bool polyB = B_.kind() == PolytopeKind::Polyhedron;
  const bool polyA = A_.kind() == PolytopeKind::Polyhedron;
  bool found = false;
  for (int i = 0; i < n; ++i) {
    const int in = poly[(i + n - 1) % n].out;
    const int out = poly[i].out;
    if (in == out) continue;  // a corner inside one arc (polygon lune), not a Gauss-map vertex
    const Vec3& approx = poly[i].u;
    WalkResult::FacetType type;
    Vec3 u;
    int fa = ia, fa2 = -1, fb = ib, fb2 = -1;
    if (!isA(in) && !isA(out)) {
      // Two arcs of B meet: a face normal of B inside -N_A(a): VF.
      if (polyB) {
        const int m = nbrB.size();
        const int kIn = labelIndex(in), kOut = labelIndex(out);
        if (kOut != (kIn + 1) % m) continue;
        fb = B_.vertexFaces(ib)[kIn];
      } else {
        fb = approx.dot(nb(0)) >= 0 ? 0 : 1;
      }
      type = WalkResult::FacetType::VF;
      u = nb(fb);
    } else if (isA(in) && isA(out)) {
      // Two clipping planes of A meet: minus a face normal of A inside N_B(b): FV.
      if (polyA) {
        const int m = nbrA.size();
        const int k1 = labelIndex(in), k2 = labelIndex(out);
        if (k2 == (k1 + 1) % m) fa = A_.vertexFaces(ia)[k1];
        else if (k1 == (k2 + 1) % m) fa = A_.vertexFaces(ia)[k2];
        else continue;
      } else {
        fa = approx.dot(na(0)) <= 0 ? 0 : 1;
      }
      type = WalkResult::FacetType::FV;
      u = -na(fa);
    } else {
      // An arc of B crosses a plane of A: edge-edge.
      fb2 = nbrB[labelIndex(isA(in) ? out : in)];
      fa2 = nbrA[labelIndex(isA(in) ? in : out)];
      const Vec3 eB = vb(fb2) - b;
      const Vec3 eA = va(fa2) - a;
      u = eB.cross(eA);
      const double len2 = u.squaredNorm();
      // Parallel edges span no facet; the facet there is reported by its VF/FV corners.
      const double minSine = tol::kParallelSine;
      if (len2 <= minSine * minSine * eB.squaredNorm() * eA.squaredNorm()) continue;
      u /= std::sqrt(len2);
      if (u.dot(approx) < 0) u = -u;
      type = WalkResult::FacetType::EE;
    }
    // The facet passes through the vertex b - a of M, so its offset is u . (b - a).
    const double d = u.dot(ba);
    if (d < best.d) {
      best.d = d;
      best.u = u;
      best.type = type;
      best.fa = fa;
      best.fa2 = fa2;
      best.fb = fb;
      best.fb2 = fb2;
      best.hubA = ia;
      best.hubB = ib;
      best.featuresKnown = true;
      found = true;
    }
  }
  return found;
}

// Vertices of P supporting the plane with normal u (B: maximizing u.x; A: minimizing), found by
// flooding the vertex graph from a supporting vertex.
void Walker::supportFeature(const ConvexPolytope& P, bool isB, int start, const Vec3& u, std::vector<int>& out) const {
  out.clear();
  auto value = [&](int v) { return isB ? u.dot(vb(v)) : -u.dot(va(v)); };
  const double top = value(start);
  out.push_back(start);
  constexpr std::size_t kMaxFeature = 512;
  for (std::size_t i = 0; i < out.size() && out.size() < kMaxFeature; ++i) {
    for (int w : P.neighbors(out[i])) {
      if (value(w) < top - tolFeature_) continue;
      if (std::find(out.begin(), out.end(), w) == out.end()) out.push_back(w);
    }
  }
}

// True when every neighbour of A's vertex v (but `except`) lies strictly above the plane through v
// with normal -u, i.e. v is alone on A's supporting plane apart from `except`.
bool Walker::aloneOnPlaneA(int v, const Vec3& u, int except) const {
  const double top = u.dot(va(v));
  for (int w : A_.neighbors(v))
    if (w != except && u.dot(va(w)) < top + tolFeature_) return false;
  return true;
}

bool Walker::aloneOnPlaneB(int v, const Vec3& u, int except) const {
  const double top = u.dot(vb(v));
  for (int w : B_.neighbors(v))
    if (w != except && u.dot(vb(w)) > top - tolFeature_) return false;
  return true;
}

// The supporting features of A and B for facet c. In general position they are known from the
// facet's type (a face and a vertex, or two edges) and only need confirming; parallel features
// (stacked boxes, parallel edges) fall back to flooding the vertex graph.
void Walker::facetFeatures(const Candidate& c) {
  auto& fa = s_.featA;
  auto& fb = s_.featB;
  fa.clear();
  fb.clear();
  bool generic = false;
  if (c.featuresKnown) switch (c.type) {
      case WalkResult::FacetType::VF:
        if (aloneOnPlaneA(c.fa, c.u, -1)) {
          fa.push_back(c.fa);
          for (int v : B_.faceVertices(c.fb)) fb.push_back(v);
          generic = true;
        }
        break;
      case WalkResult::FacetType::FV:
        if (aloneOnPlaneB(c.fb, c.u, -1)) {
          fb.push_back(c.fb);
          for (int v : A_.faceVertices(c.fa)) fa.push_back(v);
          generic = true;
        }
        break;
      case WalkResult::FacetType::EE:
        if (aloneOnPlaneA(c.fa, c.u, c.fa2) && aloneOnPlaneA(c.fa2, c.u, c.fa) && aloneOnPlaneB(c.fb, c.u, c.fb2) &&
            aloneOnPlaneB(c.fb2, c.u, c.fb)) {
          fa.push_back(c.fa);
          fa.push_back(c.fa2);
          fb.push_back(c.fb);
          fb.push_back(c.fb2);
          generic = true;
        }
        break;
    }
  if (!generic) {
    supportFeature(B_, true, c.hubB, c.u, fb);
    supportFeature(A_, false, c.hubA, c.u, fa);
  }
}

// The facet's points b - a of its supporting features, in in-plane coordinates about the foot
// point d*u (which is (0, 0)), and their convex hull (Andrew's monotone chain), counter-clockwise,
// in s_.hull.
void Walker::facetPolygon(const Candidate& c) {
  facetFeatures(c);
  Vec3 e1 = std::abs(c.u.x()) < 0.6 ? Vec3::UnitX().cross(c.u) : Vec3::UnitY().cross(c.u);
  e1.normalize();
  const Vec3 e2 = c.u.cross(e1);
  auto& pts = s_.pts;
  pts.clear();
  for (int ja : s_.featA) {
    const Vec3 a = va(ja);
    for (int jb : s_.featB) {
      const Vec3 diff = vb(jb) - a;
      pts.push_back({Vec2(e1.dot(diff), e2.dot(diff)), ja, jb});
    }
  }
  auto& hull = s_.hull;
  hull.clear();
  std::sort(pts.begin(), pts.end(), [](const FacetPoint& x, const FacetPoint& y) {
    return x.q.x() < y.q.x() || (x.q.x() == y.q.x() && x.q.y() < y.q.y());
  });
  const int np = static_cast<int>(pts.size());
  if (np == 1) {
    hull.push_back(pts[0]);
    return;
  }
  hull.resize(2 * np);
  int k = 0;
  for (int i = 0; i < np; ++i) {
    while (k >= 2 && cross2(hull[k - 1].q - hull[k - 2].q, pts[i].q - hull[k - 2].q) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (int i = np - 2, lo = k + 1; i >= 0; --i) {
    while (k >= lo && cross2(hull[k - 1].q - hull[k - 2].q, pts[i].q - hull[k - 2].q) <= 0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1);
}

void Walker::witness(const FacetPoint& x, const FacetPoint& y, const FacetPoint& z, double wx, double wy, double wz,
                     Vec3& pA, Vec3& pB) const {
  pA = wx * va(x.ia) + wy * va(y.ia) + wz * va(z.ia);
  pB = wx * vb(x.ib) + wy * vb(y.ib) + wz * vb(z.ib);
}

// A degenerate facet (an edge of M seen edge-on, or a vertex): the foot is in it when it is on
// the segment; otherwise next[] gets the segment's ends, nearest first.
bool Walker::footOnSegmentFacet(Vec3& pA, Vec3& pB, int next[4]) const {
  const auto& hull = s_.hull;
  const int nh = static_cast<int>(hull.size());
  const FacetPoint& h0 = hull[0];
  const FacetPoint& h1 = hull[nh - 1];
  const Vec2 e = h1.q - h0.q;
  const double ee = e.squaredNorm();
  const double s = ee > 0 ? std::clamp(-h0.q.dot(e) / ee, 0.0, 1.0) : 0.0;
  const Vec2 closest = h0.q + s * e;
  if (closest.norm() <= tolInside_) {
    witness(h0, h1, h1, 1 - s, s, 0, pA, pB);
    return true;
  }
  next[0] = h0.ia;
  next[1] = h0.ib;
  if (nh == 2) {
    next[2] = h1.ia;
    next[3] = h1.ib;
    if (h1.q.squaredNorm() < h0.q.squaredNorm()) {
      std::swap(next[0], next[2]);
      std::swap(next[1], next[3]);
    }
  }
  return false;
}

// The edge of the facet polygon the origin lies farthest outside of, beyond tolInside_ (signed
// distance to each edge line, positive inside), or -1 when the origin is inside.
int Walker::mostViolatedEdge() const {
  const auto& hull = s_.hull;
  const int nh = static_cast<int>(hull.size());
  int worst = -1;
  double worstDist = -tolInside_;
  for (int k = 0; k < nh; ++k) {
    const Vec2& p0 = hull[k].q;
    const Vec2 e = hull[(k + 1) % nh].q - p0;
    const double len = e.norm();
    if (len == 0) continue;
    const double dist = cross2(e, -p0) / len;
    if (dist < worstDist) {
      worstDist = dist;
      worst = k;
    }
  }
  return worst;
}

// Witnesses of a foot inside the facet polygon: barycentric coordinates in the fan triangle
// (h0, hk, hk+1) that holds it best.
void Walker::insideWitnesses(Vec3& pA, Vec3& pB) const {
  const auto& hull = s_.hull;
  const int nh = static_cast<int>(hull.size());
  int best = 1;
  double bestMin = -std::numeric_limits<double>::infinity();
  double bw[3] = {1, 0, 0};
  for (int k = 1; k + 1 < nh; ++k) {
    const Vec2 &p0 = hull[0].q, &p1 = hull[k].q, &p2 = hull[k + 1].q;
    const double area = cross2(p1 - p0, p2 - p0);
    if (area <= 0) continue;
    const double w1 = cross2(-p0, p2 - p0) / area;  // weight of p1
    const double w2 = cross2(p1 - p0, -p0) / area;  // weight of p2
    const double w0 = 1 - w1 - w2;
    const double m = std::min({w0, w1, w2});
    if (m > bestMin) {
      bestMin = m;
      best = k;
      bw[0] = w0;
      bw[1] = w1;
      bw[2] = w2;
    }
  }
  // Clamp tiny negative weights from round-off so the witnesses lie on the shapes.
  for (double& w : bw) w = std::max(w, 0.0);
  const double sum = bw[0] + bw[1] + bw[2];
  witness(hull[0], hull[best], hull[best + 1], bw[0] / sum, bw[1] / sum, bw[2] / sum, pA, pB);
}

bool Walker::footInFacet(const Candidate& c, Vec3& pA, Vec3& pB, int next[4]) {
  next[0] = next[1] = next[2] = next[3] = -1;
  facetPolygon(c);
  const auto& hull = s_.hull;
  const int nh = static_cast<int>(hull.size());
  if (nh <= 2) return footOnSegmentFacet(pA, pB, next);
  const int worst = mostViolatedEdge();
  if (worst < 0) {
    insideWitnesses(pA, pB);
    return true;
  }
  // Beyond edge `worst`: the hub pairs at its ends, nearest to the foot first.
  const FacetPoint& h0 = hull[worst];
  const FacetPoint& h1 = hull[(worst + 1) % nh];
  const bool firstNearer = h0.q.squaredNorm() <= h1.q.squaredNorm();
  const FacetPoint& n0 = firstNearer ? h0 : h1;
  const FacetPoint& n1 = firstNearer ? h1 : h0;
  next[0] = n0.ia;
  next[1] = n0.ib;
  next[2] = n1.ia;
  next[3] = n1.ib;
  return false;
}

}  // namespace deepcheck::geometry::detail
