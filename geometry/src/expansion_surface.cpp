#include "deepcheck/geometry/internal/expansion_surface.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace deepcheck::geometry::detail {
namespace {

using Vec3 = Eigen::Vector3d;

// Min-heap order on the plane distance.
struct Farther {
  template <class E>
  bool operator()(const E& x, const E& y) const {
    return x.d > y.d;
  }
};

/// The normal of the plane through p0, p1, p2 (counter-clockwise seen from outside), not
/// normalised: its length is twice the triangle's area.
Vec3 crossOfCorners(const Vec3& p0, const Vec3& p1, const Vec3& p2) { return (p1 - p0).cross(p2 - p0); }

/// Whether a plane normal's squared length can be normalised: non-zero and finite.
bool normalisable(double square) { return square > 0.0 && square <= std::numeric_limits<double>::max(); }

/// Sets n and d from the unnormalised normal m of the plane through p0, p1, p2 and `inverse`
/// (1 / |m|): d is the mean of the corners' offsets. planeThrough() does the same arithmetic.
void scalePlane(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& m, double inverse, Vec3& n, double& d) {
  d = m.dot(p0 + p1 + p2) * (inverse * (1.0 / 3.0));
  n = m * inverse;
}

/// 1 / sqrt(s0) and 1 / sqrt(s1) in one packed square root and one packed division where SSE2
/// has them. Both are correctly rounded, so the bits are those of two scalar ones. The square root
/// and the division are a plane's slowest steps, and a packed one takes about a scalar one's time.
void inverseLengths(double s0, double s1, double& i0, double& i1) {
#if defined(__SSE2__)
  const __m128d inverse = _mm_div_pd(_mm_set1_pd(1.0), _mm_sqrt_pd(_mm_set_pd(s1, s0)));
  i0 = _mm_cvtsd_f64(inverse);
  i1 = _mm_cvtsd_f64(_mm_unpackhi_pd(inverse, inverse));
#else
  i0 = 1.0 / std::sqrt(s0);
  i1 = 1.0 / std::sqrt(s1);
#endif
}

}  // namespace

void ExpansionSurface::link(Face* faces, int f, int e, int g, int h) {
  faces[f].adj[e] = 4 * g + h;
  faces[g].adj[h] = 4 * f + e;
}

bool ExpansionSurface::planeThrough(const Vec3& p0, const Vec3& p1, const Vec3& p2, Vec3& n, double& d) {
  n = crossOfCorners(p0, p1, p2);
  const double square = n.squaredNorm();
  if (!normalisable(square)) return false;
  // scalePlane()'s arithmetic written out inline, since the warm query calls this on its critical
  // path; the same operations in the same order, so both give the same bits.
  const double inverse = 1.0 / std::sqrt(square);
  d = n.dot(p0 + p1 + p2) * (inverse * (1.0 / 3.0));
  n *= inverse;
  return true;
}

bool ExpansionSurface::setPlanes(Face* faces, int count) const {
  int i = 0;
  for (; i + 1 < count; i += 2) {  // two faces at a time (inverseLengths), as planeThrough() each
    Face& f = faces[i];
    Face& g = faces[i + 1];
    const Vec3 &p0 = vertices_[f.v[0]].p, &p1 = vertices_[f.v[1]].p, &p2 = vertices_[f.v[2]].p;
    const Vec3 &q0 = vertices_[g.v[0]].p, &q1 = vertices_[g.v[1]].p, &q2 = vertices_[g.v[2]].p;
    const Vec3 mf = crossOfCorners(p0, p1, p2), mg = crossOfCorners(q0, q1, q2);
    const double sf = mf.squaredNorm(), sg = mg.squaredNorm();
    if (!normalisable(sf) || !normalisable(sg)) return false;
    double inverseF, inverseG;
    inverseLengths(sf, sg, inverseF, inverseG);
    scalePlane(p0, p1, p2, mf, inverseF, f.n, f.d);
    scalePlane(q0, q1, q2, mg, inverseG, g.n, g.d);
  }
  if (i < count) {
    Face& f = faces[i];
    return planeThrough(vertices_[f.v[0]].p, vertices_[f.v[1]].p, vertices_[f.v[2]].p, f.n, f.d);
  }
  return true;
}

