#include "deepcheck/robots/kinematics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace deepcheck::robots {
namespace {

/// R * Rot(k, angle) for a rotation about the coordinate axis k (0 x, 1 y, 2 z) given its cosine
/// c and sine s: column k stays, columns i = k + 1 and j = k + 2 (cyclic) turn in their plane.
template <int k>
inline void rotateAbout(Eigen::Matrix3d& R, double c, double s) {
  constexpr int i = (k + 1) % 3;
  constexpr int j = (k + 2) % 3;
  const Eigen::Vector3d ri = R.col(i);
  const Eigen::Vector3d rj = R.col(j);
  R.col(i) = c * ri + s * rj;
  R.col(j) = c * rj - s * ri;
}

/// rotateAbout for an axis known at run time. The columns are chosen at compile time: with
/// run-time column indices R lives in memory and each joint waits on its own stores, which made
/// forward kinematics about twice as slow (the same arithmetic, the same bits).
inline void rotateAboutCoordinateAxis(Eigen::Matrix3d& R, int k, double c, double s) {
  switch (k) {
    case 0:
      rotateAbout<0>(R, c, s);
      break;
    case 1:
      rotateAbout<1>(R, c, s);
      break;
    default:
      rotateAbout<2>(R, c, s);
      break;
  }
}

/// Two doubles in one SSE2 register (GCC's and Clang's vector extensions): the sines of two
/// joints cost about as much as one, with the same bits as one at a time.
using Pair = double __attribute__((vector_size(16)));
using PairBits = std::int64_t __attribute__((vector_size(16)));
using PairInt = std::int32_t __attribute__((vector_size(8)));

/// sinCos below is exact in its reduction for |x| under this (joint values); beyond it the
/// library's functions are used.
constexpr double kSinCosRange = 1048576.0;

/// sin x and cos x for both lanes of x, |x| < kSinCosRange, to a few ulps: x is reduced to
/// r = x - k pi/2, |r| <= pi/4 (Cody and Waite: pi/2 in three parts, the first two short enough
/// that k times them is exact, so the reduction loses nothing), then the Taylor series of sin and
/// cos to degree 17 and 18, whose truncation error on |r| <= pi/4 is below 1e-19, and the
/// quadrant k mod 4 swaps and negates them.
inline void sinCos(Pair x, Pair& sine, Pair& cosine) {
  constexpr double kTwoOverPi = 0.63661977236758134308;
  constexpr double kHalfPiHigh = 1.5707963267948965579989817342720925807952880859375;  // double(pi/2), exact
  // double(pi/2) with its low 21 bits cleared, and the rest of pi/2 (to 1e-33).
  constexpr double kHalfPi1 = 1.57079632673412561416625976562500;
  constexpr double kHalfPi2 = kHalfPiHigh - kHalfPi1;                          // exact: the cleared bits
  constexpr double kHalfPi3 = 6.123233995736766035868820147292e-17;            // pi/2 - double(pi/2)
  constexpr std::int64_t kSignBit = std::numeric_limits<std::int64_t>::min();  // the sign bit alone
  // k = x 2/pi rounded half away from zero: 0.5 with the sign of x, then truncation.
  const Pair half =
      reinterpret_cast<Pair>((reinterpret_cast<PairBits>(x) & kSignBit) | reinterpret_cast<PairBits>(Pair{0.5, 0.5}));
  const PairInt k = __builtin_convertvector(x * kTwoOverPi + half, PairInt);
  const Pair kd = __builtin_convertvector(k, Pair);
  const Pair r = ((x - kd * kHalfPi1) - kd * kHalfPi2) - kd * kHalfPi3;
  const Pair r2 = r * r;
  // 1/n! for n = 3 .. 18.
  constexpr double f3 = 1.0 / 6, f5 = f3 / 20, f7 = f5 / 42, f9 = f7 / 72, f11 = f9 / 110, f13 = f11 / 156,
                   f15 = f13 / 210, f17 = f15 / 272;
  constexpr double f2 = 0.5, f4 = f2 / 12, f6 = f4 / 30, f8 = f6 / 56, f10 = f8 / 90, f12 = f10 / 132, f14 = f12 / 182,
                   f16 = f14 / 240, f18 = f16 / 306;
  // Estrin's scheme (pairs, then pairs of pairs): a short dependency chain.
  const Pair r4 = r2 * r2;
  const Pair r8 = r4 * r4;
  const Pair ps = ((-f3 + f5 * r2) + r4 * (-f7 + f9 * r2)) + r8 * ((-f11 + f13 * r2) + r4 * (-f15 + f17 * r2));
  const Pair pc = ((f2 - f4 * r2) + r4 * (f6 - f8 * r2)) + r8 * ((f10 - f12 * r2) + r4 * (f14 - f16 * r2) + r8 * f18);
  const PairBits s = reinterpret_cast<PairBits>(r + (r * r2) * ps);
  const PairBits c = reinterpret_cast<PairBits>(1.0 - r2 * pc);
  // The quadrant without branches: odd k swaps s and c, then sine is negated for k = 2, 3 and
  // cosine for k = 1, 2 (mod 4; bit 1 of k and of k + 1 in two's complement).
  const PairBits k64 = __builtin_convertvector(k, PairBits);
  const PairBits swap = -(k64 & 1);
  sine = reinterpret_cast<Pair>(((s & ~swap) | (c & swap)) ^ (((k64 >> 1) & 1) << 63));
  cosine = reinterpret_cast<Pair>(((c & ~swap) | (s & swap)) ^ ((((k64 + 1) >> 1) & 1) << 63));
}

/// sine[i] and cosine[i] of angle[i] for i < n, two at a time.
void sinCosAll(const double* angle, int n, double* sine, double* cosine) {
  for (int i = 0; i < n; i += 2) {
    const bool two = i + 1 < n;
    const double a = angle[i];
    const double b = two ? angle[i + 1] : 0.0;
    if (std::abs(a) < kSinCosRange && std::abs(b) < kSinCosRange) {
      Pair s, c;
      sinCos(Pair{a, b}, s, c);
      sine[i] = s[0];
      cosine[i] = c[0];
      if (two) {
        sine[i + 1] = s[1];
        cosine[i + 1] = c[1];
      }
    } else {
      for (int j = i; j < std::min(i + 2, n); ++j) {
        sine[j] = std::sin(angle[j]);
        cosine[j] = std::cos(angle[j]);
      }
    }
  }
}

/// The coordinate axis (0, 1, 2) that `axis` is, exactly, or -1; `sign` is +1 or -1.
inline int coordinateAxis(const Eigen::Vector3d& axis, double& sign) {
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3;
    const int j = (k + 2) % 3;
    if (axis[i] == 0.0 && axis[j] == 0.0 && (axis[k] == 1.0 || axis[k] == -1.0)) {
      sign = axis[k];
      return k;
    }
  }
  return -1;
}

