#pragma once
// The bound stage of World::isFreeBatch: which of up to kLanes configurations (posed by
// batch_kinematics.h) are certified free by bounding volumes alone, across the lanes at once.
//
// A lane is certified free when
//   - for every robot link geometry, every world piece whose box the broad phase finds near the
//     union of the lanes' link spheres is allowed to touch it, or lies beyond the link's sphere,
//     or beyond each of its pieces (the piece's sphere beyond the world piece's box, sphere or
//     oriented box, or the piece's oriented box beyond the world box along a world axis, or apart
//     from the world piece's oriented box along one of the separating-axis test's 15 axes);
//   - every self pair is certified by its grid at the lane's q (as isFree does), or has link
//     spheres apart, or each of its piece pairs has spheres apart or oriented boxes apart (the
//     separating-axis test's 15 axes).
// "Beyond" and "apart" mean by tol::kBatchBoundRelative of the test's scale: more than the
// tests' rounding, so the pieces really are that far apart (each bound contains its piece), far
// beyond what isFree's narrow phase could report as touching; isFree then answers free.
// Anything else is left to isFree. Lanes whose poses are not finite are never certified.
//
// With margins (BatchMargins: a certified motion's sub-motions around the lanes), every test asks
// for the pair's margin more: a certified lane keeps each pair farther apart than its margin, so
// World::certifyMotion may take the whole sub-motion as certified (world_motion.cpp).
//
// The sphere tests (against spheres, world boxes and world oriented boxes) run in floats, eight
// lanes in one AVX2 register (intrinsics) or as plain loops in the baseline build: the same float
// operations in the same order, no fused multiply-adds, so both certify the same lanes bit for
// bit. The tests of oriented boxes against each other run in doubles (LaneDoublesW, four-wide
// parts in the AVX2 build, two-wide in the baseline one).

#include "batch_kinematics.h"

#include <cstdint>
#include <type_traits>
#include <vector>

namespace deepcheck::checker::detail {

/// A float per lane (one AVX2 register); lane l is v[l]. Aligned explicitly, as LaneParts.
using LaneFloatV = float __attribute__((vector_size(kLanes * sizeof(float)), aligned(32)));

/// Float copies of a point per lane and its test scale (|centre| max norm + radius + chain
/// length, tol::kBatchBoundRelative).
struct LaneFloats {
  LaneFloatV x, y, z, scale;
};

/// A robot piece's oriented box in the world per lane: its centre, its axes (R[3 k + j]: world
/// component k of box axis j), its half extents along the world axes, and its test scale
/// (|centre| max norm + those extents + chain length).
template <class L>
struct LaneBoxT {
  L c[3], R[9], e[3], scale;
};

/// A context's scratch for isFreeBatch: the poses and oriented boxes of the build that runs
/// (avx2* or baseline*), the rest shared.
struct BatchScratch {
  BatchPosesT<Avx2Lanes> avx2Poses;
  BatchPosesT<BaselineLanes> baselinePoses;
  bool posedAvx2 = false;          ///< the build whose poses the last batch computed
  std::vector<LaneFloats> linkF;   ///< per LinkGeometry
  std::vector<LaneFloats> pieceF;  ///< per RobotPiece, valid when pieceStamp == stamp
  std::vector<std::uint32_t> pieceStamp;
  std::vector<LaneBoxT<Avx2Lanes>> avx2Boxes;  ///< per RobotPiece, valid when boxStamp == stamp
  std::vector<LaneBoxT<BaselineLanes>> baselineBoxes;
  std::vector<std::uint32_t> boxStamp;
  std::uint32_t stamp = 0;
  Eigen::VectorXd q;  ///< one lane's configuration (self-pair grids)
  /// The box around every lane's configuration (and, with a demand, its sub-motion) in which the
  /// self-pair grids are asked first, per variable; made by the first grid test of a batch
  /// (boxReady).
  Eigen::VectorXd boxLower, boxUpper;
  bool boxReady = false;
  std::vector<int> candidates;  ///< world pieces from the broad phase
  std::vector<double> margins;  ///< per link geometry, then per self pair (BatchMargins)
  std::vector<double> speeds;   ///< per link geometry: its posed bound over the lanes (NaN: not made)
  /// With margins: per link geometry, then per self pair, the lanes where it may be within its
  /// margin (every lane tested against every one; the others are clear by the bounds).
  std::vector<std::uint32_t> nearLanes;

  template <class L>
  BatchPosesT<L>& poses() {
    if constexpr (std::is_same_v<L, Avx2Lanes>) {
      return avx2Poses;
    } else {
      return baselinePoses;
    }
  }
  template <class L>
  std::vector<LaneBoxT<L>>& boxes() {
    if constexpr (std::is_same_v<L, Avx2Lanes>) {
      return avx2Boxes;
    } else {
      return baselineBoxes;
    }
  }
};

/// What each lane must keep clear: nothing more than apart (isFree), or, for a certified motion's
/// sub-motions q_l + s dq, |s| <= scale, around the lanes, each pair farther apart than
/// demand.base + scale times the demand's configuration-free bound for the pair (Margins::
/// worldUpper and selfUpper). A link geometry or self pair that this leaves near some lane is
/// tested again with the posed bound over the lanes (batch_speeds.h) where that is smaller (with
/// dq, and every lane posed); a self pair's grid may also certify it along the sub-motion.
struct BatchMargins {
  const ClearanceDemand* demand = nullptr;  ///< null: no margins
  double scale = 0.0;
  const Eigen::VectorXd* dq = nullptr;  ///< the motion's displacement (with a demand)
};

/// Bit l set: lane l (l < qs.cols()) is certified free (with `margins`: clear by its margins). `avx2` chooses the AVX2
/// build (batchAvx2Available(); reads scratch.avx2Poses) or the baseline one (scratch.baselinePoses), each computed for
/// qs by batchForwardKinematics; both give the same answer.
std::uint32_t batchCertifiedLanes(const Snapshot& s, BroadPhase broadPhase, const Eigen::Ref<const Eigen::MatrixXd>& qs,
                                  bool avx2, BatchScratch& scratch, const BatchMargins& margins = {});

}  // namespace deepcheck::checker::detail
