// Obstacles: their shapes, their pieces, and adding, moving and removing them in a World.

#include "deepcheck/checker/world.h"

#include "progress.h"
#include "world_internal.h"

#include "deepcheck/geometry/pair_frame.h"
#include "deepcheck/robots/mesh_loader.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace deepcheck::checker {

using detail::buildObstaclePieces;
using detail::ObstacleData;
using detail::PieceSet;
using detail::publish;
using detail::Snapshot;
using detail::WorldBody;
using detail::WorldState;

Obstacle Obstacle::box(const std::string& name, const Eigen::Vector3d& size, const Eigen::Isometry3d& X_WO) {
  Obstacle o;
  o.name = name;
  o.geometry.type = robots::GeometryType::Box;
  o.geometry.boxSize = size;
  o.X_WO = X_WO;
  return o;
}

Obstacle Obstacle::sphere(const std::string& name, double radius, const Eigen::Isometry3d& X_WO) {
  Obstacle o;
  o.name = name;
  o.geometry.type = robots::GeometryType::Sphere;
  o.geometry.radius = radius;
  o.X_WO = X_WO;
  return o;
}

Obstacle Obstacle::cylinder(const std::string& name, double radius, double length, const Eigen::Isometry3d& X_WO) {
  Obstacle o;
  o.name = name;
  o.geometry.type = robots::GeometryType::Cylinder;
  o.geometry.radius = radius;
  o.geometry.length = length;
  o.X_WO = X_WO;
  return o;
}

Obstacle Obstacle::meshFile(const std::string& name, const std::string& path, const Eigen::Isometry3d& X_WO,
                            const Eigen::Vector3d& scale) {
  Obstacle o;
  o.name = name;
  o.geometry.type = robots::GeometryType::Mesh;
  o.geometry.meshUri = path;
  o.geometry.meshPath = path;
  o.geometry.meshScale = scale;
  o.X_WO = X_WO;
  return o;
}

Obstacle Obstacle::fromMesh(const std::string& name, robots::TriangleMesh mesh, const Eigen::Isometry3d& X_WO) {
  Obstacle o;
  o.name = name;
  o.geometry.type = robots::GeometryType::Mesh;
  o.mesh = std::make_shared<const robots::TriangleMesh>(std::move(mesh));
  o.X_WO = X_WO;
  return o;
}

namespace detail {

std::vector<robots::CollisionPiece> piecesOfGeometry(const robots::Geometry& g, const robots::TriangleMesh* mesh,
                                                     const robots::CollisionGeometryOptions& options,
                                                     const std::string& what) {
  if (g.type != robots::GeometryType::Mesh) return {robots::primitivePiece(g, options, what)};
  robots::TriangleMesh loaded;
  if (mesh == nullptr) {
    if (g.meshPath.empty()) throw std::invalid_argument(what + ": a mesh needs a file or a TriangleMesh");
    if (!g.meshScale.allFinite() || !(g.meshScale.array() != 0).all()) {
      std::ostringstream msg;
      msg << what << ": mesh scale (" << g.meshScale.transpose() << ") must be finite and non-zero";
      throw std::invalid_argument(msg.str());
    }
    try {
      loaded = robots::loadMesh(g.meshPath, g.meshScale, options.meshLoad);
    } catch (const std::exception& e) {
      throw std::invalid_argument(what + ": " + e.what());
    }
    mesh = &loaded;
  }
  std::vector<geometry::ConvexPolytope> polytopes;
  try {
    polytopes = robots::meshPolytopes(*mesh, options);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(what + ": " + e.what());
  }
  std::vector<robots::CollisionPiece> out;
  for (std::size_t i = 0; i < polytopes.size(); ++i) {
    robots::CollisionPiece piece;
    piece.core = std::make_shared<const geometry::ConvexPolytope>(std::move(polytopes[i]));
    piece.origin = what + " mesh piece " + std::to_string(i);
    out.push_back(std::move(piece));
  }
  return out;
}

}  // namespace detail

namespace detail {

/// The body and the world pieces of obstacle o, appended to `set` (its tree not rebuilt).
void appendObstacle(PieceSet& set, const ObstacleData& o) {
  const int body = static_cast<int>(set.bodies.size());
  WorldBody b;
  b.ref.kind = BodyRef::Kind::Obstacle;
  b.ref.index = o.id;
  b.name = "obstacle/" + o.source.name;
  set.bodies.push_back(b);
  for (std::size_t i = 0; i < o.pieces.size(); ++i) {
    const std::uint64_t uid = (static_cast<std::uint64_t>(o.id) << 24) | i;
    set.pieces.push_back(makeWorldPiece(o.pieces[i], o.source.X_WO, body, uid));
  }
}

std::shared_ptr<const PieceSet> buildObstaclePieces(const std::vector<std::shared_ptr<const ObstacleData>>& obstacles,
                                                    const PieceTreeFactory* external) {
  auto set = std::make_shared<PieceSet>();
  for (const auto& o : obstacles) appendObstacle(*set, *o);
  finishPieceSet(*set, external);
  return set;
}

}  // namespace detail

