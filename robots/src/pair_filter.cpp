#include "deepcheck/robots/pair_filter.h"

#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/random_configuration.h"

#include "deepcheck/geometry/signed_distance.h"
#include "in_quotes.h"

#include <algorithm>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>

namespace deepcheck::robots {

using detail::inQuotes;

int PairFilterResult::count(DisableReason reason) const {
  return static_cast<int>(
      std::count_if(disabled.begin(), disabled.end(), [&](const DisabledPair& p) { return p.reason == reason; }));
}

int PairFilterResult::numEnabled() const { return numPairs() - static_cast<int>(disabled.size()); }

namespace {

/// A piece posed in the world, with its bounding sphere for a cheap rejection test.
struct PosedPiece {
  geometry::ConvexShape shape;
  Eigen::Isometry3d X_WP;
  Eigen::Vector3d centre_W;
  double sphereRadius;
};

void posePieces(const std::vector<CollisionPiece>& pieces, const Eigen::Isometry3d& X_WL,
                std::vector<PosedPiece>& out) {
  out.clear();
  for (const CollisionPiece& p : pieces) {
    PosedPiece posed;
    posed.shape = geometry::ConvexShape{p.core.get(), p.radius};
    posed.X_WP = X_WL * p.X_LP;
    posed.centre_W = posed.X_WP * p.core->center();
    posed.sphereRadius = p.core->boundingRadius() + p.radius;
    out.push_back(posed);
  }
}

bool posedOverlap(const std::vector<PosedPiece>& a, const std::vector<PosedPiece>& b) {
  for (const PosedPiece& pa : a) {
    for (const PosedPiece& pb : b) {
      const double reach = pa.sphereRadius + pb.sphereRadius;
      // Strictly farther apart than the two spheres: the pieces cannot touch. Compared squared;
      // touching pieces (distance == reach) go on to the exact test.
      if ((pa.centre_W - pb.centre_W).squaredNorm() > reach * reach) continue;
      if (geometry::overlaps(pa.shape, pa.X_WP, pb.shape, pb.X_WP)) return true;
    }
  }
  return false;
}

std::string robotContext(const RobotModel& model) {
  return "robot " + inQuotes(model.name()) + " (" + model.source() + ")";
}

void checkPieces(const RobotModel& model, const std::vector<std::vector<CollisionPiece>>& pieces) {
  if (static_cast<int>(pieces.size()) != model.numLinks()) {
    throw std::invalid_argument(robotContext(model) + ": pair filter given pieces for " +
                                std::to_string(pieces.size()) + " links, the robot has " +
                                std::to_string(model.numLinks()));
  }
  for (int l = 0; l < model.numLinks(); ++l) {
    for (const CollisionPiece& p : pieces[l]) {
      if (!p.core) {
        throw std::invalid_argument(robotContext(model) + ": link " + inQuotes(model.link(l).name) +
                                    " has a piece without a core (" + p.origin + ")");
      }
    }
  }
}

std::vector<std::pair<int, int>> geometryPairs(const std::vector<std::vector<CollisionPiece>>& pieces) {
  std::vector<std::pair<int, int>> pairs;
  const int n = static_cast<int>(pieces.size());
  for (int i = 0; i < n; ++i) {
    if (pieces[i].empty()) continue;
    for (int j = i + 1; j < n; ++j) {
      if (!pieces[j].empty()) pairs.emplace_back(i, j);
    }
  }
  return pairs;
}

}  // namespace

Eigen::VectorXd pairFilterDefaultConfiguration(const RobotModel& model) {
  Eigen::VectorXd q(model.numVariables());
  for (int v = 0; v < q.size(); ++v) {
    const double lo = model.lowerLimits()[v];
    const double hi = model.upperLimits()[v];
    q[v] = lo <= 0.0 && 0.0 <= hi ? 0.0 : 0.5 * (lo + hi);
  }
  return q;
}

std::vector<std::pair<int, int>> adjacentLinkPairs(const RobotModel& model,
                                                   const std::vector<std::vector<CollisionPiece>>& pieces) {
  checkPieces(model, pieces);
  const int n = model.numLinks();
  // Undirected link graph through the joints.
  std::vector<std::vector<int>> neighbours(n);
  for (const Joint& j : model.joints()) {
    neighbours[j.parentLink].push_back(j.childLink);
    neighbours[j.childLink].push_back(j.parentLink);
  }
  std::set<std::pair<int, int>> adjacent;
  std::vector<int> stack;
  std::vector<int> seenBy(n, -1);  // the walk that last met each link: no clearing per walk
  for (int a = 0; a < n; ++a) {
    if (pieces[a].empty()) continue;
    // Walk from a through links without geometry; every link with geometry met is adjacent to a.
    seenBy[a] = a;
    stack.assign(1, a);
    while (!stack.empty()) {
      const int l = stack.back();
      stack.pop_back();
      for (int m : neighbours[l]) {
        if (seenBy[m] == a) continue;
        seenBy[m] = a;
        if (pieces[m].empty()) {
          stack.push_back(m);
        } else {
          adjacent.emplace(std::min(a, m), std::max(a, m));
        }
      }
    }
  }
  return {adjacent.begin(), adjacent.end()};
}

bool piecesOverlap(const std::vector<CollisionPiece>& a, const Eigen::Isometry3d& X_WA,
                   const std::vector<CollisionPiece>& b, const Eigen::Isometry3d& X_WB) {
  std::vector<PosedPiece> pa, pb;
  posePieces(a, X_WA, pa);
  posePieces(b, X_WB, pb);
  return posedOverlap(pa, pb);
}

std::vector<std::pair<int, int>> collidingLinkPairs(const RobotModel& model,
                                                    const std::vector<std::vector<CollisionPiece>>& pieces,
                                                    const std::vector<Eigen::Isometry3d>& X_WL) {
  checkPieces(model, pieces);
  if (static_cast<int>(X_WL.size()) != model.numLinks()) {
    throw std::invalid_argument(robotContext(model) + ": " + std::to_string(X_WL.size()) +
                                " link poses given, the robot has " + std::to_string(model.numLinks()) + " links");
  }
  std::vector<std::vector<PosedPiece>> posed(model.numLinks());
  for (int l = 0; l < model.numLinks(); ++l) posePieces(pieces[l], X_WL[l], posed[l]);
  std::vector<std::pair<int, int>> colliding;
  for (const auto& [i, j] : geometryPairs(pieces)) {
    if (posedOverlap(posed[i], posed[j])) colliding.emplace_back(i, j);
  }
  return colliding;
}

namespace {

/// Checks the options of computeDisabledPairs; returns the default configuration to use.
Eigen::VectorXd checkedDefaultConfiguration(const RobotModel& model, const PairFilterOptions& options) {
  if (options.samples < 0) {
    throw std::invalid_argument(robotContext(model) + ": pair filter sample count " + std::to_string(options.samples) +
                                " is negative");
  }
  if (!(options.alwaysFraction > 0.0 && options.alwaysFraction <= 1.0)) {
    std::ostringstream msg;
    msg << robotContext(model) << ": pair filter alwaysFraction " << options.alwaysFraction << " is not in (0, 1]";
    throw std::invalid_argument(msg.str());
  }
  const Eigen::VectorXd q0 =
      options.defaultConfiguration.size() == 0 ? pairFilterDefaultConfiguration(model) : options.defaultConfiguration;
  if (options.checkDefault) {
    try {
      checkConfiguration(model, q0);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("pair filter default configuration: ") + e.what());
    }
  }
  return q0;
}

/// Every pair of links with geometry, in order, the adjacent ones marked.
std::vector<LinkPairReport> adjacentMarked(const RobotModel& model,
                                           const std::vector<std::vector<CollisionPiece>>& pieces) {
  std::vector<LinkPairReport> pairs;
  for (const auto& [i, j] : geometryPairs(pieces)) {
    LinkPairReport r;
    r.link1 = i;
    r.link2 = j;
    pairs.push_back(r);
  }
  for (const auto& [i, j] : adjacentLinkPairs(model, pieces)) {
    auto it = std::lower_bound(
        pairs.begin(), pairs.end(), std::make_pair(i, j),
        [](const LinkPairReport& r, const std::pair<int, int>& key) { return std::make_pair(r.link1, r.link2) < key; });
    it->reason = DisableReason::Adjacent;  // every adjacent pair is a pair of links with geometry
  }
  return pairs;
}

/// The robot's pieces posed at one configuration.
class PosedRobot {
 public:
  PosedRobot(const RobotModel& model, const std::vector<std::vector<CollisionPiece>>& pieces)
      : model_(model), pieces_(pieces), posed_(model.numLinks()), X_WL_(model.numLinks()) {}

