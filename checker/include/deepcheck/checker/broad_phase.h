#pragma once
// The broad phase of a World: which world pieces (scene and obstacle pieces, each bounded by an
// axis-aligned box in the world frame W) may be near a robot link, before their bounding volumes
// and the narrow phase are tried. A World uses its own static AABB tree unless
// WorldOptions::externalBroadPhase supplies another: a PieceTreeFactory that builds a PieceTree
// over the boxes whenever the scene or obstacle pieces change. deepcheck::fcl_reference::
// fclBroadPhase() (deepcheck/fcl_reference/fcl_broad_phase.h) is one, on FCL's dynamic AABB tree.
// A broad phase only chooses candidates: every answer of the World is the same with any of them.
//
// Frames: all boxes are in the world frame W. Metres.

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace deepcheck::checker {

/// An axis-aligned box (empty when lo > hi).
struct Aabb {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());

  bool empty() const { return !(lo.x() <= hi.x()); }
  void extend(const Eigen::Vector3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void extend(const Aabb& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  Eigen::Vector3d center() const { return 0.5 * (lo + hi); }
  /// The box of a sphere.
  static Aabb ofSphere(const Eigen::Vector3d& c, double r) {
    Aabb b;
    b.lo = c.array() - r;
    b.hi = c.array() + r;
    return b;
  }
  /// Euclidean distance from p to the box (0 inside).
  double distance(const Eigen::Vector3d& p) const { return std::sqrt(squaredDistance(p)); }
  /// Signed distance from p to the box: the Euclidean distance outside, minus the distance to the
  /// nearest face inside. signedDistance(c) - r is the exact signed distance between the ball
  /// (c, r) and the box, so a lower bound on the signed distance between anything inside the
  /// ball and anything inside the box, overlapping or not (containment only shrinks a depth).
  /// distance(c) - r is not: inside the box it ignores how deep c lies.
  double signedDistance(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d outside = (lo - p).cwiseMax(p - hi);  // > 0 on an axis whose slab p leaves
    if ((outside.array() > 0.0).any()) return outside.cwiseMax(0.0).norm();
    return outside.maxCoeff();
  }
  /// Its square: what a test against a radius needs (no square root on the query's path).
  double squaredDistance(const Eigen::Vector3d& p) const {
    return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
  }
  bool overlaps(const Aabb& b) const {
    return (lo.array() <= b.hi.array()).all() && (b.lo.array() <= hi.array()).all();
  }
};

/// The broad phases built into the World.
enum class BroadPhase {
  AabbTree,  ///< a static AABB tree over the world pieces' boxes (the default: measured faster)
  None,      ///< every world piece is a candidate (bounding-volume tests only): a baseline to
             ///< measure a broad phase against
};
const char* toString(BroadPhase b);

/// A broad phase over items 0 .. n - 1, each with its box. Read-only once built: its queries may
/// run concurrently from any number of threads.
class PieceTree {
 public:
  virtual ~PieceTree() = default;
  /// Calls visit(item) for every item whose box overlaps `query`, until visit returns true (stop).
  /// Returns true when it was stopped.
  virtual bool visitOverlapping(const Aabb& query, const std::function<bool(int)>& visit) const = 0;
  /// Calls visit(item, lowerBound) for the items whose box is within bound() of the sphere (centre
  /// c, radius r), with lowerBound = box.signedDistance(c) - r; bound() may shrink while visiting
  /// (a best distance so far), and items no nearer than it may then be skipped.
  virtual void visitNear(const Eigen::Vector3d& c, double r, const std::function<double()>& bound,
                         const std::function<void(int, double)>& visit) const = 0;
};

/// Makes the PieceTree of a World's scene pieces and of its obstacle pieces, again after every
/// change of them (WorldOptions::externalBroadPhase). One factory may serve several Worlds: build
/// may be called from several threads at once.
class PieceTreeFactory {
 public:
  virtual ~PieceTreeFactory() = default;
  /// The name World::summary() reports.
  virtual std::string name() const = 0;
  /// The tree over items 0 .. boxes.size() - 1 (boxes is not empty).
  virtual std::shared_ptr<const PieceTree> build(const std::vector<Aabb>& boxes) const = 0;
};

}  // namespace deepcheck::checker
