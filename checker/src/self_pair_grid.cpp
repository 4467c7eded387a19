// Certified-free grids of self pairs (see self_pair_grid.h).

#include "self_pair_grid.h"

#include "world_internal.h"

#include "deepcheck/deep/gjk.h"
#include "deepcheck/deep/pair_frame.h"
#include "deepcheck/robots/kinematics.h"

#include <algorithm>
#include <cmath>
#include <map>

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

}  // namespace

int SelfPairGrid::numFreeCells() const {
  return static_cast<int>(std::count(free_.begin(), free_.end(), std::uint8_t{1}));
}

std::shared_ptr<const SelfPairGrid> SelfPairGrid::build(const RobotData& robot, int a, int b) {
  const robots::RobotModel& model = robot.model;
  int up = robot.links[a].link;
  int down = robot.links[b].link;
  int upGeometry = a;
  int downGeometry = b;
  auto isAncestor = [&](int ancestor, int link) {
    for (int l = link; l >= 0; l = model.link(l).parentLink) {
      if (l == ancestor) return true;
    }
    return false;
  };
  if (!isAncestor(up, down)) {
    if (!isAncestor(down, up)) return nullptr;  // on different branches
    std::swap(up, down);
    std::swap(upGeometry, downGeometry);
  }
  const LinkGeometry& U = robot.links[upGeometry];
  const LinkGeometry& D = robot.links[downGeometry];

  // Largest |p| of a point of D's pieces, in D's frame.
  double reachD = 0.0;
  for (int j = D.firstPiece; j < D.firstPiece + D.numPieces; ++j) {
    reachD = std::max(reachD, robot.pieces[j].center_L.norm() + robot.pieces[j].sphereRadius);
  }
  // Joints from D up to U; rho per variable.
  std::map<int, double> rho;  // variable -> sum of |multiplier| rho_k
  double below = 0.0;         // sum of |X_PJ.translation| of the joints below the current one
  for (int l = down; l != up; l = model.link(l).parentLink) {
    const robots::Joint& joint = model.joint(model.link(l).parentJoint);
    if (joint.type == robots::JointType::Prismatic) return nullptr;
    if (joint.moves()) rho[joint.variable] += std::abs(joint.multiplier) * (below + reachD);
    below += joint.X_PJ.translation().norm();
  }
  if (rho.empty() || rho.size() > 2) return nullptr;

  auto grid = std::make_shared<SelfPairGrid>();
  SelfPairGrid& g = *grid;
  g.dims_ = static_cast<int>(rho.size());
  double weight[2] = {0.0, 0.0};  // rho * range: the motion a variable can cause over its range
  double range[2] = {0.0, 0.0};
  double rhoOf[2] = {0.0, 0.0};
  int d = 0;
  for (const auto& [v, r] : rho) {
    g.variable_[d] = v;
    g.lower_[d] = model.lowerLimits()[v];
    range[d] = model.upperLimits()[v] - g.lower_[d];
    if (!(range[d] > 0.0) || !std::isfinite(range[d])) return nullptr;
    rhoOf[d] = r;
    weight[d] = std::max(r * range[d], 1e-300);
    ++d;
  }
  const long long piecePairs = static_cast<long long>(U.numPieces) * D.numPieces;
  const long long budget = std::min<long long>(tol::kGridMaxCells, tol::kGridMaxPiecePairTests / piecePairs);
  if (budget < 16) return nullptr;
  if (g.dims_ == 1) {
    g.cells_[0] = static_cast<int>(budget);
  } else {
    // Equal shares of delta: cells proportional to the weights, product within the budget.
    const double n0 = std::sqrt(static_cast<double>(budget) * weight[0] / weight[1]);
    g.cells_[0] = std::clamp(static_cast<int>(n0), 1, static_cast<int>(budget));
    g.cells_[1] = std::max(1, static_cast<int>(budget / g.cells_[0]));
  }
  double step[2] = {1.0, 1.0};
  double halfWidth[2] = {0.0, 0.0};
  for (int k = 0; k < g.dims_; ++k) {
    step[k] = range[k] / g.cells_[k];
    g.inverseStep_[k] = g.cells_[k] / range[k];
    // Padded: q's cell index comes from a rounded division, so q may lie a few ulps outside it.
    halfWidth[k] = 0.5 * step[k] * (1.0 + 1e-9) + 1e-12 * (1.0 + std::abs(g.lower_[k]) + range[k]);
    g.delta_ += rhoOf[k] * halfWidth[k];
  }

  // Each cell: the variables at its centre, the others at the default configuration (they do not
  // change D's pose in U).
  Eigen::VectorXd q = model.defaultConfiguration();
  std::vector<Eigen::Isometry3d> X_WL;
  std::vector<deep::GjkCache> caches(static_cast<std::size_t>(piecePairs));  // warm along the scan
  const int total = g.cells_[0] * g.cells_[1];
  g.free_.assign(total, 0);
  std::vector<Eigen::Isometry3d> X_UA(U.numPieces), X_UB(D.numPieces);
  for (int cell = 0; cell < total; ++cell) {
    const int i0 = cell / g.cells_[1];
    int i1 = cell % g.cells_[1];
    if (i0 % 2 == 1) i1 = g.cells_[1] - 1 - i1;  // boustrophedon: neighbouring cells in a row
    const int index = g.dims_ == 1 ? i0 : i0 * g.cells_[1] + i1;
    q[g.variable_[0]] = g.lower_[0] + (i0 + 0.5) * step[0];
    if (g.dims_ == 2) q[g.variable_[1]] = g.lower_[1] + (i1 + 0.5) * step[1];
    robots::forwardKinematics(model, q, X_WL);
    const Eigen::Isometry3d X_UD = X_WL[up].inverse() * X_WL[down];
    for (int i = 0; i < U.numPieces; ++i) X_UA[i] = robot.pieces[U.firstPiece + i].X_LP;
    for (int j = 0; j < D.numPieces; ++j) X_UB[j] = X_UD * robot.pieces[D.firstPiece + j].X_LP;
    bool certified = true;
    for (int i = 0; i < U.numPieces && certified; ++i) {
      const RobotPiece& pa = robot.pieces[U.firstPiece + i];
      const Eigen::Vector3d centerA = pa.center_L;
      for (int j = 0; j < D.numPieces && certified; ++j) {
        const RobotPiece& pb = robot.pieces[D.firstPiece + j];
        const double size = pa.sphereRadius + pb.sphereRadius;
        const double need = g.delta_ + tol::kCertifiedGapRelative * size;
        const Eigen::Vector3d centerB = X_UD * pb.center_L;
        if ((centerB - centerA).norm() - size > need) continue;
        const deep::PairFrame frame = deep::PairFrame::make(*pa.core, X_UA[i], *pb.core, X_UB[j]);
        const deep::GjkResult r = deep::gjkDistance(*pa.core, *pb.core, frame, &caches[i * D.numPieces + j]);
        if (r.status != deep::GjkStatus::Separated || !(r.distance - pa.radius - pb.radius > need)) {
          certified = false;
          break;
        }
        // GJK's distance is an upper bound; the separation along its normal is a lower bound.
        const Eigen::Vector3d n = frame.X_WP.linear() * r.normal;
        certified = separationAlong(pa, X_UA[i], pb, X_UB[j], n) > need;
      }
    }
    g.free_[index] = certified ? 1 : 0;
  }
  return grid;
}

}  // namespace deepcheck::checker::detail
