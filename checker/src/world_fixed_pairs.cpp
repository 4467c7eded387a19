// Pairs that no joint can change (world.h, "Fixed pairs"): listed by World::fixedPairs and
// reported once each on WorldOptions::progress when the world's scenes, obstacles or allowed
// collisions change.

#include "deepcheck/checker/world.h"

#include "world_internal.h"

#include "deepcheck/robots/kinematics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>

namespace deepcheck::checker {

bool movedByNoJoint(const robots::RobotModel& model, int link) {
  for (int l = link; model.link(l).parentJoint >= 0; l = model.link(l).parentLink) {
    if (model.joint(model.link(l).parentJoint).moves()) return false;
  }
  return true;
}

namespace detail {

std::string allowHint(const Contact& c) {
  return "allow it with --allow-collision " + c.nameA + ":" + c.nameB + " (World::allowCollision)";
}

namespace {

/// A distance in metres with 3 significant digits (-0.003, 0.0125): the reports' precision.
std::string metres(double d) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", d);
  return text;
}

}  // namespace

std::string fixedPairMessage(const Contact& c, const robots::RobotModel& robot) {
  const std::string link = robot.link(c.linkA).name;
  const std::string what =
      c.distance <= 0.0 ? "every configuration collides" : "no configuration has a clearance above it";
  return "deepcheck: warning: " + c.nameA + " and " + c.nameB + " are " + metres(c.distance) +
         " m apart in every configuration (no joint moves " + link + "): " + what + "; " + allowHint(c);
}

void reportFixedPairs(const World& world, WorldState& st) {
  if (st.options.progress == nullptr || !st.fixedPairReports.load()) return;
  const std::vector<Contact> pairs = world.fixedPairs();
  std::lock_guard<std::mutex> lock(st.mutex);
  for (const Contact& c : pairs) {
    if (!st.reportedFixedPairs.insert(c.nameA + "\n" + c.nameB).second) continue;
    *st.options.progress << fixedPairMessage(c, world.robot()) << "\n";
  }
  st.options.progress->flush();
}

}  // namespace detail

bool World::setFixedPairReports(bool on) {
  const bool before = state_->fixedPairReports.exchange(on);
  if (on) detail::reportFixedPairs(*this, *state_);
  return before;
}

namespace {

using detail::PieceSet;
using detail::RobotData;
using detail::RobotPiece;

/// The contact of robot piece i (at its pose X_WP) and world piece wp of `set`.
Contact pieceContact(const detail::Snapshot& s, int g, const RobotPiece& p, const Eigen::Isometry3d& X_WP,
                     const PieceSet& set, int wp) {
  const detail::WorldPiece& w = set.pieces[static_cast<std::size_t>(wp)];
  const geometry::SignedDistanceResult r = geometry::signedDistance(
      geometry::ConvexShape{p.core.get(), p.radius}, X_WP, geometry::ConvexShape{w.core.get(), w.radius}, w.X_WP);
  Contact c;
  c.distance = r.distance;
  c.normal = r.normal;
  c.pointA = r.pointA;
  c.pointB = r.pointB;
  c.status = r.status;
  c.linkA = p.link;
  const detail::LinkGeometry& lg = s.robot->links[static_cast<std::size_t>(g)];
  c.nameA = lg.attached < 0 ? s.robot->model.link(lg.link).name
                            : "attached/" + s.attached[static_cast<std::size_t>(lg.attached)]->source.name;
  c.bodyB = set.bodies[static_cast<std::size_t>(w.body)].ref;
  c.nameB = set.bodies[static_cast<std::size_t>(w.body)].name;
  return c;
}

/// The nearest contact per world body of `set` with robot geometry g (posed by X_WL) within
/// maxDistance and not allowed, appended to `out`.
void fixedContacts(const detail::Snapshot& s, const detail::AllowedMask& allowed, const PieceSet& set, int g,
                   const std::vector<Eigen::Isometry3d>& X_WL, double maxDistance, std::vector<Contact>& out) {
  const RobotData& robot = *s.robot;
  const detail::LinkGeometry& lg = robot.links[static_cast<std::size_t>(g)];
  std::vector<Contact> best(set.bodies.size());
  for (int wp = 0; wp < static_cast<int>(set.pieces.size()); ++wp) {
    const detail::WorldPiece& w = set.pieces[static_cast<std::size_t>(wp)];
    if (allowed.test(g, w.body)) continue;
    for (int i = lg.firstPiece; i < lg.firstPiece + lg.numPieces; ++i) {
      const RobotPiece& p = robot.pieces[static_cast<std::size_t>(i)];
      const Eigen::Isometry3d& X_WL_p = X_WL[static_cast<std::size_t>(p.link)];
      if (w.box.distance(X_WL_p * p.center_L) - p.sphereRadius > maxDistance) continue;  // a lower bound
      const Contact c = pieceContact(s, g, p, X_WL_p * p.X_LP, set, wp);
      Contact& b = best[static_cast<std::size_t>(w.body)];
      if (c.distance <= maxDistance && c.distance < b.distance) b = c;
    }
  }
  for (const Contact& c : best) {
    if (c.distance <= maxDistance) out.push_back(c);
  }
}

}  // namespace

std::vector<Contact> World::fixedPairs(double maxDistance) const {
  // Measured directly (no Context: a context's caches are sized by all robot-world piece pairs,
  // and this runs at every change); only the pieces of geometries on links no joint moves.
  const auto snap = state_->snapshot();
  const robots::RobotModel& model = state_->robot->model;
  const std::vector<Eigen::Isometry3d> X_WL = robots::forwardKinematics(model, model.defaultConfiguration());
  std::vector<Contact> out;
  for (int g = 0; g < static_cast<int>(snap->robot->links.size()); ++g) {
    if (!movedByNoJoint(model, snap->robot->links[static_cast<std::size_t>(g)].link)) continue;
    fixedContacts(*snap, snap->sceneAllowed, *snap->scenePieces, g, X_WL, maxDistance, out);
    fixedContacts(*snap, snap->obstacleAllowed, *snap->obstaclePieces, g, X_WL, maxDistance, out);
  }
  std::sort(out.begin(), out.end(), [](const Contact& a, const Contact& b) { return a.distance < b.distance; });
  return out;
}

}  // namespace deepcheck::checker
