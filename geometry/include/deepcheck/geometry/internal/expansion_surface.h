#pragma once
// Internal to deepcheck::geometry. The expanding surface of the certified penetration depth: a closed triangulated
// surface whose vertices are points b - a of the Minkowski difference M = B - A, stored as vertex-index pairs (a of A,
// b of B) with the point itself in the pair frame P.
//
// Started from a tetrahedron or from a checked convex surface (startConvex), the surface is the
// convex hull of its vertices (the expanding polytope of van den Bergen 2001). While it encloses
// the origin, every ray from the origin leaves M beyond some face, so the penetration depth is at
// least the smallest face-plane distance: the lower bound. A surface loaded from a warm start
// (load()) need not be convex; what the bound needs is that it winds once around the origin, and
// expand() keeps that by refusing any replacement that could sweep over the origin (see
// expand()). Faces are kept in a best-first queue ordered by that distance; expanding a face adds
// the support point of M in its normal and replaces every face that point sees by a cone of faces
// over the horizon.
//
// Fixed capacity, no allocation: the caller owns one surface (inside a PenetrationScratch,
// signed_distance.h) and reuses it for every query (one per thread). Beyond capacity, expand() refuses and the caller
// reports the bracket it has.

#include <Eigen/Core>

#include <cstdint>

namespace deepcheck::geometry::detail {

class ExpansionSurface {
 public:
  static constexpr int kMaxVertices = 160;
  static constexpr int kMaxFaces = 384;  ///< face slots (dead faces are recycled)
  static constexpr int kMaxQueue = 1024;
  static constexpr int kMaxHorizon = 128;  ///< horizon edges of one expansion

  /// A vertex of M: the point b - a in frame P and its index pair.
  struct Vertex {
    Eigen::Vector3d p;
    int a;
    int b;
  };

  /// A triangle, counter-clockwise seen from outside. adj[k] is the face across edge
  /// (v[k], v[k+1 mod 3]) times 4 plus that edge's index in it.
  struct Face {
    Eigen::Vector3d n;  ///< unit outward normal
    double d;           ///< plane offset n.p: the origin's distance to the plane (negative outside)
    int v[3];
    int adj[3];
    std::uint32_t serial;  ///< stamp distinguishing a recycled slot in the queue
    bool alive;
  };

  /// The plane through p0, p1, p2 (counter-clockwise seen from outside): unit normal n and
  /// offset d, the mean of the corners' offsets. False when the corners are collinear or the
  /// normal's length is not finite. One reciprocal of the normal's length, then products. The
  /// surface's faces (setPlanes, the same arithmetic two faces at a time) and the warm start's
  /// moved faces both get these planes, so that cold and warm queries at one pose break ties
  /// between support vertices alike and agree to the bit.
  static bool planeThrough(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                           Eigen::Vector3d& n, double& d);

  /// Starts from a tetrahedron of four vertices of M (any order, non-zero volume). Returns false
  /// when the volume is zero (the caller picks other points).
  bool startTetrahedron(const Vertex* corners);

  /// Starts from a closed surface, not necessarily convex: faces (corner indices into `vertices`,
  /// counter-clockwise seen from outside) and their neighbours (adj as in Face, face indices into
  /// `faces`). The caller guarantees it winds once around the origin. Returns false, leaving an
  /// empty surface, when it does not fit or a face is degenerate.
  bool load(const Vertex* vertices, int numVertices, const int (*faces)[3], const int (*adj)[3], int numFaces);

  /// Starts from a closed triangulated surface (as load()) that must be convex and hold the
  /// origin strictly inside: every face plane farther than `eps` from it and no vertex outside a
  /// face's plane. Both are checked; false, leaving an empty surface, when either fails or a face
  /// is degenerate.
  bool startConvex(const Vertex* vertices, int numVertices, const int (*faces)[3], const int (*adj)[3], int numFaces,
                   double eps);

  /// The live face of smallest plane distance, or -1 when there is none.
  int bestFace();

  /// Faces at or beyond `limit` (the caller's upper bound minus its tolerance: it stops before
  /// expanding them) are kept out of the queue from now on; bestFace() still returns the nearest
  /// face once none below the limit is left. The limit only decreases; start and load reset it.
  void setQueueLimit(double limit);

  /// Replaces the faces seen from `w` (at least face `from`, which must see it) by a cone over
  /// their horizon. Returns false, changing nothing, when out of capacity or when the horizon is
  /// not a single cycle or a new face is degenerate (round-off on a flat region). On a loaded
  /// (possibly non-convex) surface also when no plane through the origin (tried: normal to face
  /// `from`, to w, to the mean normal of the replaced faces) has the replaced faces and w strictly
  /// on one side; with one, the old faces and the cone bound a region without the origin, so the
  /// surface still winds once around it.
  bool expand(int from, const Vertex& w);

  const Face& face(int f) const { return faces_[f]; }
  const Vertex& vertex(int v) const { return vertices_[v]; }
  int numVertices() const { return numVertices_; }
  int numLiveFaces() const { return live_; }
  /// Face slots in use (live or recycled): iterate 0..numFaceSlots() and test face(f).alive.
  int numFaceSlots() const { return numSlots_; }
  /// True when w's index pair is already a vertex of face f.
  bool isCorner(int f, const Vertex& w) const;

 private:
  struct QueueEntry {
    double d;
    int face;
    std::uint32_t serial;
  };
  struct HorizonEdge {
    int face;  ///< the face that stays (does not see w)
    int edge;  ///< its edge on the horizon
    int from;  ///< the edge's first vertex in that face
    int to;    ///< its second
  };

  /// load() and startConvex(): the faces and their planes, the queue left to the caller.
  bool loadFaces(const Vertex* vertices, int numVertices, const int (*faces)[3], const int (*adj)[3], int numFaces);
  bool enclosesConvexly(double eps) const;
  int newFace(int v0, int v1, int v2);
  void freeFace(int f);
  /// Sets n and d of faces[0..count) from their corners, the bits planeThrough() gives; false
  /// when one is degenerate.
  bool setPlanes(Face* faces, int count) const;
  void push(int f);
  void rebuildQueue();
  bool collectHorizon(int from, const Eigen::Vector3d& w);
  bool horizonChains();
  bool horizonIsCycle() const;
  bool keepsOrigin(int from, const Eigen::Vector3d& w) const;
  static void link(Face* faces, int f, int e, int g, int h);

  Vertex vertices_[kMaxVertices];
  Face faces_[kMaxFaces];
  QueueEntry queue_[kMaxQueue];
  int freeList_[kMaxFaces];
  HorizonEdge horizon_[kMaxHorizon];
  Face cone_[kMaxHorizon];
  int made_[kMaxHorizon];
  int seen_[kMaxFaces];                // faces that see the new point (marked dead while expanding)
  int pending_[2 * kMaxFaces + 3];     // depth-first search stack of (face, edge) codes
  bool onHorizon_[kMaxVertices] = {};  // horizonChains()' per-vertex flags, false between calls
  int numVertices_ = 0;
  int numSlots_ = 0;
  int numFree_ = 0;
  int queueSize_ = 0;
  double queueLimit_ = 0.0;  // faces at or beyond it are not queued (setQueueLimit)
  int horizonSize_ = 0;
  int numSeen_ = 0;
  int live_ = 0;
  std::uint32_t serial_ = 0;
  bool convex_ = true;  // started convex (expansions keep the convex hull)
};

}  // namespace deepcheck::geometry::detail
