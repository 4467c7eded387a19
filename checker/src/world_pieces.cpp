// The pieces of a World as its queries see them, for display and export (World::linkPieces,
// World::worldPieces, World::linkExtents).

#include "world_internal.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace deepcheck::checker {

std::vector<robots::CollisionPiece> World::linkPieces(int link) const {
  const auto snap = state_->snapshot();
  const detail::RobotData& robot = *snap->robot;
  if (link < 0 || link >= robot.model.numLinks()) {
    throw std::invalid_argument("linkPieces: no link with index " + std::to_string(link));
  }
  std::vector<robots::CollisionPiece> out;
  for (const detail::LinkGeometry& g : robot.links) {
    if (g.link != link || g.attached >= 0) continue;  // attached objects: attachedObjects()
    for (int i = g.firstPiece; i < g.firstPiece + g.numPieces; ++i) {
      const detail::RobotPiece& p = robot.pieces[static_cast<std::size_t>(i)];
      out.push_back(robots::CollisionPiece{p.core, p.radius, p.X_LP, robot.model.link(link).name});
    }
  }
  return out;
}

std::vector<double> World::linkExtents() const {
  const auto snap = state_->snapshot();
  const detail::RobotData& robot = *snap->robot;
  std::vector<double> out(static_cast<std::size_t>(robot.model.numLinks()), -1.0);
  for (const detail::RobotPiece& p : robot.pieces) {
    double& e = out[static_cast<std::size_t>(p.link)];
    e = std::max(e, p.center_L.norm() + p.sphereRadius);
  }
  return out;
}

std::vector<World::WorldPieceRef> World::worldPieces() const {
  const auto snap = state_->snapshot();
  std::vector<WorldPieceRef> out;
  for (const detail::PieceSet* set : {snap->scenePieces.get(), snap->obstaclePieces.get()}) {
    for (const detail::WorldPiece& p : set->pieces) {
      const detail::WorldBody& body = set->bodies[static_cast<std::size_t>(p.body)];
      out.push_back(WorldPieceRef{body.ref, robots::CollisionPiece{p.core, p.radius, p.X_WP, body.name}});
    }
  }
  return out;
}

}  // namespace deepcheck::checker
