#pragma once
// How signedDistance computes the depth of overlapping shapes: the method and its settings, one
// options struct per method (docs/penetration-depth.md describes both methods).

namespace deepcheck::geometry {

/// The algorithm for overlapping shapes.
enum class PenetrationMethod {
  /// An expanding surface of Minkowski-difference points brackets the depth from below and above
  /// until the bracket is within tol::kCertifyRelative * L; the answer's facet is named from the
  /// certifying face. Exact and certified; the default.
  CertifiedExpansion,
  /// Walks over the overlay of the two shapes' Gauss maps (DEEP, Kim, Lin, Manocha 2002), from a
  /// few start directions: fast when warm, but a walk can stop in a local minimum (too deep).
  GaussMapWalk,
};

/// "certified" or "deep-walk", the names the command-line tools accept.
const char* toString(PenetrationMethod m);

/// Settings of the certified expansion.
struct CertifiedOptions {
  /// Cap on support points the expansion adds to its surface; beyond it the query reports its
  /// bracket with status NotConverged.
  int maxExpansions = 128;
};

/// Settings of the Gauss-map walk. The certified expansion also walks where it cannot name a
/// facet from its surface (points, segments, an expansion that did not converge); there it uses
/// these settings too.
struct WalkOptions {
  /// Cold queries walk from every start direction (the centroid difference, its opposite and both
  /// signs of the principal axes of A and B). False: one walk from the centroid difference,
  /// faster, but it ends in a worse local minimum more often.
  bool restarts = true;
  /// Visit the start directions in order of their supporting plane's offset and skip those whose
  /// plane is no closer than the best facet found so far: faster cold queries, but a walk can
  /// descend below its start, so some pairs end in a worse local minimum.
  bool pruneRestarts = false;
  /// A warm query also walks from the centroid difference, which guards against a basin that none
  /// of the cached ones leads to.
  bool warmCentroidStart = true;
  /// After this many consecutive warm queries the next one runs all cold starts, to refresh the
  /// cached basins (0: never).
  int refreshEvery = 32;
  /// Cap on hub pairs evaluated per walk (reaching it gives status NotConverged).
  int maxHubsPerWalk = 256;
};

/// The options of signedDistance for overlapping shapes.
struct PenetrationOptions {
  PenetrationMethod method = PenetrationMethod::CertifiedExpansion;
  /// Use the pair cache's warm start when it is valid (either method).
  bool warmStart = true;
  CertifiedOptions certified;
  WalkOptions walk;
};

}  // namespace deepcheck::geometry
