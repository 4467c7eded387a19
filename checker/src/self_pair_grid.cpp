// Certified-free grids of self pairs (see self_pair_grid.h).

#include "self_pair_grid.h"

#include "self_pair_grid_cache.h"
#include "world_internal.h"

#include "deepcheck/geometry/gjk.h"
#include "deepcheck/geometry/pair_frame.h"
#include "deepcheck/robots/kinematics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <string>

namespace deepcheck::checker::detail {

namespace {

/// A lower bound on the distance between two posed pieces along the unit direction n (from A to
/// B): min over B of n.x minus max over A of n.x, radii subtracted. Exact supports (every vertex).
double separationAlong(const RobotPiece& a, const Eigen::Isometry3d& X_UA, const RobotPiece& b,
                       const Eigen::Isometry3d& X_UB, const Eigen::Vector3d& n) {
  const Eigen::Vector3d nA = X_UA.linear().transpose() * n;
  const Eigen::Vector3d nB = X_UB.linear().transpose() * n;
  const double maxA = nA.dot(a.core->vertex(a.core->supportBruteForce(nA))) + n.dot(X_UA.translation());
  const double minB = nB.dot(b.core->vertex(b.core->supportBruteForce(-nB))) + n.dot(X_UB.translation());
  return minB - maxA - a.radius - b.radius;
}

/// The two link geometries of a self pair, the upper one an ancestor of the lower one.
struct Chain {
  int up;            ///< link
  int down;          ///< link
  int upGeometry;    ///< index into RobotData::links
  int downGeometry;  ///< index into RobotData::links
};

/// The pair (a, b) as a chain, or false when the links are on different branches.
bool chainOf(const RobotData& robot, int a, int b, Chain* chain) {
  const robots::RobotModel& model = robot.model;
  auto isAncestor = [&](int ancestor, int link) {
    for (int l = link; l >= 0; l = model.link(l).parentLink) {
      if (l == ancestor) return true;
    }
    return false;
  };
  *chain = {robot.links[a].link, robot.links[b].link, a, b};
  if (isAncestor(chain->up, chain->down)) return true;
  if (!isAncestor(chain->down, chain->up)) return false;
  std::swap(chain->up, chain->down);
  std::swap(chain->upGeometry, chain->downGeometry);
  return true;
}

/// rho per variable of the joints from D up to U (self_pair_grid.h): the sum over its joints of
/// |multiplier| times the reach of D's points from the joint. Empty when a prismatic joint lies
/// between them.
std::map<int, double> motionRadii(const RobotData& robot, const Chain& chain) {
  const robots::RobotModel& model = robot.model;
  const LinkGeometry& D = robot.links[chain.downGeometry];
  // Largest |p| of a point of D's pieces, in D's frame.
  double reachD = 0.0;
  for (int j = D.firstPiece; j < D.firstPiece + D.numPieces; ++j) {
    reachD = std::max(reachD, robot.pieces[j].center_L.norm() + robot.pieces[j].sphereRadius);
  }
  std::map<int, double> rho;  // variable -> sum of |multiplier| rho_k
  double below = 0.0;         // sum of |X_PJ.translation| of the joints below the current one
  for (int l = chain.down; l != chain.up; l = model.link(l).parentLink) {
    const robots::Joint& joint = model.joint(model.link(l).parentJoint);
    if (joint.type == robots::JointType::Prismatic) return {};
    if (joint.moves()) rho[joint.variable] += std::abs(joint.multiplier) * (below + reachD);
    below += joint.X_PJ.translation().norm();
  }
  return rho;
}

/// True when every piece pair of U and D (D posed by X_UD in U's frame) is certified apart by
/// more than delta over the cell. `caches`: one GJK warm start per piece pair.
bool cellCertified(const RobotData& robot, const LinkGeometry& U, const LinkGeometry& D, const Eigen::Isometry3d& X_UD,
                   double delta, std::vector<geometry::GjkCache>* caches) {
  for (int i = 0; i < U.numPieces; ++i) {
    const RobotPiece& pa = robot.pieces[U.firstPiece + i];
    const Eigen::Isometry3d& X_UA = pa.X_LP;
    for (int j = 0; j < D.numPieces; ++j) {
      const RobotPiece& pb = robot.pieces[D.firstPiece + j];
      const double size = pa.sphereRadius + pb.sphereRadius;
      const double need = delta + tol::kCertifiedGapRelative * size;
      const Eigen::Vector3d centerB = X_UD * pb.center_L;
      if ((centerB - pa.center_L).norm() - size > need) continue;
      const Eigen::Isometry3d X_UB = X_UD * pb.X_LP;
      const geometry::PairFrame frame = geometry::PairFrame::make(*pa.core, X_UA, *pb.core, X_UB);
      const geometry::GjkResult r = geometry::gjkDistance(*pa.core, *pb.core, frame, &(*caches)[i * D.numPieces + j]);
      if (r.status != geometry::GjkStatus::Separated || !(r.distance - pa.radius - pb.radius > need)) return false;
      // GJK's distance is an upper bound; the separation along its normal is a lower bound.
      const Eigen::Vector3d n = frame.X_WP.linear() * r.normal;
      if (!(separationAlong(pa, X_UA, pb, X_UB, n) > need)) return false;
    }
  }
  return true;
}

}  // namespace

int SelfPairGrid::numFreeCells() const {
  return static_cast<int>(std::count(free_.begin(), free_.end(), std::uint8_t{1}));
}

bool SelfPairGrid::layout(const robots::RobotModel& model, const std::map<int, double>& rho, long long piecePairs,
                          double step[2]) {
  dims_ = static_cast<int>(rho.size());
  double weight[2] = {0.0, 0.0};  // rho * range: the motion a variable can cause over its range
  double range[2] = {0.0, 0.0};
  double rhoOf[2] = {0.0, 0.0};
  int d = 0;
  for (const auto& [v, r] : rho) {
    variable_[d] = v;
    lower_[d] = model.lowerLimits()[v];
    range[d] = model.upperLimits()[v] - lower_[d];
    if (!(range[d] > 0.0) || !std::isfinite(range[d])) return false;
    rhoOf[d] = r;
    weight[d] = std::max(r * range[d], std::numeric_limits<double>::min());  // no division by zero
    ++d;
  }
  const long long budget = std::min<long long>(tol::kGridMaxCells, tol::kGridMaxPiecePairTests / piecePairs);
  if (budget < 16) return false;
  if (dims_ == 1) {
    cells_[0] = static_cast<int>(budget);
  } else {
    // Equal shares of delta: cells proportional to the weights, product within the budget.
    const double n0 = std::sqrt(static_cast<double>(budget) * weight[0] / weight[1]);
    cells_[0] = std::clamp(static_cast<int>(n0), 1, static_cast<int>(budget));
    cells_[1] = std::max(1, static_cast<int>(budget / cells_[0]));
  }
  for (int k = 0; k < dims_; ++k) {
    step[k] = range[k] / cells_[k];
    inverseStep_[k] = cells_[k] / range[k];
    // Padded: q's cell index comes from a rounded division, so q may lie a few ulps outside it.
    const double halfWidth = 0.5 * step[k] * (1.0 + tol::kGridCellPaddingRelative) +
                             tol::kGridCellPaddingAbsolute * (1.0 + std::abs(lower_[k]) + range[k]);
    delta_ += rhoOf[k] * halfWidth;
  }
  return true;
}

Eigen::Isometry3d SelfPairGrid::poseAtCentre(const robots::RobotModel& model, int up, int down, const double step[2],
                                             int index, Eigen::VectorXd& q,
                                             std::vector<Eigen::Isometry3d>& X_WL) const {
  const int i0 = dims_ == 1 ? index : index / cells_[1];
  q[variable_[0]] = lower_[0] + (i0 + 0.5) * step[0];
  if (dims_ == 2) q[variable_[1]] = lower_[1] + (index % cells_[1] + 0.5) * step[1];
  robots::forwardKinematics(model, q, X_WL);
  return X_WL[up].inverse() * X_WL[down];
}

void SelfPairGrid::certifyCells(const RobotData& robot, int up, int down, const LinkGeometry& U, const LinkGeometry& D,
                                const double step[2]) {
  // Each cell: the variables at its centre, the others at the default configuration (they do not
  // change D's pose in U).
  Eigen::VectorXd q = robot.model.defaultConfiguration();
  std::vector<Eigen::Isometry3d> X_WL;
  std::vector<geometry::GjkCache> caches(static_cast<std::size_t>(U.numPieces) * D.numPieces);  // warm along the scan
  const int total = cells_[0] * cells_[1];
  free_.assign(total, 0);
  for (int cell = 0; cell < total; ++cell) {
    const int i0 = cell / cells_[1];
    int i1 = cell % cells_[1];
    if (i0 % 2 == 1) i1 = cells_[1] - 1 - i1;  // boustrophedon: neighbouring cells in a row
    const int index = dims_ == 1 ? i0 : i0 * cells_[1] + i1;
    const Eigen::Isometry3d X_UD = poseAtCentre(robot.model, up, down, step, index, q, X_WL);
    free_[index] = cellCertified(robot, U, D, X_UD, delta_, &caches) ? 1 : 0;
  }
}

std::vector<double> SelfPairGrid::layoutNumbers(const double step[2]) const {
  std::vector<double> numbers = {static_cast<double>(dims_), delta_};
  for (int d = 0; d < 2; ++d) {
    numbers.insert(numbers.end(), {static_cast<double>(variable_[d]), lower_[d], step[d], inverseStep_[d],
                                   static_cast<double>(cells_[d])});
  }
  return numbers;
}

bool SelfPairGrid::spotCheck(const RobotData& robot, int up, int down, const LinkGeometry& U, const LinkGeometry& D,
                             const double step[2]) const {
  std::vector<int> freeCells;
  for (int i = 0; i < numCells(); ++i) {
    if (free_[i] != 0) freeCells.push_back(i);
  }
  const int n = static_cast<int>(freeCells.size());
  const bool all = n <= tol::kGridCacheSpotChecks;
  Eigen::VectorXd q = robot.model.defaultConfiguration();
  std::vector<Eigen::Isometry3d> X_WL;
  std::vector<geometry::GjkCache> caches(static_cast<std::size_t>(U.numPieces) * D.numPieces);
  // Golden-ratio steps through the FREE cells: spread over them, and over both variables (an
  // even stride could keep hitting the same column of the grid).
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int k = 0; k < (all ? n : tol::kGridCacheSpotChecks); ++k) {
    const int cell = all ? freeCells[k] : freeCells[static_cast<int>(std::fmod(0.5 + k * golden, 1.0) * n)];
    const Eigen::Isometry3d X_UD = poseAtCentre(robot.model, up, down, step, cell, q, X_WL);
    if (!cellCertified(robot, U, D, X_UD, delta_, &caches)) return false;
  }
  return true;
}

