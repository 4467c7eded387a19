#pragma once
// Convex polytopes built from point sets (Qhull, reentrant API).
//
// A ConvexPolytope is the convex hull of the points it was built from, of one of four kinds:
//   Point       one vertex, no faces (the core of a sphere);
//   Segment     two vertices, no faces (the core of a capsule);
//   Polygon     a flat convex polygon: k >= 3 vertices in counter-clockwise order about
//               faceNormal(0), and two faces, 0 (normal +n) and 1 (normal -n);
//   Polyhedron  a solid: faces are the hull facets with coplanar ones merged into polygons.
//
// Frames: vertices are stored in the polytope's own frame (the frame its points were given in).
// center() is the centroid of the vertices; algorithms work relative to it so that large
// coordinates in the input do not cost digits.
//
// Adjacency (Polyhedron): every vertex v has its neighbours nbr_0..nbr_{k-1} in counter-clockwise
// order seen from outside the polytope, and its face ring: ring face j contains the edges
// (v, nbr_j) and (v, nbr_{j+1 mod k}). The face ring, read as unit normals, is the vertex's region
// of the Gauss map (a convex spherical polygon), and the arc from ring normal j-1 to ring normal j
// is the Gauss image of edge (v, nbr_j). Faces list their vertices counter-clockwise seen from
// outside. For a Polygon, a vertex's neighbours are (next, previous) along the boundary and its
// face ring is (0, 1); face 0 lists the vertices 0, 1, ..., k-1 and face 1 lists them reversed
// (k-1, ..., 1, 0), so the polyhedron rule above holds for polygons too. For a Segment each vertex
// has the other as its only neighbour. Points and segments have no faces and empty face rings.

