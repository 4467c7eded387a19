#pragma once
// Internal to deepcheck::decomposition: the decomposer, its parts and pieces (decomposition.cpp
// drives them; decomposition.h gives the overview and the guarantees).
//
// Approximate convex decomposition: recursive plane cuts scored by concavity, then merging and
// vertex reduction (decomposition.h gives the contract and the guarantees).
//
// Steps:
//   1. Weld identical vertices, drop degenerate triangles, fill simple holes (a missing quad of a
//      wall is common in CAD exports), orient components outward, drop sealed inner voids.
//   2. If the hull of the whole mesh meets the target, it is the one piece ("already convex"),
//      reduced to maxVerticesPerPiece; no decomposition. Should the reduction add more than the
//      target allows, the report's warning says so: a convex mesh is never split.
//   3. Otherwise, repeatedly take the part of largest concavity and cut it by the candidate plane
//      that minimizes the larger concavity of the two sides; candidates are axis-aligned and
//      principal-axis planes at several offsets and through the features around the worst
//      concavity, and slabs between two walls. Plateaus (no single cut helps) are handled by a
//      one-cut lookahead, then by cutting along a wall. A cut triangle is clipped to both sides.
//      Each side is split again into its connected components.
//   4. When the budget's number of parts exist, merge neighbouring pieces whose merged hull meets
//      the target (cheapest first), which frees budget for more cuts; repeat. Finally, if there
//      are still more pieces than the budget, merge the cheapest pairs until there are not. The
//      final, denser concavity estimate sends pieces above the target back to be cut.
//      The budget grows in stages: steps 3-4 run first within min(maxPieces, 32) pieces; only if
//      the target is still missed do they go on from that result (pieces above the target
//      reopened, forced merges undone) with twice the budget, up to maxPieces. So a mesh that
//      meets the target within 32 pieces gets the same pieces whatever maxPieces is.
//   5. Each hull is reduced to at most maxVerticesPerPiece vertices while keeping it CONTAINING
//      the original hull (see below); the target applies to the reduced pieces, in steps 2-4.
//
// Decisions aim at kDecisionFraction (0.9) of the target, so that the final estimate, which
// samples more, stays within it. The target may still be missed when maxPieces is too small for
// the mesh: report.targetMet says so.
//
// Coverage: every point of every triangle lies in the hull of the part it was assigned to (a cut
// triangle's pieces go to both sides); for a closed mesh the solid is covered too, because each
// part's hull also takes the corners of its cell that lie inside the solid (where the solid's
// cut faces end) and parts are never split more finely than the solid is connected. Merging
// only enlarges hulls, and so does the vertex reduction. So the union of the pieces contains the
// mesh (sealed inner voids count as solid), up to the round-off of the hull computation (~1e-12
// of the mesh size).
//
// Vertex reduction (maxVerticesPerPiece) keeps CONTAINMENT: a progressive hull (Sander et al.,
// "Silhouette clipping", SIGGRAPH 2000) collapses hull edges (u, v) into a new vertex placed on or
// outside the plane of every face around u and v, so each step's hull contains the previous one;
// the collapse whose new vertex is nearest to the original hull goes first (the new vertex
// minimizes the added volume). Each collapse is verified (u and v inside the new hull). Should it
// fail to reach the budget, the fallback is an intersection of supporting half-spaces (at most
// 2k - 4 vertices for k planes). The bound: every point of a reduced piece is within `excess` of
// the unreduced hull, `excess` being the largest distance from a reduced vertex to that hull, so
// concavity(reduced) <= concavity(hull) + excess. A hull is reduced only once it meets the target,
// and the concavity that must meet the target is the reduced piece's: a part whose reduced hull
// misses it is cut further (into sides with fewer hull vertices), and so are merges.
//
// Parts. A part is the piece of the mesh surface inside a convex cell (the intersection of the
// half-spaces of the cuts that led to it): the mesh triangles clipped to the cell (convex
// polygons), plus the cell's corners that lie inside the solid. Its hull is the hull of those
// points. Coverage: the solid inside the cell is bounded by the polygons and by caps (the solid's
// cut faces) on the cell planes; a cap is bounded by polygon edges and by cell edges, whose ends
// are polygon vertices or cell corners; so the hull holds the caps, hence the solid. Each side of
// a cut is split into components joined through mesh edges and through the regions of the cut
// faces (loops of the cross-section that cross or nest, cross_section.h), never more finely
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
// Files: mesh_repair.cpp (CleanMesh, clean_mesh.h), cross_section.cpp (CrossSection,
// cross_section.h), concavity.cpp (measureConcavity, concavity.h), parts.cpp (parts and their
// components), cut_search.cpp (candidate cuts and the choice among them), merge.cpp (merging
// pieces), decomposition.cpp (the driver, Decomposer::run), obj.cpp (OBJ output); hull.h and
// bvh.h (hulls and point-to-mesh distances), basics.h (shared helpers).

