// Forward kinematics of a batch of configurations, lane by lane in structure-of-arrays form
// (batch_kinematics.h). Each joint: X_WJ = X_WP * X_PJ, then the joint's motion (a rotation of
// two columns for a coordinate axis, Rodrigues' formula for any other, a translation along the
// axis), for all lanes at once. The lane loops are compiled twice, for AVX2 and for the baseline
// instruction set, and chosen at run time.

#include "batch_kinematics.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace deepcheck::checker::detail {
namespace {

#define DC_INLINE inline __attribute__((always_inline))

using robots::Joint;
using robots::JointType;

/// sin and cos of every lane, to a few ulps, for |x| < kSinCosRange: x reduced to
/// r = x - k pi/2, |r| <= pi/4 (Cody and Waite, pi/2 in three parts, the first two short enough
/// that k times them is exact), then Taylor series of degree 17 and 18 (truncation error below
/// 1e-19 on |r| <= pi/4), and the quadrant k mod 4 swaps and negates them. Other lanes use the
/// library's functions (a NaN stays a NaN).
constexpr double kSinCosRange = 1048576.0;

/// Lanes whose integer k (the doubles' bits) plus `add` has bit `bit` set.
template <class L>
DC_INLINE typename L::Mask bitSet(const typename LaneParts<L::kWidth>::Bits (&k)[L::kParts], std::int64_t add,
                                  std::int64_t bit) {
  using Mask = typename L::Mask;
  DC_PARTWISE(Mask, ((k[i] + add) & bit) != 0);
}

template <class L>
DC_INLINE void sinCosLanes(const L& x, L& sine, L& cosine) {
  constexpr double kTwoOverPi = 0.63661977236758134308;
  constexpr double kHalfPiHigh = 1.5707963267948965579989817342720925807952880859375;
  constexpr double kHalfPi1 = 1.57079632673412561416625976562500;
  constexpr double kHalfPi2 = kHalfPiHigh - kHalfPi1;
  constexpr double kHalfPi3 = 6.123233995736766035868820147292e-17;
  constexpr double f3 = 1.0 / 6, f5 = f3 / 20, f7 = f5 / 42, f9 = f7 / 72, f11 = f9 / 110, f13 = f11 / 156,
                   f15 = f13 / 210, f17 = f15 / 272;
  constexpr double f2 = 0.5, f4 = f2 / 12, f6 = f4 / 30, f8 = f6 / 56, f10 = f8 / 90, f12 = f10 / 132, f14 = f12 / 182,
                   f16 = f14 / 240, f18 = f16 / 306;
  // k = x 2/pi rounded to an integer by adding 1.5 2^52 (|x 2/pi| < 2^51: the sum's last
  // mantissa bits are k in two's complement); no conversion instructions, which AVX2 lacks for
  // 64-bit integers.
  constexpr double kRound = 6755399441055744.0;
  const typename L::Mask in = laneAbs(x) < kSinCosRange;  // false for NaN
  const L xr = select(in, x, L{});
  const L shifted = xr * kTwoOverPi + kRound;
  using Bits = typename LaneParts<L::kWidth>::Bits;
  Bits k[L::kParts];
  for (int i = 0; i < L::kParts; ++i) k[i] = reinterpret_cast<Bits>(shifted.h[i]);
  const L kd = shifted - kRound;
  const L r = ((xr - kd * kHalfPi1) - kd * kHalfPi2) - kd * kHalfPi3;
  const L r2 = r * r, r4 = r2 * r2, r8 = r4 * r4;
  const L ps = ((-f3 + f5 * r2) + r4 * (-f7 + f9 * r2)) + r8 * ((-f11 + f13 * r2) + r4 * (-f15 + f17 * r2));
  const L pc = ((f2 - f4 * r2) + r4 * (f6 - f8 * r2)) + r8 * ((f10 - f12 * r2) + r4 * (f14 - f16 * r2) + r8 * f18);
  const L s = r + (r * r2) * ps;
  const L c = 1.0 - r2 * pc;
  // The quadrant k mod 4: odd k swaps sine and cosine; sine is negated for k = 2, 3 and cosine
  // for k = 1, 2.
  const typename L::Mask odd = bitSet<L>(k, 0, 1);
  const L s1 = select(odd, c, s);
  const L c1 = select(odd, s, c);
  sine = select(bitSet<L>(k, 0, 2), -s1, s1);
  cosine = select(bitSet<L>(k, 1, 2), -c1, c1);
  if (in.bits() == (1u << kLanes) - 1u) return;
  for (int l = 0; l < kLanes; ++l) {
    if (!in[l]) {
      sine.set(l, std::sin(x[l]));
      cosine.set(l, std::cos(x[l]));
    }
  }
}

/// X_WJ = X_WP * X_PJ for every lane.
template <class L>
DC_INLINE void jointFrame(const LanePoseT<L>& P, const Joint& joint, LanePoseT<L>& J) {
  const Eigen::Matrix3d& A = joint.X_PJ.linear();
  const Eigen::Vector3d& b = joint.X_PJ.translation();
  for (int r = 0; r < 3; ++r) {
    const L p0 = P.R[3 * r], p1 = P.R[3 * r + 1], p2 = P.R[3 * r + 2];
    for (int c = 0; c < 3; ++c) J.R[3 * r + c] = p0 * A(0, c) + p1 * A(1, c) + p2 * A(2, c);
    J.t[r] = P.t[r] + p0 * b[0] + p1 * b[1] + p2 * b[2];
  }
}

/// R * Rot(k, angle) for the coordinate axis k (sign folded into the sine): column k stays,
/// columns i = k + 1 and j = k + 2 (cyclic) turn in their plane.
template <class L>
DC_INLINE void rotateCoordinate(LanePoseT<L>& X, int k, const L& c, const L& s) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  for (int r = 0; r < 3; ++r) {
    const L a = X.R[3 * r + i], b = X.R[3 * r + j];
    X.R[3 * r + i] = c * a + s * b;
    X.R[3 * r + j] = c * b - s * a;
  }
}