  void pose(const Eigen::VectorXd& q) {
    forwardKinematics(model_, q, X_WL_);
    for (int l = 0; l < model_.numLinks(); ++l) posePieces(pieces_[l], X_WL_[l], posed_[l]);
  }
  bool overlap(const LinkPairReport& r) const { return posedOverlap(posed_[r.link1], posed_[r.link2]); }

 private:
  const RobotModel& model_;
  const std::vector<std::vector<CollisionPiece>>& pieces_;
  std::vector<std::vector<PosedPiece>> posed_;
  std::vector<Eigen::Isometry3d> X_WL_;
};

/// Counts the collisions of the pairs not adjacent over random configurations, and marks the
/// unmarked ones that never or almost always collide.
void sampleCollisions(const RobotModel& model, const PairFilterOptions& options, PosedRobot& robot,
                      std::vector<LinkPairReport>* pairs) {
  // Default pairs are sampled too, for their count (a Default pair that rarely collides in
  // the sample points at pieces that overlap at the default configuration by approximation).
  std::vector<LinkPairReport*> sampled;
  for (LinkPairReport& r : *pairs) {
    if (r.reason != DisableReason::Adjacent) sampled.push_back(&r);
  }
  std::mt19937_64 rng(options.seed);
  for (int s = 0; s < options.samples; ++s) {
    robot.pose(randomConfiguration(model, rng));
    for (LinkPairReport* r : sampled) {
      if (robot.overlap(*r)) ++r->collisions;
    }
  }
  for (LinkPairReport* r : sampled) {
    if (r->reason) continue;
    if (r->collisions == 0) {
      r->reason = DisableReason::Never;
    } else if (r->collisions >= options.alwaysFraction * options.samples) {
      r->reason = DisableReason::Always;
    }
  }
}

}  // namespace

