// The memo of certified motions (certified_motion_memo.h) on its own: random motions and pieces
// of them, computed as a planner computes them, and the same motions reversed are answered; what
// lies off a motion, past its end or in another world version is never answered.

#include "deepcheck/planners/certified_motion_memo.h"
#include "deepcheck/planners/tolerances.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <vector>

namespace dp = deepcheck::planners;

namespace {

constexpr int kDimension = 6;

/// The value wrapped into [-pi, pi), as a continuous joint's state is stored.
double wrapped(double x) { return x - 2.0 * M_PI * std::floor((x + M_PI) / (2.0 * M_PI)); }

struct RandomMotion {
  Eigen::VectorXd from, to, dq;
};

/// A motion of up to 3 rad per value from a random configuration; the first value wraps (its
/// stored end is not from + dq).
RandomMotion randomMotion(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> value(-M_PI, M_PI);
  std::uniform_real_distribution<double> step(-3.0, 3.0);
  RandomMotion m;
  m.from.resize(kDimension);
  m.dq.resize(kDimension);
  for (int i = 0; i < kDimension; ++i) {
    m.from[i] = value(rng);
    m.dq[i] = step(rng);
  }
  m.to = m.from + m.dq;
  m.to[0] = wrapped(m.to[0]);
  return m;
}

/// A unit vector orthogonal to v.
Eigen::VectorXd across(const Eigen::VectorXd& v, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::VectorXd u(v.size());
  for (Eigen::Index i = 0; i < v.size(); ++i) u[i] = normal(rng);
  u -= (u.dot(v) / v.squaredNorm()) * v;
  return u.normalized();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(certified_motion_memo)

BOOST_AUTO_TEST_CASE(a_recorded_motion_is_answered_in_its_version_only) {
  std::mt19937_64 rng(3);
  dp::CertifiedMotionMemo memo(kDimension);
  const RandomMotion m = randomMotion(rng);
  BOOST_TEST(!memo.contains(m.from, m.to, m.dq, 7));
  memo.insert(m.from, m.to, m.dq, 7);
  BOOST_TEST(memo.contains(m.from, m.to, m.dq, 7));
  BOOST_TEST(!memo.contains(m.from, m.to, m.dq, 8));
  BOOST_TEST(memo.contains(m.to, m.from, -m.dq, 7));  // the same configurations, reversed
  BOOST_TEST(memo.hits() == 2u);
  memo.clear();
  BOOST_TEST(!memo.contains(m.from, m.to, m.dq, 7));
}

// Pieces computed as a planner computes them (from + s dq; a subdivided path's pieces one after
// the other) are answered; pieces moved off the motion by far more than the tube, or reaching past
// its end, are not.
BOOST_AUTO_TEST_CASE(pieces_of_random_motions_are_answered_and_nothing_else) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  dp::CertifiedMotionMemo memo(kDimension);
  for (int trial = 0; trial < 300; ++trial) {
    const RandomMotion m = randomMotion(rng);
    const auto version = static_cast<std::uint64_t>(trial);
    memo.insert(m.from, m.to, m.dq, version);
    // Off the motion: a millionth of a radian across it, from either end; past its end.
    const double off = 1e-6;
    const Eigen::VectorXd side = off * across(m.dq, rng);
    BOOST_TEST(!memo.contains(m.from, m.to + side, m.dq + side, version));
    BOOST_TEST(!memo.contains(m.from + side, m.to, m.dq - side, version));
    BOOST_TEST(!memo.contains(m.from, m.from + 1.001 * m.dq, 1.001 * m.dq, version));
    BOOST_TEST(!memo.contains(m.from - 0.001 * m.dq, m.to, 1.001 * m.dq, version));
    // A subdivided motion, piece after piece, through points computed from its start.
    const int pieces = 2 + static_cast<int>(unit(rng) * 6.0);
    Eigen::VectorXd a = m.from;
    for (int k = 1; k <= pieces; ++k) {
      Eigen::VectorXd b = k == pieces ? m.to : Eigen::VectorXd(m.from + (static_cast<double>(k) / pieces) * m.dq);
      Eigen::VectorXd d = b - a;
      if (k == pieces) d[0] = m.dq[0] - (a[0] - m.from[0]);  // the last piece ends at the wrapped value
      BOOST_TEST(memo.contains(a, b, d, version), "trial " << trial << ", piece " << k << " of " << pieces);
      a = b;
    }
    // A piece inside, across from the start's side, off by a millionth: not answered.
    const double s0 = 0.5 * unit(rng);
    const Eigen::VectorXd inside = m.from + s0 * m.dq;
    BOOST_TEST(memo.contains(m.from, inside, s0 * m.dq, version));
    BOOST_TEST(!memo.contains(inside, m.to + side, m.dq - s0 * m.dq + side, version));
  }
}

namespace {

/// The steps of an RRTConnect connection from `from` toward `target`: each a fixed length from
/// the last one's end (OMPL's interpolation), the last one reaching the target.
std::vector<Eigen::VectorXd> connection(const Eigen::VectorXd& from, const Eigen::VectorXd& target, double range) {
  std::vector<Eigen::VectorXd> points{from};
  while ((target - points.back()).norm() > range) {
    const Eigen::VectorXd& at = points.back();
    points.push_back(at + (range / (target - at).norm()) * (target - at));
  }
  points.push_back(target);
  return points;
}

}  // namespace

// The steps of a connection recorded one by one join into one motion: any two of its points are
// answered, whichever way the steps were recorded (forward as a start tree grows, backward as a
// goal tree's motions run toward its root). A step bent off the line by a millionth of a radian
// does not join, and no more than tol::kCertifiedMotionMemoJoins steps join into one motion. A
// few pairs are not answered: an entry is dropped when two newer ones of other points share its
// bucket (the memo's fixed size; none with a memo of a million entries).
BOOST_AUTO_TEST_CASE(the_steps_of_a_straight_connection_join) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> any(0, 1 << 20);
  int asked = 0;
  int answered = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const RandomMotion m = randomMotion(rng);
    const Eigen::VectorXd target = m.from + m.dq;
    const std::vector<Eigen::VectorXd> p = connection(m.from, target, m.dq.norm() / (2.0 + trial % 20));
    const int n = static_cast<int>(p.size());
    dp::CertifiedMotionMemo forward(kDimension);
    dp::CertifiedMotionMemo backward(kDimension);
    for (int k = 0; k + 1 < n; ++k) {
      forward.insert(p[k], p[k + 1], p[k + 1] - p[k], 1);
      backward.insert(p[n - 1 - k], p[n - 2 - k], p[n - 2 - k] - p[n - 1 - k], 1);
    }
    for (int pick = 0; pick < 10; ++pick) {
      const int i = any(rng) % n;
      const int j = any(rng) % n;
      answered += forward.contains(p[i], p[j], p[j] - p[i], 1) ? 1 : 0;
      answered += backward.contains(p[i], p[j], p[j] - p[i], 1) ? 1 : 0;
      asked += 2;
    }
    // The middle point off the line: its two steps stay apart.
    dp::CertifiedMotionMemo bent(kDimension);
    const Eigen::VectorXd middle = p[1] + 1e-6 * across(m.dq, rng);
    bent.insert(p[0], middle, middle - p[0], 1);
    bent.insert(middle, p[2], p[2] - middle, 1);
    BOOST_TEST(!bent.contains(p[0], p[2], p[2] - p[0], 1), "trial " << trial);
  }
  BOOST_TEST(asked == 200 * 20);
  BOOST_TEST(answered >= asked - asked / 100);
  // 40 steps: the first 33 join, the rest start a motion of their own.
  const Eigen::VectorXd from = Eigen::VectorXd::Constant(kDimension, -1.0);
  const std::vector<Eigen::VectorXd> p = connection(from, -from, 2.0 * from.norm() / 40.5);
  BOOST_TEST(p.size() == 42u);
  dp::CertifiedMotionMemo memo(kDimension);
  for (std::size_t k = 0; k + 1 < p.size(); ++k) memo.insert(p[k], p[k + 1], p[k + 1] - p[k], 1);
  const int joined = dp::tol::kCertifiedMotionMemoJoins + 1;
  BOOST_TEST(memo.contains(p[0], p[joined], p[joined] - p[0], 1));
  BOOST_TEST(!memo.contains(p[0], p[joined + 1], p[joined + 1] - p[0], 1));
  BOOST_TEST(memo.contains(p[joined], p[41], p[41] - p[joined], 1));
}

BOOST_AUTO_TEST_CASE(a_point_motion_and_empty_configurations) {
  dp::CertifiedMotionMemo memo(kDimension);
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(kDimension, 0.25);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(kDimension);
  memo.insert(q, q, zero, 1);
  BOOST_TEST(memo.contains(q, q, zero, 1));
  Eigen::VectorXd r = q;
  r[2] += 1e-9;
  BOOST_TEST(!memo.contains(q, r, r - q, 1));
  BOOST_TEST(!memo.contains(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(3), 1));
  BOOST_CHECK_THROW(dp::CertifiedMotionMemo(-1), std::invalid_argument);
  dp::CertifiedMotionMemo none(0);
  none.insert(Eigen::VectorXd(), Eigen::VectorXd(), Eigen::VectorXd(), 2);
  BOOST_TEST(none.contains(Eigen::VectorXd(), Eigen::VectorXd(), Eigen::VectorXd(), 2));
}

BOOST_AUTO_TEST_SUITE_END()
