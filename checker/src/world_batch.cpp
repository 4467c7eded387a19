// World::isFreeBatch: up to kLanes configurations posed at once (batch_kinematics.h), the ones
// the bound stage certifies free (batch_bounds.h) answered free, every other answered by isFree;
// World::isClearBatch likewise with the demand's margins, and isClear.
//
// Why the answers are isFree's: in a certified configuration every checked pair (robot piece
// and world piece, or self piece pair) is farther apart, by bounding volumes that contain the
// pieces, than tol::kBatchBoundRelative of the coordinates' scale (batch_bounds.h); isFree's
// bounding tests reject such a pair or its narrow phase finds it apart (it reports touching only
// within geometry::tol::kContactRelative, 1e-12, of the pair's length scale), so isFree answers
// free. Any other configuration gets isFree's own answer. With margins, the bounding volumes are
// that much farther apart than each pair's margin, which is isClear's test.

#include "world_clearance_internal.h"

#include <bitset>
#include <stdexcept>
#include <string>

namespace deepcheck::checker {

using namespace detail;  // NOLINT: the queries' own internals

namespace {

/// Checks qs's shape (naming `query` when it is wrong); brings the context up to the world's snapshot.
const Snapshot& prepareBatch(const WorldState& state, Impl& c, const Eigen::Ref<const Eigen::MatrixXd>& qs,
                             const char* query) {
  const Snapshot& s = current(state, c);
  const int vars = s.robot->model.numVariables();
  if (qs.rows() != vars || qs.cols() < 1 || qs.cols() > kLanes) {
    throw std::invalid_argument(std::string(query) + ": qs is " + std::to_string(qs.rows()) + " x " +
                                std::to_string(qs.cols()) + "; it must be " + std::to_string(vars) +
                                " (the robot's variables) x 1 to " + std::to_string(kLanes) + " configurations");
  }
  if (c.batch == nullptr) c.batch = std::make_unique<BatchScratch>();
  return s;
}

}  // namespace

namespace detail {

std::uint32_t batchFreeLanes(const WorldState& state, Impl& c, const Eigen::Ref<const Eigen::MatrixXd>& qs,
                             const BatchMargins& margins) {
  const Snapshot& s = prepareBatch(state, c, qs, margins.demand != nullptr ? "isClearBatch" : "isFreeBatch");
  if (margins.demand != nullptr) Margins::validate(*margins.demand, *s.robot, margins.scale);
  const bool avx2 = batchAvx2Available() && !state.batchBaseline.load(std::memory_order_relaxed);
  c.batch->posedAvx2 = avx2;
  if (avx2) {
    batchForwardKinematics(*s.robot, qs, c.batch->avx2Poses);
  } else {
    batchForwardKinematics(*s.robot, qs, c.batch->baselinePoses);
  }
  const std::uint32_t certified = batchCertifiedLanes(s, state.options.broadPhase, qs, avx2, *c.batch, margins);
  const auto count = std::bitset<kLanes>(certified).count();
  c.stats.queries += count;
  c.stats.batchCertified += count;
  return certified;
}

}  // namespace detail

void World::isFreeBatch(const Eigen::Ref<const Eigen::MatrixXd>& qs, bool* free, Context& context) const {
  Impl& c = *context.impl_;
  const std::uint32_t certified = batchFreeLanes(*state_, c, qs);
  for (int l = 0; l < static_cast<int>(qs.cols()); ++l) {
    free[l] = (certified >> l & 1u) != 0 || isFree(qs.col(l), context);
  }
}

void World::isClearBatch(const Eigen::Ref<const Eigen::MatrixXd>& qs, bool* clear, Context& context,
                         const ClearanceDemand& demand) const {
  Impl& c = *context.impl_;
  BatchMargins margins;
  margins.demand = &demand;
  margins.scale = demand.scale;
  const std::uint32_t certified = batchFreeLanes(*state_, c, qs, margins);
  for (int l = 0; l < static_cast<int>(qs.cols()); ++l) {
    clear[l] = (certified >> l & 1u) != 0 || isClear(qs.col(l), context, demand);
  }
}

}  // namespace deepcheck::checker
