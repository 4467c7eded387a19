// The memo of certified motions (certified_motion_memo.h).

#include "deepcheck/planners/certified_motion_memo.h"

#include "deepcheck/planners/tolerances.h"

#include <cstring>
#include <stdexcept>
#include <string>

namespace deepcheck::planners {

namespace {

/// One step of a 64-bit mix (splitmix64's finaliser) over the running hash and one word.
std::uint64_t mix(std::uint64_t h, std::uint64_t word) {
  h ^= word + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ULL;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebULL;
  return h ^ (h >> 31);
}

std::uint64_t bitsOf(double x) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}

}  // namespace

CertifiedMotionMemo::CertifiedMotionMemo(int dimension) : n_(dimension) {
  if (dimension < 0) {
    throw std::invalid_argument("CertifiedMotionMemo: a negative dimension (" + std::to_string(dimension) + ")");
  }
  const auto slots = static_cast<std::size_t>(tol::kCertifiedMotionMemoSlots);
  slots_.assign(slots, Slot{});
  values_.assign(slots * 2 * static_cast<std::size_t>(n_), 0.0);
}

std::uint64_t CertifiedMotionMemo::hash(const Eigen::Ref<const Eigen::VectorXd>& from,
                                        const Eigen::Ref<const Eigen::VectorXd>& to, std::uint64_t version) const {
  std::uint64_t h = mix(0, version);
  for (int i = 0; i < n_; ++i) h = mix(h, bitsOf(from[i]));
  for (int i = 0; i < n_; ++i) h = mix(h, bitsOf(to[i]));
  return h == 0 ? 1 : h;  // 0 marks an empty slot
}

bool CertifiedMotionMemo::contains(const Eigen::Ref<const Eigen::VectorXd>& from,
                                   const Eigen::Ref<const Eigen::VectorXd>& to, std::uint64_t version) const {
  if (from.size() != n_ || to.size() != n_) return false;
  const std::uint64_t key = hash(from, to, version);
  const std::size_t slot = key % slots_.size();
  std::lock_guard<std::mutex> guard(lock(slot));
  const Slot& s = slots_[slot];
  if (s.key != key || s.version != version) return false;
  // The hash only chooses the slot: the configurations themselves must match, exactly.
  const double* v = values(slot);
  for (int i = 0; i < n_; ++i) {
    if (!(v[i] == from[i]) || !(v[n_ + i] == to[i])) return false;
  }
  hits_.fetch_add(1, std::memory_order_relaxed);
  return true;
}

void CertifiedMotionMemo::insert(const Eigen::Ref<const Eigen::VectorXd>& from,
                                 const Eigen::Ref<const Eigen::VectorXd>& to, std::uint64_t version) {
  if (from.size() != n_ || to.size() != n_) return;
  const std::uint64_t key = hash(from, to, version);
  const std::size_t slot = key % slots_.size();
  std::lock_guard<std::mutex> guard(lock(slot));
  slots_[slot] = Slot{key, version};
  double* v = values(slot);
  for (int i = 0; i < n_; ++i) {
    v[i] = from[i];
    v[n_ + i] = to[i];
  }
}

void CertifiedMotionMemo::clear() {
  for (std::size_t slot = 0; slot < slots_.size(); ++slot) {
    std::lock_guard<std::mutex> guard(lock(slot));
    slots_[slot] = Slot{};
  }
}

}  // namespace deepcheck::planners