std::shared_ptr<const SelfPairGrid> SelfPairGrid::build(const RobotData& robot, int a, int b,
                                                        const SelfPairGridCache* cache, std::ostream* notes) {
  Chain chain;
  if (!chainOf(robot, a, b, &chain)) return nullptr;
  const std::map<int, double> rho = motionRadii(robot, chain);
  if (rho.empty() || rho.size() > 2) return nullptr;
  const LinkGeometry& U = robot.links[chain.upGeometry];
  const LinkGeometry& D = robot.links[chain.downGeometry];
  auto grid = std::make_shared<SelfPairGrid>();
  double step[2] = {1.0, 1.0};
  if (!grid->layout(robot.model, rho, static_cast<long long>(U.numPieces) * D.numPieces, step)) return nullptr;
  if (cache != nullptr && cache->enabled()) {
    grid->certifyThroughCache(robot, chain.up, chain.down, U, D, step, *cache, notes);
  } else {
    grid->certifyCells(robot, chain.up, chain.down, U, D, step);
  }
  grid->countBlocked();
  return grid;
}

void SelfPairGrid::countBlocked() {
  const int rows = cells_[0];
  const int cols = columns();
  const auto stride = static_cast<std::size_t>(cols) + 1;
  blockedBefore_.assign((static_cast<std::size_t>(rows) + 1) * stride, 0);
  for (int i = 0; i < rows; ++i) {
    int inRow = 0;  // blocked cells of row i before column j + 1
    for (int j = 0; j < cols; ++j) {
      inRow += free_[static_cast<std::size_t>(i) * cols + j] == 0 ? 1 : 0;
      blockedBefore_[(i + 1) * stride + j + 1] = blockedBefore_[i * stride + j + 1] + inRow;
    }
  }
}

void SelfPairGrid::certifyThroughCache(const RobotData& robot, int up, int down, const LinkGeometry& U,
                                       const LinkGeometry& D, const double step[2], const SelfPairGridCache& cache,
                                       std::ostream* notes) {
  const std::string key = selfPairGridKey(robot, up, down, U, D, layoutNumbers(step));
  const std::size_t numCells = static_cast<std::size_t>(cells_[0]) * cells_[1];
  std::string problem;
  if (std::optional<std::vector<std::uint8_t>> flags = cache.load(key, numCells, &problem)) {
    free_ = std::move(*flags);
    if (spotCheck(robot, up, down, U, D, step)) return;
    problem = cache.pathFor(key) + ": a FREE cell fails its certificate when checked again";
  }
  if (!problem.empty() && notes != nullptr) {
    *notes << "deepcheck: self-pair grid cache: " << problem << "; certifying the grid again\n";
  }
  certifyCells(robot, up, down, U, D, step);
  cache.store(key, free_);  // a failed write (read-only directory) leaves the grid uncached
}

}  // namespace deepcheck::checker::detail