namespace {

/// The narrow phase's own check of a pose (finite, a rotation within geometry::tol::kOrthonormal),
/// made once when an obstacle is placed: isFree's narrow phase skips it (overlapsUnchecked).
void checkObstaclePose(const Eigen::Isometry3d& X_WO, const std::string& name) {
  geometry::checkPose(X_WO, ("obstacle '" + name + "'").c_str());
}

std::size_t findObstacle(const Snapshot& s, int id) {
  for (std::size_t i = 0; i < s.obstacles.size(); ++i) {
    if (s.obstacles[i]->id == id) return i;
  }
  throw std::invalid_argument("no obstacle with id " + std::to_string(id));
}

}  // namespace

int World::addObstacle(const Obstacle& obstacle) { return addObstacles({obstacle}).front(); }

std::vector<int> World::addObstacles(const std::vector<Obstacle>& obstacles) {
  std::vector<int> ids = addObstaclesLocked(obstacles);
  detail::reportFixedPairs(*this, *state_);
  return ids;
}

std::vector<int> World::addObstaclesLocked(const std::vector<Obstacle>& obstacles) {
  WorldState& st = *state_;
  // Under the lock: the decomposer records the geometry excess in state shared by the world's
  // changes. Every obstacle's pieces are made before the world changes: a bad one leaves it as it was.
  std::lock_guard<std::mutex> lock(st.mutex);
  std::vector<std::shared_ptr<ObstacleData>> added;
  added.reserve(obstacles.size());
  detail::Progress progress(st.options.progress, "obstacles made into pieces", obstacles.size(),
                            tol::kProgressQuietSeconds);
  for (const Obstacle& obstacle : obstacles) {
    progress.update(added.size());
    if (obstacle.name.empty()) throw std::invalid_argument("addObstacle: the obstacle has no name");
    checkObstaclePose(obstacle.X_WO, obstacle.name);
    auto data = std::make_shared<ObstacleData>();
    data->source = obstacle;
    data->pieces = detail::piecesOfGeometry(obstacle.geometry, obstacle.mesh.get(), st.geometry,
                                            "obstacle '" + obstacle.name + "'");
    added.push_back(std::move(data));
  }
  auto snap = std::make_shared<Snapshot>(*st.current);
  // The pieces of the obstacles already there are kept as they are; only the tree is rebuilt.
  auto pieces = std::make_shared<PieceSet>(*snap->obstaclePieces);
  std::vector<int> ids;
  for (const auto& data : added) {
    data->id = st.nextObstacleId++;
    ids.push_back(data->id);
    snap->obstacles.push_back(data);
    detail::appendObstacle(*pieces, *data);
  }
  detail::finishPieceSet(*pieces, st.options.externalBroadPhase.get());
  snap->obstaclePieces = pieces;
  publish(st, snap);
  return ids;
}

void World::removeObstacle(int id) {
  WorldState& st = *state_;
  std::lock_guard<std::mutex> lock(st.mutex);
  const std::size_t i = findObstacle(*st.current, id);
  auto snap = std::make_shared<Snapshot>(*st.current);
  snap->obstacles.erase(snap->obstacles.begin() + static_cast<std::ptrdiff_t>(i));
  snap->obstaclePieces = buildObstaclePieces(snap->obstacles, st.options.externalBroadPhase.get());
  publish(st, snap);
}

void World::setObstaclePose(int id, const Eigen::Isometry3d& X_WO) {
  WorldState& st = *state_;
  std::lock_guard<std::mutex> lock(st.mutex);
  const std::size_t i = findObstacle(*st.current, id);
  checkObstaclePose(X_WO, st.current->obstacles[i]->source.name);
  auto snap = std::make_shared<Snapshot>(*st.current);
  auto moved = std::make_shared<ObstacleData>(*snap->obstacles[i]);
  moved->source.X_WO = X_WO;
  snap->obstacles[i] = moved;
  snap->obstaclePieces = buildObstaclePieces(snap->obstacles, st.options.externalBroadPhase.get());
  publish(st, snap);
}

std::vector<int> World::obstacleIds() const {
  const auto snap = state_->snapshot();
  std::vector<int> ids;
  for (const auto& o : snap->obstacles) ids.push_back(o->id);
  return ids;
}

Obstacle World::obstacle(int id) const {
  const auto snap = state_->snapshot();
  return snap->obstacles[findObstacle(*snap, id)]->source;
}

}  // namespace deepcheck::checker