void ExpansionSurface::push(int f) {
  if (!(faces_[f].d < queueLimit_)) return;  // never expanded; bestFace() finds it when nearest
  if (queueSize_ == kMaxQueue) rebuildQueue();
  // std::push_heap's sift-up, the new entry kept in registers (storing it first and reading it
  // back stalls on store forwarding): the same heap as std::push_heap makes.
  const QueueEntry e{faces_[f].d, f, faces_[f].serial};
  int i = queueSize_++;
  while (i > 0) {
    const int parent = (i - 1) / 2;
    if (!Farther{}(queue_[parent], e)) break;
    queue_[i] = queue_[parent];
    i = parent;
  }
  queue_[i] = e;
}

void ExpansionSurface::rebuildQueue() {
  queueSize_ = 0;
  for (int f = 0; f < numSlots_; ++f)
    if (faces_[f].alive && faces_[f].d < queueLimit_) queue_[queueSize_++] = {faces_[f].d, f, faces_[f].serial};
  std::make_heap(queue_, queue_ + queueSize_, Farther{});
}

int ExpansionSurface::newFace(int v0, int v1, int v2) {
  const int f = numFree_ > 0 ? freeList_[--numFree_] : numSlots_++;
  Face& face = faces_[f];
  face.v[0] = v0;
  face.v[1] = v1;
  face.v[2] = v2;
  face.serial = ++serial_;
  face.alive = true;
  ++live_;
  return f;
}

void ExpansionSurface::freeFace(int f) {
  freeList_[numFree_++] = f;
  --live_;
}

bool ExpansionSurface::startTetrahedron(const Vertex* corners) {
  numVertices_ = numSlots_ = numFree_ = queueSize_ = live_ = 0;
  queueLimit_ = std::numeric_limits<double>::infinity();
  convex_ = true;
  for (int i = 0; i < 4; ++i) vertices_[numVertices_++] = corners[i];
  const Vec3& p0 = corners[0].p;
  const double volume = (corners[1].p - p0).cross(corners[2].p - p0).dot(corners[3].p - p0);
  if (!(volume != 0.0) || !std::isfinite(volume)) return false;
  // With positive volume, (0, 2, 1) is counter-clockwise seen from outside (vertex 3 behind it).
  const int a = volume > 0 ? 1 : 2, b = volume > 0 ? 2 : 1;
  const int f0 = newFace(0, b, a), f1 = newFace(0, a, 3), f2 = newFace(a, b, 3), f3 = newFace(b, 0, 3);
  // Edges: f0 (0,b)(b,a)(a,0); f1 (0,a)(a,3)(3,0); f2 (a,b)(b,3)(3,a); f3 (b,0)(0,3)(3,b).
  link(faces_, f0, 0, f3, 0);
  link(faces_, f0, 1, f2, 0);
  link(faces_, f0, 2, f1, 0);
  link(faces_, f1, 1, f2, 2);
  link(faces_, f1, 2, f3, 1);
  link(faces_, f2, 1, f3, 2);
  if (!setPlanes(faces_, 4)) return false;  // the four were the first slots
  for (int f : {f0, f1, f2, f3}) push(f);
  return true;
}

bool ExpansionSurface::loadFaces(const Vertex* vertices, int numVertices, const int (*faces)[3], const int (*adj)[3],
                                 int numFaces) {
  numVertices_ = numSlots_ = numFree_ = queueSize_ = live_ = 0;
  queueLimit_ = std::numeric_limits<double>::infinity();
  if (numVertices > kMaxVertices || numFaces > kMaxFaces) return false;
  std::copy(vertices, vertices + numVertices, vertices_);
  numVertices_ = numVertices;
  for (int f = 0; f < numFaces; ++f) {
    Face& face = faces_[newFace(faces[f][0], faces[f][1], faces[f][2])];  // slot f
    std::copy(adj[f], adj[f] + 3, face.adj);
  }
  if (!setPlanes(faces_, numFaces)) {
    numVertices_ = numSlots_ = live_ = 0;
    return false;
  }
  return true;
}

bool ExpansionSurface::load(const Vertex* vertices, int numVertices, const int (*faces)[3], const int (*adj)[3],
                            int numFaces) {
  convex_ = false;
  if (!loadFaces(vertices, numVertices, faces, adj, numFaces)) return false;
  rebuildQueue();
  return true;
}

