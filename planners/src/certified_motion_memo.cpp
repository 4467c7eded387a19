// The memo of certified motions (certified_motion_memo.h).

#include "deepcheck/planners/certified_motion_memo.h"

#include "deepcheck/planners/tolerances.h"
#include "memo_hash.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace deepcheck::planners {

namespace {

/// True when x lies within `tube` (per value) of the segment from 0 to `motion`. A template, so
/// that x may be an expression: no vector is made for it.
template <class Derived>
bool onSegment(const Eigen::MatrixBase<Derived>& x, const Eigen::Map<const Eigen::VectorXd>& motion, double tube) {
  const double length2 = motion.squaredNorm();
  const double s = length2 > 0.0 ? std::clamp(x.dot(motion) / length2, 0.0, 1.0) : 0.0;
  return (x - s * motion).template lpNorm<Eigen::Infinity>() <= tube;  // NaN: not on it
}

}  // namespace

CertifiedMotionMemo::CertifiedMotionMemo(int dimension) : n_(dimension) {
  if (dimension < 0) {
    throw std::invalid_argument("CertifiedMotionMemo: a negative dimension (" + std::to_string(dimension) + ")");
  }
  const auto entries = static_cast<std::size_t>(tol::kCertifiedMotionMemoSlots);
  entries_.assign(entries, Entry{});
  values_.assign(entries * 3 * static_cast<std::size_t>(n_), 0.0);
}

std::uint64_t CertifiedMotionMemo::hash(const Eigen::Ref<const Eigen::VectorXd>& point, std::uint64_t version) const {
  return detail::hashOf(point, version);
}

bool CertifiedMotionMemo::lookup(const Eigen::Ref<const Eigen::VectorXd>& point, std::uint64_t version,
                                 const Eigen::Ref<const Eigen::VectorXd>& dq, double side, Place& place) const {
  const std::uint64_t key = hash(point, version);
  const std::size_t bucket = bucketOf(key);
  const auto n = static_cast<Eigen::Index>(n_);
  std::lock_guard<std::mutex> guard(lock(bucket));
  for (std::size_t e = bucket * kWays; e < (bucket + 1) * kWays; ++e) {
    if (!keeps(e, key, version, point.data())) continue;
    const double* v = values(e);
    const Eigen::Map<const Eigen::VectorXd> at(v + n_, n);
    const Eigen::Map<const Eigen::VectorXd> along(v + 2 * n_, n);
    const double tube =
        tol::kCertifiedMotionMemoTube * (1.0 + point.lpNorm<Eigen::Infinity>() + along.lpNorm<Eigen::Infinity>());
    if (onSegment(at, along, tube) && onSegment(at + side * dq, along, tube)) {
      place.offset = at;
      place.motion = along;
      place.joins = entries_[e].joins;
      return true;
    }
  }
  return false;
}

bool CertifiedMotionMemo::joinable(const Eigen::Ref<const Eigen::VectorXd>& point, std::uint64_t version,
                                   const Eigen::Ref<const Eigen::VectorXd>& dq, double side, Place& joined) const {
  const std::uint64_t key = hash(point, version);
  const std::size_t bucket = bucketOf(key);
  const auto n = static_cast<Eigen::Index>(n_);
  std::lock_guard<std::mutex> guard(lock(bucket));
  for (std::size_t e = bucket * kWays; e < (bucket + 1) * kWays; ++e) {
    if (!keeps(e, key, version, point.data()) || entries_[e].joins >= tol::kCertifiedMotionMemoJoins) continue;
    const double* v = values(e);
    const Eigen::Map<const Eigen::VectorXd> at(v + n_, n);
    const Eigen::Map<const Eigen::VectorXd> along(v + 2 * n_, n);
    // The recorded piece kept: before the point (side +1) or after it (-1). None: nothing to join.
    const double kept = side > 0.0 ? at.lpNorm<Eigen::Infinity>() : (along - at).lpNorm<Eigen::Infinity>();
    if (!(kept > 0.0)) continue;
    // In the joined motion's coordinates, from its start: the new motion's start and the joint.
    if (side > 0.0) {
      joined.motion = at + dq;
      joined.offset = at;
    } else {
      joined.motion = dq + (along - at);
      joined.offset.setZero(n);
    }
    const double tube = tol::kCertifiedMotionMemoTube / tol::kCertifiedMotionMemoJoins *
                        (1.0 + point.lpNorm<Eigen::Infinity>() + joined.motion.lpNorm<Eigen::Infinity>());
    const Eigen::Map<const Eigen::VectorXd> motion(joined.motion.data(), n);
    if (side > 0.0 ? onSegment(joined.offset, motion, tube) : onSegment(dq, motion, tube)) {
      joined.joins = entries_[e].joins + 1;
      return true;
    }
  }
  return false;
}

