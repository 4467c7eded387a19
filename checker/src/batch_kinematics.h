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

/// Lanes as parts of kPartLanes doubles each, GCC vectors of the size of a register (a vector of
/// eight doubles is lowered badly without AVX-512: scalars spread through memory). Aligned
/// explicitly: without AVX enabled GCC gives a 32-byte vector type only 16-byte alignment, and
/// the AVX2 build's aligned loads would then fault. Four, an AVX2 register: the baseline build
/// then lowers each part through memory (its kinematics take about 7 times as long as AVX2's on
/// the bundled arm); with two, AVX2's would take 1.5 times as long and the baseline's 1.7 times
/// AVX2's with four.
constexpr int kPartLanes = 4;
constexpr int kParts = kLanes / kPartLanes;
using LanePart = double __attribute__((vector_size(kPartLanes * sizeof(double)), aligned(kPartLanes * sizeof(double))));
using LanePartBits =
    std::int64_t __attribute__((vector_size(kPartLanes * sizeof(std::int64_t)), aligned(kPartLanes * sizeof(double))));

#define DC_LANES inline __attribute__((always_inline))

/// A comparison's result per lane (all bits set: true).
struct LaneMask {
  LanePartBits h[kParts];
  DC_LANES bool operator[](int l) const { return h[l / kPartLanes][l % kPartLanes] != 0; }
  /// Bit l set for lane l true.
  DC_LANES std::uint32_t bits() const {
    std::uint32_t b = 0;
    for (int l = 0; l < kLanes; ++l) b |= static_cast<std::uint32_t>((*this)[l]) << l;
    return b;
  }
};

/// A double per lane; lane l is v[l]. Its operations act on every lane; all are inlined, so each
/// build (AVX2, baseline) compiles them for its instruction set.
struct LaneDoubles {
  LanePart h[kParts];
  DC_LANES double operator[](int l) const { return h[l / kPartLanes][l % kPartLanes]; }
  DC_LANES void set(int l, double v) { h[l / kPartLanes][l % kPartLanes] = v; }
  DC_LANES static LaneDoubles all(double v) {
    LaneDoubles r;
    for (int i = 0; i < kParts; ++i) r.h[i] = LanePart{} + v;
    return r;
  }
};

/// The body of a lane-wise operation: `expr` of part i for every part.
#define DC_PARTWISE(Type, expr)                     \
  Type r;                                           \
  for (int i = 0; i < kParts; ++i) r.h[i] = (expr); \
  return r

DC_LANES LaneMask operator|(const LaneMask& a, const LaneMask& b) { DC_PARTWISE(LaneMask, a.h[i] | b.h[i]); }
DC_LANES LaneDoubles operator+(const LaneDoubles& a, const LaneDoubles& b) {
  DC_PARTWISE(LaneDoubles, a.h[i] + b.h[i]);
}
DC_LANES LaneDoubles operator-(const LaneDoubles& a, const LaneDoubles& b) {
  DC_PARTWISE(LaneDoubles, a.h[i] - b.h[i]);
}
DC_LANES LaneDoubles operator*(const LaneDoubles& a, const LaneDoubles& b) {
  DC_PARTWISE(LaneDoubles, a.h[i] * b.h[i]);
}
DC_LANES LaneDoubles operator-(const LaneDoubles& a) { DC_PARTWISE(LaneDoubles, -a.h[i]); }
DC_LANES LaneDoubles operator+(const LaneDoubles& a, double s) { DC_PARTWISE(LaneDoubles, a.h[i] + s); }
DC_LANES LaneDoubles operator-(const LaneDoubles& a, double s) { DC_PARTWISE(LaneDoubles, a.h[i] - s); }
DC_LANES LaneDoubles operator*(const LaneDoubles& a, double s) { DC_PARTWISE(LaneDoubles, a.h[i] * s); }
DC_LANES LaneDoubles operator+(double s, const LaneDoubles& a) { DC_PARTWISE(LaneDoubles, s + a.h[i]); }
DC_LANES LaneDoubles operator-(double s, const LaneDoubles& a) { DC_PARTWISE(LaneDoubles, s - a.h[i]); }
DC_LANES LaneDoubles operator*(double s, const LaneDoubles& a) { DC_PARTWISE(LaneDoubles, s * a.h[i]); }
DC_LANES LaneDoubles& operator+=(LaneDoubles& a, const LaneDoubles& b) { return a = a + b; }
DC_LANES LaneMask operator<(const LaneDoubles& a, double s) { DC_PARTWISE(LaneMask, a.h[i] < s); }
DC_LANES LaneMask operator>(const LaneDoubles& a, const LaneDoubles& b) { DC_PARTWISE(LaneMask, a.h[i] > b.h[i]); }
/// m ? a : b, lane by lane.
DC_LANES LaneDoubles select(const LaneMask& m, const LaneDoubles& a, const LaneDoubles& b) {
  DC_PARTWISE(LaneDoubles, m.h[i] ? a.h[i] : b.h[i]);
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
