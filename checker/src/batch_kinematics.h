#pragma once
// Forward kinematics of up to kLanes configurations at once, in structure-of-arrays form: every
// quantity is a LaneDoublesW, a double per lane, whose operations act on all lanes (two AVX2
// registers in the AVX2 build, four SSE2 ones in the baseline build; World::isFreeBatch,
// world_batch.cpp).
//
// Doubles, like robots::forwardKinematics: the poses agree with it to a few ulps of the chain's
// length (the same products in a different order, and sines of our own to a few ulps). The bound
// stage (batch_bounds.h) rounds the centres to floats and its margin (tol::kBatchBoundRelative)
// covers both.

#include "world_internal.h"

#include <Eigen/Core>

#include <algorithm>
#include <cstdint>

#include <vector>

namespace deepcheck::checker::detail {

/// Configurations per batch: one AVX2 register of floats.
constexpr int kLanes = 8;

/// Lanes as parts of W doubles each, GCC vectors of the size of a register: W = 4 (an AVX2
/// register) in the AVX2 build, W = 2 (SSE2) in the baseline one. A vector wider than the
/// registers is lowered through memory, scalar by scalar: eight doubles at once made the AVX2
/// build's kinematics 5 times slower, four at once the baseline build's 4 times slower. Aligned explicitly: without
/// AVX enabled GCC gives a 32-byte vector type only 16-byte alignment, and the AVX2 build's
/// aligned loads would then fault.
template <int W>
struct LaneParts;
template <>
struct LaneParts<2> {
  using Doubles = double __attribute__((vector_size(2 * sizeof(double)), aligned(16)));
  using Bits = std::int64_t __attribute__((vector_size(2 * sizeof(std::int64_t)), aligned(16)));
};
template <>
struct LaneParts<4> {
  using Doubles = double __attribute__((vector_size(4 * sizeof(double)), aligned(32)));
  using Bits = std::int64_t __attribute__((vector_size(4 * sizeof(std::int64_t)), aligned(32)));
};

#define DC_LANES inline __attribute__((always_inline))

/// A comparison's result per lane (all bits set: true).
template <int W>
struct LaneMaskW {
  static constexpr int kParts = kLanes / W;
  typename LaneParts<W>::Bits h[kParts];
  DC_LANES bool operator[](int l) const { return h[l / W][l % W] != 0; }
  /// Bit l set for lane l true.
  DC_LANES std::uint32_t bits() const {
    std::uint32_t b = 0;
    for (int l = 0; l < kLanes; ++l) b |= static_cast<std::uint32_t>((*this)[l]) << l;
    return b;
  }
};

/// A double per lane; lane l is v[l]. Its operations act on every lane; all are inlined, so each
/// build compiles them for its instruction set.
template <int W>
struct LaneDoublesW {
  static constexpr int kWidth = W;
  static constexpr int kParts = kLanes / W;
  using Mask = LaneMaskW<W>;
  typename LaneParts<W>::Doubles h[kParts];
  DC_LANES double operator[](int l) const { return h[l / W][l % W]; }
  DC_LANES void set(int l, double v) { h[l / W][l % W] = v; }
  DC_LANES static LaneDoublesW all(double v) {
    LaneDoublesW r;
    for (int i = 0; i < kParts; ++i) r.h[i] = typename LaneParts<W>::Doubles{} + v;
    return r;
  }
};

/// The body of a lane-wise operation: `expr` of part i for every part.
#define DC_PARTWISE(Type, expr)                           \
  Type r;                                                 \
  for (int i = 0; i < Type::kParts; ++i) r.h[i] = (expr); \
  return r

template <int W>
using LD = LaneDoublesW<W>;

template <int W>
DC_LANES LaneMaskW<W> operator|(const LaneMaskW<W>& a, const LaneMaskW<W>& b) {
  DC_PARTWISE(LaneMaskW<W>, a.h[i] | b.h[i]);
}
template <int W>
DC_LANES LD<W> operator+(const LD<W>& a, const LD<W>& b) {
  DC_PARTWISE(LD<W>, a.h[i] + b.h[i]);
}
template <int W>
DC_LANES LD<W> operator-(const LD<W>& a, const LD<W>& b) {
  DC_PARTWISE(LD<W>, a.h[i] - b.h[i]);
}
template <int W>
DC_LANES LD<W> operator*(const LD<W>& a, const LD<W>& b) {
  DC_PARTWISE(LD<W>, a.h[i] * b.h[i]);
}
template <int W>
DC_LANES LD<W> operator-(const LD<W>& a) {
  DC_PARTWISE(LD<W>, -a.h[i]);
}
template <int W>
DC_LANES LD<W> operator+(const LD<W>& a, double s) {
  DC_PARTWISE(LD<W>, a.h[i] + s);
}
template <int W>
DC_LANES LD<W> operator-(const LD<W>& a, double s) {
  DC_PARTWISE(LD<W>, a.h[i] - s);
}
template <int W>
DC_LANES LD<W> operator*(const LD<W>& a, double s) {
  DC_PARTWISE(LD<W>, a.h[i] * s);
}
template <int W>
DC_LANES LD<W> operator+(double s, const LD<W>& a) {
  DC_PARTWISE(LD<W>, s + a.h[i]);
}
template <int W>
DC_LANES LD<W> operator-(double s, const LD<W>& a) {
  DC_PARTWISE(LD<W>, s - a.h[i]);
}
template <int W>
DC_LANES LD<W> operator*(double s, const LD<W>& a) {
  DC_PARTWISE(LD<W>, s * a.h[i]);
}
template <int W>
DC_LANES LD<W>& operator+=(LD<W>& a, const LD<W>& b) {
  return a = a + b;
}
template <int W>
DC_LANES LaneMaskW<W> operator<(const LD<W>& a, double s) {
  DC_PARTWISE(LaneMaskW<W>, a.h[i] < s);
}
template <int W>
DC_LANES LaneMaskW<W> operator>(const LD<W>& a, const LD<W>& b) {
  DC_PARTWISE(LaneMaskW<W>, a.h[i] > b.h[i]);
}
/// m ? a : b, lane by lane.
template <int W>
DC_LANES LD<W> select(const LaneMaskW<W>& m, const LD<W>& a, const LD<W>& b) {
  DC_PARTWISE(LD<W>, m.h[i] ? a.h[i] : b.h[i]);
}
template <int W>
DC_LANES LD<W> laneAbs(const LD<W>& a) {
  return select(a < 0.0, -a, a);
}
template <int W>
DC_LANES LD<W> laneMax(const LD<W>& a, const LD<W>& b) {
  return select(a > b, a, b);
}

/// The smallest of a's lanes (`largest` false) or the largest: part against part, then within
/// the remaining part (no lane may be NaN).
template <class L>
DC_LANES double extremeLane(const L& a, bool largest) {
  auto m = a.h[0];
  for (int i = 1; i < L::kParts; ++i) m = (largest ? a.h[i] > m : a.h[i] < m) ? a.h[i] : m;
  double v = m[0];
  for (int j = 1; j < L::kWidth; ++j) v = largest ? std::max(v, m[j]) : std::min(v, m[j]);
  return v;
}

/// A point per lane.
template <class L>
struct LanePointT {
  L x, y, z;
};

/// A rigid pose per lane: R[3 * row + col] and t[row], each over the lanes.
template <class L>
struct LanePoseT {
  L R[9];
  L t[3];
};

/// X p for every lane (p in X's frame).
template <class L>
DC_LANES void posePoint(const LanePoseT<L>& X, const Eigen::Vector3d& p, LanePointT<L>& out) {
  out.x = X.t[0] + X.R[0] * p[0] + X.R[1] * p[1] + X.R[2] * p[2];
  out.y = X.t[1] + X.R[3] * p[0] + X.R[4] * p[1] + X.R[5] * p[2];
  out.z = X.t[2] + X.R[6] * p[0] + X.R[7] * p[1] + X.R[8] * p[2];
}

/// What the batch's forward kinematics gives: per lane, the links' poses and the centres of the
/// link geometries' bounding spheres in the world (robot pieces are posed by the bound stage,
/// only those it gets to).
template <class L>
struct BatchPosesT {
  std::vector<LanePoseT<L>> links;        ///< per model link
  std::vector<LanePointT<L>> linkCenter;  ///< per LinkGeometry (RobotData::links): center_L posed
  /// Per lane: q finite and every link translation finite (otherwise the lane is left to isFree,
  /// which throws as it does).
  bool finite[kLanes] = {};
  /// Per lane: an upper bound on the length of the chains the poses were computed along (metres:
  /// the base translation, every joint origin's offset, every prismatic joint's travel); the
  /// round-off of the poses is a few ulps of it.
  L chainLength = {};
  std::vector<L> laneQ;  ///< scratch: the lanes' values, variable by variable
};

/// The lanes of the AVX2 build and of the baseline one: the same doubles, the same operations in
/// the same order (no fused multiply-adds), so the same bits.
using Avx2Lanes = LaneDoublesW<4>;
using BaselineLanes = LaneDoublesW<2>;

/// Poses of the columns of qs (robot.model's variables x n, 1 <= n <= kLanes; lanes n and on
/// repeat column n - 1) into `out`, compiled for AVX2 (call only when batchAvx2Available()) or
/// for the baseline instruction set. Does not check qs: a lane with a value that is not finite
/// gets finite[lane] false.
void batchForwardKinematics(const RobotData& robot, const Eigen::Ref<const Eigen::MatrixXd>& qs,
                            BatchPosesT<Avx2Lanes>& out);
void batchForwardKinematics(const RobotData& robot, const Eigen::Ref<const Eigen::MatrixXd>& qs,
                            BatchPosesT<BaselineLanes>& out);

/// True when the processor runs AVX2 code. (No FMA: fused and unfused products round differently,
/// and the two builds are to give the same bits.)
bool batchAvx2Available();

}  // namespace deepcheck::checker::detail
