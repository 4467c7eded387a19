// The memo of refused motions (refused_motion_memo.h).

#include "deepcheck/planners/refused_motion_memo.h"

#include "deepcheck/planners/tolerances.h"
#include "memo_hash.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace deepcheck::planners {

RefusedMotionMemo::RefusedMotionMemo(int dimension) : n_(dimension) {
  if (dimension < 0) {
    throw std::invalid_argument("RefusedMotionMemo: a negative dimension (" + std::to_string(dimension) + ")");
  }
  const auto slots = static_cast<std::size_t>(tol::kRefusedMotionMemoSlots);
  keys_.assign(slots, 0);
  versions_.assign(slots, 0);
  values_.assign(slots * 3 * static_cast<std::size_t>(n_), 0.0);
}

std::uint64_t RefusedMotionMemo::hash(const Eigen::Ref<const Eigen::VectorXd>& from,
                                      const Eigen::Ref<const Eigen::VectorXd>& to, std::uint64_t version) const {
  const std::uint64_t h = detail::mix(detail::hashOf(from, version) ^ detail::hashOf(to, version), version);
  return h == 0 ? 1 : h;  // 0 marks an empty slot
}

bool RefusedMotionMemo::contains(const Eigen::Ref<const Eigen::VectorXd>& from,
                                 const Eigen::Ref<const Eigen::VectorXd>& to,
                                 const Eigen::Ref<const Eigen::VectorXd>& dq, std::uint64_t version) {
  if (from.size() != n_ || to.size() != n_ || dq.size() != n_) return false;
  const std::uint64_t key = hash(from, to, version);
  const std::size_t slot = key % keys_.size();
  std::lock_guard<std::mutex> guard(lock(slot));
  if (keys_[slot] != key || versions_[slot] != version) return false;
  const Eigen::Map<const Eigen::VectorXd> a(values(slot), n_), b(values(slot) + n_, n_), d(values(slot) + 2 * n_, n_);
  const bool same = a == from && b == to && d == dq;
  const bool reversed = !same && a == to && b == from && d == -dq;
  if (!same && !reversed) return false;
  hits_.fetch_add(1, std::memory_order_relaxed);
  return true;
}

void RefusedMotionMemo::insert(const Eigen::Ref<const Eigen::VectorXd>& from,
                               const Eigen::Ref<const Eigen::VectorXd>& to, const Eigen::Ref<const Eigen::VectorXd>& dq,
                               std::uint64_t version) {
  if (from.size() != n_ || to.size() != n_ || dq.size() != n_) {
    throw std::invalid_argument("RefusedMotionMemo::insert: a motion of " + std::to_string(from.size()) + ", " +
                                std::to_string(to.size()) + " and " + std::to_string(dq.size()) +
                                " values for configurations of " + std::to_string(n_));
  }
  const std::uint64_t key = hash(from, to, version);
  const std::size_t slot = key % keys_.size();
  std::lock_guard<std::mutex> guard(lock(slot));
  keys_[slot] = key;
  versions_[slot] = version;
  Eigen::Map<Eigen::VectorXd>(values(slot), n_) = from;
  Eigen::Map<Eigen::VectorXd>(values(slot) + n_, n_) = to;
  Eigen::Map<Eigen::VectorXd>(values(slot) + 2 * n_, n_) = dq;
}

void RefusedMotionMemo::clear() {
  for (std::size_t slot = 0; slot < keys_.size(); ++slot) {
    std::lock_guard<std::mutex> guard(lock(slot));
    keys_[slot] = 0;
  }
}

}  // namespace deepcheck::planners
