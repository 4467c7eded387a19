#pragma once
// The motions a certified motion validator has refused, remembered so that the same motion asked
// again is refused without a new test. Path simplification asks again: OMPL's vertex reduction
// draws vertex pairs at random, runs twice in a shortening pass, and starts each time with the
// path's first and last states, most often a motion through an obstacle.
//
// A motion is kept as its two configurations and its displacement, by their exact bits, with the
// World::version() it was refused in; only the same motion in the same world is answered, or the
// same configurations the other way round with exactly the opposite displacement. A fixed number
// of slots (tol::kRefusedMotionMemoSlots), indexed by a hash of the motion: a new motion replaces
// the one in its slot. Thread safe (one lock per group of slots).

#include <Eigen/Core>

#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <vector>

namespace deepcheck::planners {

class RefusedMotionMemo {
 public:
  /// For configurations of `dimension` values (>= 0; std::invalid_argument otherwise).
  explicit RefusedMotionMemo(int dimension);

  /// True when the motion from `from` to `to` (displacement `dq`), or from `to` to `from` with
  /// displacement -dq, was recorded refused in world version `version`.
  bool contains(const Eigen::Ref<const Eigen::VectorXd>& from, const Eigen::Ref<const Eigen::VectorXd>& to,
                const Eigen::Ref<const Eigen::VectorXd>& dq, std::uint64_t version);
  /// Records the motion from `from` to `to` (displacement `dq`) as refused in world version
  /// `version`.
  void insert(const Eigen::Ref<const Eigen::VectorXd>& from, const Eigen::Ref<const Eigen::VectorXd>& to,
              const Eigen::Ref<const Eigen::VectorXd>& dq, std::uint64_t version);
  /// Forgets every motion.
  void clear();

  /// Lookups that found their motion.
  std::uint64_t hits() const { return hits_.load(std::memory_order_relaxed); }

 private:
  static constexpr int kLocks = 16;

  /// The slot's motion: from, to and the displacement (3 n values).
  double* values(std::size_t slot) { return values_.data() + slot * 3 * static_cast<std::size_t>(n_); }
  /// The same for both directions of a motion: the ends' hashes combined without their order.
  std::uint64_t hash(const Eigen::Ref<const Eigen::VectorXd>& from, const Eigen::Ref<const Eigen::VectorXd>& to,
                     std::uint64_t version) const;
  std::mutex& lock(std::size_t slot) const { return locks_[slot % kLocks]; }

  int n_;
  std::vector<std::uint64_t> keys_;  ///< per slot: the hash of its motion (0: empty)
  std::vector<std::uint64_t> versions_;
  std::vector<double> values_;
  mutable std::array<std::mutex, kLocks> locks_;
  std::atomic<std::uint64_t> hits_{0};
};

}  // namespace deepcheck::planners
