#pragma once
// All tolerances and effort settings of deepcheck::decomposition, in one place. Lengths are
// relative to the mesh's bounding-box diagonal D (so a mesh in millimetres decomposes like the
// same mesh in metres) or to the concavity target T; none is absolute.

namespace deepcheck::decomposition::tol {

/// A mesh vertex counts as covered by the pieces (coverageProblem, decomposition.h) when it lies
/// inside some piece grown by kCoverageToleranceRelative * D: far above the round-off of the
/// hulls (~1e-12 D, see Coverage in decomposition.h), far below any feature of a collision mesh.
constexpr double kCoverageToleranceRelative = 1e-9;

/// A hull facet lies on a cut plane when their unit normals differ by less than
/// kOnPlaneNormal (1 - |n1.n2|) and their offsets by less than kOnPlaneRelative * D. The cut
/// points are interpolated on the plane, so their distance to it is round-off (~1e-16 D); the
/// tolerances are far above that and far below any geometric feature.
constexpr double kOnPlaneNormal = 1e-9;
constexpr double kOnPlaneRelative = 1e-9;

/// Each side of a cut must hold a mesh point at least kMinSlabRelative * D away from the plane;
/// thinner slices are not cuts but round-off.
constexpr double kMinSlabRelative = 1e-6;

/// A triangle (input or clipped) whose area is at most (kDegenerateRelative * D)^2 is dropped:
/// it has no surface to sample or to measure against.
constexpr double kDegenerateRelative = 1e-9;

/// Decisions (a part is done, a merge is accepted) compare sampled concavities with
/// kDecisionFraction * T: the final report samples more densely and may find a little more.
constexpr double kDecisionFraction = 0.9;

/// Two cuts whose scores (larger concavity of the two sides) differ by at most kTieFraction * T
/// are equally good; the smaller sum of the sides' hull volumes then decides. Sampling makes the
/// scores noisy at about this level.
constexpr double kTieFraction = 0.1;

/// A decomposition running longer than this (seconds) reports its progress on stderr, at most
/// once per this interval.
constexpr double kProgressSeconds = 1.0;

/// Rounds of cutting (until the budget is spent) and merging (which frees budget).
constexpr int kMaxRounds = 4;
/// Times the final estimate may send pieces back to be cut (decomposition.h, step 4).
constexpr int kVerifyRounds = 2;

/// Piece budget of the first stage: the decomposition works within min(maxPieces, this) pieces
/// and doubles the budget (up to maxPieces) only while the target is missed, so the pieces of a
/// mesh that meets it within this budget do not depend on maxPieces (decomposition.h, step 4).
constexpr int kFirstPieceBudget = 32;

/// Face areas of two cuts (mesh polygons lying in the plane) differing by less than
/// kFaceAreaTie * D^2 are equal.
constexpr double kFaceAreaTie = 1e-6;

/// Two pieces are neighbours (merge candidates) when their hulls' bounding boxes overlap after
/// growing by T.
constexpr double kNeighbourFraction = 1.0;

/// Effort: hull-surface samples per concavity estimate (a candidate cut's side, a part, a
/// merge, the final report), offsets tried per cut direction, and offset refinement rounds.
constexpr int kCandidateSamples = 256;
constexpr int kPartSamples = 1024;
constexpr int kReportSamples = 4096;
constexpr int kOffsetsPerDirection = 6;
/// Planes through the part's points near its worst hull sample: at most kFeatureOffsets per
/// direction, nearest first, at least kFeatureSpacingFraction * T apart.
constexpr int kFeatureOffsets = 4;
constexpr int kQuickFeatureOffsets = 3;  ///< in the lookahead's second cut
constexpr double kFeatureSpacingFraction = 0.25;
constexpr int kRefinementRounds = 3;

/// Hill-climbing of the largest distance on the hull surface: from the last kRefineSeeds samples
/// that raised the maximum, at most kRefineSteps steps each.
constexpr int kRefineSeeds = 3;
constexpr int kRefineSteps = 24;
constexpr int kCandidateRefineSeeds = 1;  ///< for candidate cuts, which are many
constexpr int kCandidateRefineSteps = 12;

/// Three planes whose unit normals have a 3x3 determinant below this meet in no point worth
/// computing (two of them are nearly parallel).
constexpr double kSingularPlanes = 1e-9;

/// Rays cast from a cell corner inside the solid to find the part it belongs to.
constexpr int kCornerRays = 4;

/// Triangles probed (the largest ones) to tell a void from an inside-out component.
constexpr int kVoidProbes = 16;

/// A cut is on a plateau when its score (the larger concavity of its sides) is above
/// kPlateauFraction times the part's concavity: then the cuts through the worst sample, the
/// nearest ones around it, and the kLookaheadBest best scored are compared by what the best
/// second cut leaves.
constexpr double kPlateauFraction = 0.9;
/// When even the lookahead leaves more than kStructuralFraction of the concavity, the cut along
/// the largest mesh face (a wall of the pocket or frame being decomposed) is taken instead.
constexpr double kStructuralFraction = 0.75;
constexpr int kLookaheadBest = 2;
constexpr int kLookaheadCuts = 8;  ///< at most, the greedy choice first

/// A cut leaving a side with at least kSliverVolume of the part's hull volume, and as concave,
/// only shaved a sliver off: no progress.
constexpr double kSliverVolume = 0.99;

/// Two parallel cuts closer than kSameOffsetFraction * T are the same cut (tried once).
constexpr double kSameOffsetFraction = 0.02;

/// Two cut directions closer than this (|cos| of their angle) are the same direction.
constexpr double kSameDirectionCos = 0.966;

}  // namespace deepcheck::decomposition::tol
