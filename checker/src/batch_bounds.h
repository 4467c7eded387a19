#pragma once
// The bound stage of World::isFreeBatch: which of up to kLanes configurations (posed by
// batch_kinematics.h) are certified free by bounding spheres alone, in floats across the lanes.
//
// A lane is certified free when, for every robot link geometry, every world piece whose box the
// broad phase finds near the union of the lanes' link spheres either is allowed to touch it, or
// lies beyond the link's sphere, or beyond each of its pieces' spheres (against the box or the
// world piece's sphere); and every self pair is certified by its grid at the lane's q or has
// link spheres apart. "Beyond" means by tol::kBatchBoundRelative of the test's scale: then the
// scalar isFree's double bounding tests reject that pair too (tolerances.h), and isFree is true.
// Anything else is left to isFree. The lanes whose poses are not finite are never certified.
//
// The tests are compiled twice: with AVX2 intrinsics (eight float lanes in one register) and as
// plain loops for the baseline instruction set. Both evaluate the same float operations in the
// same order without fused multiply-adds, so they certify the same lanes bit for bit.

#include "batch_kinematics.h"

#include <cstdint>
#include <vector>

namespace deepcheck::checker::detail {

/// Float copies of a point per lane and its test scale (|centre| max norm + radius + chain
/// length, tol::kBatchBoundRelative).
struct LaneFloats {
  alignas(32) float x[kLanes];
  alignas(32) float y[kLanes];
  alignas(32) float z[kLanes];
  alignas(32) float scale[kLanes];
};

/// A context's scratch for isFreeBatch.
struct BatchScratch {
  BatchPoses poses;
  std::vector<LaneFloats> linkF;   ///< per LinkGeometry
  std::vector<LaneFloats> pieceF;  ///< per RobotPiece
  Eigen::VectorXd q;               ///< one lane's configuration (self-pair grids)
  std::vector<int> candidates;     ///< world pieces from the broad phase
};

/// Bit l set: lane l (l < qs.cols()) is certified free. Reads scratch.poses, computed for qs by
/// batchForwardKinematics; `avx2` chooses the AVX2 tests (batchAvx2Available()) or the baseline
/// ones, with the same answer.
std::uint32_t batchCertifiedLanes(const Snapshot& s, BroadPhase broadPhase, const Eigen::Ref<const Eigen::MatrixXd>& qs,
                                  bool avx2, BatchScratch& scratch);

}  // namespace deepcheck::checker::detail
