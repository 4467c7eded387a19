// World::certifyMotion: adaptive dynamic collision checking of a straight motion (Schwarzer,
// Saha, Latombe, IEEE T-RO 21(3), 2005) on the clearance test of isClear.
//
// A sub-motion is a part [t0, t1] of [0, 1], tested at its middle q(tm) with its half length h
// as the scale of the bounds. A pair is clear over a sub-motion when it is farther apart than
// base + h times its bound at q(tm) (isClear's test: its robot piece grown; a self pair may instead
// be certified by its grid over the whole sub-motion). A pair clear over a sub-motion is clear
// over its parts, so only the pairs found within their margins are tested again. Such a pair at a
// distance d (GJK's lower bound) is still clear of the base clearance within (d - base) / (margin
// - base) of h around the middle: the sub-motion's parts left for the next level are the two ends
// outside the smallest of these around its middle (a dyadic bisection would test the middles of
// its halves, in a part already proven). Within the base clearance, the motion collides there. A
// sub-motion with no pair left is certified. Levels are visited in order and each level in
// increasing t: the configurations tested first are spread along the motion, so a collision is met
// early, as with a discrete check in bisection order. Against the halves, on RRTConnect and the
// path simplification on MotionBenchMaker problems (bench/mbm_bench): 15 % less time.
//
// Sub-motions over which some point moves more than tol::kCertifyBelowMove skip the clearance
// test (such a clearance is rare in a robot's workspace, and the test would only fail). These are
// the dyadic levels above the first whose sub-motions move less (2^k sub-motions of length 2^-k
// at level k); the clearance tests start at that first level with every pair. Before them, the
// middles of the levels above it but the last two are tested for collision alone, kRakeWidth
// configurations per call (the rake): a motion through an obstacle is usually refused there, at a
// fraction of a clearance test's cost. The motion's middle goes first by itself when a batch
// follows: two thirds of the motions the rake refuses collide there (RRTConnect's motions on
// MotionBenchMaker problems, bench/motion_bench), and one configuration costs less than a batch
// (certified motion checks 5 % faster on the mean). The last two levels above are left out: their
// middles are three quarters as many as the first level's sub-motions, whose bound stage and
// clearance tests find the same collisions, and most motions a planner asks about are free.
// Leaving out the last level saves about 5 % of the time (RRTConnect and the path simplification
// on MotionBenchMaker problems, bench/mbm_bench), the second last 1 to 2 % more there and 4 to 9 %
// of RRTConnect's motion checks (bench/motion_bench); leaving out a third costs 50 % there.
//
// The first level's sub-motions go kRakeWidth at a time through isFreeBatch's bound stage with
// their margins (batch_bounds.h, BatchMargins: the configuration-free bound, then, where that
// leaves a pair near, the posed one over the eight sub-motions, batch_speeds.h): a sub-motion it
// certifies clear is certified, every other is tested as above.
// Most are certified there, at a fraction of a clearance test's cost. The configurations a batch
// posed are tested with its link poses (prepareLane), without a forward kinematics of their own.
//
// A sub-motion over which every point moves less than tol::kCertifiedResolution that is still
// neither certified nor colliding leaves the motion Unproven, as do more than
// tol::kCertifiedMaxTests tests.

#include "world_clearance_internal.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::checker {

using namespace detail;  // NOLINT: the queries' own internals

namespace {

/// A sub-motion to examine: the part [t0, t1] of the motion, and the pairs to test there (those
/// its parent found within their margins), or every pair (first < 0).
struct SubMotion {
  double t0 = 0.0;
  double t1 = 1.0;
  int first = -1;  ///< into the level's pair list
  int count = 0;
  double middle() const { return 0.5 * (t0 + t1); }
  double half() const { return 0.5 * (t1 - t0); }
};

/// firstClearanceLevel looks no further (its dyadic sub-motions have 64-bit indices); a motion
/// that large is left Unproven by the test budget before anything is tested.
constexpr int kMaxLevel = 62;

/// Configurations tested for collision together by the rake (rakeGroup).
constexpr int kRakeWidth = 8;

/// Smaller groups of rake configurations are tested one by one, which stops at the first
/// collision; the batch's fixed part (the kinematics of eight lanes, a broad-phase query per link
/// for all of them) is spread over nearly full groups only. Most motions a planner asks about rake
/// 1 to 3 configurations, where batching measured the same (RRTConnect's motions on
/// MotionBenchMaker problems: 12.2 us per motion on the mean either way, bench/motion_bench); eight
/// states along a motion take 290 ns each batched against 400 one by one (checker_bench --batch,
/// Panda in the shelf).
constexpr int kRakeBatchMin = 6;

/// The scratch of one thread's motion checks, reused from motion to motion.
struct MotionScratch {
  Eigen::VectorXd q, dq;
  Eigen::MatrixXd rake;                   ///< configurations tested together (columns)
  std::vector<SubMotion> level, next;     ///< the sub-motions of this level and of the next
  std::vector<PairKey> pairs, nextPairs;  ///< their pair lists
  std::vector<PairKey> near;              ///< the pairs one sub-motion found within their margins
  double cover = 0.0;                     ///< ... and the fraction of its half length they stay clear
  std::uint32_t batchClear = 0;           ///< first-level sub-motions the bound stage certified
  PosedSpeeds speeds;                     ///< the posed bound at the current sub-motion
};

}  // namespace

