#pragma once
// Internal to deepcheck::robots: the pieces of the approximate convex decomposer
// (decomposition.cpp drives them; decomposition.h gives the overview and the guarantees).
//
// Approximate convex decomposition: recursive plane cuts scored by concavity, then merging and
// vertex reduction (decomposition.h gives the overview and the guarantees).
//
// Parts. A part is the piece of the mesh surface inside a convex cell (the intersection of the
// half-spaces of the cuts that led to it): the mesh triangles clipped to the cell (convex
// polygons), plus the cell's corners that lie inside the solid. Its hull is the hull of those
// points. Coverage: the solid inside the cell is bounded by the polygons and by caps (the solid's
// cut faces) on the cell planes; a cap is bounded by polygon edges and by cell edges, whose ends
// are polygon vertices or cell corners; so the hull holds the caps, hence the solid. Each side of
// a cut is split into components joined through mesh edges and through the regions of the cut
// faces (loops of the cross-section that cross or nest, CrossSection below), never more finely
// than the solid is connected; each cell corner goes to the component whose surface a ray from
// the corner into the cell meets first.
//
// Concavity of a hull: the largest distance from a point of its surface to the mesh solid,
// estimated by sampling the surface and hill-climbing from the worst samples. A sample outside
// the solid is measured against the whole mesh (a BVH query: exact). A sample inside the solid is
// at distance 0; on a part's own hull that only happens on the cell's planes (a surface point
// strictly inside the cell and the solid would be interior to the part, hence to its hull), so
// only samples on hull facets lying on a cut plane are tested, by the 2D winding number of the
// mesh's cross-section by that plane. For merged or reduced pieces, whose hull may reach into the
// solid elsewhere, the value is an upper bound.
//
// Search. Each step cuts the part of largest concavity by the candidate plane that minimizes the
// larger concavity of its sides (ties: the cut along the most mesh face area, then the smaller
// hull volumes). Candidates: the axes and the part's principal axes, through the worst sample,
// through the mesh point nearest to it, through mesh points near it, through the walls that rays
// from it meet (and along those walls' own planes), a few evenly spaced offsets, a refinement of
// the best offset, and slabs between the walls on both sides of the worst sample (a slot or gap
// is cut out in one step). When the best cut does not lower the concavity much (a plateau: a
// hole needs two cuts through its axis, a frame around a pocket a cut along each wall), the most
// promising cuts are compared one cut ahead; if that shows no progress either, the cut along the
// largest mesh face near the concavity is taken.
//
// Departures from the papers. V-HACD voxelizes and cuts the voxel set; CoACD cuts the mesh,
// re-triangulates the caps to keep parts manifold, and searches cut sequences with a Monte-Carlo
// tree. Here caps are never built (their extent is the cell corners', their inside the cross
// sections'), and the search is greedy with the one-cut lookahead, slabs and wall cuts above.
//
// Files: decomposition_mesh_repair.cpp (CleanMesh), decomposition_cross_section.cpp
// (CrossSection), decomposition_concavity.cpp (measureConcavity), decomposition_parts.cpp (parts
// and their components), decomposition_cut_search.cpp (candidate cuts and the choice among them),
// decomposition_merge.cpp (merging pieces), decomposition.cpp (the driver, Decomposer::run),
// decomposition_obj.cpp (OBJ output).

#include "deepcheck/robots/decomposition.h"
#include "deepcheck/robots/format_number.h"

#include "decomposition_bvh.h"
#include "decomposition_hull.h"
#include "decomposition_tolerances.h"
#include "union_find.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace deepcheck::robots {

namespace dt = detail::decomp;

namespace detail::decomp {

using Eigen::Vector3d;
using detail::findRoot;
using detail::unite;

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kPi = 3.141592653589793;

/// A mesh as messages name it: its source in quotes, or "(generated mesh)".
inline std::string meshName(const std::string& source) {
  return source.empty() ? std::string("(generated mesh)") : "'" + source + "'";
}
inline std::string meshName(const TriangleMesh& mesh) { return meshName(mesh.source); }

/// A length or ratio for a message read by a person: 3 significant digits.
inline std::string roundedNumber(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", v);
  return buffer;
}

/// Twice the vector area of a convex polygon given by its corners in order (the sum of the cross
/// products of its fan triangles): its normal, times twice its area.
inline Vector3d doubleVectorArea(const std::vector<Vector3d>& corners) {
  Vector3d area = Vector3d::Zero();
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
    area += (corners[k] - corners[0]).cross(corners[k + 1] - corners[0]);
  }
  return area;
}

