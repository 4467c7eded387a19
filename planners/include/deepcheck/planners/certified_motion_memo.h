#pragma once
// The motions a certified motion validator has accepted, remembered so that the same motion, or a
// piece of it, asked again is answered without a new certification.
//
// A planner's path is checked motion by motion several times: by the planner, by each
// simplification step that keeps it, by simplifySolutionChecked's final check and by certifyPath
// (setup.h). Simplification also cuts certified motions into pieces (B-spline smoothing subdivides
// the path; a user may interpolate it before certifyPath). Every validator made on one
// StateValidityChecker (the planner's and the ones certifyPath makes) shares the checker's memo,
// so a path that came out of solve and simplifySolutionChecked is certified again at the cost of
// a few lookups.
//
// A motion is given as its two configurations and its displacement (the short way round for
// wrapping joints, as the certification moved), in the order asked. The memo keeps points of
// certified motions, keyed by their exact bits and the World::version() the motion was certified
// in: each end of a certified motion, with where it lies on that motion. A motion asked is
// answered when one of its ends is such a point and both ends lie on the certified motion of that
// point, to tol::kCertifiedMotionMemoTube (a few ulps: the round-off of computing a point of a
// segment, which the certification's own configurations carry too). The motion's other end is then
// kept as a point of the same certified motion, so the pieces of a subdivided motion are answered
// one after the other. Positions are always relative to the certified motion itself, so answers
// never drift from it. The same motion reversed is answered too (the same configurations); one the
// other way round a wrapping joint is not.
//
// A motion inserted that continues a recorded one in a straight line, from its end or into its
// start (the steps of an RRTConnect connection, each from the last one's end toward one target),
// is recorded joined to it: the one segment from the first step's start to the last one's end.
// A shortcut between two points of such a line is then answered without a new certification. The
// joint between the two pieces must lie on the joined segment to tol::kCertifiedMotionMemoTube
// divided by tol::kCertifiedMotionMemoJoins, and a recorded motion joins at most that many pieces,
// so the joined segment stays within the tube of the certified pieces.
//
// Any change of the world (an obstacle added, moved or removed, an object attached) changes the
// version, and no entry of an older one answers. The checker's validity options are fixed at its
// construction, so they need no key. Only acceptances are kept: a rejected motion is asked again
// rarely, and its lastValid fraction would need keeping too.
//
// A fixed number of entries (tol::kCertifiedMotionMemoSlots) in buckets of two, indexed by a hash
// of the point: a new entry replaces the older of its bucket. Thread safe (one lock per group of
// buckets).

#include <Eigen/Core>

#include <algorithm>
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

  /// True when the motion from `from` to `to` (displacement `dq`) lies on a motion recorded as
  /// certified in world version `version`.
  bool contains(const Eigen::Ref<const Eigen::VectorXd>& from, const Eigen::Ref<const Eigen::VectorXd>& to,
                const Eigen::Ref<const Eigen::VectorXd>& dq, std::uint64_t version);
  /// Records the motion from `from` to `to` (displacement `dq`) as certified in world version
  /// `version`.
  void insert(const Eigen::Ref<const Eigen::VectorXd>& from, const Eigen::Ref<const Eigen::VectorXd>& to,
              const Eigen::Ref<const Eigen::VectorXd>& dq, std::uint64_t version);
  /// Forgets every entry.
  void clear();

  /// Lookups that found their motion.
  std::uint64_t hits() const { return hits_.load(std::memory_order_relaxed); }

 private:
  static constexpr int kLocks = 16;
  static constexpr int kWays = 2;

  /// One point of a certified motion: the motion is the segment from some start c along
  /// `motion`; the point is c + `offset` (both unwrapped, in the motion's own coordinates).
  struct Entry {
    std::uint64_t key = 0;      ///< the hash of the point and version (0: empty)
    std::uint64_t version = 0;  ///< the world version the motion was certified in
    int joins = 0;              ///< the motion's pieces joined after the first (insert)
  };
  /// Where a point lies on a recorded motion: c + offset of the motion c + s motion, s in [0, 1],
  /// made of joins + 1 certified pieces.
  struct Place {
    Eigen::VectorXd offset, motion;
    int joins = 0;
  };
  /// The entry's point, offset and motion (3 n values).
  double* values(std::size_t entry) { return values_.data() + entry * 3 * static_cast<std::size_t>(n_); }
  const double* values(std::size_t entry) const { return values_.data() + entry * 3 * static_cast<std::size_t>(n_); }
  /// Entry `e` keeps exactly `point` (hashed to `key`) in world version `version`: the hash only
  /// chooses the bucket, the point itself must match.
  bool keeps(std::size_t e, std::uint64_t key, std::uint64_t version, const double* point) const {
    return entries_[e].key == key && entries_[e].version == version && std::equal(values(e), values(e) + n_, point);
  }
  std::uint64_t hash(const Eigen::Ref<const Eigen::VectorXd>& point, std::uint64_t version) const;
  std::size_t bucketOf(std::uint64_t key) const { return key % (entries_.size() / kWays); }
  std::mutex& lock(std::size_t bucket) const { return locks_[bucket % kLocks]; }
  /// True when an entry of `point` has a certified motion that holds the segment from point to
  /// point + side dq (side +1: point is the motion asked's start; -1: its end); the entry's offset
  /// and motion are then copied out.
  bool lookup(const Eigen::Ref<const Eigen::VectorXd>& point, std::uint64_t version,
              const Eigen::Ref<const Eigen::VectorXd>& dq, double side, Place& place) const;
  /// True when an entry of `point` has a certified motion that the motion from point to
  /// point + side dq continues in a straight line (side +1: point is the new motion's start, on
  /// the recorded one; -1: its end), with joins to spare; `joined` is then the new motion's start
  /// (side +1: point itself; -1: point - dq) on the joined motion.
  bool joinable(const Eigen::Ref<const Eigen::VectorXd>& point, std::uint64_t version,
                const Eigen::Ref<const Eigen::VectorXd>& dq, double side, Place& joined) const;
  /// Keeps `point` as `place` of the world version `version`.
  void keep(const Eigen::Ref<const Eigen::VectorXd>& point, const Place& place, std::uint64_t version);

  int n_;
  std::vector<Entry> entries_;  ///< buckets of kWays, the newest first
  std::vector<double> values_;
  mutable std::array<std::mutex, kLocks> locks_;
  std::atomic<std::uint64_t> hits_{0};
};

}  // namespace deepcheck::planners