namespace detail {

/// For link geometry g, S_g with h S_g bounding how far its points move over the sub-motion
/// q + s dq, |s| <= h, around the posed q: the smaller of two bounds on a point's speed there.
///
/// Per joint: a revolute joint k (rate sigma_k = dq_k m_k) moves a point p at |sigma_k|
/// dist(p, axis_k) per unit of s; at the pose dist(p, axis_k) <= d_k = |(c_g - o_k) x a_k| + r_g
/// (c_g, r_g: g's bounding sphere), and over the sub-motion it changes only by the motion of the
/// joints below k, at most h D_g (the configuration-free bound of the whole motion). A prismatic
/// joint moves every point below it at |sigma_k|.
///
/// Rigid: at the pose the link moves as a rigid body, p at V_c + W x (p - c_g) (V_c the centre's
/// velocity, W = sum sigma_k a_k), at most |V_c| + |W| r_g: the joints' contributions partly
/// cancel, which the per-joint sum ignores. Over the sub-motion joint k's contribution
/// sigma_k a_k x (p - o_k), seen from the link before it, turns with that link (by at most
/// h Wbar_k, Wbar_k the sum of |sigma_j| above k) and changes by p's motion relative to it (at most
/// h P_k, P_k the per-joint bound of the joints from k down): it moves by at most
/// h |sigma_k| (Wbar_k (d_k + h D_g) + P_k) (a prismatic joint's only turns: h |sigma_k| Wbar_k).
double PosedSpeeds::compute(int g) {
  const RobotData& robot = *robot_;
  const LinkGeometry& lg = robot.links[static_cast<std::size_t>(g)];
  const Eigen::Vector3d& center = c_->linkCenter[static_cast<std::size_t>(g)];
  const std::vector<int>& chain = robot.chains[static_cast<std::size_t>(g)];
  const double drift = h_ * motion_->link[lg.link];
  terms_.resize(chain.size());
  double perJoint = 0.0;
  double turning = 0.0;  // sum of the revolute |sigma_k|
  Eigen::Vector3d centerVelocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < chain.size(); ++i) {
    const robots::Joint& joint = robot.model.joint(chain[i]);
    const double sigma = (*dq_)[joint.variable] * joint.multiplier;
    const bool prismatic = joint.type == robots::JointType::Prismatic;
    terms_[i] = SpeedTerm{std::abs(sigma), 0.0, prismatic};
    if (sigma == 0.0) continue;
    const Eigen::Vector3d& a = axis(chain[i]);
    if (prismatic) {
      perJoint += std::abs(sigma);
      centerVelocity += sigma * a;
      continue;
    }
    const Eigen::Vector3d arm = center - c_->X_WL[joint.childLink].translation();
    terms_[i].reach = arm.cross(a).norm() + lg.radius + drift;
    perJoint += std::abs(sigma) * terms_[i].reach;
    centerVelocity += sigma * a.cross(arm);
    angular += sigma * a;
    turning += std::abs(sigma);
  }
  const double rigid = centerVelocity.norm() + angular.norm() * lg.radius + h_ * rigidDrift(terms_, turning);
  return std::min(perJoint, rigid);
}