bool ExpansionSurface::startConvex(const Vertex* vertices, int numVertices, const int (*faces)[3], const int (*adj)[3],
                                   int numFaces, double eps) {
  convex_ = true;
  if (!loadFaces(vertices, numVertices, faces, adj, numFaces) || !enclosesConvexly(eps)) {
    numVertices_ = numSlots_ = live_ = 0;
    return false;
  }
  rebuildQueue();
  return true;
}

// Every face plane beyond eps from the origin, every vertex on or inside every face plane. A
// vertex of the face itself may be off its plane by round-off (the plane's offset is the mean of
// its corners'), so the test compares with the face's own corners' largest offset.
bool ExpansionSurface::enclosesConvexly(double eps) const {
  for (int f = 0; f < numSlots_; ++f) {
    const Face& face = faces_[f];
    if (!(face.d > eps)) return false;
    double top = face.d;
    for (int k = 0; k < 3; ++k) top = std::max(top, face.n.dot(vertices_[face.v[k]].p));
    for (int v = 0; v < numVertices_; ++v)
      if (face.n.dot(vertices_[v].p) > top) return false;
  }
  return true;
}

int ExpansionSurface::bestFace() {
  while (queueSize_ > 0) {
    const QueueEntry& top = queue_[0];
    const Face& f = faces_[top.face];
    if (f.alive && f.serial == top.serial) {
      if (top.d < queueLimit_) return top.face;
      break;
    }
    std::pop_heap(queue_, queue_ + queueSize_, Farther{});
    --queueSize_;
  }
  // Every face left, queued or not, is at or beyond the limit: the nearest of them all (usually
  // once per query, when the caller is about to stop).
  int best = -1;
  for (int f = 0; f < numSlots_; ++f)
    if (faces_[f].alive && (best < 0 || faces_[f].d < faces_[best].d)) best = f;
  return best;
}

void ExpansionSurface::setQueueLimit(double limit) { queueLimit_ = std::min(queueLimit_, limit); }

bool ExpansionSurface::isCorner(int f, const Vertex& w) const {
  for (int k = 0; k < 3; ++k) {
    const Vertex& c = vertices_[faces_[f].v[k]];
    if (c.a == w.a && c.b == w.b) return true;
  }
  return false;
}

// Depth-first search from face `from` over the faces that see w; faces that do not see w but
// border one that does give the horizon edges. Seen faces are marked dead (restored by the
// caller on failure) and listed in seen_.
bool ExpansionSurface::collectHorizon(int from, const Vec3& w) {
  // Counters in locals, stored once at the end: the members could alias the arrays written in
  // the loop, which would keep them in memory on its dependency chain.
  int numSeen = 0, numHorizon = 0, numPending = 0;
  bool fits = true;
  faces_[from].alive = false;
  seen_[numSeen++] = from;
  for (int e = 2; e >= 0; --e) pending_[numPending++] = faces_[from].adj[e];
  while (numPending > 0) {
    const int code = pending_[--numPending];
    const int g = code >> 2, e = code & 3;
    Face& face = faces_[g];
    if (!face.alive) continue;
    const int next = e == 2 ? 0 : e + 1, previous = e == 0 ? 2 : e - 1;
    if (face.n.dot(w) > face.d) {
      face.alive = false;
      seen_[numSeen++] = g;
      pending_[numPending++] = face.adj[previous];
      pending_[numPending++] = face.adj[next];
    } else {
      if (numHorizon == kMaxHorizon) {
        fits = false;
        break;
      }
      horizon_[numHorizon++] = {g, e, face.v[e], face.v[next]};
    }
  }
  numSeen_ = numSeen;
  horizonSize_ = numHorizon;
  return fits && numHorizon >= 3;
}

