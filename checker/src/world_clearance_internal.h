#pragma once
// Internal to deepcheck::checker: the clearance tests shared by World::isFree, World::isClear
// (world_is_free.cpp) and World::certifyMotion (world_motion.cpp). A pair is "within" its margin
// when its bounding volumes, grown by the margin, meet and the narrow phase finds the robot piece
// grown by the margin overlapping the other piece: its distance is at most the margin (margin 0:
// they overlap).

#include "self_pair_grid.h"
#include "world_queries_internal.h"

#include "deepcheck/robots/format_number.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace deepcheck::checker::detail {

/// One joint of a link geometry's chain in the posed bound (world_motion.cpp): its rate |sigma_k|
/// and, for a revolute joint, the reach d_k + h D_g (0 when prismatic).
struct SpeedTerm {
  double rate = 0.0;
  double reach = 0.0;
  bool prismatic = false;
};

/// The posed bound's drift of the rigid form over a sub-motion, per unit of h: the sum over the
/// chain's joints (from the geometry up to the root) of |sigma_k| (Wbar_k reach_k + P_k)
/// (world_motion.cpp), `turning` the sum of the revolute |sigma_k|. It grows with every reach.
double rigidDrift(const std::vector<SpeedTerm>& terms, double turning);

/// How far each geometry of the robot may move over a sub-motion of a straight motion q + s dq,
/// |s| <= h, around the posed configuration, per unit of h (metres): World::certifyMotion's bound
/// from the pose (world_motion.cpp), tighter than the configuration-free one. Computed for a link
/// geometry when a test first asks for it at the pose: most of a sub-motion's link geometries are
/// decided by the configuration-free bound alone.
class PosedSpeeds {
 public:
  /// A new pose (the context's) of `robot`, for the sub-motion of half length h of `motion` along dq.
  void reset(const Impl& c, const RobotData& robot, const ClearanceDemand& motion, double h,
             const Eigen::VectorXd& dq) {
    c_ = &c;
    robot_ = &robot;
    motion_ = &motion;
    h_ = h;
    dq_ = &dq;
    known_.assign(robot.links.size(), 0);
    value_.resize(robot.links.size());
    axisKnown_.assign(static_cast<std::size_t>(robot.model.numJoints()), 0);
    axis_.resize(static_cast<std::size_t>(robot.model.numJoints()));
  }
  /// S_g for link geometry g (world_motion.cpp).
  double of(int g) {
    if (!known_[static_cast<std::size_t>(g)]) {
      value_[static_cast<std::size_t>(g)] = compute(g);
      known_[static_cast<std::size_t>(g)] = 1;
    }
    return value_[static_cast<std::size_t>(g)];
  }
  const Eigen::VectorXd& dq() const { return *dq_; }

 private:
  double compute(int g);
  /// Joint k's axis in the world at the pose.
  const Eigen::Vector3d& axis(int k);

  const Impl* c_ = nullptr;
  const RobotData* robot_ = nullptr;
  const ClearanceDemand* motion_ = nullptr;
  double h_ = 0.0;
  const Eigen::VectorXd* dq_ = nullptr;
  std::vector<char> known_, axisKnown_;
  std::vector<double> value_;
  std::vector<SpeedTerm> terms_;  ///< compute's scratch, per joint of the chain
  std::vector<Eigen::Vector3d> axis_;
};