#include "deepcheck/geometry/tolerances.h"

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace deepcheck::geometry {

namespace detail {
struct PolytopeAccess;
}

enum class PolytopeKind {
  Point,       ///< a single point
  Segment,     ///< two distinct points
  Polygon,     ///< flat, at least three vertices
  Polyhedron,  ///< a solid
};

const char* toString(PolytopeKind kind);

/// A read-only view of a contiguous run of indices.
struct IndexRange {
  const int* first = nullptr;
  const int* last = nullptr;
  const int* begin() const { return first; }
  const int* end() const { return last; }
  int size() const { return static_cast<int>(last - first); }
  int operator[](int i) const { return first[i]; }
};

class ConvexPolytope {
 public:
  /// Builds the convex hull of `points` (in the polytope's own frame).
  /// Throws std::invalid_argument when the list is empty, a coordinate is NaN, infinite or beyond
  /// range::kMaxCoordinate, or the points span less than range::kMinExtent without coinciding
  /// (input_range.h); the message names the offending point index and value. `name` is used in
  /// messages only.
  static ConvexPolytope fromPoints(const std::vector<Eigen::Vector3d>& points, const std::string& name = "points");

  /// An axis-aligned box centred at the origin. `size`: its full edge lengths along x, y and z
  /// (all > 0), metres, as a URDF <box size>, a MoveIt box primitive and Obstacle::box take them.
  static ConvexPolytope box(const Eigen::Vector3d& size);

  PolytopeKind kind() const { return kind_; }
  int numVertices() const { return static_cast<int>(vertices_.size()); }
  int numFaces() const { return static_cast<int>(faceNormals_.size()); }
  int numEdges() const;

  const Eigen::Vector3d& vertex(int v) const { return vertices_[v]; }
  const std::vector<Eigen::Vector3d>& vertices() const { return vertices_; }

  /// Unit outward normal n and offset d of face f: the face lies in {x : n.x = d}.
  const Eigen::Vector3d& faceNormal(int f) const { return faceNormals_[f]; }
  double faceOffset(int f) const { return faceOffsets_[f]; }
  /// Vertices of face f, counter-clockwise seen from outside.
  IndexRange faceVertices(int f) const;

  /// Neighbours of vertex v, counter-clockwise seen from outside (see the header comment).
  IndexRange neighbors(int v) const;
  /// Face ring of vertex v: ring face j lies between edges (v, nbr_j) and (v, nbr_{j+1}).
  IndexRange vertexFaces(int v) const;

  /// Centroid of the vertices, and the largest distance from it to a vertex (>= 0).
  const Eigen::Vector3d& center() const { return center_; }
  double boundingRadius() const { return radius_; }
  /// Length scale used to scale tolerances: max(boundingRadius, tiny) — never zero.
  double lengthScale() const { return lengthScale_; }
  /// Unit principal axes of the vertex distribution (columns, largest extent first). A rotation:
  /// right-handed, the largest-magnitude entry of the first two columns is positive.
  const Eigen::Matrix3d& principalAxes() const { return axes_; }
  /// Absolute flatness tolerance the hull was built with: max(kFlatRelative * extent of the input,
  /// kCoordinateRoundoff * largest |coordinate|). Points closer than this are one point, sets
  /// thinner than this are flat, faces coplanar within it are merged.
  double flatTolerance() const { return flatTol_; }
  /// What the hull guarantees, absolute: every input point is inside every face plane, every
  /// face's vertices are on its plane, within hullTolerance() = tol::kHullToleranceFactor *
  /// flatTolerance() (tolerances.h says why).
  double hullTolerance() const { return tol::kHullToleranceFactor * flatTol_; }
  /// Vertex v relative to center(), stored (support() works on these).
  const Eigen::Vector3d& localVertex(int v) const { return local_[v]; }

  /// Index of a vertex maximizing dir.x. Hill climbing over the vertex adjacency from `hint`
  /// (any vertex index; out-of-range hints start at vertex 0) or from the direction index's
  /// vertex for dir, whichever is higher along dir; brute force on small hulls.
  int support(const Eigen::Vector3d& dir, int hint = 0) const;
  /// Index of a vertex maximizing dir.x by testing every vertex: no climb and no direction
  /// index, so its ties break by vertex order alone. For a few calls on small hulls, and as the
  /// reference support() is checked against.
  int supportBruteForce(const Eigen::Vector3d& dir) const;
  /// A vertex maximizing faceNormal(f).x: support() in face f's own normal, computed once when
  /// the hull is built. That normal ties a whole face's vertices, which support() would search
  /// as a plateau on every call; penetration depth queries support in it once per answer.
  int faceSupport(int f) const { return faceSupport_[f]; }
  /// Radius of the largest ball about center() inside the hull: the smallest distance from the
  /// centre to a face plane (0 for points, segments and polygons).
  double insideRadius() const { return insideRadius_; }

 private:
  ConvexPolytope() = default;
  // Data and checks for deep's own algorithms and tests (internal/polytope_access.h).
  friend struct detail::PolytopeAccess;
  static constexpr int kProbeDirections = 12;
  void prefetchSupportData() const;
  int supportStart(const Eigen::Vector3d& dir) const;
  std::string validate() const;

  // Computes center, local vertices, radius, axes, face offsets, the inside radius, the direction
  // index, the face supports and the probe supports.
  void finish();
  // validate(); the O(V F) test of every vertex against every face plane only when asked.
  std::string checkInvariants(bool globalConvexity) const;

  friend class PolytopeBuilder;
  friend class PolytopeInvariants;

  PolytopeKind kind_ = PolytopeKind::Point;
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<Eigen::Vector3d> local_;  // vertices_[v] - center_, contiguous for support()
  std::vector<Eigen::Vector3d> faceNormals_;
  std::vector<double> faceOffsets_;
  std::vector<int> faceStart_;  // face f's vertices are faceVerts_[faceStart_[f] .. faceStart_[f+1])
  std::vector<int> faceVerts_;
  std::vector<int> adjStart_;  // vertex v's neighbours/ring are at [adjStart_[v] .. adjStart_[v+1])
  std::vector<int> adjVerts_;
  std::vector<int> adjFaces_;
  Eigen::Vector3d center_ = Eigen::Vector3d::Zero();
  double radius_ = 0.0;
  double lengthScale_ = 1.0;
  Eigen::Matrix3d axes_ = Eigen::Matrix3d::Identity();
  double flatTol_ = 0.0;
  // Direction index (hulls beyond brute-force size): the support vertex of the centre direction
  // of each cell of a cube map, 6 faces of kDirectionGrid x kDirectionGrid cells.
  static constexpr int kDirectionGrid = 8;
  std::vector<int> directionIndex_;
  void buildDirectionIndex();
  std::vector<int> faceSupport_;  // faceSupport(f), one per face
  void buildFaceSupports();
  int probeSupport_[kProbeDirections] = {};
  void buildProbeSupports();
  double insideRadius_ = 0.0;
};

}  // namespace deepcheck::geometry
