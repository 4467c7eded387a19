#pragma once
// Approximate convex decomposition of a triangle mesh (collision meshes of robot links and scenes).
//
// Ideas from V-HACD (Mamou, "Volumetric hierarchical approximate convex decomposition", Game
// Engine Gems 3, 2016) and CoACD (Wei et al., "Approximate convex decomposition for 3D meshes
// with collision-aware concavity and tree search", SIGGRAPH 2022): recursive splitting by planes,
// scored by the concavity of the two parts, then merging of neighbours whose common hull stays
// within the concavity target. Written here from the papers' ideas; no code is shared.
//
// Concavity of a piece: the largest distance from a point of its convex hull's surface to the
// mesh solid (zero for points inside it). It is estimated by sampling the hull surface (random
// points, triangle centroids and edge midpoints) and hill-climbing from the worst samples; the
// distance of each sample is exact, so the estimate can only miss a maximum between samples.
//
// Guarantees. Coverage: the union of the pieces contains the mesh (for a closed mesh, its solid;
// sealed inner voids count as solid), up to the round-off of the hull computation (~1e-12 of the
// mesh size). Each piece has at most maxVerticesPerPiece vertices; its reduced hull contains the
// hull of what it covers. The concavity target is met unless maxPieces is too small for the mesh
// (report.targetMet says so). Deterministic for a given seed. The algorithm (cuts, merges,
// vertex reduction) is described in src/decomposer.h.
//
// Units: whatever the mesh is in (metres for URDF meshes); minConcavityAbs is in the same unit.

#include "deepcheck/decomposition/mesh.h"
#include "deepcheck/decomposition/tolerances.h"
#include "deepcheck/geometry/polytope.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace deepcheck::decomposition {

/// Bumped whenever a change of the algorithm changes its output: it is part of the cache key.
constexpr int kDecompositionAlgorithmVersion = 10;

/// Default of DecompositionParams::maxTriangles.
constexpr int kDefaultMaxTriangles = 200000;

struct DecompositionParams {
  /// Concavity target as a fraction of the mesh's bounding-box diagonal, in (0, 1].
  double maxConcavity = 0.01;
  /// Absolute floor of the concavity target (mesh units, metres for URDF), >= 0 and finite:
  /// target = max(maxConcavity * diagonal, minConcavityAbs).
  double minConcavityAbs = 0.002;
  /// Largest number of pieces, >= 1. When the target cannot be met within it, the report says so.
  /// More than 32 are used only by meshes that miss the target with 32.
  int maxPieces = 64;
  /// Largest number of vertices of a piece, >= 4.
  int maxVerticesPerPiece = 64;
  /// Largest number of triangles of a mesh to decompose, >= 1: decomposeConvex refuses a larger
  /// one (std::invalid_argument naming the mesh, its count and this field). The time grows about
  /// linearly with the triangles (bench/README.md, "Loading"); the default caps a load at a minute
  /// or two. Not part of the cache key: it decides whether to decompose, not the result.
  int maxTriangles = kDefaultMaxTriangles;
  /// Merge neighbouring pieces whose merged hull still meets the target.
  bool mergePieces = true;
  /// Seed of the hull-surface sampling (the only randomness; the result is deterministic).
  std::uint64_t seed = 20240611;

  /// The absolute concavity target for a mesh of the given bounding-box diagonal.
  double targetConcavity(double diagonal) const;
  /// Throws std::invalid_argument naming the first parameter out of range and its value.
  void validate() const;
};

/// One convex piece: its hull's vertices and triangulated faces.
struct ConvexPiece {
  std::vector<Eigen::Vector3d> vertices;      ///< in the mesh's frame
  std::vector<std::array<int, 3>> triangles;  ///< hull faces, counter-clockwise seen from outside
                                              ///< (empty for a flat or lower-dimensional piece)
  double volume = 0.0;                        ///< hull volume (0 when flat)
  double concavity = 0.0;                     ///< this piece's concavity (sampled, see above)
};

/// How the on-disk cache took part in a decomposition (see cache.h).
enum class CacheStatus {
  NotUsed,      ///< no cache was used (none given, or caching disabled)
  Hit,          ///< read from the cache: no decomposition ran
  Stored,       ///< not in the cache: decomposed, then written to it
  Replaced,     ///< the cache file was unreadable (truncated, corrupt, other version) or its pieces
                ///< did not cover the mesh (coverageProblem): decomposed, then rewritten
  StoreFailed,  ///< decomposed, but writing the cache failed (report.cacheMessage says why)
};

const char* toString(CacheStatus status);

