#pragma once
// Certified-free grids for the self pairs whose relative pose depends on one or two variables.
//
// Two robot links U and D, D below U in the tree, with only revolute (or continuous) and fixed
// joints between them: the pose of D in U's frame depends only on the variables of those joints.
// When there are one or two such variables (the Panda's link5 against link7 and against the hand:
// joints 6 and 7), the box of their limits is cut into cells, and a cell is marked FREE at
// construction when every piece pair of (U, D) is certified apart over the whole cell:
//
//     d(centre) > delta + gap,
//
// d the GJK distance of the two pieces (radii included) with the variables at the cell's centre,
// delta a bound on how far any point of a piece of D can move relative to U while the variables
// stay in the cell,
//
//     delta = sum over the moving joints k between U and D of |multiplier_k| h_k rho_k,
//     rho_k = sum of |X_PJ.translation| of the joints below k down to D + max |p_D| over D's pieces,
//
// h_k the cell's half-width in joint k's variable, and gap tol::kCertifiedGapRelative times the
// pieces' size plus GJK's own relative accuracy. Why it holds: a rotation by t about an axis moves
// a point at distance r from the axis by at most r t; joint k's child origin lies on its axis, and
// by the triangle inequality every point of D is within rho_k of it in every configuration
// (rotations below k keep lengths, translations add up). Moving from the centre one variable at
// a time, the displacements add up to at most delta, and a distance shrinks by at most the
// displacement. So in a FREE cell the narrow phase would find every piece pair apart: isFree skips
// the pair. Cells that are not certified (pieces nearer than delta, or in contact) and
// configurations outside the limits go through the usual tests: the grid never changes an
// answer, only its cost.
//
// Grid size: cells are split between the two variables so that each contributes about the same
// to delta, up to tol::kGridMaxCells cells and tol::kGridMaxPiecePairTests piece-pair evaluations
// (bounding spheres first, GJK for the pairs within reach), which bounds construction time. On
// the Panda, 128 x 128 cells give delta of 5 to 10 mm.
//
// Cache: build reads the cells' flags from the on-disk cache when it holds an entry for the
// pair's key (self_pair_grid_cache.h), re-certifies tol::kGridCacheSpotChecks of its FREE cells
// and uses it only if all pass; otherwise it certifies every cell and stores the result. The
// flags, hence every answer, are the same with and without the cache.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <iosfwd>
#include <map>
#include <memory>
#include <vector>

namespace deepcheck::robots {
class RobotModel;
}

namespace deepcheck::checker::detail {

struct RobotData;
struct LinkGeometry;
class SelfPairGridCache;

class SelfPairGrid {
 public:
  /// The grid of the self pair of link geometries (a, b) (indices into RobotData::links), or null
  /// when the pair does not qualify (not on one branch, a prismatic joint or more than two
  /// variables between them, degenerate limits, or too many piece pairs for the budget).
  /// Through `cache` when given and enabled; a corrupt or rejected entry is noted in one line on
  /// `notes` (when not null) and rebuilt.
  static std::shared_ptr<const SelfPairGrid> build(const RobotData& robot, int a, int b,
                                                   const SelfPairGridCache* cache = nullptr,
                                                   std::ostream* notes = nullptr);

  /// True when q lies in a cell certified free (q must have the robot's size).
  bool certifiedFree(const Eigen::VectorXd& q) const {
    int index = 0;
    for (int d = 0; d < dims_; ++d) {
      const double x = (q[variable_[d]] - lower_[d]) * inverseStep_[d];
      if (!(x >= 0.0 && x < cells_[d])) return false;  // outside the limits (or NaN)
      index = index * cells_[d] + static_cast<int>(x);
    }
    return free_[index] != 0;
  }

  /// True when every configuration q + s dq, |s| <= h, lies in a cell certified free: the pair
  /// is then apart all along that motion (q must have the robot's size).
  bool certifiedFreeAlong(const Eigen::VectorXd& q, const Eigen::VectorXd& dq, double h) const {
    int lo[2] = {0, 0};
    int hi[2] = {0, 0};
    for (int d = 0; d < dims_; ++d) {
      const double reach = h * std::abs(dq[variable_[d]]);
      if (!cellRange(d, q[variable_[d]] - reach, q[variable_[d]] + reach, lo[d], hi[d])) return false;
    }
    return cellsFree(lo, hi);
  }