/// The point where the planes of three half-spaces meet; false when two of them are (nearly)
/// parallel (see kSingularPlanes) or the point is not finite.
inline bool planesMeet(const Halfspace& a, const Halfspace& b, const Halfspace& c, Vector3d* point) {
  Eigen::Matrix3d A;
  A.row(0) = a.normal;
  A.row(1) = b.normal;
  A.row(2) = c.normal;
  if (std::abs(A.determinant()) < dt::kSingularPlanes) return false;
  *point = A.inverse() * Vector3d(a.offset, b.offset, c.offset);
  return point->allFinite();
}

/// The smallest and largest of d.p over `points`.
struct Extent {
  double lo, hi;
};
inline Extent extentAlong(const std::vector<Vector3d>& points, const Vector3d& d) {
  Extent e{kInf, -kInf};
  for (const Vector3d& p : points) {
    e.lo = std::min(e.lo, d.dot(p));
    e.hi = std::max(e.hi, d.dot(p));
  }
  return e;
}

// ------------------------------------------------------------------------------------------------
// Deterministic random numbers (splitmix64): the same on every platform, unlike std distributions.

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t state_;
};

// ------------------------------------------------------------------------------------------------
// The input, cleaned: identical vertices welded, degenerate triangles dropped, edge adjacency.

struct CleanMesh {
  std::vector<Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> edgeOf;     ///< 3 per triangle: the undirected edge (v[e], v[e+1 mod 3])
  std::vector<int> edgeStart;  ///< edge k's triangles: edgeTris[edgeStart[k] .. edgeStart[k+1])
  std::vector<int> edgeTris;
  std::vector<int> component;  ///< connected component of each triangle (through edges)
  int numComponents = 0;
  std::vector<int> group;      ///< components with overlapping bounding boxes, per triangle
  int numGroups = 0;
  double diagonal = 0.0;
  bool closed = false;  ///< after filling holes
  int holesFilled = 0;
  int voidsRemoved = 0;    ///< closed inward-facing components sealed inside others
  int duplicatesRemoved = 0;  ///< triangles on the same three vertices as an earlier one
  int inputVertices = 0;   ///< before filling holes
  int inputTriangles = 0;
  double volume = 0.0;  ///< sum of the components' volumes (voids count negative); NaN when open
};

/// The input, cleaned (decomposition_mesh_repair.cpp): welded, holes filled, oriented outward.
CleanMesh cleanMesh(const TriangleMesh& mesh);

/// Throws std::invalid_argument naming the mesh (`name`, as meshName gives) for a mesh without
/// triangles, a vertex that is not finite or an index out of range.
void checkInput(const TriangleMesh& mesh, const std::string& name);
/// The bounding box of the vertices the triangles use.
Eigen::AlignedBox3d usedBox(const TriangleMesh& mesh);
/// A triangle whose area is at most (kDegenerateRelative * diagonal)^2: cleanMesh drops it.
bool isDegenerate(const Vector3d& a, const Vector3d& b, const Vector3d& c, double diagonal);

// ------------------------------------------------------------------------------------------------
// Cross-section of the whole mesh by a plane: "is this point of the plane inside the solid", and
// which pieces of the mesh surface are joined through the solid's cut face there.
//
// Each triangle crossing the plane gives one segment, oriented along n x (triangle normal): for a
// closed outward-facing mesh (cleanMesh orients every closed component outward) the section's
// loops then run counter-clockwise about n around solid regions, and the winding number is +1
// inside (overlapping components add up). A vertex on the plane counts as above it (symbolic
// perturbation), so every edge is crossed consistently and the loops close even when the plane
// passes through vertices. Crossing points are computed from the edge's lower-index end, so the
// two triangles of an edge produce the same point.
//
// Closed meshes: crossing-number winding, with segments bucketed along the second plane axis so
// that a query scans one bucket. Open meshes: the generalized winding number (the signed angle the
// segments subtend, over 2 pi, inside when >= 1/2), which degrades gracefully at holes.
//
// Regions (only for the planes of accepted cuts): segments chain into loops through the mesh
// edges they cross; loops that cross or nest are joined into one region. The cut face of the
// solid is a union of regions, and two surface pieces bordering the same region may be connected
// through the solid (see components()).

