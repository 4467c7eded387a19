#pragma once
// All numerical tolerances of deepcheck::geometry, in one place.
//
// Every tolerance is relative: it is multiplied by a length scale L of the shapes involved
// (for a single hull, its bounding radius about its centroid; for a pair, the larger of the two
// bounding radii plus the distance between their centres), so results do not change when
// a scene is expressed in millimetres instead of metres. Absolute values are never used.

namespace deepcheck::geometry::tol {

/// Thickness of a point set, relative to its size, below which it is treated as lower-dimensional:
/// a set whose points all lie within kFlatRelative * L of a plane is a polygon, of a line a
/// segment, of a point a point. Chosen far above double round-off (1e-16) so that rotated exactly
/// flat inputs are recognized, far below any real geometric feature of a robot mesh.
constexpr double kFlatRelative = 1e-10;

/// Round-off carried by input coordinates, relative to their largest magnitude: the coordinates of
/// a point set are only known to about kCoordinateRoundoff * max|x| (a few tens of ulps), so a
/// thickness or a distance below that is noise, not geometry. Hull building uses
/// max(kFlatRelative * L, kCoordinateRoundoff * max|x|) as its flatness tolerance; the floor only
/// matters for small shapes given far from their frame's origin (1 mm at 10 km).
constexpr double kCoordinateRoundoff = 1e-14;

/// Two hull facets whose normals differ by less than this angle (radians) and whose vertices all
/// lie within kFlatRelative * L of the common plane are merged into one polygonal face, so Gauss
/// maps have no zero-length arcs.
constexpr double kCoplanarAngle = 1e-10;

/// Tolerance for "a vertex supports this direction too" when collecting supporting features
/// (the face, edge or vertex of a hull touching a supporting plane): kFeatureRelative * L.
constexpr double kFeatureRelative = 1e-11;

/// Convergence of GJK distance: stop when the lower and upper bounds on the squared distance
/// agree to this relative precision.
constexpr double kGjkRelative = 1e-14;

/// gjkBound's looser convergence (relative, of the squared distance): its lower bound v.w / |v|
/// then lies within this fraction of the distance. A caller bounding a motion's sweep by it
/// (certified motions) trades a smaller certified part per test against GJK iterations: 0.02, 0.1,
/// 0.3 and 0.6 measured 1.01x, 1.00x, 0.99x and 1.10x the time of 0.1 on RRTConnect's
/// MotionBenchMaker problems (bench/mbm_bench).
constexpr double kGjkBoundGap = 0.3;

/// A DEEP step must improve the depth by more than kImproveRelative * L to be taken; smaller
/// changes are round-off, and accepting them could cycle.
constexpr double kImproveRelative = 1e-14;

/// The foot point of the origin on a Minkowski-difference facet may lie outside the facet by at
/// most kInsideRelative * L for the facet to count as a local minimum (KKT point).
constexpr double kInsideRelative = 1e-12;

/// Edge directions whose cross product is shorter than kParallelSine * |e1| * |e2| are treated as
/// parallel: they span no edge-edge facet of the Minkowski difference.
constexpr double kParallelSine = 1e-9;

/// Gauss map clipping (the walk's local overlays): a unit direction within this of a clipping plane
/// (the sine of its angle to the plane, dimensionless) counts as on the plane, so that corners of
/// degenerate overlays (parallel faces) are kept instead of being decided by round-off.
constexpr double kOnPlaneSine = 1e-13;

/// Naming the facet a certified surface face lies on: a feature's unit normal whose cosine with
/// the face's normal exceeds this (dimensionless) may be that facet's. Corners on one facet give a
/// face normal equal to the facet's to round-off, corners on different facets one off by far
/// more; a support query then decides, so this only pre-selects.
constexpr double kSameNormalCosine = 1.0 - 1e-6;

/// What a built hull guarantees, as a multiple of its flatness tolerance (polytope.h,
/// hullTolerance): merging coplanar facets within the flatness tolerance and dropping vertices
/// within it of the hull of their neighbours add up to a few times it.
constexpr double kHullToleranceFactor = 8.0;

/// ConvexPolytope's invariant check: stored unit normals are unit, and a polygon's two face
/// normals opposite, to this (dimensionless, round-off of a normalised double vector).
constexpr double kUnitRoundoff = 1e-12;

/// Shapes whose GJK distance is below kContactRelative * L are treated as touching and handed to
/// DEEP, whose depth is then ~0: this keeps the signed distance continuous through contact.
constexpr double kContactRelative = 1e-12;

/// Certified penetration depth: the expansion stops when its upper bound (a support of M) is
/// within kCertifyRelative * L of its lower bound (the nearest face of the expanding surface), L
/// the pair's length scale. A few ulps of L above the round-off of a face-plane offset, so that
/// a certified depth is also within 1e-12 of the depth whenever the depth exceeds L / 100.
constexpr double kCertifyRelative = 1e-14;

/// A pose is rejected when its rotation R has max |(R^T R - I)_ij| at or above this (dimensionless).
constexpr double kOrthonormal = 1e-6;

/// Body penetration depth (body_depth.h): a point is strictly inside a Minkowski difference of two
/// pieces when it is inside every face plane by more than kBodyMemberRelative * L, and on a face
/// when within that of its plane and inside the others' by -that; L is the bodies' length scale
/// (the largest distance of a piece vertex from A's origin, in metres). Above the round-off of
/// plane intersections of size-L coordinates (1e-15 L), far below any real feature.
constexpr double kBodyMemberRelative = 1e-12;

/// Body penetration depth: two lines in a face plane whose unit directions have a cross product
/// shorter than this (dimensionless, the sine of their angle) are parallel and not intersected;
/// two planes likewise have no trace on each other.
constexpr double kBodyParallelSine = 1e-9;

}  // namespace deepcheck::geometry::tol
