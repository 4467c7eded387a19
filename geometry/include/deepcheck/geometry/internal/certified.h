#pragma once
// The certified expansion (PenetrationMethod::CertifiedExpansion), internal to deepcheck::geometry.
// Certified penetration depth: an expanding surface of Minkowski vertices (van den Bergen 2001's
// expanding polytope), run best-first from GJK's simplex or from supports in twelve directions.
//
// M = B - A contains the origin when A and B overlap. A closed convex surface S of points of M
// that encloses the origin gives a lower bound on the depth: every ray from the origin leaves M
// beyond some face of S, so PD >= min over faces of the face-plane distance. Every support query
// h_M(u) = max u.(b - a), u unit, gives an upper bound: translating B by h_M(u) along -u
// separates the shapes. The expansion pops the nearest face, queries the support in its normal
// (lowering the upper bound), and adds that support point to S (raising the lower bound); it
// stops when the bounds meet within tau = tol::kCertifyRelative * L, L the pair's length scale.
// The result always carries its bracket [lower, upper]; a cap hit or a degenerate surface returns
// the bracket with NotConverged, never a silent guess.
//
// Starts: for pairs known to overlap, the supports of M in twelve directions joined as an
// icosahedron, when that surface is convex and holds the origin strictly inside
// (certifiedFromProbes: no GJK), or the four generic directions below (certifiedWithoutGjk).
// Otherwise GJK's simplex when it is a tetrahedron strictly enclosing the origin; otherwise (the
// origin on the simplex, identical shapes at one pose, touching contact, a flat simplex) the
// supports of M in four generic directions, completed to a tetrahedron with supports normal to
// their span. Faces seen from the origin's far side (negative distance) are expanded first, which
// encloses the origin. A flat M (no tetrahedron of positive volume) returns NotConverged with
// lower bound 0: the caller handles flat pairs (their depth is zero).

#include "deepcheck/geometry/gjk.h"
#include "deepcheck/geometry/internal/certified_warm_start.h"
#include "deepcheck/geometry/internal/expansion_surface.h"
#include "deepcheck/geometry/internal/gauss_map_walk.h"
#include "deepcheck/geometry/penetration_options.h"

