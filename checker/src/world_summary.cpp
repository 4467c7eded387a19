// A World's description: body names, counts and the summary text.

#include "deepcheck/checker/world.h"

#include "world_internal.h"

#include <cstdio>
#include <sstream>

namespace deepcheck::checker {

using detail::RobotData;
using detail::SceneData;
using detail::SelfPair;

const char* toString(BroadPhase b) {
  switch (b) {
    case BroadPhase::AabbTree:
      return "aabb-tree";
    case BroadPhase::None:
      return "none";
  }
  return "unknown";
}

std::string World::bodyName(const BodyRef& body) const {
  const auto snap = state_->snapshot();
  switch (body.kind) {
    case BodyRef::Kind::RobotLink:
      if (body.index < 0 || body.index >= snap->robot->model.numLinks()) break;
      return snap->robot->model.link(body.index).name;
    case BodyRef::Kind::SceneLink:
      if (body.scene < 0 || body.scene >= static_cast<int>(snap->scenes.size())) break;
      if (body.index < 0 || body.index >= snap->scenes[body.scene]->model.numLinks()) break;
      return "scene/" + snap->scenes[body.scene]->model.link(body.index).name;
    case BodyRef::Kind::Obstacle:
      for (const auto& o : snap->obstacles) {
        if (o->id == body.index) return "obstacle/" + o->source.name;
      }
      break;
    case BodyRef::Kind::Attached:
      if (body.scene < 0 || body.scene >= static_cast<int>(snap->attached.size())) break;
      return "attached/" + snap->attached[body.scene]->source.name;
  }
  throw std::invalid_argument("bodyName: no such body (index " + std::to_string(body.index) + ")");
}

World::Summary World::summaryCounts() const {
  const auto snap = state_->snapshot();
  Summary s;
  const RobotData& r = *state_->robot;  // the robot's own links, without attached objects
  s.robotLinks = r.model.numLinks();
  s.robotLinksWithGeometry = static_cast<int>(r.links.size());
  s.robotPieces = static_cast<int>(r.pieces.size());
  s.selfPairs = static_cast<int>(snap->selfPairs.size());
  s.selfPiecePairs = snap->selfCacheSize;
  s.disabledAdjacent = snap->disabledAdjacent;
  s.disabledRigid = snap->disabledRigid;
  s.disabledByUser = snap->disabledByUser;
  s.unreachablePairs = snap->unreachablePairs;
  s.scenes = static_cast<int>(snap->scenes.size());
  for (const auto& sc : snap->scenes) {
    s.sceneLinksWithGeometry += sc->linksWithGeometry;
    s.scenePiecesKept += sc->piecesKept;
    s.scenePiecesDropped += sc->piecesDropped;
  }
  s.obstacles = static_cast<int>(snap->obstacles.size());
  s.obstaclePieces = static_cast<int>(snap->obstaclePieces->pieces.size());
  s.attachedObjects = static_cast<int>(snap->attached.size());
  s.attachedPieces = static_cast<int>(snap->robot->pieces.size() - r.pieces.size());
  s.allowedCollisions = static_cast<int>(snap->allowed.pairs.size() + snap->allowed.always.size());
  s.geometryExcess = snap->excess;
  return s;
}

std::string World::summary() const {
  const Summary s = summaryCounts();
  const auto snap = state_->snapshot();
  const robots::RobotModel& m = snap->robot->model;
  std::ostringstream out;
  out << "robot '" << m.name() << "': " << s.robotLinks << " links (" << s.robotLinksWithGeometry << " with geometry), "
      << m.numVariables() << " variables, " << s.robotPieces << " pieces\n";
  out << "self pairs: " << s.selfPairs << " link pairs checked (" << s.selfPiecePairs << " piece pairs), "
      << s.disabledAdjacent << " disabled as adjacent, " << s.disabledRigid << " as rigidly attached, "
      << s.disabledByUser << " by name (SRDF)";
  if (s.unreachablePairs > 0) out << ", " << s.unreachablePairs << " never within reach";
  out << "\n";
  for (std::size_t i = 0; i < snap->scenes.size(); ++i) {
    const SceneData& sc = *snap->scenes[i];
    out << "scene " << i << " '" << sc.model.name() << "': " << sc.model.numLinks() << " links ("
        << sc.linksWithGeometry << " with geometry), pieces kept " << sc.piecesKept << ", dropped " << sc.piecesDropped
        << " (unreachable)\n";
  }
  out << "scene pieces: kept " << s.scenePiecesKept << ", dropped " << s.scenePiecesDropped << " (reach margin "
      << state_->options.reachMargin << " m)\n";
  out << "obstacles: " << s.obstacles << " (" << s.obstaclePieces << " pieces)\n";
  if (s.attachedObjects > 0)
    out << "attached objects: " << s.attachedObjects << " (" << s.attachedPieces << " pieces)\n";
  if (s.allowedCollisions > 0) out << "allowed collisions: " << s.allowedCollisions << " entries (pairs and names)\n";
  const long long worldPairs =
      static_cast<long long>(s.robotPieces + s.attachedPieces) * (s.scenePiecesKept + s.obstaclePieces);
  int grids = 0, cells = 0, freeCells = 0;
  for (const SelfPair& p : snap->selfPairs) {
    if (p.grid == nullptr) continue;
    ++grids;
    cells += p.grid->numCells();
    freeCells += p.grid->numFreeCells();
  }
  if (grids > 0) {
    char share[32];
    std::snprintf(share, sizeof share, "%.1f", 100.0 * freeCells / cells);
    out << "self pairs with a certified-free grid: " << grids << " (" << cells << " cells, " << share
        << " % certified free)\n";
  }
  out << "pairs checked at most: " << worldPairs << " robot-world piece pairs, " << s.selfPiecePairs
      << " self piece pairs; broad phase "
      << (state_->options.externalBroadPhase ? state_->options.externalBroadPhase->name()
                                             : std::string(toString(state_->options.broadPhase)))
      << "\n";
  char excess[64];
  std::snprintf(excess, sizeof excess, "%.3g", s.geometryExcess);
  out << "geometry excess (pieces beyond the original shapes): " << (std::isnan(s.geometryExcess) ? "unknown" : excess)
      << " m\n";
  return out.str();
}

}  // namespace deepcheck::checker