PairFilterResult computeDisabledPairs(const RobotModel& model, const std::vector<std::vector<CollisionPiece>>& pieces,
                                      const PairFilterOptions& options) {
  checkPieces(model, pieces);
  const Eigen::VectorXd q0 = checkedDefaultConfiguration(model, options);

  PairFilterResult result;
  for (const auto& p : pieces) result.numGeometryLinks += p.empty() ? 0 : 1;
  result.pairs = adjacentMarked(model, pieces);

  PosedRobot robot(model, pieces);
  if (options.checkDefault) {
    robot.pose(q0);
    for (LinkPairReport& r : result.pairs) {
      if (!r.reason && robot.overlap(r)) r.reason = DisableReason::Default;
    }
  }
  result.samples = options.samples;
  if (options.samples > 0) sampleCollisions(model, options, robot, &result.pairs);

  for (const LinkPairReport& r : result.pairs) {
    if (r.reason) {
      result.disabled.push_back(DisabledPair{model.link(r.link1).name, model.link(r.link2).name, *r.reason});
    }
  }
  return result;
}

void checkDisabledPairs(const RobotModel& model, const std::vector<DisabledPair>& disabled, const std::string& source) {
  for (const DisabledPair& p : disabled) {
    const std::string entry = "<disable_collisions link1=" + inQuotes(p.link1) + " link2=" + inQuotes(p.link2) + ">";
    for (const std::string* name : {&p.link1, &p.link2}) {
      if (model.linkIndex(*name) < 0) {
        throw std::invalid_argument(source + ": " + entry + ": link " + inQuotes(*name) + " is not a link of " +
                                    robotContext(model));
      }
    }
    if (p.link1 == p.link2) {
      throw std::invalid_argument(source + ": " + entry + ": names the same link twice");
    }
  }
}

std::vector<std::pair<int, int>> enabledLinkPairs(const RobotModel& model,
                                                  const std::vector<std::vector<CollisionPiece>>& pieces,
                                                  const std::vector<DisabledPair>& disabled) {
  checkPieces(model, pieces);
  checkDisabledPairs(model, disabled, "disabled pairs");
  std::set<std::pair<int, int>> off;
  for (const DisabledPair& p : disabled) {
    const int a = model.linkIndex(p.link1);
    const int b = model.linkIndex(p.link2);
    off.emplace(std::min(a, b), std::max(a, b));
  }
  std::vector<std::pair<int, int>> enabled;
  for (const auto& pair : geometryPairs(pieces)) {
    if (off.count(pair) == 0) enabled.push_back(pair);
  }
  return enabled;
}

}  // namespace deepcheck::robots
