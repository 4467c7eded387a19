#pragma once
// Forward kinematics of up to kLanes configurations at once, in structure-of-arrays form: every
// quantity is a LaneDoubles, a double per lane, whose operations act on all lanes (two AVX2
// registers in the AVX2 build, SSE2 pairs in the baseline one; World::isFreeBatch,
// world_batch.cpp).
//
// Doubles, like robots::forwardKinematics: the poses agree with it to a few ulps of the chain's
// length (the same products in a different order, and sines of our own to a few ulps). The bound
// stage (batch_bounds.h) rounds the centres to floats and its margin (tol::kBatchBoundRelative)
// covers both.

#include "world_internal.h"

#include <Eigen/Core>

#include <cstdint>

#include <vector>

namespace deepcheck::checker::detail {

/// Configurations per batch: one AVX2 register of floats.
constexpr int kLanes = 8;

/// Lanes as two halves of four doubles, GCC vectors of the size of an AVX2 register (a vector of
/// eight doubles is lowered badly without AVX-512: scalars spread through memory). Aligned
/// explicitly: without AVX enabled GCC gives the type only 16-byte alignment, and the AVX2
/// build's aligned loads would then fault.
using LaneHalf = double __attribute__((vector_size(4 * sizeof(double)), aligned(32)));
using LaneHalfBits = std::int64_t __attribute__((vector_size(4 * sizeof(std::int64_t)), aligned(32)));

#define DC_LANES inline __attribute__((always_inline))

/// A comparison's result per lane (all bits set: true).
struct LaneMask {
  LaneHalfBits h[2];
  DC_LANES bool operator[](int l) const { return h[l >> 2][l & 3] != 0; }
  /// Bit l set for lane l true.
  DC_LANES std::uint32_t bits() const {
    std::uint32_t b = 0;
    for (int l = 0; l < kLanes; ++l) b |= static_cast<std::uint32_t>((*this)[l]) << l;
    return b;
  }
};

DC_LANES LaneMask operator|(const LaneMask& a, const LaneMask& b) { return {{a.h[0] | b.h[0], a.h[1] | b.h[1]}}; }

/// A double per lane; lane l is v[l]. Its operations act on every lane; all are inlined, so each
/// build (AVX2, baseline) compiles them for its instruction set.
struct LaneDoubles {
  LaneHalf h[2];
  DC_LANES double operator[](int l) const { return h[l >> 2][l & 3]; }
  DC_LANES void set(int l, double v) { h[l >> 2][l & 3] = v; }
  DC_LANES static LaneDoubles all(double v) { return {{LaneHalf{} + v, LaneHalf{} + v}}; }
};

DC_LANES LaneDoubles operator+(const LaneDoubles& a, const LaneDoubles& b) {
  return {{a.h[0] + b.h[0], a.h[1] + b.h[1]}};
}
DC_LANES LaneDoubles operator-(const LaneDoubles& a, const LaneDoubles& b) {
  return {{a.h[0] - b.h[0], a.h[1] - b.h[1]}};
}
DC_LANES LaneDoubles operator*(const LaneDoubles& a, const LaneDoubles& b) {
  return {{a.h[0] * b.h[0], a.h[1] * b.h[1]}};
}
DC_LANES LaneDoubles operator-(const LaneDoubles& a) { return {{-a.h[0], -a.h[1]}}; }
DC_LANES LaneDoubles operator+(const LaneDoubles& a, double s) { return {{a.h[0] + s, a.h[1] + s}}; }
DC_LANES LaneDoubles operator-(const LaneDoubles& a, double s) { return {{a.h[0] - s, a.h[1] - s}}; }
DC_LANES LaneDoubles operator*(const LaneDoubles& a, double s) { return {{a.h[0] * s, a.h[1] * s}}; }
DC_LANES LaneDoubles operator+(double s, const LaneDoubles& a) { return {{s + a.h[0], s + a.h[1]}}; }
DC_LANES LaneDoubles operator-(double s, const LaneDoubles& a) { return {{s - a.h[0], s - a.h[1]}}; }
DC_LANES LaneDoubles operator*(double s, const LaneDoubles& a) { return {{s * a.h[0], s * a.h[1]}}; }
DC_LANES LaneDoubles& operator+=(LaneDoubles& a, const LaneDoubles& b) { return a = a + b; }
DC_LANES LaneMask operator<(const LaneDoubles& a, double s) { return {{a.h[0] < s, a.h[1] < s}}; }
DC_LANES LaneMask operator>(const LaneDoubles& a, const LaneDoubles& b) { return {{a.h[0] > b.h[0], a.h[1] > b.h[1]}}; }
/// m ? a : b, lane by lane.
DC_LANES LaneDoubles select(const LaneMask& m, const LaneDoubles& a, const LaneDoubles& b) {
  return {{m.h[0] ? a.h[0] : b.h[0], m.h[1] ? a.h[1] : b.h[1]}};
}
DC_LANES LaneDoubles laneAbs(const LaneDoubles& a) { return select(a < 0.0, -a, a); }
DC_LANES LaneDoubles laneMax(const LaneDoubles& a, const LaneDoubles& b) { return select(a > b, a, b); }

/// A point per lane.
struct LanePoint {
  LaneDoubles x, y, z;
};

/// A rigid pose per lane: R[3 * row + col] and t[row], each over the lanes.
struct LanePose {
  LaneDoubles R[9];
  LaneDoubles t[3];
};

/// X p for every lane (p in X's frame).
DC_LANES void posePoint(const LanePose& X, const Eigen::Vector3d& p, LanePoint& out) {
  out.x = X.t[0] + X.R[0] * p[0] + X.R[1] * p[1] + X.R[2] * p[2];
  out.y = X.t[1] + X.R[3] * p[0] + X.R[4] * p[1] + X.R[5] * p[2];
  out.z = X.t[2] + X.R[6] * p[0] + X.R[7] * p[1] + X.R[8] * p[2];
}

/// What the batch's forward kinematics gives: per lane, the links' poses and the centres of the
/// link geometries' bounding spheres in the world (robot pieces are posed by the bound stage,
/// only those it gets to).
struct BatchPoses {
  std::vector<LanePose> links;        ///< per model link
  std::vector<LanePoint> linkCenter;  ///< per LinkGeometry (RobotData::links): center_L posed
  /// Per lane: q finite and every link translation finite (otherwise the lane is left to isFree,
  /// which throws as it does).
  bool finite[kLanes] = {};
  /// Per lane: an upper bound on the length of the chains the poses were computed along (metres:
  /// the base translation, every joint origin's offset, every prismatic joint's travel); the
  /// round-off of the poses is a few ulps of it.
  LaneDoubles chainLength = {};
  std::vector<LaneDoubles> laneQ;  ///< scratch: the lanes' values, variable by variable
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