/// R * Rot(axis, angle) for any unit axis a (Rodrigues: c I + s [a]x + (1 - c) a a^T).
template <class L>
DC_INLINE void rotateAxis(LanePoseT<L>& X, const Eigen::Vector3d& a, const L& c, const L& s) {
  // Rot(m, col): c on the diagonal, plus (1 - c) a_m a_col, plus s [a]x(m, col), which is
  // -a_{m+2} one column right of the diagonal and a_{m+1} two columns right (cyclic).
  L rot[9];
  const L oneMinusC = 1.0 - c;
  for (int m = 0; m < 3; ++m) {
    for (int col = 0; col < 3; ++col) {
      L v = oneMinusC * (a[m] * a[col]);
      if (m == col) v = v + c;
      const int cross = (col - m + 3) % 3;
      if (cross == 1) v = v - s * a[(m + 2) % 3];
      if (cross == 2) v = v + s * a[(m + 1) % 3];
      rot[3 * m + col] = v;
    }
  }
  for (int r = 0; r < 3; ++r) {
    const L x0 = X.R[3 * r], x1 = X.R[3 * r + 1], x2 = X.R[3 * r + 2];
    for (int col = 0; col < 3; ++col) X.R[3 * r + col] = x0 * rot[col] + x1 * rot[3 + col] + x2 * rot[6 + col];
  }
}

/// The coordinate axis (0, 1, 2) that `axis` is, exactly, or -1; `sign` is +1 or -1.
int coordinateAxis(const Eigen::Vector3d& axis, double& sign) {
  for (int k = 0; k < 3; ++k) {
    if (axis[(k + 1) % 3] == 0.0 && axis[(k + 2) % 3] == 0.0 && (axis[k] == 1.0 || axis[k] == -1.0)) {
      sign = axis[k];
      return k;
    }
  }
  return -1;
}

/// The child link's pose of `joint` from X_WJ (in C) for the joint values `value`, every lane;
/// adds a prismatic joint's travel to `chain`.
template <class L>
DC_INLINE void jointMotion(const Joint& joint, const L& value, LanePoseT<L>& C, L& chain) {
  if (joint.type == JointType::Prismatic) {
    const Eigen::Vector3d& a = joint.axis;
    for (int r = 0; r < 3; ++r) C.t[r] += value * (C.R[3 * r] * a[0] + C.R[3 * r + 1] * a[1] + C.R[3 * r + 2] * a[2]);
    chain += laneAbs(value);
    return;
  }
  double sign = 1.0;
  const int k = coordinateAxis(joint.axis, sign);
  L s, c;
  sinCosLanes(value, s, c);
  if (k >= 0) {
    rotateCoordinate(C, k, c, s * sign);
  } else {
    rotateAxis(C, joint.axis, c, s);
  }
}

