// DEEP penetration depth. The algorithm and where it departs from the paper are described in
// deep.h; this file follows the same vocabulary:
//   M = B - A          Minkowski difference, in the pair frame P;
//   hub pair (a, b)    a vertex of A and of B such that b - a is a vertex of M;
//   C(a, b)            the Gauss region of that vertex of M: N_B(b) ∩ -N_A(a);
//   facet              a facet of M, with outward unit normal u and offset d = u . x (x on it).
// The origin is inside M when A and B overlap; the penetration depth is then min_F d_F and the
// answer's normal (from A to B) is -u.

#include "deepcheck/deep/deep.h"

#include "deepcheck/deep/tolerances.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace deepcheck::deep {
namespace {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

// Arc labels of the local Gauss map polygons: which edge's Gauss arc (or which clipping plane) a
// polygon side lies on. B-side labels name the hub's B neighbour index, A-side the A neighbour.
constexpr int kSideA = 1 << 16;
inline int labelB(int k) { return k; }
inline int labelA(int k) { return kSideA | k; }
inline bool isA(int label) { return (label & kSideA) != 0; }
inline int labelIndex(int label) { return label & (kSideA - 1); }

/// A corner of the (clipped) local Gauss map polygon: a direction, not necessarily unit length,
/// and the label of the arc that leaves it towards the next corner.
struct Corner {
  Vec3 u;
  int out;
};

struct Candidate {
  double d = std::numeric_limits<double>::infinity();
  Vec3 u = Vec3::UnitZ();
  DeepResult::FacetType type = DeepResult::FacetType::VF;
  int fa = 0, fa2 = -1, fb = 0, fb2 = -1;
  int hubA = 0, hubB = 0;
  bool featuresKnown = true;  // fa..fb2 name the facet's features (false: find them by flooding)
  bool valid() const { return std::isfinite(d); }
};

/// Vertices of the facet's supporting features, paired: point k of the facet is b[ib] - a[ia].
struct FacetPoint {
  Vec2 q;  // in-plane coordinates of b - a (the foot point of the origin is q = 0)
  int ia, ib;
};

/// Hub pairs evaluated in this query: their best candidate, and whether a walk moved through
/// them. Open addressing with generation stamps, so clearing costs nothing.
struct HubMemo {
  static constexpr int kSize = 1024;  // power of two
  struct Entry {
    std::uint64_t key = 0;
    std::uint32_t gen = 0;
    bool evaluated = false;
    bool valid = false;    // the hub has a Gauss region (a best candidate)
    bool visited = false;  // a walk adopted this hub's best candidate
    Candidate best;
  };
  std::vector<Entry> table = std::vector<Entry>(kSize);
  std::uint32_t gen = 1;
  int used = 0;

  void clear() {
    ++gen;
    used = 0;
  }
  static std::uint64_t slot(std::uint64_t key) { return (key * 0x9E3779B97F4A7C15ull) >> 54; }
  static constexpr int kMaxProbe = 32;
  /// The entry for key, or null when it is not in the table.
  Entry* lookup(std::uint64_t key) {
    std::uint64_t h = slot(key);
    for (int probe = 0; probe < kMaxProbe; ++probe, h = (h + 1) & (kSize - 1)) {
      Entry& e = table[h];
      if (e.gen != gen) return nullptr;
      if (e.key == key) return &e;
    }
    return nullptr;
  }
  /// The entry for key, created (unevaluated, unvisited) if absent; null when the table is too
  /// full, in which case nothing more is memoized in this query.
  Entry* insert(std::uint64_t key) {
    std::uint64_t h = slot(key);
    for (int probe = 0; probe < kMaxProbe; ++probe, h = (h + 1) & (kSize - 1)) {
      Entry& e = table[h];
      if (e.gen != gen) {
        if (used >= kSize / 2) return nullptr;
        ++used;
        e.gen = gen;
        e.key = key;
        e.evaluated = false;
        e.valid = false;
        e.visited = false;
        return &e;
      }
      if (e.key == key) return &e;
    }
    return nullptr;
  }
};

/// Per-thread scratch space, grown on demand and never shrunk: a warm query does not allocate.
struct Scratch {
  std::vector<Corner> poly, clipped;
  std::vector<double> side;
  std::vector<int> featA, featB;
  std::vector<FacetPoint> pts, hull;
  HubMemo memo;
  // B's vertices and face normals in frame P, transformed on first use in a query.
  std::vector<Vec3> bVertex, bNormal;
  std::vector<std::uint32_t> bVertexGen, bNormalGen;
  std::uint32_t gen = 0;
};

Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

/// Everything a walk needs about the pair, in frame P.
class Walker {
 public:
  Walker(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& F)
      : A_(A), B_(B), F_(F), s_(scratch()) {
    if (++s_.gen == 0) {  // wrapped: invalidate every stamp
      std::fill(s_.bVertexGen.begin(), s_.bVertexGen.end(), 0);
      std::fill(s_.bNormalGen.begin(), s_.bNormalGen.end(), 0);
      s_.gen = 1;
    }
    if (static_cast<int>(s_.bVertexGen.size()) < B.numVertices()) {
      s_.bVertex.resize(B.numVertices());
      s_.bVertexGen.resize(B.numVertices(), 0);
    }
    if (static_cast<int>(s_.bNormalGen.size()) < B.numFaces()) {
      s_.bNormal.resize(B.numFaces());
      s_.bNormalGen.resize(B.numFaces(), 0);
    }
    s_.memo.clear();
    L_ = std::max(A.lengthScale(), B.lengthScale()) + F.t.norm();
    tolFeature_ = tol::kFeatureRelative * L_;
    tolImprove_ = tol::kImproveRelative * L_;
    tolInside_ = tol::kInsideRelative * L_;
  }