  /// True when every configuration whose values lie within [lower, upper] (per variable; both of
  /// the robot's size) lies in a cell certified free. Its cells hold those of every q + s dq,
  /// |s| <= h, that certifiedFreeAlong would test for q in the range when lower and upper are the
  /// range's ends less and plus h |dq|, computed as it computes them: rounding keeps their order.
  bool certifiedFreeWithin(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) const {
    int lo[2] = {0, 0};
    int hi[2] = {0, 0};
    for (int d = 0; d < dims_; ++d) {
      if (!cellRange(d, lower[variable_[d]], upper[variable_[d]], lo[d], hi[d])) return false;
    }
    return cellsFree(lo, hi);
  }

  int numCells() const { return static_cast<int>(free_.size()); }
  int numFreeCells() const;
  /// Whether cell `index` (row-major, first variable slowest) is certified free.
  bool cellFree(int index) const { return free_[index] != 0; }
  /// The largest motion bound delta over the cells, metres.
  double motionBound() const { return delta_; }

 private:
  /// The cells of grid variable d from value x0 to x1: false beyond the limits (or NaN).
  bool cellRange(int d, double x0, double x1, int& first, int& last) const {
    const double a = (x0 - lower_[d]) * inverseStep_[d];
    const double b = (x1 - lower_[d]) * inverseStep_[d];
    if (!(a >= 0.0 && b < cells_[d])) return false;
    first = static_cast<int>(a);
    last = static_cast<int>(b);
    return true;
  }
  /// Every cell from lo to hi (per grid variable) is certified free: no cell of that block is
  /// counted in blockedBefore_.
  bool cellsFree(const int lo[2], const int hi[2]) const {
    const int stride = columns() + 1;
    const auto at = [&](int i, int j) { return blockedBefore_[static_cast<std::size_t>(i) * stride + j]; };
    return at(hi[0] + 1, hi[1] + 1) - at(lo[0], hi[1] + 1) - at(hi[0] + 1, lo[1]) + at(lo[0], lo[1]) == 0;
  }
  /// Cells along the second grid variable (1 for a grid of one variable).
  int columns() const { return dims_ == 2 ? cells_[1] : 1; }
  /// Fills blockedBefore_ from free_.
  void countBlocked();
  /// The grid's variables, cells and delta for the motion radii `rho` (variable -> rho) within
  /// the cell budget for `piecePairs` piece pairs; the cell widths in `step`. False when the
  /// limits are degenerate or the budget too small.
  bool layout(const robots::RobotModel& model, const std::map<int, double>& rho, long long piecePairs, double step[2]);
  /// Marks each cell free when every piece pair of U and D is certified apart over it.
  void certifyCells(const RobotData& robot, int up, int down, const LinkGeometry& U, const LinkGeometry& D,
                    const double step[2]);
  /// X_UD, the pose of D in U, with the variables at the centre of cell `index` (q and X_WL:
  /// scratch; q has the robot's size).
  Eigen::Isometry3d poseAtCentre(const robots::RobotModel& model, int up, int down, const double step[2], int index,
                                 Eigen::VectorXd& q, std::vector<Eigen::Isometry3d>& X_WL) const;
  /// certifyCells through `cache`: the flags of its entry when it passes spotCheck, else
  /// certified and stored (a corrupt or rejected entry noted on `notes`).
  void certifyThroughCache(const RobotData& robot, int up, int down, const LinkGeometry& U, const LinkGeometry& D,
                           const double step[2], const SelfPairGridCache& cache, std::ostream* notes);
  /// The layout's numbers, as the cache key hashes them.
  std::vector<double> layoutNumbers(const double step[2]) const;
  /// True when tol::kGridCacheSpotChecks of the FREE cells, spread over them deterministically,
  /// are certified again (all of them when there are fewer).
  bool spotCheck(const RobotData& robot, int up, int down, const LinkGeometry& U, const LinkGeometry& D,
                 const double step[2]) const;

  int dims_ = 0;
  int variable_[2] = {-1, -1};
  double lower_[2] = {0.0, 0.0};
  double inverseStep_[2] = {0.0, 0.0};
  int cells_[2] = {1, 1};
  double delta_ = 0.0;
  std::vector<std::uint8_t> free_;  // row-major, first variable slowest
  /// The cells not certified free among those before (i, j) along both variables, at
  /// i (columns() + 1) + j: a block's count in four lookups, however many cells it spans.
  std::vector<int> blockedBefore_;
};

}  // namespace deepcheck::checker::detail