double rigidDrift(const std::vector<SpeedTerm>& terms, double turning) {
  double from = 0.0;    // P_k: the per-joint bound of the joints from k down
  double turned = 0.0;  // the revolute |sigma_j| from k down; Wbar_k = turning - turned
  double sum = 0.0;
  for (const SpeedTerm& t : terms) {
    if (t.rate == 0.0) continue;
    if (t.prismatic) {
      from += t.rate;
      sum += t.rate * (turning - turned);
      continue;
    }
    from += t.rate * t.reach;
    turned += t.rate;
    sum += t.rate * ((turning - turned) * t.reach + from);
  }
  return sum;
}

const Eigen::Vector3d& PosedSpeeds::axis(int k) {
  const auto j = static_cast<std::size_t>(k);
  if (!axisKnown_[j]) {
    const robots::Joint& joint = robot_->model.joint(k);
    axis_[j] = c_->X_WL[joint.childLink].linear() * joint.axis;
    axisKnown_[j] = 1;
  }
  return axis_[j];
}

}  // namespace detail

namespace {

void checkSizes(int n, const Eigen::Ref<const Eigen::VectorXd>& q1, const Eigen::Ref<const Eigen::VectorXd>& dq) {
  if (q1.size() != n || dq.size() != n) {
    throw std::invalid_argument("certifyMotion: a motion from " + std::to_string(q1.size()) + " values by " +
                                std::to_string(dq.size()) + " for a robot of " + std::to_string(n) + " variables");
  }
}

/// The most any point moves over the whole motion (metres).
double largestMove(const ClearanceDemand& motion) {
  const double link = motion.link.size() > 0 ? motion.link.maxCoeff() : 0.0;
  const double self = motion.self.size() > 0 ? motion.self.maxCoeff() : 0.0;
  return std::max(link, self);
}

enum class Outcome { Certified, Split, Collides, Unproven };

/// Tests the configurations (columns of qs) not set in `known` for collision at the motion's base
/// clearance, one after the other: `clear` false at the first that collides. With `batched`, qs
/// is the batch batchFreeLanes posed last, whose poses are used. Returns false when the world
/// changed since `held` (set when null) was taken.
bool rakeOneByOne(const WorldState& state, Impl& c, const Eigen::Ref<const Eigen::MatrixXd>& qs, std::uint32_t known,
                  bool batched, const ClearanceDemand& motion, bool& clear, std::shared_ptr<const Snapshot>& held) {
  clear = true;
  for (Eigen::Index i = 0; i < qs.cols() && clear; ++i) {
    if ((known >> i & 1u) != 0) continue;
    const Snapshot& s = batched ? prepareLane(state, c, qs.col(i), static_cast<int>(i)) : prepare(state, c, qs.col(i));
    if (!held) held = c.snap;
    if (c.snap != held) return false;
    clear = clearOfAll(c, s, Margins(motion, *s.robot, 0.0));
  }
  return true;
}

/// The rake's test of up to kRakeWidth configurations: groups of at least kRakeBatchMin first
/// through isFreeBatch's bound stage (it decides isFree, so only at a base clearance of 0), the
/// configurations it cannot certify free then one by one.
bool rakeGroup(const WorldState& state, Impl& c, const Eigen::Ref<const Eigen::MatrixXd>& qs,
               const ClearanceDemand& motion, bool& clear, std::shared_ptr<const Snapshot>& held) {
  std::uint32_t free = 0;
  const bool batched = motion.base == 0.0 && qs.cols() >= kRakeBatchMin;
  if (batched) {
    free = batchFreeLanes(state, c, qs);
    if (!held) held = c.snap;
    if (c.snap != held) return false;
  }
  return rakeOneByOne(state, c, qs, free, batched, motion, clear, held);
}

/// Examines one sub-motion (middle q(tm), half length h) for clearance at the context's current
/// pose (a first-level one only what `only` names); on Split, w.near holds the pairs its halves
/// must test.
Outcome examine(Impl& c, const Snapshot& s, const ClearanceDemand& motion, double h, double move, const SubMotion& sub,
                MotionScratch& w, const NearFilter* only) {
  const RobotData& robot = *s.robot;
  w.speeds.reset(c, robot, motion, h, w.dq);
  Margins margins(motion, robot, h, &w.speeds);
  Clearance found = Clearance::Clear;
  if (sub.first < 0) {
    found = collectNear(c, s, margins, w.near, w.cover, only);
  } else {
    // The pairs the parent found near; the others are clear over the whole parent.
    w.near.clear();
    w.cover = kCoverClear;
    for (int i = sub.first; i < sub.first + sub.count; ++i) {
      const PairKey& k = w.pairs[static_cast<std::size_t>(i)];
      const double f = pairCover(c, s, k, margins);
      if (f == kCoverCollides) return Outcome::Collides;
      if (f == kCoverClear) continue;
      w.cover = std::min(w.cover, f);
      w.near.push_back(k);
    }
    found = w.near.empty() ? Clearance::Clear : Clearance::Near;
  }
  if (found == Clearance::Collides) return Outcome::Collides;
  if (found == Clearance::Clear) return Outcome::Certified;
  if (h * move < tol::kCertifiedResolution) return Outcome::Unproven;
  return Outcome::Split;
}

/// Where the middle of sub-motion `index` of level k lies along the motion: 2^-k (index + 1/2).
double middleOf(int k, std::int64_t index) { return std::ldexp(static_cast<double>(index) + 0.5, -k); }

/// Queues for the next level the parts of `sub` that `examine` left uncovered, on either side of
/// the part around its middle where its near pairs stay clear (w.cover of its half length), with
/// those pairs.
void split(const SubMotion& sub, MotionScratch& w) {
  SubMotion part;
  part.first = static_cast<int>(w.nextPairs.size());
  part.count = static_cast<int>(w.near.size());
  w.nextPairs.insert(w.nextPairs.end(), w.near.begin(), w.near.end());
  const double covered = w.cover * sub.half();
  part.t0 = sub.t0;
  part.t1 = std::max(sub.t0, sub.middle() - covered);
  w.next.push_back(part);
  part.t0 = std::min(sub.t1, sub.middle() + covered);
  part.t1 = sub.t1;
  w.next.push_back(part);
}

/// The first level whose sub-motions are tested for clearance: above it every sub-motion moves
/// some point more than tol::kCertifyBelowMove and is only tested for collision at its middle
/// (then split), whatever that test finds.
int firstClearanceLevel(double move) {
  int k = 0;
  while (k < kMaxLevel && std::ldexp(0.5, -k) * move > tol::kCertifyBelowMove) ++k;
  return k;
}

/// Tests the middles of the levels above `level` (level by level and in increasing t within a
/// level) for collision at the base clearance, kRakeWidth at a time.
/// Collides at the first group with a colliding configuration, else Certified (nothing found).
/// False when the world changed under it.
bool rakeAbove(int level, const WorldState& state, Impl& c, const Eigen::Ref<const Eigen::VectorXd>& q1,
               const ClearanceDemand& motion, MotionScratch& w, MotionCertificate& out,
               std::shared_ptr<const Snapshot>& held) {
  const std::int64_t needed = (std::int64_t{1} << level) - 1;
  w.rake.resize(q1.size(), kRakeWidth);
  int lanes = 0;
  int k = 0;
  std::int64_t i = 0;  // the n-th middle: index i of level k
  for (std::int64_t n = 0; n < needed; ++n) {
    w.rake.col(lanes++) = q1 + middleOf(k, i) * w.dq;
    if (++i == (std::int64_t{1} << k)) {
      ++k;
      i = 0;
    }
    // The motion's middle by itself when a batch follows (see the top of this file).
    const int width = n == 0 && needed > kRakeBatchMin ? 1 : kRakeWidth;
    if (lanes < width && n + 1 < needed) continue;
    out.configurations += lanes;
    bool clear = true;
    if (!rakeGroup(state, c, w.rake.leftCols(lanes), motion, clear, held)) return false;
    lanes = 0;
    if (!clear) {
      out.verdict = MotionCertificate::Verdict::Collides;
      return true;
    }
  }
  return true;
}

/// The bound stage with the sub-motions' margins (BatchMargins) on the middles of the sub-motions
/// w.level[at, at + kRakeWidth) of the first level, k: w.batchClear gets those it certifies clear
/// (bit l: w.level[at + l]). False when the world changed since `held`.
bool batchFirstLevel(const WorldState& state, Impl& c, const Eigen::Ref<const Eigen::VectorXd>& q1,
                     const ClearanceDemand& motion, int k, std::size_t at, MotionScratch& w,
                     std::shared_ptr<const Snapshot>& held) {
  const auto lanes = static_cast<int>(std::min<std::size_t>(kRakeWidth, w.level.size() - at));
  w.rake.resize(q1.size(), kRakeWidth);
  for (int l = 0; l < lanes; ++l) w.rake.col(l) = q1 + w.level[at + static_cast<std::size_t>(l)].middle() * w.dq;
  BatchMargins margins;
  margins.demand = &motion;
  margins.scale = std::ldexp(0.5, -k);
  margins.dq = &w.dq;
  w.batchClear = batchFreeLanes(state, c, w.rake.leftCols(lanes), margins);
  if (!held) held = c.snap;
  return c.snap == held;
}

/// One certification; false when the world changed under it (its pair lists are then void).
bool certifyOnce(const WorldState& state, Impl& c, const Eigen::Ref<const Eigen::VectorXd>& q1,
                 const ClearanceDemand& motion, MotionScratch& w, MotionCertificate& out) {
  const double move = largestMove(motion);
  out = MotionCertificate{};
  out.verdict = MotionCertificate::Verdict::Certified;
  std::shared_ptr<const Snapshot> held;
  const int first = firstClearanceLevel(move);
  // The first level alone would test more configurations than allowed (a robot moving hundreds of
  // metres): nothing is tested. Below it, every level at least halves its sub-motions, so the
  // levels end (at kCertifiedResolution) long before the 64-bit indices would.
  if ((std::int64_t{1} << first) > tol::kCertifiedMaxTests) {
    out.verdict = MotionCertificate::Verdict::Unproven;
    return true;
  }
  if (!rakeAbove(std::max(0, first - 2), state, c, q1, motion, w, out, held)) return false;
  if (out.verdict != MotionCertificate::Verdict::Certified) return true;
  w.level.clear();
  for (std::int64_t i = 0; i < (std::int64_t{1} << first); ++i) {
    w.level.push_back(
        SubMotion{std::ldexp(static_cast<double>(i), -first), std::ldexp(static_cast<double>(i + 1), -first)});
  }
  w.pairs.clear();
  for (int k = first; !w.level.empty(); ++k) {
    w.next.clear();
    w.nextPairs.clear();
    for (std::size_t at = 0; at < w.level.size(); ++at) {
      const SubMotion& sub = w.level[at];
      // Only the first level's sub-motions test every pair.
      if (sub.first < 0 && at % kRakeWidth == 0 && !batchFirstLevel(state, c, q1, motion, k, at, w, held)) {
        return false;
      }
      if (sub.first < 0 && (w.batchClear >> (at % kRakeWidth) & 1u) != 0) {
        if (++out.configurations <= tol::kCertifiedMaxTests) continue;
        out.verdict = MotionCertificate::Verdict::Unproven;
        return true;
      }
      w.q = q1 + sub.middle() * w.dq;
      ++out.configurations;
      // A first-level sub-motion's middle is a lane of the batch just posed.
      const Snapshot& s =
          sub.first < 0 ? prepareLane(state, c, w.q, static_cast<int>(at % kRakeWidth)) : prepare(state, c, w.q);
      if (!held) held = c.snap;
      if (c.snap != held) return false;
      // A first-level sub-motion examines only what the bound stage could not clear.
      NearFilter batched;
      if (sub.first < 0)
        batched = NearFilter{&c.batch->nearLanes, static_cast<int>(at % kRakeWidth), s.robot->links.size()};
      const Outcome o = examine(c, s, motion, sub.half(), move, sub, w, sub.first < 0 ? &batched : nullptr);
      if (o == Outcome::Collides || o == Outcome::Unproven || out.configurations > tol::kCertifiedMaxTests) {
        out.verdict =
            o == Outcome::Collides ? MotionCertificate::Verdict::Collides : MotionCertificate::Verdict::Unproven;
        return true;
      }
      if (o == Outcome::Split) split(sub, w);
    }
    std::swap(w.level, w.next);
    std::swap(w.pairs, w.nextPairs);
  }
  return true;
}

}  // namespace

MotionCertificate World::certifyMotion(const Eigen::Ref<const Eigen::VectorXd>& q1,
                                       const Eigen::Ref<const Eigen::VectorXd>& dq, const ClearanceDemand& motion,
                                       Context& context) const {
  Impl& c = *context.impl_;
  checkSizes(robot().numVariables(), q1, dq);
  thread_local MotionScratch w;
  w.dq = dq;
  MotionCertificate out;
  // A change of the world during the check (another thread adding an obstacle) starts it again.
  while (!certifyOnce(*state_, c, q1, motion, w, out)) {
  }
  return out;
}

}  // namespace deepcheck::checker