/// The clearance each pair must keep in this query (metres): 0 everywhere for isFree, the
/// ClearanceDemand at a scale (isClear: the demand's own; a motion: the half length of a
/// sub-motion, where the posed bound may lower it). Indexed by link geometry (RobotData::links).
class Margins {
 public:
  Margins() = default;
  /// With posed speeds, the pairs are checked for the sub-motion q + s dq, |s| <= scale, around
  /// the configuration: each margin is the smaller of the demand's and the posed bound's, and a
  /// self pair's grid may certify its pair (gridCertifies).
  Margins(const ClearanceDemand& d, const RobotData& robot, double scale, PosedSpeeds* posed = nullptr)
      : d_(&d), links_(&robot.links), scale_(scale), posed_(posed) {
    validate(d, robot, scale);
  }
  /// Throws, naming the value, unless the demand fits the robot and its base clearance and the
  /// scale are finite and >= 0.
  static void validate(const ClearanceDemand& d, const RobotData& robot, double scale) {
    const int numLinks = robot.model.numLinks();
    if (d.link.size() != numLinks || d.self.rows() != numLinks || d.self.cols() != numLinks) {
      throw std::invalid_argument("isClear: the demand has " + std::to_string(d.link.size()) + " link entries and a " +
                                  std::to_string(d.self.rows()) + " x " + std::to_string(d.self.cols()) +
                                  " self matrix; the robot has " + std::to_string(numLinks) + " links");
    }
    checked(d.base);
    checked(scale);
  }
  /// Robot link geometry g against a world body.
  double world(int g) const {
    const double upper = worldUpper(g);
    if (posed_ == nullptr || scale_ == 0.0) return upper;
    return std::min(upper, checked(d_->base + scale_ * posed_->of(g)));
  }
  /// Robot link geometries a and b.
  double self(int a, int b) const {
    const double upper = selfUpper(a, b);
    if (posed_ == nullptr || scale_ == 0.0) return upper;
    return std::min(upper, checked(d_->base + scale_ * (posed_->of(a) + posed_->of(b))));
  }
  /// At least world(g), without the posed bound (cheaper; the same without posed speeds).
  double worldUpper(int g) const {
    if (d_ == nullptr) return 0.0;
    return checked(d_->base + scale_ * d_->link[(*links_)[g].link]);
  }
  /// At least self(a, b), likewise.
  double selfUpper(int a, int b) const {
    if (d_ == nullptr) return 0.0;
    return checked(d_->base + scale_ * d_->self((*links_)[a].link, (*links_)[b].link));
  }
  double scale() const { return scale_; }
  /// The clearance at scale 0 (0 for isFree).
  double base() const { return d_ == nullptr ? 0.0 : d_->base; }
  /// From now on, the base clearance only (scale 0).
  void dropToBase() { scale_ = 0.0; }
  /// True when `grid` certifies its pair apart over the whole sub-motion around q (margin 0:
  /// at q), which is all a motion asks of a pair when the base clearance is 0.
  bool gridCertifies(const SelfPairGrid& grid, const Eigen::VectorXd& q, double margin) const {
    if (margin == 0.0) return grid.certifiedFree(q);
    return posed_ != nullptr && d_->base == 0.0 && grid.certifiedFreeAlong(q, posed_->dq(), scale_);
  }

 private:
  static double checked(double m) {
    if (!(m >= 0.0 && m < std::numeric_limits<double>::infinity())) {
      throw std::invalid_argument("isClear: a demanded clearance is " + robots::formatNumber(m) +
                                  " (must be finite and >= 0)");
    }
    return m;
  }
  const ClearanceDemand* d_ = nullptr;
  const std::vector<LinkGeometry>* links_ = nullptr;
  double scale_ = 0.0;
  PosedSpeeds* posed_ = nullptr;
};

/// `shape` grown by `margin`: the pair overlaps grown exactly when it is within margin.
inline geometry::ConvexShape grown(geometry::ConvexShape shape, double margin) {
  shape.radius += margin;
  return shape;
}

/// What collectNear found.
enum class Clearance {
  Clear,     ///< every pair is farther apart than its margin
  Near,      ///< some pair is within its margin, none within the base clearance
  Collides,  ///< some pair is within the base clearance (margin 0: overlaps)
};

/// The link geometries and self pairs a clearance test must examine: those the batch bound stage
/// found possibly within their margins in one lane (BatchScratch::nearLanes); the others are
/// clear by their bounding volumes.
struct NearFilter {
  const std::vector<std::uint32_t>* nearLanes = nullptr;  ///< per link geometry, then self pair
  int lane = 0;
  std::size_t links = 0;  ///< the number of link geometries: where the self pairs start
  bool link(std::size_t g) const { return ((*nearLanes)[g] >> lane & 1u) != 0; }
  bool self(std::size_t i) const { return link(links + i); }
};

/// pairCover's answers beside a fraction in (0, 1]: the pair is clear over the whole sub-motion, or
/// within the base clearance at its middle.
constexpr double kCoverClear = std::numeric_limits<double>::infinity();
constexpr double kCoverCollides = -1.0;

/// Pair k (as collectNear lists it) at the context's configuration, the middle of a sub-motion of
/// half length h whose margins are `margins`: kCoverClear when it is farther apart than its margin
/// (or a self pair its grid certifies over the sub-motion, Margins::gridCertifies), kCoverCollides
/// when within the base clearance, else the fraction f of h over which it stays clear of the base
/// clearance around the middle: its distance's lower bound above the base clearance over its
/// margin's, as the margin is the base clearance plus h times the pair's speed bound.
double pairCover(Impl& c, const Snapshot& s, const PairKey& k, const Margins& margins);

/// Every pair within its margin at the context's configuration, the middle of a sub-motion,
/// listed in `near` when none is within the base clearance (Near; Clear when none is within its
/// margin), with `cover` the smallest of their fractions (pairCover); Collides at the first pair
/// within the base clearance (the list is then incomplete). With a filter, only its link
/// geometries and self pairs are examined (margins no larger than the batch's).
Clearance collectNear(Impl& c, const Snapshot& s, const Margins& margins, std::vector<PairKey>& near, double& cover,
                      const NearFilter* only = nullptr);

/// isFree (no margins) or isClear at the context's configuration (`s` from prepare): false at the
/// first pair within its margin (remembered in c.lastHit and tried first next time).
bool clearOfAll(Impl& c, const Snapshot& s, const Margins& margins);

}  // namespace deepcheck::checker::detail
