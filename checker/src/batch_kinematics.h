#pragma once
// Forward kinematics of up to kLanes configurations at once, in structure-of-arrays form: every
// quantity is an array over the lanes, so the loops over the lanes are plain loops of kLanes
// independent operations that the compiler vectorizes (World::isFreeBatch, world_batch.cpp).
//
// Doubles, like robots::forwardKinematics: the poses agree with it to a few ulps of the chain's
// length (the same products in a different order, and sines of our own to a few ulps). The bound
// stage (batch_bounds.h) rounds the centres to floats and its margin (tol::kBatchBoundRelative)
// covers both.

#include "world_internal.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace deepcheck::checker::detail {

/// Configurations per batch: one AVX2 register of floats.
constexpr int kLanes = 8;

using LaneDoubles = std::array<double, kLanes>;

/// A point per lane.
struct LanePoint {
  alignas(64) LaneDoubles x, y, z;
};

/// A rigid pose per lane: R[3 * row + col] and t[row], each over the lanes.
struct LanePose {
  alignas(64) std::array<LaneDoubles, 9> R;
  alignas(64) std::array<LaneDoubles, 3> t;
};

/// What the batch's forward kinematics gives: per lane, the centres of the link geometries'
/// and the robot pieces' bounding spheres in the world.
struct BatchPoses {
  std::vector<LanePose> links;         ///< per model link
  std::vector<LanePoint> linkCenter;   ///< per LinkGeometry (RobotData::links): center_L posed
  std::vector<LanePoint> pieceCenter;  ///< per RobotPiece: center_L posed
  /// Per lane: q finite and every link translation finite (otherwise the lane is left to isFree,
  /// which throws as it does).
  std::array<bool, kLanes> finite{};
  /// Per lane: an upper bound on the length of the chains the poses were computed along (metres:
  /// the base translation, every joint origin's offset, every prismatic joint's travel); the
  /// round-off of the poses is a few ulps of it.
  LaneDoubles chainLength{};
  std::vector<double> laneQ;  ///< scratch: the lanes' values, variable by variable
};

/// Poses of the columns of qs (robot.model's variables x n, 1 <= n <= kLanes; lanes n and on
/// repeat column n - 1) into `out`. Does not check qs: a lane with a value that is not finite
/// gets finite[lane] false. `avx2`: run the lane loops compiled for AVX2 (batchAvx2Available()),
/// else those compiled for the baseline instruction set; the same arithmetic either way.
void batchForwardKinematics(const RobotData& robot, const Eigen::Ref<const Eigen::MatrixXd>& qs, bool avx2,
                            BatchPoses& out);

/// True when the processor runs AVX2 code. (No FMA: fused and unfused products round differently,
/// and the two builds are to give the same bits.)
bool batchAvx2Available();

}  // namespace deepcheck::checker::detail
