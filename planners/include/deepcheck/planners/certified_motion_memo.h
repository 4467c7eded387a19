#pragma once
// The motions a certified motion validator has accepted, remembered so that the same motion asked
// again is answered without a new certification.
//
// A planner's path is checked motion by motion several times: by the planner, by each
// simplification step that keeps it, by simplifySolutionChecked's final check and by certifyPath
// (setup.h). Every validator made on one StateValidityChecker (the planner's and the ones
// certifyPath makes) shares the checker's memo, so a path that came out of solve and
// simplifySolutionChecked is certified again at the cost of a few lookups.
//
// An entry is the exact pair of configurations (bit for bit, in the order asked: a motion's
// displacement is the short way round for wrapping joints, which need not be symmetric at exactly
// half a turn) and the World::version() it was certified in. Any change of the world (an obstacle
// added, moved or removed, an object attached) changes the version, and no entry of an older one
// answers. The checker's validity options are fixed at its construction, so they need no key.
// Only acceptances are kept: a rejected motion is asked again rarely, and its lastValid fraction
// would need keeping too.
//
// A fixed number of slots (tol::kCertifiedMotionMemoSlots), indexed by a hash of the key: a new
// entry replaces whatever held its slot. Thread safe (one lock per group of slots).

#include <Eigen/Core>

#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <vector>

namespace deepcheck::planners {

class CertifiedMotionMemo {
 public:
  /// For configurations of `dimension` values (>= 0; std::invalid_argument otherwise).
  explicit CertifiedMotionMemo(int dimension);

  /// True when the motion from `from` to `to` was recorded as certified in world version `version`.
  bool contains(const Eigen::Ref<const Eigen::VectorXd>& from, const Eigen::Ref<const Eigen::VectorXd>& to,
                std::uint64_t version) const;
  /// Records the motion as certified in world version `version`.
  void insert(const Eigen::Ref<const Eigen::VectorXd>& from, const Eigen::Ref<const Eigen::VectorXd>& to,
              std::uint64_t version);
  /// Forgets every entry.
  void clear();

  /// Lookups that found their motion.
  std::uint64_t hits() const { return hits_.load(std::memory_order_relaxed); }

 private:
  static constexpr int kLocks = 16;
  std::uint64_t hash(const Eigen::Ref<const Eigen::VectorXd>& from, const Eigen::Ref<const Eigen::VectorXd>& to,
                     std::uint64_t version) const;
  /// The slot's stored configurations (2 n values) and its lock.
  double* values(std::size_t slot) { return values_.data() + slot * 2 * static_cast<std::size_t>(n_); }
  const double* values(std::size_t slot) const { return values_.data() + slot * 2 * static_cast<std::size_t>(n_); }
  std::mutex& lock(std::size_t slot) const { return locks_[slot % kLocks]; }

  struct Slot {
    std::uint64_t key = 0;      ///< the hash of the entry (0: empty)
    std::uint64_t version = 0;  ///< the world version it was certified in
  };
  int n_;
  std::vector<Slot> slots_;
  std::vector<double> values_;
  mutable std::array<std::mutex, kLocks> locks_;
  mutable std::atomic<std::uint64_t> hits_{0};
};

}  // namespace deepcheck::planners