void CertifiedMotionMemo::keep(const Eigen::Ref<const Eigen::VectorXd>& point, const Place& place,
                               std::uint64_t version) {
  const std::uint64_t key = hash(point, version);
  const std::size_t bucket = bucketOf(key);
  const std::size_t first = bucket * kWays;
  std::lock_guard<std::mutex> guard(lock(bucket));
  if (entries_[first].key == key && entries_[first].version == version) {
    const double* v = values(first);
    if (std::equal(v, v + n_, point.data()) && std::equal(v + n_, v + 2 * n_, place.offset.data()) &&
        std::equal(v + 2 * n_, v + 3 * n_, place.motion.data())) {
      return;  // already the newest
    }
  }
  // The newest entry first: the older ones move down a way, the oldest is dropped.
  for (std::size_t e = first + kWays - 1; e > first; --e) {
    entries_[e] = entries_[e - 1];
    std::copy(values(e - 1), values(e - 1) + 3 * n_, values(e));
  }
  entries_[first] = Entry{key, version, place.joins};
  double* v = values(first);
  std::copy(point.data(), point.data() + n_, v);
  std::copy(place.offset.data(), place.offset.data() + n_, v + n_);
  std::copy(place.motion.data(), place.motion.data() + n_, v + 2 * n_);
}

bool CertifiedMotionMemo::contains(const Eigen::Ref<const Eigen::VectorXd>& from,
                                   const Eigen::Ref<const Eigen::VectorXd>& to,
                                   const Eigen::Ref<const Eigen::VectorXd>& dq, std::uint64_t version) {
  if (from.size() != n_ || to.size() != n_ || dq.size() != n_) return false;
  thread_local Place place;
  if (lookup(from, version, dq, 1.0, place)) {
    place.offset += dq;
    keep(to, place, version);
  } else if (lookup(to, version, dq, -1.0, place)) {
    place.offset -= dq;
    keep(from, place, version);
  } else {
    return false;
  }
  hits_.fetch_add(1, std::memory_order_relaxed);
  return true;
}

void CertifiedMotionMemo::insert(const Eigen::Ref<const Eigen::VectorXd>& from,
                                 const Eigen::Ref<const Eigen::VectorXd>& to,
                                 const Eigen::Ref<const Eigen::VectorXd>& dq, std::uint64_t version) {
  if (from.size() != n_ || to.size() != n_ || dq.size() != n_) return;
  thread_local Place place;
  if (!joinable(from, version, dq, 1.0, place) && !joinable(to, version, dq, -1.0, place)) {
    place.offset.setZero(n_);
    place.motion = dq;
    place.joins = 0;
  }
  keep(from, place, version);
  place.offset += dq;
  keep(to, place, version);
}

void CertifiedMotionMemo::clear() {
  for (std::size_t e = 0; e < entries_.size(); ++e) {
    std::lock_guard<std::mutex> guard(lock(e / kWays));
    entries_[e] = Entry{};
  }
}

}  // namespace deepcheck::planners