  const Vec3& va(int i) const { return A_.localVertex(i); }
  const Vec3& vb(int j) const {
    if (s_.bVertexGen[j] != s_.gen) {
      s_.bVertex[j] = F_.vertexB(B_, j);
      s_.bVertexGen[j] = s_.gen;
    }
    return s_.bVertex[j];
  }
  const Vec3& na(int f) const { return A_.faceNormal(f); }
  const Vec3& nb(int f) const {
    if (s_.bNormalGen[f] != s_.gen) {
      s_.bNormal[f] = F_.R * B_.faceNormal(f);
      s_.bNormalGen[f] = s_.gen;
    }
    return s_.bNormal[f];
  }

  /// Hub pair extreme in direction u: b maximizes u.b, a minimizes u.a.
  void hubFor(const Vec3& u, int& ia, int& ib, int hintA, int hintB) const {
    ia = A_.support(-u, hintA);
    ib = B_.support(F_.toB(u), hintB);
  }

  bool evaluateHub(int ia, int ib, Candidate& best);
  /// Tests whether the facet contains its foot point. If it does, fills the witnesses and returns
  /// true. Otherwise returns false and the hub pairs at the ends of the facet edge the foot lies
  /// beyond (nearest first; second may be -1).
  bool footInFacet(const Candidate& c, Vec3& pA, Vec3& pB, int next[4]);

  /// Best candidate of hub pair (ia, ib), memoized for the query. Returns false when the hub
  /// pair has no Gauss region (b - a is not a vertex of M).
  bool hub(int ia, int ib, Candidate& best, DeepStats& stats) {
    HubMemo::Entry* e = s_.memo.insert(key(ia, ib));
    if (e && e->evaluated) {
      if (e->valid) best = e->best;
      return e->valid;
    }
    ++stats.hubs;
    Candidate c;
    const bool ok = evaluateHub(ia, ib, c);
    if (e) {
      e->evaluated = true;
      e->valid = ok;
      e->best = c;
    }
    if (ok) best = c;
    return ok;
  }
  /// Hub pairs a walk moved through (adopted the best candidate of). A later walk reaching one
  /// follows the same path from there, so it stops.
  static std::uint64_t key(int ia, int ib) {
    return (static_cast<std::uint64_t>(ia) << 32) | static_cast<std::uint32_t>(ib);
  }
  bool isVisited(int ia, int ib) {
    const HubMemo::Entry* e = s_.memo.lookup(key(ia, ib));
    return e && e->visited;
  }
  void markVisited(int ia, int ib) {
    if (HubMemo::Entry* e = s_.memo.insert(key(ia, ib))) e->visited = true;
  }
  /// Corners of the facet last examined by footInFacet (hub pairs of M's vertices on it).
  int numFacetCorners() const { return static_cast<int>(s_.hull.size()); }
  void facetCorner(int k, int& ia, int& ib) const {
    ia = s_.hull[k].ia;
    ib = s_.hull[k].ib;
  }
  double lengthScale() const { return L_; }
  double tolImprove() const { return tolImprove_; }