/// Quality report of one decomposition. Lengths are in mesh units.
struct DecompositionReport {
  std::string source;     ///< the mesh's source (file name), "" when generated
  int numTriangles = 0;   ///< triangles used (after welding and dropping degenerate ones)
  int numVertices = 0;    ///< distinct vertices used
  int numComponents = 0;  ///< connected components of the mesh
  int numPieces = 0;
  int maxPieceVertices = 0;            ///< the most vertices of a piece
  double diagonal = 0.0;               ///< bounding-box diagonal of the mesh
  double targetConcavity = 0.0;        ///< absolute target, params.targetConcavity(diagonal)
  double concavity = 0.0;              ///< achieved: max over pieces (sampled, see the header comment)
  double concavityRelative = 0.0;      ///< concavity / diagonal
  bool targetMet = false;              ///< concavity <= targetConcavity
  double hullConcavity = 0.0;          ///< concavity of the mesh's own hull (before vertex reduction)
  bool alreadyConvex = false;          ///< the mesh's own hull met the target: one piece, no cuts (its
                                       ///< concavity includes what the vertex reduction added)
  int holesFilled = 0;                 ///< simple holes (boundary loops) closed before decomposing
  int duplicatesRemoved = 0;           ///< triangles dropped as repeats of an earlier one (the same
                                       ///< three vertices, either winding: repeated or two-sided faces)
  int voidsRemoved = 0;                ///< sealed inner cavities (inward-facing closed components inside
                                       ///< others) ignored: they cannot be reached, covering them is free
  bool meshClosed = false;             ///< every edge is shared by an even number (>= 2) of triangles,
                                       ///< once the holes are filled
  double meshVolume = 0.0;             ///< by the divergence theorem, once the holes are filled (voids
                                       ///< count negative); NaN when not closed
  double piecesVolume = 0.0;           ///< sum of the piece hull volumes (overlaps counted twice)
  double volumeRatio = 0.0;            ///< piecesVolume / meshVolume; NaN when not closed
  double decomposeMilliseconds = 0.0;  ///< wall time of the decomposition (as stored, on a hit)
  double milliseconds = 0.0;           ///< wall time of this call (a cache read on a hit)
  CacheStatus cache = CacheStatus::NotUsed;
  std::string cacheMessage;  ///< why a cache file was replaced or could not be written
  /// One line naming the mesh, how far its worst piece ends outside it and the target, when a
  /// piece misses the target; "" otherwise (targetWarning). decomposeConvexCached prints it on
  /// stderr; callers of decomposeConvex print it themselves.
  std::string warning;
};

struct ConvexDecomposition {
  std::vector<ConvexPiece> pieces;
  DecompositionReport report;

  /// The pieces as polytopes (ConvexPolytope::fromPoints of each piece's vertices).
  std::vector<geometry::ConvexPolytope> polytopes() const;
};

/// Decomposes `mesh` as described above. Throws std::invalid_argument, with a message naming the
/// mesh's source and the bad input, when the mesh has no triangle, a vertex is NaN or infinite,
/// a triangle index is out of range, all triangles are degenerate, or a parameter is out of range.
ConvexDecomposition decomposeConvex(const TriangleMesh& mesh, const DecompositionParams& params = {});

/// The report's warning (see DecompositionReport::warning) for `pieces` and the report's source,
/// target and piece limits: "" when every piece meets the target.
std::string targetWarning(const DecompositionReport& report, const std::vector<ConvexPiece>& pieces);

/// Why `pieces` do not cover `mesh`: "" when every vertex of its non-degenerate triangles lies
/// inside some piece grown by tol::kCoverageToleranceRelative of the diagonal (the pieces' face
/// planes decide); otherwise a phrase naming the first vertex outside, its position and its
/// distance to the nearest piece. Throws std::invalid_argument for an invalid mesh, as
/// decomposeConvex does. Costs about (vertices x faces of one piece): a cheap check of a result
/// read from elsewhere (the cache) before it is trusted.
std::string coverageProblem(const TriangleMesh& mesh, const std::vector<ConvexPiece>& pieces);

/// True when `point` is inside `piece` or within `tolerance` of it (uses the hull faces; a flat
/// piece counts as a plate of thickness 2 * tolerance).
bool pieceContains(const ConvexPiece& piece, const Eigen::Vector3d& point, double tolerance);

/// Writes the pieces as a Wavefront OBJ text: one `o piece_<i>` object per piece with its
/// vertices and hull faces (indices global, 1-based, as OBJ wants). Throws std::runtime_error
/// naming the file when it cannot be written.
void writePiecesObj(const std::string& path, const std::vector<ConvexPiece>& pieces);

}  // namespace deepcheck::decomposition