class CrossSection {
 public:
  CrossSection(const CleanMesh& mesh, const Vector3d& normal, double offset, bool withRegions);

  /// True when p (a point on the plane) is inside the solid's cross-section.
  bool contains(const Vector3d& p) const {
    if (segments_.empty()) return false;
    const double pu = u_.dot(p);
    const double pv = v_.dot(p);
    return windingAt(pu, pv);
  }

  /// Region of the cut face bordered by the segment of mesh triangle `triangle` (-1: none).
  int regionOfTriangle(int triangle) const {
    const auto it = regionOfTriangle_.find(triangle);
    return it == regionOfTriangle_.end() ? -1 : it->second;
  }

  /// Region with a loop enclosing p, a point on the plane (-1: none). Enclosing loops nest, so
  /// they all belong to one region.
  int regionAt(const Vector3d& p) const {
    const double pu = u_.dot(p);
    const double pv = v_.dot(p);
    for (std::size_t l = 0; l < loops_.size(); ++l) {
      if (insideLoop(pu, pv, loops_[l])) return loopRegion_[l];
    }
    return -1;
  }

 private:
  struct Segment {
    double au, av, bu, bv;
    int triangle;
  };

  bool insideLoop(double pu, double pv, const std::vector<int>& loop) const {
    bool inside = false;
    for (int k : loop) {
      const Segment& s = segments_[k];
      if ((s.av > pv) != (s.bv > pv)) {
        const double u = s.au + (pv - s.av) / (s.bv - s.av) * (s.bu - s.au);
        if (u > pu) inside = !inside;
      }
    }
    return inside;
  }

  int bucketOf(double v) const {
    // Clamped before the cast: a point far off the section (or NaN) has no int bucket index.
    const double last = static_cast<double>(buckets_.size() - 1);
    const double b = (v - vlo_) / width_;
    return b >= 0.0 ? static_cast<int>(std::min(b, last)) : 0;
  }

  void buildBuckets();

  /// Winding test of (pu, pv): against all segments (generalized winding number), or against the
  /// bucket of pv (crossing number).
  bool windingAt(double pu, double pv) const {
    const std::vector<int>* subset = buckets_.empty() ? nullptr : &buckets_[bucketOf(pv)];
    const int n = subset != nullptr ? static_cast<int>(subset->size()) : static_cast<int>(segments_.size());
    if (generalized_) {
      double angle = 0.0;
      for (int k = 0; k < n; ++k) {
        const Segment& s = segments_[subset != nullptr ? (*subset)[k] : k];
        const double ax = s.au - pu;
        const double ay = s.av - pv;
        const double bx = s.bu - pu;
        const double by = s.bv - pv;
        angle += std::atan2(ax * by - ay * bx, ax * bx + ay * by);
      }
      return std::abs(angle) >= kPi;  // |winding| >= 1/2
    }
    int winding = 0;
    for (int k = 0; k < n; ++k) {
      const Segment& s = segments_[subset != nullptr ? (*subset)[k] : k];
      const double side = (s.bu - s.au) * (pv - s.av) - (pu - s.au) * (s.bv - s.av);
      if (s.av <= pv && pv < s.bv) {
        if (side > 0.0) ++winding;  // upward crossing to the right of p
      } else if (s.bv <= pv && pv < s.av) {
        if (side < 0.0) --winding;  // downward crossing to the right of p
      }
    }
    return winding != 0;
  }

  void buildRegions(const std::vector<int>& segmentEdges);

  bool generalized_ = false;
  Vector3d u_;
  Vector3d v_;
  std::vector<Segment> segments_;
  double vlo_ = 0.0;
  double width_ = 1.0;
  std::vector<std::vector<int>> buckets_;
  std::unordered_map<int, int> regionOfTriangle_;
  std::vector<std::vector<int>> loops_;  ///< segment indices of each loop
  std::vector<int> loopRegion_;
};

// ------------------------------------------------------------------------------------------------
// Concavity of a hull by surface sampling.

