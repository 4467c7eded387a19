#pragma once
// DEEP's walk, internal: the vocabulary shared by its files (deep_facets.cpp: the local Gauss map
// overlay and the facets of M it yields; deep_walk.cpp: the walks and the query; low_dim_facets.cpp:
// points and segments). The algorithm and where it departs from the paper are described in
// deepcheck/geometry/internal/gauss_map_walk.h:
//   M = B - A          Minkowski difference, in the pair frame P;
//   hub pair (a, b)    a vertex of A and of B such that b - a is a vertex of M;
//   C(a, b)            the Gauss region of that vertex of M: N_B(b) ∩ -N_A(a);
//   facet              a facet of M, with outward unit normal u and offset d = u . x (x on it).
// The origin is inside M when A and B overlap; the penetration depth is then min_F d_F and the
// answer's normal (from A to B) is -u.

#include "deepcheck/geometry/internal/gauss_map_walk.h"
#include "deepcheck/geometry/tolerances.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

namespace deepcheck::geometry::detail {

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
  WalkResult::FacetType type = WalkResult::FacetType::VF;
  int fa = 0, fa2 = -1, fb = 0, fb2 = -1;
  int hubA = 0, hubB = 0;
  bool featuresKnown = true;  // fa..fb2 name the facet's features (false: find them by flooding)
  bool valid() const { return std::isfinite(d); }
};

inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

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
    bool evaluated = false;
    bool valid = false;    // the hub has a Gauss region (a best candidate)
    bool visited = false;  // a walk adopted this hub's best candidate
    Candidate best;
  };
  static_assert(std::is_trivially_destructible_v<Entry>, "slots are reused without destruction");
  /// Storage of one entry, constructed when the slot is taken in a query: a new table costs an
  /// allocation, not a pass over kSize entries (a caller without scratch makes one per query).
  struct Slot {
    alignas(Entry) unsigned char bytes[sizeof(Entry)];
  };
  std::unique_ptr<std::uint32_t[]> stamps;  // query generation that took each slot (0: none)
  std::unique_ptr<Slot[]> slots;            // both allocated by the first insert
  std::uint32_t gen = 1;
  int used = 0;

  void clear() {
    used = 0;
    if (++gen != 0) return;
    gen = 1;  // wrapped: no slot may look taken
    if (stamps) std::fill(stamps.get(), stamps.get() + kSize, 0u);
  }
  static std::uint64_t slot(std::uint64_t key) { return (key * 0x9E3779B97F4A7C15ull) >> 54; }
  static constexpr int kMaxProbe = 32;
  Entry& entry(std::uint64_t h) { return *std::launder(reinterpret_cast<Entry*>(slots[h].bytes)); }
  /// The entry for key, or null when it is not in the table.
  Entry* lookup(std::uint64_t key) {
    if (!stamps) return nullptr;
    std::uint64_t h = slot(key);
    for (int probe = 0; probe < kMaxProbe; ++probe, h = (h + 1) & (kSize - 1)) {
      if (stamps[h] != gen) return nullptr;
      if (entry(h).key == key) return &entry(h);
    }
    return nullptr;
  }
  /// The entry for key, created (unevaluated, unvisited) if absent; null when the table is too
  /// full, in which case nothing more is memoized in this query.
  Entry* insert(std::uint64_t key) {
    if (!stamps) {
      stamps = std::make_unique<std::uint32_t[]>(kSize);  // zeroed
      slots.reset(new Slot[kSize]);                       // left uninitialized
    }
    std::uint64_t h = slot(key);
    for (int probe = 0; probe < kMaxProbe; ++probe, h = (h + 1) & (kSize - 1)) {
      if (stamps[h] != gen) {
        if (used >= kSize / 2) return nullptr;
        ++used;
        stamps[h] = gen;
        Entry* e = new (slots[h].bytes) Entry();
        e->key = key;
        return e;
      }
      if (entry(h).key == key) return &entry(h);
    }
    return nullptr;
  }
};

/// The walk's scratch space (walk_scratch.h), grown on demand and never shrunk: a query with the
/// caller's scratch does not allocate.
struct WalkScratchData {
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

/// Everything a walk needs about the pair, in frame P.
class Walker {
 public:
  Walker(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& F, WalkScratchData& s)
      : A_(A), B_(B), F_(F), s_(s) {
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
    L_ = pairLengthScale(A, B, F);
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
  bool hub(int ia, int ib, Candidate& best, WalkStats& stats) {
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
  int overlayRegion(int ia, int ib, const Corner** poly);
  void supportFeature(const ConvexPolytope& P, bool isB, int start, const Vec3& u, std::vector<int>& out) const;
  void facetFeatures(const Candidate& c);
  void facetPolygon(const Candidate& c);
  void witness(const FacetPoint& x, const FacetPoint& y, const FacetPoint& z, double wx, double wy, double wz, Vec3& pA,
               Vec3& pB) const;
  bool footOnSegmentFacet(Vec3& pA, Vec3& pB, int next[4]) const;
  int mostViolatedEdge() const;
  void insideWitnesses(Vec3& pA, Vec3& pB) const;
  bool aloneOnPlaneA(int v, const Vec3& u, int except) const;
  bool aloneOnPlaneB(int v, const Vec3& u, int except) const;

  const ConvexPolytope& A_;
  const ConvexPolytope& B_;
  const PairFrame& F_;
  WalkScratchData& s_;
  double L_ = 1.0;
  double tolFeature_ = 0.0;
  double tolImprove_ = 0.0;
  double tolInside_ = 0.0;
};

/// Result of one walk.
struct WalkEnd {
  Candidate facet;
  Vec3 pA = Vec3::Zero(), pB = Vec3::Zero();
  bool converged = false;  // ended at a facet containing its foot point
  bool joined = false;     // stopped on reaching a hub pair an earlier walk visited
  bool witnessed = false;
};

/// One walk from `start` over the facets of M, until a facet contains its foot point and no facet
/// at its corners is closer, or maxHubs hub pairs were evaluated (deep_walk.cpp).
WalkEnd walk(Walker& w, Candidate start, int maxHubs, WalkStats& stats);

bool isLowDim(const ConvexPolytope& P);

/// The depth when A or B is a point or a segment (low_dim_facets.cpp): M's facets enumerated
/// directly, or depth 0 for a flat M. Returns false, leaving `result` alone, when both are
/// polygons or polyhedra with a solid M (the walks' case).
bool lowDimPenetration(Walker& w, const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                       WalkResult& result);

}  // namespace deepcheck::geometry::detail
