#pragma once
// All numerical tolerances and defaults of deepcheck::checker, in one place.
//
// Lengths are in metres. Relative tolerances say what they are multiplied by.

namespace deepcheck::checker::tol {

/// Bounding volumes (spheres and boxes of pieces and links) are grown by this fraction of
/// (their radius + the distance of their centre from the world origin), so that the round-off of
/// posing them (a few ulps of those magnitudes) can never make a bounding volume miss a point of
/// its piece. 1e-9 is far above double round-off and far below anything a robot could resolve
/// (1 nm at 1 m).
constexpr double kBoundingRelative = 1e-9;

/// World::isFreeBatch's bound stage (checker/src/batch_bounds.h) tests bounding spheres against
/// world boxes, world oriented boxes and each other in floats, and oriented boxes against each
/// other in doubles, and may only conclude "apart". It does so when the computed gap exceeds this
/// fraction (dimensionless) of the test's scale S, metres: the largest |coordinate| of the centres
/// and box corners involved, plus the radii or box extents, plus the length of the kinematic chains
/// that posed the centres (batch_kinematics.h: base offset, joint offsets, prismatic travel).
/// Why it covers the rounding: every float input (a centre coordinate, a box face, a radius) is
/// within u S of its double value (u = 2^-24, about 6e-8), every float box axis within u of its
/// unit vector per component; the coordinate differences (at most 2 S), their projections on a
/// box's axes (about 16 u S with the axes' own error), the clamp to the box and the sum of three
/// squares then add at most about 24 u S to the distance, and the squared threshold a few u of
/// itself: below 32 u S = 2e-6 S in all. The doubles (the poses, the oriented boxes) are off by a
/// few hundred ulps (1e-16) of S at most. So a gap certified this way is a true gap of at least
/// 8e-6 S: far beyond the round-off of the scalar isFree's double bounding tests and the contact
/// tolerance of its narrow phase (geometry::tol::kContactRelative, 1e-12 of the pair's length
/// scale), so isFree finds no overlap there either.
constexpr double kBatchBoundRelative = 1e-5;

/// Added to every |cosine| between box axes in the oriented-box separating-axis test (obb.h), so
/// that nearly parallel edges, whose cross product is numerically meaningless, can never produce
/// a false separating axis; it grows each box by this fraction of its half extents at most
/// (dimensionless).
constexpr double kObbParallel = 1e-9;

/// signedDistance's warm starts are used only between consecutive queries of a context whose
/// configurations differ by at most this in every variable (radians or metres), the steps of
/// motion validation and of optimizers; a query further from the previous one starts every pair
/// cold: DEEP runs fewer restarts when warm, so a stale start would cost accuracy. isFree keeps
/// GJK's warm start across any step (its answer does not depend on it).
constexpr double kWarmStartMaxStep = 0.1;

/// A step of a world's construction (pieces of the robot's links, self-pair grids, obstacles)
/// prints no progress line before it has run this long, and then at most one line this often
/// (seconds; WorldOptions::progress).
constexpr double kProgressQuietSeconds = 1.0;

/// Default margin of the reachability filter, metres: a scene piece is dropped at load time when
/// it is farther than this from every point any robot link can ever reach (the reach spheres of
/// reach.h). Distances reported by the world are exact up to this margin; above it they are only
/// guaranteed to be at least the margin (a dropped piece may be nearer than a kept one then).
constexpr double kDefaultReachMargin = 0.05;

/// Self-pair grids (self_pair_grid.h): a cell is certified free only when the pieces' distance at
/// its centre exceeds the motion bound by this fraction of the pair's size (the sum of the two
/// pieces' bounding radii) on top of the GJK's own relative accuracy: far above the round-off of
/// posing the pieces and of the contact tolerance of the narrow phase (geometry::tol::kContactRelative
/// times the pair's length scale), so a certified pair is one the narrow phase finds apart.
constexpr double kCertifiedGapRelative = 1e-9;

/// Self-pair grids: at most this many cells per grid, and at most kGridMaxPiecePairTests
/// narrow-phase evaluations to build one (cells times piece pairs whose bounding spheres are
/// within reach), which bounds the world's construction time (about a microsecond each).
constexpr int kGridMaxCells = 16384;
constexpr long long kGridMaxPiecePairTests = 1LL << 17;

/// Self-pair grids: a cell's half-width in delta is padded by this fraction of itself plus
/// kGridCellPaddingAbsolute times (1 + |lower limit| + range) of its variable (radians): q's cell
/// index comes from a rounded division, so q may lie a few ulps outside the cell it is given.
constexpr double kGridCellPaddingRelative = 1e-9;
constexpr double kGridCellPaddingAbsolute = 1e-12;

/// Self-pair grid cache (self_pair_grid_cache.h): an entry read from disk is used only when this
/// many of its FREE cells, spread over them deterministically, are certified again (each costs
/// about what one cell's certification costs at construction, of 16,384 cells).
constexpr int kGridCacheSpotChecks = 32;

/// A pair that no joint can change (a robot link moved by no joint, or an object attached to
/// one, against a scene link or an obstacle) is reported at load when its distance is at most
/// this, metres (World::fixedPairs): it bounds the clearance of every state, and below zero makes
/// every state collide. 1 cm: a base bolted to a table top, resting on it or a few millimetres
/// above, is reported; a wall across the room is not.
constexpr double kFixedPairReportDistance = 0.01;

/// Names within this edit distance (or containing one another) of an unknown name are listed as
/// near matches in the error message (allowed collisions, attached objects).
constexpr int kNearMatchEdits = 3;

/// World::certifyMotion refines a sub-motion until no point moves more than this over it (metres,
/// by the bounds); a sub-motion still not certified then leaves the motion Unproven. So a
/// motion that passes within about this of the threshold without reaching it may be refused, and
/// none is ever accepted unproven. Far below any planning tolerance, far above the distances'
/// rounding.
constexpr double kCertifiedResolution = 1e-5;

/// ... and at most this many configurations are tested per motion before it is left Unproven (a
/// motion sliding along a surface within kCertifiedResolution over a long stretch).
constexpr int kCertifiedMaxTests = 1 << 10;

/// World::certifyMotion tests a sub-motion for clearance only when no point moves more than this
/// over it (metres): larger clearances are rare in a robot's workspace and the test would fail;
/// such a sub-motion is only split. Measured on the Panda in MotionBenchMaker's scenes (plan and
/// simplify, bench/mbm_bench): 0.2 m is best, 0.15 and 0.25 m within 5 %.
constexpr double kCertifyBelowMove = 0.2;

}  // namespace deepcheck::checker::tol