void checkLink(const RobotModel& model, const std::vector<Eigen::Isometry3d>& X_WL, int link) {
  if (link < 0 || link >= model.numLinks()) {
    std::ostringstream msg;
    msg << "robot '" << model.name() << "': link index " << link << " out of range [0, " << model.numLinks() << ")";
    throw std::invalid_argument(msg.str());
  }
  if (static_cast<int>(X_WL.size()) != model.numLinks()) {
    std::ostringstream msg;
    msg << "robot '" << model.name() << "': " << X_WL.size() << " link poses given, the robot has " << model.numLinks()
        << " links";
    throw std::invalid_argument(msg.str());
  }
}

/// Adds the contribution of every moving joint between the root and `link` to the columns of
/// J (angular rows only when `angular`), for the point p_WQ.
template <typename AngularBlock, typename LinearBlock>
void accumulate(const RobotModel& model, const std::vector<Eigen::Isometry3d>& X_WL, int link,
                const Eigen::Vector3d& p_WQ, AngularBlock* angular, LinearBlock& linear) {
  for (int l = link; model.link(l).parentJoint >= 0; l = model.link(l).parentLink) {
    const Joint& joint = model.joint(model.link(l).parentJoint);
    if (!joint.moves()) continue;
    // The axis is the same in J and C; the child origin lies on a revolute axis.
    const Eigen::Isometry3d& X_WC = X_WL[joint.childLink];
    const Eigen::Vector3d a_W = X_WC.linear() * joint.axis;
    if (joint.type == JointType::Prismatic) {
      linear.col(joint.variable) += joint.multiplier * a_W;
    } else {
      linear.col(joint.variable) += joint.multiplier * a_W.cross(p_WQ - X_WC.translation());
      if (angular != nullptr) angular->col(joint.variable) += joint.multiplier * a_W;
    }
  }
}

}  // namespace

void checkConfiguration(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& q) {
  if (q.size() != model.numVariables()) {
    std::ostringstream msg;
    msg << "robot '" << model.name() << "': configuration has " << q.size() << " values, the robot has "
        << model.numVariables() << " variables (";
    for (int v = 0; v < model.numVariables(); ++v) {
      msg << (v ? ", " : "") << model.variableNames()[v];
    }
    msg << ")";
    throw std::invalid_argument(msg.str());
  }
  for (int v = 0; v < q.size(); ++v) {
    if (!std::isfinite(q[v])) {
      std::ostringstream msg;
      msg << "robot '" << model.name() << "': configuration value q[" << v << "] (" << model.variableNames()[v]
          << ") is " << q[v];
      throw std::invalid_argument(msg.str());
    }
  }
}

