// The memo of refused motions (refused_motion_memo.h) on its own: a recorded motion is answered in
// its world version, forwards and reversed; a motion that differs in any bit of its ends or of its
// displacement, or that was pushed out of its slot, is not; two threads see each other's motions.

#include "deepcheck/planners/refused_motion_memo.h"
#include "deepcheck/planners/tolerances.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

namespace dp = deepcheck::planners;

namespace {

constexpr int kJoints = 7;

struct AskedMotion {
  Eigen::VectorXd from, to, dq;
};

AskedMotion randomAsked(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> value(-M_PI, M_PI);
  AskedMotion m;
  m.from.resize(kJoints);
  m.to.resize(kJoints);
  for (int i = 0; i < kJoints; ++i) {
    m.from[i] = value(rng);
    m.to[i] = value(rng);
  }
  m.dq = m.to - m.from;
  return m;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(refused_motion_memo)

BOOST_AUTO_TEST_CASE(a_recorded_motion_is_answered_in_its_version_forwards_and_reversed) {
  std::mt19937_64 rng(5);
  dp::RefusedMotionMemo memo(kJoints);
  const AskedMotion m = randomAsked(rng);
  BOOST_TEST(!memo.contains(m.from, m.to, m.dq, 3));
  memo.insert(m.from, m.to, m.dq, 3);
  BOOST_TEST(memo.contains(m.from, m.to, m.dq, 3));
  BOOST_TEST(memo.contains(m.to, m.from, -m.dq, 3));
  BOOST_TEST(memo.hits() == 2u);
  BOOST_TEST(!memo.contains(m.from, m.to, m.dq, 4));  // another world
  BOOST_TEST(!memo.contains(m.to, m.from, m.dq, 3));  // the ends swapped, the displacement not
  memo.clear();
  BOOST_TEST(!memo.contains(m.from, m.to, m.dq, 3));
  BOOST_TEST(memo.hits() == 2u);
}

BOOST_AUTO_TEST_CASE(one_bit_off_is_another_motion) {
  std::mt19937_64 rng(6);
  dp::RefusedMotionMemo memo(kJoints);
  const AskedMotion m = randomAsked(rng);
  memo.insert(m.from, m.to, m.dq, 1);
  for (int i = 0; i < kJoints; ++i) {
    for (Eigen::VectorXd AskedMotion::*part : {&AskedMotion::from, &AskedMotion::to, &AskedMotion::dq}) {
      AskedMotion off = m;
      (off.*part)[i] = std::nextafter((off.*part)[i], 10.0);
      BOOST_TEST(!memo.contains(off.from, off.to, off.dq, 1), "value " << i);
    }
  }
  // A wrapping joint's other way round: the same ends, another displacement.
  AskedMotion around = m;
  around.dq[0] += around.dq[0] > 0.0 ? -2.0 * M_PI : 2.0 * M_PI;
  BOOST_TEST(!memo.contains(around.from, around.to, around.dq, 1));
  BOOST_TEST(memo.contains(m.from, m.to, m.dq, 1));
}

BOOST_AUTO_TEST_CASE(many_motions_keep_the_recent_ones_and_never_answer_a_stranger) {
  std::mt19937_64 rng(7);
  dp::RefusedMotionMemo memo(kJoints);
  std::vector<AskedMotion> recorded;
  const int count = 4 * dp::tol::kRefusedMotionMemoSlots;
  for (int k = 0; k < count; ++k) {
    recorded.push_back(randomAsked(rng));
    memo.insert(recorded.back().from, recorded.back().to, recorded.back().dq, 9);
  }
  // The last one is always kept; the memo holds at most its slots; strangers are never answered.
  BOOST_TEST(memo.contains(recorded.back().from, recorded.back().to, recorded.back().dq, 9));
  int kept = 0;
  for (const AskedMotion& m : recorded) kept += memo.contains(m.from, m.to, m.dq, 9) ? 1 : 0;
  BOOST_TEST(kept <= dp::tol::kRefusedMotionMemoSlots);
  BOOST_TEST(kept > dp::tol::kRefusedMotionMemoSlots / 2);
  for (int k = 0; k < 1000; ++k) {
    const AskedMotion stranger = randomAsked(rng);
    BOOST_TEST_REQUIRE(!memo.contains(stranger.from, stranger.to, stranger.dq, 9));
  }
}

BOOST_AUTO_TEST_CASE(two_threads_share_it) {
  dp::RefusedMotionMemo memo(kJoints);
  std::vector<std::vector<AskedMotion>> motions(2);
  std::mt19937_64 rng(8);
  for (auto& list : motions) {
    for (int k = 0; k < 50; ++k) list.push_back(randomAsked(rng));
  }
  std::vector<std::thread> threads;
  for (const auto& list : motions) {
    threads.emplace_back([&memo, &list] {
      for (const AskedMotion& m : list) memo.insert(m.from, m.to, m.dq, 2);
    });
  }
  for (std::thread& t : threads) t.join();
  int found = 0;
  for (const auto& list : motions) {
    for (const AskedMotion& m : list) found += memo.contains(m.from, m.to, m.dq, 2) ? 1 : 0;
  }
  // 100 motions in 256 slots: a few may share a slot; most are there.
  BOOST_TEST(found > 80);
}

BOOST_AUTO_TEST_CASE(wrong_sizes_are_refused_by_name) {
  BOOST_CHECK_THROW(dp::RefusedMotionMemo(-1), std::invalid_argument);
  dp::RefusedMotionMemo memo(kJoints);
  const Eigen::VectorXd shortOne = Eigen::VectorXd::Zero(kJoints - 1);
  const Eigen::VectorXd full = Eigen::VectorXd::Zero(kJoints);
  BOOST_CHECK_THROW(memo.insert(shortOne, full, full, 0), std::invalid_argument);
  BOOST_TEST(!memo.contains(shortOne, full, full, 0));
}

BOOST_AUTO_TEST_SUITE_END()