/// What a hull is measured against: the union of some parts' triangles (optionally clipped by a
/// half-space), and the cut planes whose cross-sections say where the plane is inside the solid.
struct Cap {
  Vector3d normal;
  double offset;
  const CrossSection* section;
};

struct Target {
  const TriangleBvh* mesh = nullptr;  ///< the whole mesh's triangles
  std::vector<Cap> caps;
};

struct Concavity {
  double value = 0.0;
  bool aborted = false;  ///< stopped once value exceeded the caller's bound
  bool hasWorst = false;
  Vector3d worstSample = Vector3d::Zero();
  Vector3d worstNearest = Vector3d::Zero();  ///< the mesh point nearest to worstSample
};

/// Which fixed points of the hull's triangles are sampled besides the random ones.
enum class Extra {
  None,   ///< random samples only (candidate cuts, which are many)
  Dense,  ///< each triangle's centroid and edge midpoints (parts, merges, the final report):
          ///< catches thin slivers of hull and maxima on hull edges
};

/// Samples `count` random points on the surface of `hull` (area-weighted), plus the `extra`
/// points, and returns the largest distance to `target`.
/// Stops as soon as the largest distance exceeds `abortAbove` (aborted = true).
/// Samples `count` random points on the surface of `hull` (area-weighted), plus the `extra`
/// points, and returns the largest distance to `target`.
/// Stops as soon as the largest distance exceeds `abortAbove` (aborted = true).
Concavity measureConcavity(const Hull& hull, const Target& target, int count, Extra extra,
                           std::uint64_t seed, double abortAbove, double diagonal,
                           const Vector3d* hint = nullptr);

// ------------------------------------------------------------------------------------------------
// Parts and the decomposer.

/// A convex polygon of a part: a mesh triangle clipped to the part's cell.
struct PartPolygon {
  std::vector<Vector3d> corners;
  int source;  ///< index of the mesh triangle it was clipped from
};

/// A cut plane and the mesh's cross-section by it.
struct CutPlane {
  Vector3d normal;
  double offset;
  CrossSection section;
};

struct CellSide {
  int plane;     ///< index into the decomposer's cut planes
  bool flipped;  ///< false: the part keeps n.x <= d; true: n.x >= d
};

struct Part {
  std::vector<CellSide> cell;
  std::vector<PartPolygon> polygons;
  /// Corners of the cell inside the solid and bordering this part: the solid's cut faces end
  /// there, so the hull needs them (the cut faces are not in the polygons).
  std::vector<Vector3d> cellCorners;
  std::vector<Vector3d> points;  ///< distinct corners of the polygons, and the cell corners
  Hull hull;                     ///< hull of the points
  Hull finalHull;                ///< hull, reduced to the vertex budget when it met the target
  double hullConcavity = 0.0;    ///< concavity of `hull`
  double concavity = 0.0;        ///< concavity of `finalHull`: what has to meet the target
  bool reductionLimited = false; ///< hull meets the target, but not once reduced
  bool hasWorst = false;
  Vector3d worstSample = Vector3d::Zero();   ///< hull surface point farthest from the part
  Vector3d worstNearest = Vector3d::Zero();  ///< the part's point nearest to it
  bool unsplittable = false;  ///< no valid cut was found
  bool reduced = false;       ///< finishPart ran
  bool noSlivers = false;     ///< a sliver cut made no progress: cuts leaving a sliver are skipped
};

struct Piece {
  std::vector<int> parts;
  Hull hull;       ///< hull of the parts' points
  Hull finalHull;  ///< hull reduced to the vertex budget
  double concavity = 0.0;  ///< of finalHull
};