/// The root's pose in every lane, and the base translation and joint offsets as every chain's
/// fixed length.
template <class L>
DC_INLINE void startChains(const robots::RobotModel& model, BatchPosesT<L>& out) {
  const Eigen::Isometry3d& X_WR = model.basePose();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out.links[0].R[3 * r + c] = L::all(X_WR.linear()(r, c));
    out.links[0].t[r] = L::all(X_WR.translation()[r]);
  }
  double length = X_WR.translation().norm();
  for (const Joint& joint : model.joints()) length += joint.X_PJ.translation().norm();
  out.chainLength = L::all(length);
}

/// Lane l: q finite and every link translation finite (0 * x is 0 for finite x, NaN otherwise).
template <class L>
DC_INLINE void markFinite(BatchPosesT<L>& out) {
  L zero{};
  for (const L& q : out.laneQ) zero += q * 0.0;
  for (const LanePoseT<L>& X : out.links) zero += (X.t[0] + X.t[1] + X.t[2]) * 0.0;
  for (int l = 0; l < kLanes; ++l) out.finite[l] = zero[l] == 0.0;
}

/// The lanes' values of every variable, columns from qs.cols() on repeating the last one.
template <class L>
DC_INLINE void laneValues(const Eigen::Ref<const Eigen::MatrixXd>& qs, BatchPosesT<L>& out) {
  const int n = static_cast<int>(qs.cols());
  for (Eigen::Index v = 0; v < qs.rows(); ++v) {
    double values[kLanes];  // filled as doubles, then copied whole (a lane written into a
                            // vector one at a time goes through memory eight times)
    for (int l = 0; l < kLanes; ++l) values[l] = qs(v, l < n ? l : n - 1);
    std::memcpy(&out.laneQ[v], values, sizeof values);
  }
}

template <class L>
DC_INLINE void poseAll(const RobotData& robot, const Eigen::Ref<const Eigen::MatrixXd>& qs, BatchPosesT<L>& out) {
  const robots::RobotModel& model = robot.model;
  laneValues(qs, out);
  startChains(model, out);
  for (const Joint& joint : model.joints()) {
    LanePoseT<L>& C = out.links[joint.childLink];
    jointFrame(out.links[joint.parentLink], joint, C);
    if (joint.type == JointType::Fixed) continue;
    const L value = out.laneQ[joint.variable] * joint.multiplier + joint.offset;
    jointMotion(joint, value, C, out.chainLength);
  }
  for (std::size_t g = 0; g < robot.links.size(); ++g) {
    posePoint(out.links[robot.links[g].link], robot.links[g].center_L, out.linkCenter[g]);
  }
  markFinite(out);
}

__attribute__((target("avx2"))) void poseAllAvx2(const RobotData& robot, const Eigen::Ref<const Eigen::MatrixXd>& qs,
                                                 BatchPosesT<Avx2Lanes>& out) {
  poseAll(robot, qs, out);
}

void poseAllBaseline(const RobotData& robot, const Eigen::Ref<const Eigen::MatrixXd>& qs,
                     BatchPosesT<BaselineLanes>& out) {
  poseAll(robot, qs, out);
}

template <class L>
void resize(const RobotData& robot, const Eigen::Ref<const Eigen::MatrixXd>& qs, BatchPosesT<L>& out) {
  out.links.resize(robot.model.numLinks());
  out.linkCenter.resize(robot.links.size());
  out.laneQ.resize(qs.rows());
}

}  // namespace

bool batchAvx2Available() {
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
}

void batchForwardKinematics(const RobotData& robot, const Eigen::Ref<const Eigen::MatrixXd>& qs,
                            BatchPosesT<Avx2Lanes>& out) {
  resize(robot, qs, out);
  poseAllAvx2(robot, qs, out);
}

void batchForwardKinematics(const RobotData& robot, const Eigen::Ref<const Eigen::MatrixXd>& qs,
                            BatchPosesT<BaselineLanes>& out) {
  resize(robot, qs, out);
  poseAllBaseline(robot, qs, out);
}

}  // namespace deepcheck::checker::detail