namespace deepcheck::geometry::detail {

enum class CertifiedStatus {
  Certified,     ///< upper - lower <= tau
  NotConverged,  ///< cap hit, flat M or a degenerate surface; the bracket is still valid
};

const char* toString(CertifiedStatus s);

/// The facet of M that a surface face's corners name (certifiedFacet): DEEP's facet type and
/// features, set as WalkResult sets them, and the facet's exact unit outward normal u.
struct NamedFacet {
  enum class State {
    Unknown,  ///< not looked up yet
    Named,    ///< the corners name this facet
    None,     ///< the corners name no facet
  };
  State state = State::Unknown;
  WalkResult::FacetType type = WalkResult::FacetType::VF;
  int featureA = 0;
  int featureA2 = -1;
  int featureB = 0;
  int featureB2 = -1;
  Eigen::Vector3d u = Eigen::Vector3d::UnitZ();
};

struct CertifiedResult {
  CertifiedStatus status = CertifiedStatus::NotConverged;
  double lower = 0.0;  ///< PD >= lower >= 0 (frame P units)
  double upper = 0.0;  ///< PD <= upper: h_M(direction)
  double tau = 0.0;    ///< the stopping tolerance, tol::kCertifyRelative * L
  /// Unit outward normal of M at the upper bound (the answer's normal, from A towards B, is its
  /// opposite), and the support pair there: A's vertex minimizing direction.a, B's maximizing
  /// direction.b. Only meaningful when upper is finite.
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  int supportA = 0;
  int supportB = 0;
  /// The certifying face (status Certified): its corners' index pairs, unit normal and offset.
  int faceA[3] = {0, 0, 0};
  int faceB[3] = {0, 0, 0};
  Eigen::Vector3d faceNormal = Eigen::Vector3d::UnitZ();
  /// The facet the certifying face's corners name, when the query looked it up already (a warm
  /// query supports in its normal); Unknown: certifiedFacet() looks it up.
  NamedFacet facet;
  int expansions = 0;  ///< support points added to the surface
  int faces = 0;       ///< live faces at the end
};

/// Certified penetration depth of A and B (cores, Polygon or Polyhedron; for points and segments
/// the depth is enumerated directly by walkPenetration) in the pair frame. Meaningful when GJK
/// found them overlapping or touching: `gjk` is that result (its simplex seeds the surface).
/// `surface` is the caller's scratch space, overwritten; no allocation.
CertifiedResult certifiedPenetration(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                                     const GjkResult& gjk, ExpansionSurface& surface,
                                     const CertifiedOptions& options = {});

/// certifiedPenetration without GJK, for polyhedra the caller knows overlap: the surface starts
/// from the supports of M in four generic directions, completed to a tetrahedron (faces the
/// origin lies beyond are expanded first, which encloses it).
CertifiedResult certifiedWithoutGjk(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                                    ExpansionSurface& surface, const CertifiedOptions& options = {});

/// The best-first expansion of certifiedPenetration from a surface the caller started (a warm
/// start's moved surface, ExpansionSurface::load), which must wind once around the origin.
CertifiedResult certifiedFromSurface(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                                     ExpansionSurface& surface, const CertifiedOptions& options = {});

/// certifiedPenetration without GJK, for polyhedra the caller knows overlap: the surface starts
/// from the supports of M in the twelve probe directions (detail::probeSupport), joined as
/// an icosahedron's faces. False, with `result` untouched, when that is no start: two directions
/// share a support, or the surface is not convex or does not hold the origin strictly inside (the
/// caller then starts otherwise: certifiedWithoutGjk). True with the expansion's result otherwise.
bool certifiedFromProbes(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                         ExpansionSurface& surface, const CertifiedOptions& options, CertifiedResult& result);

/// Saves the surface of a certified cold query at `frame`, the reference of the pair's warm start;
/// leaves `warm` invalid when the surface has more than kMaxFaces faces or a face at non-positive
/// distance (the next query runs cold).
void saveWarmStart(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                   const ExpansionSurface& surface, const CertifiedResult& result, CertifiedWarmStart& warm);

/// The warm query: Certified when the cached surface certifies the depth without expanding,
/// else NotConverged (the caller runs certifiedPenetration).
CertifiedResult certifiedWarm(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                              CertifiedWarmStart& warm);

/// The warm query's second stage, when certifiedWarm() did not certify: the cached surface at
/// the current pose is loaded into `surface` (overwritten) and expanded best-first
/// (certifiedFromSurface). A certified result becomes the warm start's new reference. NotConverged
/// when the surface is not this pair's, a face could have crossed the origin, or the expansion
/// did not converge (the caller then runs certifiedPenetration).
CertifiedResult expandWarm(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame,
                           CertifiedWarmStart& warm, ExpansionSurface& surface, const CertifiedOptions& options = {});

/// Names the facet of M a certified result converged on, from its certifying face's corners
/// (certified_facet.cpp): one vertex of A and a face of B (VF), the reverse (FV), or an edge of
/// each (EE); the facet's exact normal from those features, its offset from one support query in
/// that normal, witness points from the features. Returns false when the corners
/// do not name one facet (they span several coplanar features, or the features found do not
/// support the normal); the caller then names it otherwise (DEEP's facet at the direction,
/// facetInDirection in gauss_map_walk.h, or DEEP's walk from it).
bool certifiedFacet(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, const CertifiedResult& c,
                    WalkResult& out);

/// The facet of M that a surface face's corners (index pairs faceA[k], faceB[k]; unit normal
/// `normal`) name, looked up as certifiedFacet() looks it up: state Named with its type, features
/// and exact normal u, or None. A warm query supports in u and hands the facet on in
/// CertifiedResult::facet, so that certifiedFacet() need not look it up or query u again.
NamedFacet facetOfFace(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, const int* faceA,
                       const int* faceB, const Eigen::Vector3d& normal);

/// The support pair of M in a named facet's normal u, each index in/out (in: the climb's hint):
/// the side whose face the facet is (B's for VF, A's for FV) from ConvexPolytope::faceSupport,
/// the other side (both for EE) by support() from its hint. certifiedFacet() and the warm query
/// both query u here, so that they reach the same vertices.
void facetSupports(const ConvexPolytope& A, const ConvexPolytope& B, const PairFrame& frame, const NamedFacet& facet,
                   int& a, int& b);

}  // namespace deepcheck::geometry::detail