 private:
  int gaussPolygonB(int ib, const Vec3& b, Corner* poly);
  int clip(const Corner* in, int n, Corner* out, double* side, const Vec3& h, int label);
  void supportFeature(const ConvexPolytope& P, bool isB, int start, const Vec3& u, std::vector<int>& out) const;
  void facetFeatures(const Candidate& c);
  bool aloneOnPlaneA(int v, const Vec3& u, int except) const;
  bool aloneOnPlaneB(int v, const Vec3& u, int except) const;

  const ConvexPolytope& A_;
  const ConvexPolytope& B_;
  const PairFrame& F_;
  Scratch& s_;
  double L_ = 1.0;
  double tolFeature_ = 0.0;
  double tolImprove_ = 0.0;
  double tolInside_ = 0.0;
};

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
  // Corners are unit directions. Those within this angle of the plane count as on it: keeps
  // boundary corners of degenerate overlays (parallel faces) instead of letting round-off decide.
  constexpr double kOnPlane = 1e-13;
  const double onPlane = -kOnPlane * h.norm();
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

bool Walker::evaluateHub(int ia, int ib, Candidate& best) {
  const Vec3 a = va(ia);
  const Vec3 b = vb(ib);
  const Vec3 ba = b - a;
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
  int n = gaussPolygonB(ib, b, cur);
  for (int k = 0; k < nbrA.size() && n > 0; ++k) {
    const int m = clip(cur, n, spare, s_.side.data(), va(nbrA[k]) - a, labelA(k));
    if (m < 0) continue;
    std::swap(cur, spare);
    n = m;
  }
  if (n < 3) return false;
  const Corner* poly = cur;

  const IndexRange nbrB = B_.neighbors(ib);
  const bool polyB = B_.kind() == PolytopeKind::Polyhedron;
  const bool polyA = A_.kind() == PolytopeKind::Polyhedron;
  bool found = false;
  for (int i = 0; i < n; ++i) {
    const int in = poly[(i + n - 1) % n].out;
    const int out = poly[i].out;
    if (in == out) continue;  // a corner inside one arc (polygon lune), not a Gauss-map vertex
    const Vec3& approx = poly[i].u;
    DeepResult::FacetType type;
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
      type = DeepResult::FacetType::VF;
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
      type = DeepResult::FacetType::FV;
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
      type = DeepResult::FacetType::EE;
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
void Walker::supportFeature(const ConvexPolytope& P, bool isB, int start, const Vec3& u,
                            std::vector<int>& out) const {
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
    case DeepResult::FacetType::VF:
      if (aloneOnPlaneA(c.fa, c.u, -1)) {
        fa.push_back(c.fa);
        for (int v : B_.faceVertices(c.fb)) fb.push_back(v);
        generic = true;
      }
      break;
    case DeepResult::FacetType::FV:
      if (aloneOnPlaneB(c.fb, c.u, -1)) {
        fb.push_back(c.fb);
        for (int v : A_.faceVertices(c.fa)) fa.push_back(v);
        generic = true;
      }
      break;
    case DeepResult::FacetType::EE:
      if (aloneOnPlaneA(c.fa, c.u, c.fa2) && aloneOnPlaneA(c.fa2, c.u, c.fa) &&
          aloneOnPlaneB(c.fb, c.u, c.fb2) && aloneOnPlaneB(c.fb2, c.u, c.fb)) {
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

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

bool Walker::footInFacet(const Candidate& c, Vec3& pA, Vec3& pB, int next[4]) {
  next[0] = next[1] = next[2] = next[3] = -1;
  facetFeatures(c);

  // In-plane basis; the foot point d*u has in-plane coordinates (0, 0).
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

  // Convex hull of the facet's points (Andrew's monotone chain), counter-clockwise.
  auto& hull = s_.hull;
  hull.clear();
  std::sort(pts.begin(), pts.end(), [](const FacetPoint& x, const FacetPoint& y) {
    return x.q.x() < y.q.x() || (x.q.x() == y.q.x() && x.q.y() < y.q.y());
  });
  const int np = static_cast<int>(pts.size());
  if (np == 1) {
    hull.push_back(pts[0]);
  } else {
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
  const int nh = static_cast<int>(hull.size());

  auto witness = [&](const FacetPoint& x, const FacetPoint& y, const FacetPoint& z, double wx,
                     double wy, double wz) {
    pA = wx * va(x.ia) + wy * va(y.ia) + wz * va(z.ia);
    pB = wx * vb(x.ib) + wy * vb(y.ib) + wz * vb(z.ib);
  };

  if (nh <= 2) {
    // A degenerate facet (an edge of M seen edge-on): the foot is in it when it is on the segment.
    const FacetPoint& h0 = hull[0];
    const FacetPoint& h1 = hull[nh - 1];
    const Vec2 e = h1.q - h0.q;
    const double ee = e.squaredNorm();
    const double s = ee > 0 ? std::clamp(-h0.q.dot(e) / ee, 0.0, 1.0) : 0.0;
    const Vec2 closest = h0.q + s * e;
    if (closest.norm() <= tolInside_) {
      witness(h0, h1, h1, 1 - s, s, 0);
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

  // Most violated edge: signed distance of the origin to each edge line (positive inside).
  int worst = -1;
  double worstDist = -tolInside_;
  for (int k = 0; k < nh; ++k) {
    const Vec2& p0 = hull[k].q;
    const Vec2& p1 = hull[(k + 1) % nh].q;
    const Vec2 e = p1 - p0;
    const double len = e.norm();
    if (len == 0) continue;
    const double dist = cross2(e, -p0) / len;
    if (dist < worstDist) {
      worstDist = dist;
      worst = k;
    }
  }
  if (worst < 0) {
    // Inside: barycentric coordinates in the fan triangle (h0, hk, hk+1) containing the origin.
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
    witness(hull[0], hull[best], hull[best + 1], bw[0] / sum, bw[1] / sum, bw[2] / sum);
    return true;
  }
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

/// Result of one walk.
struct WalkEnd {
  Candidate facet;
  Vec3 pA = Vec3::Zero(), pB = Vec3::Zero();
  bool converged = false;  // ended at a facet containing its foot point
  bool joined = false;     // stopped on reaching a hub pair an earlier walk visited
  bool witnessed = false;
};

WalkEnd walk(Walker& w, Candidate start, int maxHubs, DeepStats& stats) {
  WalkEnd end;
  end.facet = start;
  int next[4];
  // Hub pairs at the corners of the current facet, copied out of the scratch space.
  constexpr int kMaxCorners = 64;
  int cornerA[kMaxCorners], cornerB[kMaxCorners];
  for (int hubs = 0; hubs < maxHubs;) {
    if (w.footInFacet(end.facet, end.pA, end.pB, next)) {
      // The foot is in the facet (a KKT point). A facet sharing one of its corners may still lie
      // closer to the origin; only when none does is this a local minimum of the walk.
      end.witnessed = true;
      const int nc = std::min(w.numFacetCorners(), kMaxCorners);
      for (int k = 0; k < nc; ++k) w.facetCorner(k, cornerA[k], cornerB[k]);
      Candidate bestNear;
      for (int k = 0; k < nc; ++k) {
        if (w.isVisited(cornerA[k], cornerB[k])) continue;
        Candidate c;
        ++hubs;
        if (w.hub(cornerA[k], cornerB[k], c, stats) && c.d < bestNear.d) bestNear = c;
      }
      if (bestNear.valid() && bestNear.d < end.facet.d - w.tolImprove()) {
        w.markVisited(bestNear.hubA, bestNear.hubB);
        end.facet = bestNear;
        end.witnessed = false;
        ++stats.steps;
        continue;
      }
      end.converged = true;
      return end;
    }
    end.witnessed = false;
    bool moved = false;
    for (int option = 0; option < 2 && !moved; ++option) {
      const int ia = next[2 * option], ib = next[2 * option + 1];
      if (ia < 0) continue;
      if (w.isVisited(ia, ib)) {
        // An earlier walk moved through this hub pair: from here on it follows the same path.
        end.joined = true;
        return end;
      }
      Candidate c;
      ++hubs;
      if (w.hub(ia, ib, c, stats) && c.d < end.facet.d - w.tolImprove()) {
        w.markVisited(ia, ib);
        end.facet = c;
        ++stats.steps;
        moved = true;
      }
    }
    if (!moved) {
      // The foot lies outside the facet, yet no neighbour improves by more than round-off:
      // a numerically flat spot. The facet is still a valid separating direction.
      end.converged = true;
      return end;
    }
  }
  return end;
}

// ---------------------------------------------------------------------------------------------
// Points and segments: M = X - S has O(F + E) facets, enumerated directly.

struct LowDimAnswer {
  Candidate facet;
  bool flat = false;  // M has no interior: depth 0
};

/// Facets of M = X (+) (-S), X a polygon or polyhedron, S a point or segment given by its
/// vertices s0, s1 (equal for a point), all in frame P. `xVertex`/`xNormal` map X's vertex and
/// face normal into P. Returns the facet of smallest offset.
template <class VertexFn, class NormalFn>
Candidate lowDimFacets(const ConvexPolytope& X, VertexFn xVertex, NormalFn xNormal, const Vec3& s0,
                       const Vec3& s1, bool segment) {
  Candidate best;
  auto consider = [&](const Vec3& u, const Vec3& onX, DeepResult::FacetType type) {
    const Vec3 s = u.dot(s0) <= u.dot(s1) ? s0 : s1;  // support of S in -u
    const double d = u.dot(onX - s);
    if (d < best.d) {
      best.d = d;
      best.u = u;
      best.type = type;
      best.featuresKnown = false;
    }
  };
  for (int f = 0; f < X.numFaces(); ++f) consider(xNormal(f), xVertex(X.faceVertices(f)[0]), DeepResult::FacetType::VF);
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
      if (onArc) consider(u, xv, DeepResult::FacetType::EE);
    }
  }
  return best;
}

bool isLowDim(const ConvexPolytope& P) {
  return P.kind() == PolytopeKind::Point || P.kind() == PolytopeKind::Segment;
}

}  // namespace

DeepResult deepPenetration(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                           DeepCache* cache, const DeepOptions& options) {
  DeepResult result;
  Walker w(A, B, frame);

  // Lower-dimensional Minkowski differences: no interior, the depth is zero.
  const bool flatPair =
      (isLowDim(A) && isLowDim(B)) ||
      (isLowDim(A) && B.kind() == PolytopeKind::Polygon && A.kind() == PolytopeKind::Point) ||
      (isLowDim(B) && A.kind() == PolytopeKind::Polygon && B.kind() == PolytopeKind::Point) ||
      (A.kind() == PolytopeKind::Polygon && B.kind() == PolytopeKind::Polygon &&
       A.faceNormal(0).cross(frame.R * B.faceNormal(0)).norm() < tol::kParallelSine);
  if (flatPair) {
    Vec3 u = Vec3::UnitZ();
    if (A.kind() == PolytopeKind::Polygon) u = A.faceNormal(0);
    else if (B.kind() == PolytopeKind::Polygon) u = frame.R * B.faceNormal(0);
    else if (A.kind() == PolytopeKind::Segment && B.kind() == PolytopeKind::Segment) {
      const Vec3 c = (w.va(1) - w.va(0)).cross(w.vb(1) - w.vb(0));
      if (c.norm() > 0) u = c.normalized();
    }
    result.status = DeepStatus::Converged;
    result.depth = 0;
    result.normal = -u;
    result.pointA = w.va(0);
    result.pointB = result.pointA;
    return result;
  }

  if (isLowDim(A) || isLowDim(B)) {
    // One side is a point or segment, the other a polygon or polyhedron.
    const bool aLow = isLowDim(A);
    Candidate c;
    if (aLow) {
      const Vec3 s0 = w.va(0), s1 = w.va(A.numVertices() - 1);
      c = lowDimFacets(B, [&](int v) { return w.vb(v); }, [&](int f) { return w.nb(f); }, s0, s1,
                       A.kind() == PolytopeKind::Segment);
    } else {
      // M = B - A = -(A - B): facets of A - B with normals negated.
      const Vec3 s0 = w.vb(0), s1 = w.vb(B.numVertices() - 1);
      c = lowDimFacets(A, [&](int v) { return w.va(v); }, [&](int f) { return w.na(f); }, s0, s1,
                       B.kind() == PolytopeKind::Segment);
      c.u = -c.u;
    }
    result.status = DeepStatus::Converged;
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
    return result;
  }

  // General case: walks on the Minkowski difference.
  DeepStats& stats = result.stats;
  WalkEnd best;
  best.facet.d = std::numeric_limits<double>::infinity();
  // Where walks ended: to count those that stopped in a worse local minimum, and to remember
  // the best distinct ones as basins for the next warm query.
  constexpr int kMaxEnds = 32;
  Candidate ends[kMaxEnds];
  int ended = 0;

  auto runFrom = [&](int ia, int ib) {
    if (w.isVisited(ia, ib)) return;
    w.markVisited(ia, ib);
    Candidate c;
    if (!w.hub(ia, ib, c, stats)) return;
    ++stats.starts;
    WalkEnd e = walk(w, c, options.maxHubsPerWalk, stats);
    if (!e.joined && ended < kMaxEnds) ends[ended++] = e.facet;
    if (e.facet.d < best.facet.d || (e.facet.d == best.facet.d && e.witnessed && !best.witnessed)) best = e;
  };

  const Vec3 centroidDir = frame.t.norm() > 0 ? Vec3(-frame.t.normalized()) : Vec3(Vec3::UnitZ());
  const bool warm = options.warmStart && cache && cache->valid && cache->count > 0 &&
                    (options.refreshEvery <= 0 || cache->warmQueries < options.refreshEvery);
  int ia = 0, ib = 0;
  if (warm) {
    stats.warm = true;
    for (int k = 0; k < cache->count; ++k) {
      const int hintA = std::clamp(cache->hubA[k], 0, A.numVertices() - 1);
      const int hintB = std::clamp(cache->hubB[k], 0, B.numVertices() - 1);
      w.hubFor(cache->u[k], ia, ib, hintA, hintB);
      runFrom(ia, ib);
    }
    if (options.warmCentroidStart) {
      w.hubFor(centroidDir, ia, ib, ia, ib);
      runFrom(ia, ib);
    }
  } else {
    // The origin lies off M's centre by -t: the nearest boundary is most likely that way.
    w.hubFor(centroidDir, ia, ib, 0, 0);
    runFrom(ia, ib);
    if (options.restarts) {
      // The other starts: the opposite direction and both signs of each shape's principal axes.
      constexpr int kStarts = 13;
      Vec3 dirs[kStarts];
      dirs[0] = -centroidDir;
      const Eigen::Matrix3d axesA = A.principalAxes();
      const Eigen::Matrix3d axesB = frame.R * B.principalAxes();
      for (int k = 0; k < 3; ++k) {
        dirs[1 + 4 * k] = axesA.col(k);
        dirs[2 + 4 * k] = -axesA.col(k);
        dirs[3 + 4 * k] = axesB.col(k);
        dirs[4 + 4 * k] = -axesB.col(k);
      }
      int hubsA[kStarts], hubsB[kStarts], order[kStarts];
      double offset[kStarts];
      for (int k = 0; k < kStarts; ++k) {
        w.hubFor(dirs[k], hubsA[k], hubsB[k], ia, ib);
        ia = hubsA[k];
        ib = hubsB[k];
        offset[k] = dirs[k].dot(w.vb(ib) - w.va(ia));
        order[k] = k;
      }
      if (options.pruneRestarts)
        std::sort(order, order + kStarts, [&](int x, int y) { return offset[x] < offset[y]; });
      for (int j = 0; j < kStarts; ++j) {
        const int k = order[j];
        if (options.pruneRestarts && offset[k] >= best.facet.d - w.tolImprove()) break;
        runFrom(hubsA[k], hubsB[k]);
      }
    }
  }

  for (int k = 0; k < ended; ++k)
    if (ends[k].d > best.facet.d + w.tolImprove()) ++stats.localMinima;

  const Candidate& f = best.facet;
  result.status = best.converged ? DeepStatus::Converged : DeepStatus::NotConverged;
  result.depth = f.d;
  result.normal = -f.u;
  result.type = f.type;
  result.featureA = f.fa;
  result.featureA2 = f.fa2;
  result.featureB = f.fb;
  result.featureB2 = f.fb2;
  if (best.witnessed) {
    result.pointA = best.pA;
    result.pointB = best.pB;
  } else {
    int next[4];
    Vec3 pA, pB;
    if (w.footInFacet(f, pA, pB, next)) {
      result.pointA = pA;
      result.pointB = pB;
    } else {
      result.pointB = w.vb(f.hubB);
      result.pointA = result.pointB + f.d * result.normal;
    }
  }
  if (cache) {
    // Basins for the next warm query: the answer first, then the best other distinct ends.
    cache->valid = true;
    cache->warmQueries = warm ? cache->warmQueries + 1 : 0;
    cache->count = 0;
    auto remember = [&](const Candidate& c) {
      for (int k = 0; k < cache->count; ++k)
        if (cache->hubA[k] == c.hubA && cache->hubB[k] == c.hubB) return;
      if (cache->count == DeepCache::kBasins) return;
      cache->hubA[cache->count] = c.hubA;
      cache->hubB[cache->count] = c.hubB;
      cache->u[cache->count] = c.u;
      ++cache->count;
    };
    remember(f);
    std::sort(ends, ends + ended, [](const Candidate& x, const Candidate& y) { return x.d < y.d; });
    for (int k = 0; k < ended; ++k) remember(ends[k]);
  }
  return result;
}

}  // namespace deepcheck::deep