// X_WC = X_WP * X_PJ * X_JC(value), computed without 4 x 4 products: first X_WJ = X_WP * X_PJ
// (a 3 x 3 product and a rotated translation), then the joint's motion applied in place: a
// rotation about a coordinate axis (every joint of the Panda, the UR5 and the bundled arm) turns
// two columns of R_WJ by the angle (one sine and cosine, sinCos above); any other axis multiplies by the
// angle-axis matrix; a prismatic joint moves the origin along R_WJ * axis. The child origin lies
// on a revolute axis, so the translation is t_WJ for revolute joints. Agrees with the plain
// product of the three transforms to round-off (tests/robots/test_kinematics.cpp).
void forwardKinematics(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                       std::vector<Eigen::Isometry3d>& X_WL) {
  checkConfiguration(model, q);
  if (static_cast<int>(X_WL.size()) != model.numLinks()) X_WL.resize(model.numLinks());
  X_WL[0] = model.basePose();
  // Joint i is the parent joint of link i + 1, and parents precede children. The sines and
  // cosines come first, in blocks (they do not depend on the chain of products, which is
  // sequential): the processor overlaps them.
  const std::vector<Joint>& joints = model.joints();
  constexpr int kBlock = 16;
  double angles[kBlock], sines[kBlock], cosines[kBlock];
  int axes[kBlock];   // the coordinate axis of a revolute joint (coordinateAxis), else -1
  int slots[kBlock];  // where its sine is, when it has an axis
  for (int first = 0; first < static_cast<int>(joints.size()); first += kBlock) {
    const int end = std::min(first + kBlock, static_cast<int>(joints.size()));
    int n = 0;
    for (int i = first; i < end; ++i) {
      const Joint& joint = joints[i];
      axes[i - first] = -1;
      if (joint.type != JointType::Revolute && joint.type != JointType::Continuous) continue;
      double sign = 1.0;
      axes[i - first] = coordinateAxis(joint.axis, sign);
      if (axes[i - first] < 0) continue;
      slots[i - first] = n;
      angles[n++] = sign * (joint.multiplier * q[joint.variable] + joint.offset);
    }
    sinCosAll(angles, n, sines, cosines);
    for (int i = first; i < end; ++i) {
      const Joint& joint = joints[i];
      const Eigen::Isometry3d& X_WP = X_WL[joint.parentLink];
      Eigen::Isometry3d& X_WC = X_WL[joint.childLink];
      Eigen::Matrix3d R;
      R.noalias() = X_WP.linear() * joint.X_PJ.linear();
      Eigen::Vector3d t = X_WP.translation();
      t.noalias() += X_WP.linear() * joint.X_PJ.translation();
      switch (joint.type) {
        case JointType::Fixed:
          break;
        case JointType::Revolute:
        case JointType::Continuous: {
          const int k = axes[i - first];
          if (k >= 0) {
            rotateAboutCoordinateAxis(R, k, cosines[slots[i - first]], sines[slots[i - first]]);
          } else {
            const double value = joint.multiplier * q[joint.variable] + joint.offset;
            R = R * Eigen::AngleAxisd(value, joint.axis).toRotationMatrix();
          }
          break;
        }
        case JointType::Prismatic: {
          const double value = joint.multiplier * q[joint.variable] + joint.offset;
          t.noalias() += value * (R * joint.axis);
          break;
        }
      }
      X_WC.linear() = R;
      X_WC.translation() = t;
      X_WC.makeAffine();
    }
  }
}

std::vector<Eigen::Isometry3d> forwardKinematics(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& q) {
  std::vector<Eigen::Isometry3d> X_WL;
  forwardKinematics(model, q, X_WL);
  return X_WL;
}

void pointJacobian(const RobotModel& model, const std::vector<Eigen::Isometry3d>& X_WL, int link,
                   const Eigen::Vector3d& p_LQ, Eigen::Matrix3Xd& J_WQ) {
  checkLink(model, X_WL, link);
  if (J_WQ.cols() != model.numVariables()) J_WQ.resize(3, model.numVariables());
  J_WQ.setZero();
  const Eigen::Vector3d p_WQ = X_WL[link] * p_LQ;
  accumulate<Eigen::Matrix3Xd>(model, X_WL, link, p_WQ, nullptr, J_WQ);
}

Eigen::Matrix3Xd pointJacobian(const RobotModel& model, const std::vector<Eigen::Isometry3d>& X_WL, int link,
                               const Eigen::Vector3d& p_LQ) {
  Eigen::Matrix3Xd J;
  pointJacobian(model, X_WL, link, p_LQ, J);
  return J;
}

Eigen::Matrix3Xd pointJacobian(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& q, int link,
                               const Eigen::Vector3d& p_LQ) {
  return pointJacobian(model, forwardKinematics(model, q), link, p_LQ);
}

void spatialJacobian(const RobotModel& model, const std::vector<Eigen::Isometry3d>& X_WL, int link,
                     const Eigen::Vector3d& p_LQ, Eigen::Matrix<double, 6, Eigen::Dynamic>& J) {
  checkLink(model, X_WL, link);
  if (J.cols() != model.numVariables()) J.resize(6, model.numVariables());
  J.setZero();
  const Eigen::Vector3d p_WQ = X_WL[link] * p_LQ;
  auto angular = J.topRows<3>();
  auto linear = J.bottomRows<3>();
  accumulate(model, X_WL, link, p_WQ, &angular, linear);
}

}  // namespace deepcheck::robots