// The search walks the seen region's boundary in order, so edge i + 1 usually ends where edge i
// starts. When every consecutive pair, the last and the first included, chains so and no vertex
// starts two edges, the horizon is one cycle in that order: checked in one pass, with a flag per
// vertex (cleared again before returning). Otherwise horizonIsCycle() decides.
bool ExpansionSurface::horizonChains() {
  const HorizonEdge* h = horizon_;
  const int n = horizonSize_;
  bool chains = h[0].to == h[n - 1].from;
  for (int i = 0; i + 1 < n; ++i) chains &= h[i + 1].to == h[i].from;
  if (!chains) return false;
  int i = 0;
  for (; i < n && !onHorizon_[h[i].from]; ++i) onHorizon_[h[i].from] = true;
  const bool simple = i == n;
  for (int k = 0; k < i; ++k) onHorizon_[h[k].from] = false;
  return simple;
}

// Follows the horizon from its first edge, each time to the first edge that starts where the
// last one ended: one cycle through all edges exactly when it returns to the first after visiting
// every edge. (A vertex starting two edges sends every walk through the same, lower-numbered one,
// so the other is never visited; several cycles leave edges unvisited too.)
bool ExpansionSurface::horizonIsCycle() const {
  int length = 0, i = 0;
  do {
    int next = 0;
    while (next < horizonSize_ && horizon_[next].from != horizon_[i].to) ++next;
    if (next == horizonSize_) return false;
    i = next;
    ++length;
  } while (i != 0 && length <= horizonSize_);
  return length == horizonSize_;
}

bool ExpansionSurface::keepsOrigin(int from, const Vec3& w) const {
  if (convex_) return true;
  // Candidate planes through the origin: normal to face `from`, to w, to the removed faces' mean.
  Vec3 mean = Vec3::Zero();
  for (int i = 0; i < numSeen_; ++i) mean += faces_[seen_[i]].n;
  const Vec3 candidates[3] = {faces_[from].n, w, mean};
  for (const Vec3& n : candidates) {
    bool beyond = n.dot(w) > 0;
    for (int i = 0; i < numSeen_ && beyond; ++i)
      for (int k = 0; k < 3 && beyond; ++k) beyond = n.dot(vertices_[faces_[seen_[i]].v[k]].p) > 0;
    if (beyond) return true;
  }
  return false;
}

bool ExpansionSurface::expand(int from, const Vertex& w) {
  numSeen_ = 0;
  const bool collected = numVertices_ < kMaxVertices && collectHorizon(from, w.p);
  const bool chained = collected && horizonChains();
  const bool ok = collected && (chained || horizonIsCycle()) && keepsOrigin(from, w.p) &&
                  numFree_ + numSeen_ + (kMaxFaces - numSlots_) >= horizonSize_;
  auto restore = [&] {
    for (int i = 0; i < numSeen_; ++i) faces_[seen_[i]].alive = true;
    return false;
  };
  if (!ok) return restore();
  // Cone faces (y, x, w) over each horizon edge x -> y; their planes first, so that a
  // degenerate one leaves the surface untouched.
  const int iw = numVertices_;
  vertices_[iw] = w;
  for (int i = 0; i < horizonSize_; ++i) {
    cone_[i].v[0] = horizon_[i].to;
    cone_[i].v[1] = horizon_[i].from;
    cone_[i].v[2] = iw;
  }
  if (!setPlanes(cone_, horizonSize_)) return restore();
  ++numVertices_;
  for (int i = 0; i < numSeen_; ++i) freeFace(seen_[i]);
  for (int i = 0; i < horizonSize_; ++i) {
    made_[i] = newFace(cone_[i].v[0], cone_[i].v[1], cone_[i].v[2]);
    faces_[made_[i]].n = cone_[i].n;
    faces_[made_[i]].d = cone_[i].d;
    link(faces_, made_[i], 0, horizon_[i].face, horizon_[i].edge);
  }
  // Edge 1 (x -> w) of cone face i meets edge 2 (w -> x) of the cone face whose y is x: on a
  // chained horizon the next one (its edge ends at x), else found by search.
  for (int i = 0; i < horizonSize_; ++i) {
    int j = i + 1 < horizonSize_ ? i + 1 : 0;
    if (!chained) {
      j = 0;
      while (j < horizonSize_ && faces_[made_[j]].v[0] != faces_[made_[i]].v[1]) ++j;
    }
    if (j < horizonSize_) link(faces_, made_[i], 1, made_[j], 2);
    push(made_[i]);
  }
  return true;
}

}  // namespace deepcheck::geometry::detail
