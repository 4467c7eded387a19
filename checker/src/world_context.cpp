// The per-thread query Context of a World: its state, its refresh when the world changed, the
// preparation both queries share, and the calling thread's own contexts.
//
// Both queries share one preparation step: refresh the context when the world changed (one
// atomic load otherwise), forward kinematics into the context's scratch poses, and the world
// centres of the links' bounding spheres. Robot pieces are posed lazily (a stamp per piece), so a
// query only poses the pieces whose link came near something.
//
// Bounding volumes: a robot piece has a sphere (centre in its link frame); a robot link the sphere
// around its pieces' spheres; a world piece a box (of its vertices, grown by its radius) and a
// sphere. A pair reaches the narrow phase only when every bounding test passes.

#include "world_queries_internal.h"

#include "deepcheck/robots/kinematics.h"

#include <algorithm>
#include <stdexcept>
#include <unordered_map>

namespace deepcheck::checker {

using namespace detail;  // NOLINT: the queries' own internals

World::Context::Context(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
World::Context::Context(Context&&) noexcept = default;
World::Context& World::Context::operator=(Context&&) noexcept = default;
World::Context::~Context() = default;
const QueryStats& World::Context::stats() const { return impl_->stats; }
void World::Context::resetStats() { impl_->stats = QueryStats{}; }
void World::Context::resetCaches() {
  for (auto* v : {&impl_->selfCaches, &impl_->sceneCaches, &impl_->obstacleCaches}) {
    for (geometry::PairCache& c : *v) c.reset();
  }
  impl_->lastHit = PairKey{};
  impl_->lastClosest = PairKey{};
}

World::Context World::makeContext() const {
  auto impl = std::make_unique<Context::Impl>();
  impl->state = state_.get();
  impl->worldUid = state_->uid;
  return Context(std::move(impl));
}

namespace detail {

/// Brings the context up to the world's current snapshot, keeping what warm starts it can.
void refresh(Impl& c) {
  std::shared_ptr<const Snapshot> next;
  std::uint64_t generation;
  {
    std::lock_guard<std::mutex> lock(c.state->mutex);
    next = c.state->current;
    generation = c.state->generation.load(std::memory_order_relaxed);
  }
  // Attaching or detaching an object changes the robot's pieces: then nothing is kept.
  const Snapshot* prev = c.snap != nullptr && c.snap->robot == next->robot ? c.snap.get() : nullptr;
  const RobotData& robot = *next->robot;
  const std::size_t nRobot = robot.pieces.size();
  if (prev == nullptr) {
    c.X_WL.assign(robot.model.numLinks(), Eigen::Isometry3d::Identity());
    c.X_WP.assign(nRobot, Eigen::Isometry3d::Identity());
    c.pieceCenter.assign(nRobot, Eigen::Vector3d::Zero());
    c.pieceObb.assign(nRobot, Obb{});
    c.pieceStamp.assign(nRobot, 0);
    c.transformStamp.assign(nRobot, 0);
    c.linkCenter.assign(robot.links.size(), Eigen::Vector3d::Zero());
    c.J_A.resize(3, robot.model.numVariables());
    c.J_B.resize(3, robot.model.numVariables());
  }
  // Self caches: kept when the pair list is unchanged.
  bool sameSelf = prev != nullptr && prev->selfPairs.size() == next->selfPairs.size();
  for (std::size_t i = 0; sameSelf && i < next->selfPairs.size(); ++i) {
    sameSelf = prev->selfPairs[i].a == next->selfPairs[i].a && prev->selfPairs[i].b == next->selfPairs[i].b;
  }
  if (!sameSelf) {
    c.selfCaches.assign(next->selfCacheSize, geometry::PairCache{});
    c.selfAxes.assign(next->selfCacheSize, 0);
  }
  if (prev == nullptr || prev->scenePieces != next->scenePieces) {
    c.sceneCaches.assign(nRobot * next->scenePieces->pieces.size(), geometry::PairCache{});
    c.sceneAxes.assign(c.sceneCaches.size(), 0);
  }
  if (prev == nullptr || prev->obstaclePieces != next->obstaclePieces) {
    // Obstacle pieces are renumbered by every change; carry the caches over by piece uid.
    const std::vector<WorldPiece>& now = next->obstaclePieces->pieces;
    std::vector<geometry::PairCache> caches(nRobot * now.size());
    if (prev != nullptr) {
      const std::vector<WorldPiece>& before = prev->obstaclePieces->pieces;
      std::unordered_map<std::uint64_t, std::size_t> old;
      for (std::size_t j = 0; j < before.size(); ++j) old.emplace(before[j].uid, j);
      for (std::size_t j = 0; j < now.size(); ++j) {
        auto it = old.find(now[j].uid);
        if (it == old.end()) continue;
        for (std::size_t i = 0; i < nRobot; ++i) {
          caches[i * now.size() + j] = c.obstacleCaches[i * before.size() + it->second];
        }
      }
    }
    c.obstacleCaches = std::move(caches);
    c.obstacleAxes.assign(c.obstacleCaches.size(), 0);
  }
  c.lastHit = PairKey{};
  c.lastClosest = PairKey{};
  c.snap = std::move(next);
  c.generation = generation;
}

const Snapshot& current(const WorldState& state, Impl& c) {
  if (c.worldUid != state.uid) {
    throw std::invalid_argument("World: the Context was made by another world");
  }
  if (c.generation != state.generation.load(std::memory_order_acquire)) refresh(c);
  return *c.snap;
}

namespace {

/// What prepare does once the link poses c.X_WL are those of q: coherence, link sphere centres, a
/// new stamp for piece poses.
void posed(const RobotData& robot, Impl& c, const Eigen::Ref<const Eigen::VectorXd>& q) {
  c.coherent = c.lastQ.size() == q.size() && (q - c.lastQ).cwiseAbs().maxCoeff() <= tol::kWarmStartMaxStep;
  c.lastQ = q;
  for (std::size_t g = 0; g < robot.links.size(); ++g) {
    c.linkCenter[g] = c.X_WL[robot.links[g].link] * robot.links[g].center_L;
  }
  if (++c.stamp == 0) {
    std::fill(c.pieceStamp.begin(), c.pieceStamp.end(), 0);
    std::fill(c.transformStamp.begin(), c.transformStamp.end(), 0);
    c.stamp = 1;
  }
  ++c.stats.queries;
}

/// Lane l of the batch poses into X_WL.
template <class L>
void lanePoses(const BatchPosesT<L>& poses, int l, std::vector<Eigen::Isometry3d>& X_WL) {
  X_WL.resize(poses.links.size());
  for (std::size_t k = 0; k < poses.links.size(); ++k) {
    const LanePoseT<L>& X = poses.links[k];
    Eigen::Isometry3d& out = X_WL[k];
    for (int i = 0; i < 9; ++i) out.linear()(i / 3, i % 3) = X.R[i][l];
    for (int i = 0; i < 3; ++i) out.translation()[i] = X.t[i][l];
    out.makeAffine();
  }
}

}  // namespace

const Snapshot& prepare(const WorldState& state, Impl& c, const Eigen::Ref<const Eigen::VectorXd>& q) {
  const Snapshot& s = current(state, c);
  robots::forwardKinematics(s.robot->model, q, c.X_WL);  // checks q (size, finite), naming the variable
  posed(*s.robot, c, q);
  return s;
}

const Snapshot& prepareLane(const WorldState& state, Impl& c, const Eigen::Ref<const Eigen::VectorXd>& q, int lane) {
  const BatchScratch& b = *c.batch;
  const Snapshot* posedIn = c.snap.get();  // the batch's poses are of this snapshot's robot
  const Snapshot& s = current(state, c);
  const bool finite = b.posedAvx2 ? b.avx2Poses.finite[lane] : b.baselinePoses.finite[lane];
  if (!finite || &s != posedIn) return prepare(state, c, q);
  if (b.posedAvx2) {
    lanePoses(b.avx2Poses, lane, c.X_WL);
  } else {
    lanePoses(b.baselinePoses, lane, c.X_WL);
  }
  posed(*s.robot, c, q);
  return s;
}

}  // namespace detail

// --- the thread's own contexts ---------------------------------------------------------------

namespace {

/// The calling thread's context for `state`'s world: a thread_local table keyed by the world's
/// uid (never reused), with entries of dead worlds swept as the table grows.
World::Context& threadContext(const World& world, const std::shared_ptr<WorldState>& state) {
  struct Entry {
    std::weak_ptr<WorldState> state;
    std::unique_ptr<World::Context> context;
  };
  thread_local std::unordered_map<std::uint64_t, Entry> table;
  thread_local std::uint64_t lastUid = 0;
  thread_local World::Context* last = nullptr;
  if (lastUid == state->uid) return *last;
  auto it = table.find(state->uid);
  if (it == table.end()) {
    if (table.size() >= 4) {
      for (auto e = table.begin(); e != table.end();) {
        e = e->second.state.expired() ? table.erase(e) : std::next(e);
      }
    }
    it = table.emplace(state->uid, Entry{state, std::make_unique<World::Context>(world.makeContext())}).first;
  }
  lastUid = state->uid;
  last = it->second.context.get();
  return *last;
}

}  // namespace

bool World::isFree(const Eigen::Ref<const Eigen::VectorXd>& q) const { return isFree(q, threadContext(*this, state_)); }

void World::isFreeBatch(const Eigen::Ref<const Eigen::MatrixXd>& qs, bool* free) const {
  isFreeBatch(qs, free, threadContext(*this, state_));
}

bool World::isClear(const Eigen::Ref<const Eigen::VectorXd>& q, const ClearanceDemand& demand) const {
  return isClear(q, threadContext(*this, state_), demand);
}

void World::isClearBatch(const Eigen::Ref<const Eigen::MatrixXd>& qs, bool* clear,
                         const ClearanceDemand& demand) const {
  isClearBatch(qs, clear, threadContext(*this, state_), demand);
}

MotionCertificate World::certifyMotion(const Eigen::Ref<const Eigen::VectorXd>& q1,
                                       const Eigen::Ref<const Eigen::VectorXd>& dq,
                                       const ClearanceDemand& motion) const {
  return certifyMotion(q1, dq, motion, threadContext(*this, state_));
}

DistanceResult World::signedDistance(const Eigen::Ref<const Eigen::VectorXd>& q, const DistanceOptions& options) const {
  return signedDistance(q, threadContext(*this, state_), options);
}

}  // namespace deepcheck::checker
