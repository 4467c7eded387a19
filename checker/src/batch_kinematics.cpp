// Forward kinematics of a batch of configurations, lane by lane in structure-of-arrays form
// (batch_kinematics.h). Each joint: X_WJ = X_WP * X_PJ, then the joint's motion (a rotation of
// two columns for a coordinate axis, Rodrigues' formula for any other, a translation along the
// axis), for all lanes at once. The lane loops are compiled twice, for AVX2 and for the baseline
// instruction set, and chosen at run time.

#include "batch_kinematics.h"

#include <cmath>
#include <cstdint>

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

DC_INLINE void sinCosLanes(const LaneDoubles& x, LaneDoubles& sine, LaneDoubles& cosine) {
  constexpr double kTwoOverPi = 0.63661977236758134308;
  constexpr double kHalfPiHigh = 1.5707963267948965579989817342720925807952880859375;
  constexpr double kHalfPi1 = 1.57079632673412561416625976562500;
  constexpr double kHalfPi2 = kHalfPiHigh - kHalfPi1;
  constexpr double kHalfPi3 = 6.123233995736766035868820147292e-17;
  constexpr double f3 = 1.0 / 6, f5 = f3 / 20, f7 = f5 / 42, f9 = f7 / 72, f11 = f9 / 110, f13 = f11 / 156,
                   f15 = f13 / 210, f17 = f15 / 272;
  constexpr double f2 = 0.5, f4 = f2 / 12, f6 = f4 / 30, f8 = f6 / 56, f10 = f8 / 90, f12 = f10 / 132, f14 = f12 / 182,
                   f16 = f14 / 240, f18 = f16 / 306;
  bool allInRange = true;
  for (int l = 0; l < kLanes; ++l) {
    const bool in = std::abs(x[l]) < kSinCosRange;
    allInRange &= in;
    const double xl = in ? x[l] : 0.0;
    const int k = static_cast<int>(xl * kTwoOverPi + (xl >= 0.0 ? 0.5 : -0.5));
    const double kd = k;
    const double r = ((xl - kd * kHalfPi1) - kd * kHalfPi2) - kd * kHalfPi3;
    const double r2 = r * r, r4 = r2 * r2, r8 = r4 * r4;
    const double ps = ((-f3 + f5 * r2) + r4 * (-f7 + f9 * r2)) + r8 * ((-f11 + f13 * r2) + r4 * (-f15 + f17 * r2));
    const double pc =
        ((f2 - f4 * r2) + r4 * (f6 - f8 * r2)) + r8 * ((f10 - f12 * r2) + r4 * (f14 - f16 * r2) + r8 * f18);
    const double s = r + (r * r2) * ps;
    const double c = 1.0 - r2 * pc;
    const bool odd = (k & 1) != 0;
    const double s1 = odd ? c : s;
    const double c1 = odd ? s : c;
    sine[l] = (k & 2) != 0 ? -s1 : s1;
    cosine[l] = ((k + 1) & 2) != 0 ? -c1 : c1;
  }
  if (allInRange) return;
  for (int l = 0; l < kLanes; ++l) {
    if (!(std::abs(x[l]) < kSinCosRange)) {
      sine[l] = std::sin(x[l]);
      cosine[l] = std::cos(x[l]);
    }
  }
}

/// X_WJ = X_WP * X_PJ for every lane.
DC_INLINE void jointFrame(const LanePose& P, const Joint& joint, LanePose& J) {
  const Eigen::Matrix3d& A = joint.X_PJ.linear();
  const Eigen::Vector3d& b = joint.X_PJ.translation();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      const double a0 = A(0, c), a1 = A(1, c), a2 = A(2, c);
      for (int l = 0; l < kLanes; ++l) {
        J.R[3 * r + c][l] = P.R[3 * r][l] * a0 + P.R[3 * r + 1][l] * a1 + P.R[3 * r + 2][l] * a2;
      }
    }
    for (int l = 0; l < kLanes; ++l) {
      J.t[r][l] = P.t[r][l] + P.R[3 * r][l] * b[0] + P.R[3 * r + 1][l] * b[1] + P.R[3 * r + 2][l] * b[2];
    }
  }
}

