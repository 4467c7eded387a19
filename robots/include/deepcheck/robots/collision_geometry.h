#pragma once
// The convex pieces of each link, as the collision checker consumes them.
//
// A piece is a convex core (a geometry::ConvexPolytope: point, segment, polygon or polyhedron) plus a
// radius, placed in its link's frame by X_LP. The checker poses it at X_WL * X_LP. Pieces are
// shared (shared_ptr to const): the same mesh used twice (the Panda's two fingers) is loaded and
// decomposed once per call.
//
// Primitives stay primitive (no mesh is made):
//   box       ConvexPolytope::box(size): 8 vertices, exact.
//   sphere    a Point core with the sphere's radius: exact.
//   cylinder  a circumscribed prism: a regular N-gon whose edges are tangent to the circle of
//             radius r (apothem r, so its corners are at r / cos(pi / N)), extruded over the full
//             length. The prism CONTAINS the cylinder (a missed collision is worse than a false
//             alarm) and sticks out of it by at most r * (1 / cos(pi / N) - 1) (at the corners;
//             zero at the caps and along the tangent lines). N is the smallest number of sides
//             that keeps this within `cylinderMaxDeviation` (default tol::kCylinderMaxDeviation
//             = 1 mm), clamped to [tol::kCylinderMinSides, tol::kCylinderMaxSides].
//             Why not exact: a cylinder is not a core plus a radius (a segment plus a radius is a
//             capsule, which overshoots by r at both ends: 5 cm on a 5 cm-radius part, far worse
//             than a prism), and the deep library's shapes are polytope cores with a radius.
// Meshes: the mesh is loaded (mesh_loader.h: URDF scale applied, degenerate triangles dropped) and
// handed to a MeshDecomposer, which returns convex polytopes in the mesh's frame G. The default,
// convexHullDecomposer, returns the single convex hull of the vertices; meshDecomposer gives the
// convex decomposition (deepcheck/decomposition/decomposition.h) through its on-disk cache.
//
// Frames: L the link, G the collision element (URDF <collision><origin>), P the piece; for every
// piece built here P = G, so X_LP = CollisionElement::X_LG. Metres.

#include "deepcheck/robots/mesh.h"
#include "deepcheck/robots/mesh_loader.h"
#include "deepcheck/robots/robot_model.h"
#include "deepcheck/robots/tolerances.h"

#include "deepcheck/decomposition/decomposition.h"
#include "deepcheck/geometry/polytope.h"

#include <Eigen/Geometry>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace deepcheck::robots {

struct CollisionPiece {
  std::shared_ptr<const geometry::ConvexPolytope> core;
  double radius = 0.0;                                     ///< >= 0, metres
  Eigen::Isometry3d X_LP = Eigen::Isometry3d::Identity();  ///< pose of the piece in its link
  /// Where it comes from, for messages and reports, e.g.
  /// "link panda_link3 collision 0 mesh link3.stl piece 2" or "link ee_link collision 0 box".
  std::string origin;
};

/// Turns a collision mesh (in its frame G, metres) into convex polytopes in G whose union
/// contains it. Throws std::invalid_argument on failure.
using MeshDecomposer = std::function<std::vector<geometry::ConvexPolytope>(const TriangleMesh& mesh)>;

/// The default decomposer: one piece, the convex hull of the mesh's vertices.
std::vector<geometry::ConvexPolytope> convexHullDecomposer(const TriangleMesh& mesh);

/// Which decomposer meshDecomposer makes.
struct DecomposerOptions {
  /// Convex decomposition when true; one convex hull per mesh (convexHullDecomposer) when false.
  bool decompose = true;
  decomposition::DecompositionParams parameters;
  /// Directory of the decomposition's on-disk cache; "" means
  /// decomposition::DecompositionCache::defaultDirectory().
  std::string cacheDir;
};

/// The decomposer of `options`: decomposition::decomposeConvexCached with options.parameters
/// through the cache in options.cacheDir, or convexHullDecomposer. `largestConcavity`, when
/// given, records how far pieces may stick out of their meshes: raised to the concavity of every
/// decomposition made (DecompositionReport::concavity, mesh units), NaN once a mesh is made into
/// its hull, which is not measured. Throws std::invalid_argument for parameters out of range
/// (DecompositionParams::validate) when `decompose` is on.
MeshDecomposer meshDecomposer(const DecomposerOptions& options, std::shared_ptr<double> largestConcavity = nullptr);

struct CollisionGeometryOptions {
  /// Largest distance the prism of a cylinder may stick out of it, metres (> 0).
  double cylinderMaxDeviation = tol::kCylinderMaxDeviation;
  /// How meshes become pieces; empty means convexHullDecomposer.
  MeshDecomposer decomposer;
  /// How mesh files are read (their size limit).
  MeshLoadOptions meshLoad;
};

/// Number of sides of the circumscribed prism of a cylinder of radius `radius` (see above).
int cylinderSides(double radius, double maxDeviation);

/// The circumscribed prism of a cylinder along z, centred at the origin (see above).
geometry::ConvexPolytope cylinderPrism(double radius, double length, double maxDeviation);

/// The piece of a primitive geometry (box, sphere or cylinder, as above) in its own frame G
/// (X_LP identity). `what` names it: the piece's origin is `what` followed by " box", " sphere" or
/// " cylinder (N-sided prism)". Throws std::invalid_argument, starting with `what`, for a size
/// that is not positive and finite, or for a mesh geometry (see meshPolytopes).
CollisionPiece primitivePiece(const Geometry& geometry, const CollisionGeometryOptions& options,
                              const std::string& what);

/// The convex polytopes of a mesh by options.decomposer (convexHullDecomposer when empty).
/// Throws std::invalid_argument for an empty mesh, or when the decomposer fails or returns none.
std::vector<geometry::ConvexPolytope> meshPolytopes(const TriangleMesh& mesh, const CollisionGeometryOptions& options);

/// Pieces of one link (empty for a link without collision geometry).
std::vector<CollisionPiece> linkCollisionPieces(const RobotModel& model, int link,
                                                const CollisionGeometryOptions& options = {});

/// Pieces of every link: result[link]. Each mesh (path and scale) is loaded and decomposed once.
/// Errors (unreadable meshes, decomposer failures) are std::invalid_argument naming the URDF,
/// link and collision element.
std::vector<std::vector<CollisionPiece>> collisionPieces(const RobotModel& model,
                                                         const CollisionGeometryOptions& options = {});

}  // namespace deepcheck::robots
