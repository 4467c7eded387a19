#pragma once
// The one entry point to Qhull (reentrant API) in deepcheck: the 3-d convex hull of a point set
// as facet loops of point indices, for every caller that needs Qhull's hull (polytope building,
// the exact reference, the convex decomposition). Qhull's types stay behind this header.
//
// Error strategy, the same for every caller: input Qhull cannot hull as a solid throws
// QhullError, whose message starts with the caller's `name` and says why (fewer than four
// points, or Qhull's own diagnosis: a flat or collinear set, all points equal, a precision
// failure). Non-finite or out-of-range coordinates throw std::invalid_argument naming the point.
// Nothing is printed. Callers that have a lower-dimensional answer (a polygon, a segment, a
// point) classify their input first or catch QhullError and fall back; the wrapper itself never
// guesses.

#include <Eigen/Core>

#include <stdexcept>
#include <string>
#include <vector>

namespace deepcheck::geometry {

/// Qhull could not build a 3-d hull of the points (flat, collinear or too few points, or a
/// precision failure). what() names the caller's point set and carries Qhull's diagnosis.
class QhullError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct QhullOptions {
  /// Absolute merge distance m: Qhull pre-merges facets whose centrum lies within m of a
  /// neighbour's plane (option C-m), so coplanar triangles come out as one polygonal facet.
  /// Negative: Qhull's default for 3-d (merging at round-off level, 'C-0' implied).
  double mergeDistance = -1.0;
  /// Triangulate every facet (option Qt): loops of three points, coplanar facets share a plane.
  bool triangulate = false;
  /// Search all points for the initial simplex (option Qs): slower to start, robust on thin sets.
  bool searchAllPoints = true;
};

/// Qhull's 3-d hull, as indices into the caller's point list.
struct QhullHull {
  /// Points that are hull vertices, in Qhull's vertex order.
  std::vector<int> vertices;
  /// Facet loops, counter-clockwise seen from outside (about the facet's normal). Triangles of a
  /// triangulated hull start at Qhull's first vertex of the facet.
  std::vector<std::vector<int>> loops;
  /// Per facet: Qhull's unit outward normal n and offset d, the facet's plane being n.x = d.
  std::vector<Eigen::Vector3d> normals;
  std::vector<double> offsets;
};

/// Minimum number of points of a 3-d hull (a tetrahedron); fewer throw QhullError.
constexpr int kQhullMinPoints = 4;
/// Largest accepted magnitude of a coordinate, in the caller's unit: Qhull's determinants are
/// cubes of coordinate differences, (2 * 1e100)^3 = 8e300 < DBL_MAX. Twice range::kMaxCoordinate
/// and more (Minkowski differences of valid shapes) fit.
constexpr double kQhullMaxCoordinate = 1e100;

/// The convex hull of `points`. Throws std::invalid_argument for a non-finite coordinate or one
/// beyond kQhullMaxCoordinate, QhullError when no solid hull exists (see the header comment).
/// Duplicated points are allowed (one of them becomes the vertex). `name` is used in messages only.
QhullHull qhullHull(const std::vector<Eigen::Vector3d>& points, const QhullOptions& options, const std::string& name);

}  // namespace deepcheck::geometry