/// R * Rot(k, angle) for the coordinate axis k (sign folded into the sine): column k stays,
/// columns i = k + 1 and j = k + 2 (cyclic) turn in their plane.
DC_INLINE void rotateCoordinate(LanePose& X, int k, const LaneDoubles& c, const LaneDoubles& s) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  for (int r = 0; r < 3; ++r) {
    LaneDoubles& ri = X.R[3 * r + i];
    LaneDoubles& rj = X.R[3 * r + j];
    for (int l = 0; l < kLanes; ++l) {
      const double a = ri[l], b = rj[l];
      ri[l] = c[l] * a + s[l] * b;
      rj[l] = c[l] * b - s[l] * a;
    }
  }
}

/// R * Rot(axis, angle) for any unit axis (Rodrigues: c I + s [a]x + (1 - c) a a^T).
DC_INLINE void rotateAxis(LanePose& X, const Eigen::Vector3d& a, const LaneDoubles& c, const LaneDoubles& s) {
  for (int r = 0; r < 3; ++r) {
    LaneDoubles row[3] = {X.R[3 * r], X.R[3 * r + 1], X.R[3 * r + 2]};
    for (int col = 0; col < 3; ++col) {
      for (int l = 0; l < kLanes; ++l) {
        double sum = 0.0;
        for (int m = 0; m < 3; ++m) {
          // Rot(m, col): c on the diagonal, plus (1 - c) a_m a_col, plus s [a]x(m, col), which is
          // -a_{m+2} one column right of the diagonal and a_{m+1} two columns right (cyclic).
          double rot = (1.0 - c[l]) * a[m] * a[col] + (m == col ? c[l] : 0.0);
          const int cross = (col - m + 3) % 3;
          if (cross == 1) rot -= s[l] * a[(m + 2) % 3];
          if (cross == 2) rot += s[l] * a[(m + 1) % 3];
          sum += row[m][l] * rot;
        }
        X.R[3 * r + col][l] = sum;
      }
    }
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

/// The joint's value in every lane (multiplier * q[variable] + offset).
DC_INLINE void jointValues(const Joint& joint, const double* q, LaneDoubles& value) {
  for (int l = 0; l < kLanes; ++l) value[l] = joint.multiplier * q[l] + joint.offset;
}

/// The child link's pose of `joint` from X_WJ (in C), every lane; adds a prismatic joint's travel
/// to `chain`.
DC_INLINE void jointMotion(const Joint& joint, const LaneDoubles& value, LanePose& C, LaneDoubles& chain) {
  if (joint.type == JointType::Prismatic) {
    const Eigen::Vector3d& a = joint.axis;
    for (int r = 0; r < 3; ++r) {
      for (int l = 0; l < kLanes; ++l) {
        C.t[r][l] += value[l] * (C.R[3 * r][l] * a[0] + C.R[3 * r + 1][l] * a[1] + C.R[3 * r + 2][l] * a[2]);
      }
    }
    for (int l = 0; l < kLanes; ++l) chain[l] += std::abs(value[l]);
    return;
  }
  if (joint.type == JointType::Fixed) return;
  double sign = 1.0;
  const int k = coordinateAxis(joint.axis, sign);
  LaneDoubles s, c;
  sinCosLanes(value, s, c);
  if (k >= 0) {
    for (int l = 0; l < kLanes; ++l) s[l] *= sign;
    rotateCoordinate(C, k, c, s);
  } else {
    rotateAxis(C, joint.axis, c, s);
  }
}

/// The world centre of p_L in link `link`'s frame, every lane.
DC_INLINE void posePoint(const LanePose& X, const Eigen::Vector3d& p, LanePoint& out) {
  LaneDoubles* o[3] = {&out.x, &out.y, &out.z};
  for (int r = 0; r < 3; ++r) {
    for (int l = 0; l < kLanes; ++l) {
      (*o[r])[l] = X.t[r][l] + X.R[3 * r][l] * p[0] + X.R[3 * r + 1][l] * p[1] + X.R[3 * r + 2][l] * p[2];
    }
  }
}

/// The root's pose in every lane, and the base translation as the start of every chain.
void startChains(const robots::RobotModel& model, BatchPoses& out) {
  const Eigen::Isometry3d& X_WR = model.basePose();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out.links[0].R[3 * r + c].fill(X_WR.linear()(r, c));
    out.links[0].t[r].fill(X_WR.translation()[r]);
  }
  double length = X_WR.translation().norm();
  for (const Joint& joint : model.joints()) length += joint.X_PJ.translation().norm();
  out.chainLength.fill(length);
}

/// Lane l: q finite and every link translation finite.
void markFinite(const Eigen::Ref<const Eigen::MatrixXd>& qs, int lanesGiven, BatchPoses& out) {
  for (int l = 0; l < kLanes; ++l) {
    const int col = l < lanesGiven ? l : lanesGiven - 1;
    bool finite = qs.col(col).allFinite();
    for (const LanePose& X : out.links) {
      finite &= std::isfinite(X.t[0][l]) && std::isfinite(X.t[1][l]) && std::isfinite(X.t[2][l]);
    }
    out.finite[l] = finite;
  }
}

DC_INLINE void poseAll(const RobotData& robot, const Eigen::Ref<const Eigen::MatrixXd>& qs, BatchPoses& out) {
  const robots::RobotModel& model = robot.model;
  const int n = static_cast<int>(qs.cols());
  // The lanes' values of every variable, columns past n repeating the last one.
  const int vars = model.numVariables();
  std::vector<double>& q = out.laneQ;
  q.resize(static_cast<std::size_t>(vars) * kLanes);
  for (int v = 0; v < vars; ++v) {
    for (int l = 0; l < kLanes; ++l) q[static_cast<std::size_t>(v) * kLanes + l] = qs(v, l < n ? l : n - 1);
  }
  startChains(model, out);
  LaneDoubles value{};
  for (const Joint& joint : model.joints()) {
    LanePose& C = out.links[joint.childLink];
    jointFrame(out.links[joint.parentLink], joint, C);
    if (joint.type == JointType::Fixed) continue;
    jointValues(joint, &q[static_cast<std::size_t>(joint.variable) * kLanes], value);
    jointMotion(joint, value, C, out.chainLength);
  }
  for (std::size_t g = 0; g < robot.links.size(); ++g) {
    posePoint(out.links[robot.links[g].link], robot.links[g].center_L, out.linkCenter[g]);
  }
  for (std::size_t i = 0; i < robot.pieces.size(); ++i) {
    posePoint(out.links[robot.pieces[i].link], robot.pieces[i].center_L, out.pieceCenter[i]);
  }
}

__attribute__((target("avx2"))) void poseAllAvx2(const RobotData& robot, const Eigen::Ref<const Eigen::MatrixXd>& qs,
                                                 BatchPoses& out) {
  poseAll(robot, qs, out);
}

void poseAllBaseline(const RobotData& robot, const Eigen::Ref<const Eigen::MatrixXd>& qs, BatchPoses& out) {
  poseAll(robot, qs, out);
}

}  // namespace

bool batchAvx2Available() {
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
}

void batchForwardKinematics(const RobotData& robot, const Eigen::Ref<const Eigen::MatrixXd>& qs, bool avx2,
                            BatchPoses& out) {
  out.links.resize(robot.model.numLinks());
  out.linkCenter.resize(robot.links.size());
  out.pieceCenter.resize(robot.pieces.size());
  if (avx2) {
    poseAllAvx2(robot, qs, out);
  } else {
    poseAllBaseline(robot, qs, out);
  }
  markFinite(qs, static_cast<int>(qs.cols()), out);
}

}  // namespace deepcheck::checker::detail
