// World::certifyMotion: adaptive dynamic collision checking of a straight motion (Schwarzer,
// Saha, Latombe, IEEE T-RO 21(3), 2005) on the clearance test of isClear.
//
// The sub-motions are the dyadic intervals of [0, 1]: at level k the 2^k intervals of length
// 2^-k, each tested at its middle q(tm) with its half length h = 2^-(k+1) as the scale of the
// bounds. A sub-motion is certified when every pair is farther apart than base + h times its
// bound there (isClear: the robot's pieces grown; a self pair may instead be certified by its
// grid over the whole sub-motion). Otherwise q(tm) itself is tested (isFree, or isClear at the
// base clearance): a pair within the base there means the motion collides; if not, the two
// halves are examined at the next level. Levels are visited in order and each level in
// increasing t: the configurations tested first are spread along the motion, so a collision is
// met early, as with a discrete check in bisection order.
//
// Sub-motions over which some point moves more than tol::kCertifyBelowMove skip the clearance
// test (such a clearance is rare in a robot's workspace, and the test would only fail): there
// q(tm) is tested for collision alone. A sub-motion over which every point moves less than
// tol::kCertifiedResolution that is still neither certified nor colliding leaves the motion
// Unproven, as do more than tol::kCertifiedMaxTests tests.

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

/// The scratch of one thread's motion checks, reused from motion to motion.
struct MotionScratch {
  Eigen::VectorXd q, dq;
  std::vector<std::int64_t> level, next;  ///< sub-motions (index within their level) to examine
  const RobotData* chainsOf = nullptr;    ///< the robot data `chains` was made for
  std::vector<std::vector<int>> chains;   ///< per link geometry, its moving joints up to the root
  std::vector<double> speed;              ///< per link geometry, its posed bound (PosedMotion)
};

/// The moving joints between each link geometry and the root.
void buildChains(const RobotData& robot, MotionScratch& w) {
  w.chains.assign(robot.links.size(), {});
  for (std::size_t g = 0; g < robot.links.size(); ++g) {
    for (int l = robot.links[g].link; robot.model.link(l).parentJoint >= 0; l = robot.model.link(l).parentLink) {
      const int j = robot.model.link(l).parentJoint;
      if (robot.model.joint(j).moves() && robot.model.joint(j).variable >= 0) w.chains[g].push_back(j);
    }
  }
  w.chainsOf = &robot;
}

/// For each link geometry g, S_g with h S_g bounding how far its points move over the sub-motion
/// q + s dq, |s| <= h, around the posed q. A revolute joint k moves a point p at
/// |dq_k m_k| dist(p, axis_k) per unit of s; at the pose dist(p, axis_k) <= |(c_g - o_k) x a_k| +
/// r_g (c_g, r_g: g's bounding sphere), and over the sub-motion it changes only by the motion of
/// the joints below k, at most h D_g (the configuration-free bound of the whole motion). A
/// prismatic joint moves every point below it at |dq_k m_k|.
void posedSpeeds(const Impl& c, const RobotData& robot, const ClearanceDemand& motion, double h, MotionScratch& w) {
  w.speed.resize(robot.links.size());
  for (std::size_t g = 0; g < robot.links.size(); ++g) {
    const LinkGeometry& lg = robot.links[g];
    const Eigen::Vector3d& center = c.linkCenter[g];
    const double drift = lg.radius + h * motion.link[lg.link];
    double sum = 0.0;
    for (const int k : w.chains[g]) {
      const robots::Joint& joint = robot.model.joint(k);
      const double rate = std::abs(w.dq[joint.variable] * joint.multiplier);
      if (rate == 0.0) continue;
      if (joint.type == robots::JointType::Prismatic) {
        sum += rate;
        continue;
      }
      const Eigen::Isometry3d& X_WJ = c.X_WL[joint.childLink];
      const Eigen::Vector3d axis = X_WJ.linear() * joint.axis;
      sum += rate * ((center - X_WJ.translation()).cross(axis).norm() + drift);
    }
    w.speed[g] = sum;
  }
}

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

/// Examines one sub-motion (middle q(tm), half length h) at the context's current pose.
Outcome examine(Impl& c, const Snapshot& s, const ClearanceDemand& motion, double h, double move, MotionScratch& w) {
  const RobotData& robot = *s.robot;
  const bool certify = h * move <= tol::kCertifyBelowMove;
  if (certify) {
    if (w.chainsOf != &robot) buildChains(robot, w);
    posedSpeeds(c, robot, motion, h, w);
  }
  Margins margins(motion, robot, certify ? h : 0.0, certify ? PosedMotion{&w.dq, &w.speed} : PosedMotion{});
  const Clearance found = classify(c, s, margins);
  if (found == Clearance::Collides) return Outcome::Collides;
  // Clear at scale 0 only says q(tm) is valid.
  if (found == Clearance::Clear && certify) return Outcome::Certified;
  if (h * move < tol::kCertifiedResolution) return Outcome::Unproven;
  return Outcome::Split;
}

}  // namespace

MotionCertificate World::certifyMotion(const Eigen::Ref<const Eigen::VectorXd>& q1,
                                       const Eigen::Ref<const Eigen::VectorXd>& dq, const ClearanceDemand& motion,
                                       Context& context) const {
  Impl& c = *context.impl_;
  checkSizes(robot().numVariables(), q1, dq);
  thread_local MotionScratch w;
  w.dq = dq;
  const double move = largestMove(motion);
  MotionCertificate out;
  out.verdict = MotionCertificate::Verdict::Certified;
  w.level.assign(1, 0);
  for (int k = 0; !w.level.empty(); ++k) {
    const double h = 0.5 / static_cast<double>(std::int64_t{1} << k);
    w.next.clear();
    for (const std::int64_t j : w.level) {
      w.q = q1 + (2.0 * h * (static_cast<double>(j) + 0.5)) * dq;
      ++out.configurations;
      const Snapshot& s = prepare(*state_, c, w.q);
      const Outcome o = examine(c, s, motion, h, move, w);
      if (o == Outcome::Collides || o == Outcome::Unproven || out.configurations > tol::kCertifiedMaxTests) {
        out.verdict = o == Outcome::Collides ? MotionCertificate::Verdict::Collides
                                             : MotionCertificate::Verdict::Unproven;
        return out;
      }
      if (o == Outcome::Split) {
        w.next.push_back(2 * j);
        w.next.push_back(2 * j + 1);
      }
    }
    std::swap(w.level, w.next);
  }
  return out;
}

}  // namespace deepcheck::checker