class Decomposer {
 public:
  /// `target`: the absolute concavity target; decisions aim at kDecisionFraction of it.
  /// `name`: the mesh as messages name it (meshName), for the progress lines.
  Decomposer(const CleanMesh& mesh, const DecompositionParams& params, double target, std::string name)
      : mesh_(mesh),
        params_(params),
        target_(dt::kDecisionFraction * target),
        reportTarget_(target),
        diagonal_(mesh.diagonal),
        name_(std::move(name)) {
    std::vector<Triangle> triangles;
    triangles.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) triangles.push_back({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});
    meshBvh_ = TriangleBvh(std::move(triangles));
  }

  /// Runs the whole algorithm; fills `pieces` (hulls, reduced) and the concavity fields of `report`.
  std::vector<ConvexPiece> run(DecompositionReport* report);

 private:
  // The steps of run() (decomposition.cpp).
  void addPart(std::vector<Piece>* pieces, Part part);
  /// The whole mesh as one part, or one part per group when its hull misses the target.
  std::vector<Piece> initialPieces(DecompositionReport* report);
  /// Cuts the worst part that can still be cut; false when there is none.
  bool cutWorst(std::vector<Piece>* pieces);
  /// Rounds of cuts within the budget and merges of neighbours, then the forced merges.
  void cutAndMerge(std::vector<Piece>* pieces, bool alreadyConvex);
  /// One line on stderr (pieces so far, their worst concavity, the time) once the decomposition
  /// has run kProgressSeconds since the start or the last such line.
  void reportProgress(const std::vector<Piece>& pieces);
  /// Reduces every piece hull still above maxVerticesPerPiece (a part that missed the target
  /// was not reduced, expecting a cut that never came).
  void capVertices(std::vector<Piece>* pieces);
  /// The final, denser concavity estimate of each piece.
  std::vector<Concavity> finalConcavities(const std::vector<Piece>& pieces);
  /// Pieces whose final estimate is above the report's target go back to be cut: a part keeps
  /// its larger concavity and the worst sample found; a merged piece is split back into its
  /// parts. `forbidAll`: none of those parts may be merged together again; otherwise only those
  /// of a merge that the decisions had accepted (a forced merge is undone, not judged). False
  /// when every piece met the target.
  bool reopen(std::vector<Piece>* pieces, const std::vector<Concavity>& final, bool forbidAll);

  std::uint64_t nextSeed() { return params_.seed ^ (0x9e3779b97f4a7c15ULL * ++evaluations_); }
  Halfspace halfspaceOf(const CellSide& side) const {
    const CutPlane& plane = *planes_[side.plane];
    return side.flipped ? Halfspace{-plane.normal, -plane.offset} : Halfspace{plane.normal, plane.offset};
  }
  void addCaps(const Part& part, std::vector<Cap>* caps) const {
    for (const CellSide& side : part.cell) {
      const CutPlane& plane = *planes_[side.plane];
      caps->push_back({plane.normal, plane.offset, &plane.section});
    }
  }

  /// A part from its cell and polygons: points, hull, concavity; with `reduce`, finishPart too.
  /// `hint`: where the parent's worst hull sample was (sampled first, see measureConcavity).
  Part makePart(std::vector<CellSide> cell, std::vector<PartPolygon> polygons,
                std::vector<Vector3d> cellCorners, bool reduce = true, const Vector3d* hint = nullptr);
  /// Reduces the part's hull to the vertex budget (once) and measures the reduced hull.
  void finishPart(Part* part);
  struct Component {
    std::vector<PartPolygon> polygons;
    std::vector<Vector3d> cellCorners;
  };
  std::vector<Component> components(std::vector<PartPolygon> polygons,
                                    const std::vector<CellSide>& cell) const;
  // The steps of components() (decomposition_parts.cpp): union-find over the source triangles
  // (`node`: triangle -> index in `sources`) and the regions of the cut faces.
  void joinAcrossEdges(const std::unordered_map<int, int>& node, const std::vector<int>& sources,
                       const std::vector<Halfspace>& halfspaces, std::vector<int>* parent) const;
  void joinThroughCutFaces(const std::vector<PartPolygon>& polygons, const std::vector<CellSide>& cell,
                           const std::unordered_map<int, int>& node, const std::vector<int>& sources,
                           const std::vector<Halfspace>& halfspaces, std::vector<int>* parent) const;
  std::vector<PartPolygon> clip(const std::vector<PartPolygon>& polygons, const Halfspace& keep) const;
  /// Corners of the cell (vertices of the intersection of its half-spaces) inside the solid, with
  /// the cell planes through each.
  struct CellCorner {
    Vector3d point;
    std::vector<int> planes;  ///< indices into the cell
  };
  std::vector<CellCorner> solidCellCorners(const std::vector<CellSide>& cell) const;
  /// Gives each cell corner inside the solid to the components whose hulls must hold it.
  void assignCellCorners(const std::vector<CellSide>& cell, const std::vector<Halfspace>& halfspaces,
                         std::vector<Component>* out) const;
  /// The components a corner belongs to, by rays into the cell (empty: none found).
  std::vector<int> cornerOwners(const CellCorner& corner, const std::vector<Halfspace>& halfspaces,
                                const std::vector<Component>& out, const std::vector<char>& touchesCell) const;

  struct SideResult {
    bool valid = false;
    bool aborted = false;
    double concavity = 0.0;
    double volume = 0.0;
    int vertices = 0;
  };
  /// A half-space a side keeps, with the mesh's cross-section by its plane.
  struct Keep {
    Halfspace plane;
    const CrossSection* section;
  };
  /// Hull and concavity of the part's side within all `keeps` (one cut, or the middle of a slab).
  SideResult evaluateSide(const Part& part, const std::vector<Keep>& keeps, double abortAbove);
  /// A scored cut: `cut` keeps its negative side for one child, the positive side for the other.
  struct Candidate {
    Halfspace cut;
    double score;   ///< larger concavity of the two sides
    double volume;  ///< sum of the two sides' hull volumes
    int vertices;   ///< larger hull vertex count of the two sides
    bool throughWorst;
    double faceArea;  ///< area of the part's polygons lying in the plane (a wall cut along)
    int direction;    ///< index of its normal among the part's cut directions (axes first)
    /// A slab: a second, parallel cut at this larger offset (NaN for a single cut). The part is
    /// cut in three: below `cut`, between the two planes, above this one.
    double slabOffset = std::numeric_limits<double>::quiet_NaN();
    bool isSlab() const { return !std::isnan(slabOffset); }
  };
  /// Splits `part` by the candidate (one cut, or the two planes of a slab).
  std::vector<Part> applyCut(const Part& part, const Candidate& candidate, bool reduce);
  /// Scores the candidate cuts of `part` (decomposition.h lists them); `quick`: fewer offsets and
  /// no refinement. Cuts scoring above `bound` are dropped early.
  std::vector<Candidate> scoreCuts(const Part& part, bool quick, double bound, double* bestScore);
  /// The state and steps of one scoreCuts call (decomposition_cut_search.cpp).
  struct CutSearch;
  const Candidate* pickBest(const Part& part, const std::vector<Candidate>& scored,
                            double bestScore) const;
  /// Tie-break between two cuts of equal score.
  bool betterTie(const Candidate& a, const Candidate& b) const;
  /// Chooses the cut of `part` (with a one-cut lookahead on plateaus) and returns its children.
  bool chooseSplit(const Part& part, std::vector<Part>* children);
  /// The cuts the lookahead tries, `pick` (the greedy choice) first.
  std::vector<const Candidate*> lookaheadOrder(const Part& part, const std::vector<Candidate>& scored,
                                               const Candidate* pick) const;
  /// The cut of `order` whose children leave the least concavity after one more quick cut; its
  /// children in `children` (which holds pick's on entry) and that concavity in `bestAhead`.
  const Candidate* lookahead(const Part& part, const std::vector<const Candidate*>& order, const Candidate* pick,
                             std::vector<Part>* children, double* bestAhead);
  std::vector<Part> split(const Part& part, const Halfspace& cut, bool reduce = true);

  Hull pieceHull(const Piece& a, const Piece* b) const;
  Target pieceTarget(const Piece& a, const Piece* b) const;
  /// Concavity of the merge of a and b (infinite when it is forbidden or exceeds `abortAbove`);
  /// `merged` receives the merged piece when it is finite.
  double mergeCost(const Piece& a, const Piece& b, double abortAbove, Piece* merged);
  std::vector<Piece> merge(std::vector<Piece> pieces, bool forced);

  const CleanMesh& mesh_;
  const DecompositionParams& params_;
  const double target_;        ///< what decisions aim at
  const double reportTarget_;  ///< what the report checks
  const double diagonal_;
  TriangleBvh meshBvh_;
  std::set<std::pair<int, int>> forbidden_;  ///< parts whose merge failed the final check
  std::vector<std::unique_ptr<CutPlane>> planes_;
  std::vector<Part> parts_;
  int budget_ = 0;  ///< pieces allowed in the current budget stage (see run), <= maxPieces
  const std::string name_;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point lastProgress_ = start_;
  std::uint64_t evaluations_ = 0;
};

}  // namespace detail::decomp
}  // namespace deepcheck::robots