#include "deepcheck/decomposition/decomposition.h"
#include "deepcheck/decomposition/tolerances.h"

#include "basics.h"
#include "bvh.h"
#include "clean_mesh.h"
#include "concavity.h"
#include "cross_section.h"
#include "hull.h"
#include "union_find.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace deepcheck::decomposition::detail {

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
  std::vector<Vector3d> points;   ///< distinct corners of the polygons, and the cell corners
  Hull hull;                      ///< hull of the points
  Hull finalHull;                 ///< hull, reduced to the vertex budget when it met the target
  double hullConcavity = 0.0;     ///< concavity of `hull`
  double concavity = 0.0;         ///< concavity of `finalHull`: what has to meet the target
  bool reductionLimited = false;  ///< hull meets the target, but not once reduced
  bool hasWorst = false;
  Vector3d worstSample = Vector3d::Zero();   ///< hull surface point farthest from the part
  Vector3d worstNearest = Vector3d::Zero();  ///< the part's point nearest to it
  bool unsplittable = false;                 ///< no valid cut was found
  bool reduced = false;                      ///< finishPart ran
  bool noSlivers = false;                    ///< a sliver cut made no progress: cuts leaving a sliver are skipped
};

struct Piece {
  std::vector<int> parts;
  Hull hull;               ///< hull of the parts' points
  Hull finalHull;          ///< hull reduced to the vertex budget
  double concavity = 0.0;  ///< of finalHull
};

class Decomposer {
 public:
  /// `target`: the absolute concavity target; decisions aim at kDecisionFraction of it.
  /// `name`: the mesh as messages name it (meshName), for the progress lines.
  Decomposer(const CleanMesh& mesh, const DecompositionParams& params, double target, std::string name)
      : mesh_(mesh),
        params_(params),
        target_(tol::kDecisionFraction * target),
        reportTarget_(target),
        diagonal_(mesh.diagonal),
        name_(std::move(name)) {
    std::vector<Triangle> triangles;
    triangles.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles)
      triangles.push_back({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});
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
  Part makePart(std::vector<CellSide> cell, std::vector<PartPolygon> polygons, std::vector<Vector3d> cellCorners,
                bool reduce = true, const Vector3d* hint = nullptr);
  /// Reduces the part's hull to the vertex budget (once) and measures the reduced hull.
  void finishPart(Part* part);
  struct Component {
    std::vector<PartPolygon> polygons;
    std::vector<Vector3d> cellCorners;
  };
  std::vector<Component> components(std::vector<PartPolygon> polygons, const std::vector<CellSide>& cell) const;
  // The steps of components() (parts.cpp): union-find over the source triangles
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
  /// The state and steps of one scoreCuts call (cut_search.cpp).
  struct CutSearch;
  const Candidate* pickBest(const Part& part, const std::vector<Candidate>& scored, double bestScore) const;
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

}  // namespace deepcheck::decomposition::detail
