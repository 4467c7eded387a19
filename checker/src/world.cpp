// World construction, changes (scenes, obstacles, disabled pairs) and description. The queries
// are in world_queries.cpp.

#include "deepcheck/checker/world.h"

#include "external_broad_phase.h"
#include "world_internal.h"

#include "deepcheck/deep/pair_frame.h"
#include "deepcheck/robots/decomposition_cache.h"
#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/mesh_loader.h"
#include "deepcheck/robots/pair_filter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace deepcheck::checker {

using detail::LinkGeometry;
using detail::ObstacleData;
using detail::PieceSet;
using detail::RobotData;
using detail::RobotPiece;
using detail::SceneData;
using detail::SelfPair;
using detail::Snapshot;
using detail::WorldBody;
using detail::WorldPiece;
using detail::WorldState;

const char* toString(BroadPhase b) {
  switch (b) {
    case BroadPhase::AabbTree: return "aabb-tree";
    case BroadPhase::FclTree: return "fcl-dynamic-aabb-tree";
    case BroadPhase::None: return "none";
  }
  return "unknown";
}

// --- obstacles -------------------------------------------------------------------------------

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

Obstacle Obstacle::cylinder(const std::string& name, double radius, double length,
                            const Eigen::Isometry3d& X_WO) {
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
  auto finite = [](double v) { return std::isfinite(v); };
  std::vector<robots::CollisionPiece> out;
  robots::CollisionPiece piece;
  switch (g.type) {
    case robots::GeometryType::Box:
      if (!(g.boxSize.array() > 0).all() || !g.boxSize.allFinite()) {
        std::ostringstream msg;
        msg << what << ": box size (" << g.boxSize.transpose() << ") must be positive and finite";
        throw std::invalid_argument(msg.str());
      }
      piece.core = std::make_shared<const deep::ConvexPolytope>(deep::ConvexPolytope::box(0.5 * g.boxSize));
      piece.origin = what + " box";
      out.push_back(piece);
      break;
    case robots::GeometryType::Sphere:
      if (!(g.radius > 0) || !finite(g.radius)) {
        throw std::invalid_argument(what + ": sphere radius " + std::to_string(g.radius) +
                                    " must be positive and finite");
      }
      piece.core = std::make_shared<const deep::ConvexPolytope>(
          deep::ConvexPolytope::fromPoints({Eigen::Vector3d::Zero()}, what));
      piece.radius = g.radius;
      piece.origin = what + " sphere";
      out.push_back(piece);
      break;
    case robots::GeometryType::Cylinder:
      if (!(g.radius > 0) || !finite(g.radius) || !(g.length > 0) || !finite(g.length)) {
        throw std::invalid_argument(what + ": cylinder radius " + std::to_string(g.radius) + " and length " +
                                    std::to_string(g.length) + " must be positive and finite");
      }
      piece.core = std::make_shared<const deep::ConvexPolytope>(
          robots::cylinderPrism(g.radius, g.length, options.cylinderMaxDeviation));
      piece.origin = what + " cylinder";
      out.push_back(piece);
      break;
    case robots::GeometryType::Mesh: {
      robots::TriangleMesh loaded;
      if (mesh == nullptr) {
        if (g.meshPath.empty()) throw std::invalid_argument(what + ": a mesh needs a file or a TriangleMesh");
        if (!g.meshScale.allFinite() || !(g.meshScale.array() != 0).all()) {
          std::ostringstream msg;
          msg << what << ": mesh scale (" << g.meshScale.transpose() << ") must be finite and non-zero";
          throw std::invalid_argument(msg.str());
        }
        try {
          loaded = robots::loadMesh(g.meshPath, g.meshScale);
        } catch (const std::exception& e) {
          throw std::invalid_argument(what + ": " + e.what());
        }
        mesh = &loaded;
      }
      if (mesh->empty()) throw std::invalid_argument(what + ": the mesh has no triangle");
      std::vector<deep::ConvexPolytope> polytopes;
      try {
        polytopes = options.decomposer ? options.decomposer(*mesh) : robots::convexHullDecomposer(*mesh);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(what + ": " + e.what());
      }
      if (polytopes.empty()) throw std::invalid_argument(what + ": the mesh decomposer returned no piece");
      for (std::size_t i = 0; i < polytopes.size(); ++i) {
        piece.core = std::make_shared<const deep::ConvexPolytope>(std::move(polytopes[i]));
        piece.origin = what + " mesh piece " + std::to_string(i);
        out.push_back(piece);
      }
      break;
    }
  }
  return out;
}

}  // namespace detail

// --- adjacency -------------------------------------------------------------------------------

std::vector<std::pair<int, int>> rigidLinkPairs(const robots::RobotModel& model, const std::vector<bool>& hasGeometry) {
  const int n = model.numLinks();
  if (static_cast<int>(hasGeometry.size()) != n) {
    throw std::invalid_argument("rigidLinkPairs: robot '" + model.name() + "' has " + std::to_string(n) +
                                " links, hasGeometry has " + std::to_string(hasGeometry.size()) + " entries");
  }
  // Rigid groups: links joined by fixed joints. Parents precede children, so one pass suffices.
  std::vector<int> group(n);
  for (int l = 0; l < n; ++l) {
    const robots::Link& link = model.link(l);
    group[l] = (link.parentJoint >= 0 && !model.joint(link.parentJoint).moves()) ? group[link.parentLink] : l;
  }
  std::vector<std::pair<int, int>> out;
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      if (hasGeometry[a] && hasGeometry[b] && group[a] == group[b]) out.emplace_back(a, b);
    }
  }
  return out;
}

// --- building --------------------------------------------------------------------------------

namespace {

std::uint64_t nextWorldUid() {
  static std::atomic<std::uint64_t> counter{1};
  return counter.fetch_add(1);
}

/// The default mesh decomposer of a world: convex decomposition through the on-disk cache; it
/// records the largest concavity reached in `excess`.
robots::MeshDecomposer makeDecomposer(const WorldOptions& options, std::shared_ptr<double> excess) {
  if (!options.decompose) {
    return [excess](const robots::TriangleMesh& mesh) {
      // One hull: how far it sticks out of the mesh is not measured here.
      *excess = std::numeric_limits<double>::quiet_NaN();
      return robots::convexHullDecomposer(mesh);
    };
  }
  options.decomposition.validate();
  const robots::DecompositionParams params = options.decomposition;
  const robots::DecompositionCache cache(options.decompositionCacheDir);
  return [params, cache, excess](const robots::TriangleMesh& mesh) {
    const robots::ConvexDecomposition d = robots::decomposeConvexCached(mesh, params, cache);
    if (!std::isnan(*excess)) *excess = std::max(*excess, d.report.concavity);
    return d.polytopes();
  };
}

std::shared_ptr<const RobotData> buildRobot(robots::RobotModel model, const robots::CollisionGeometryOptions& geometry) {
  auto robot = std::make_shared<RobotData>(RobotData{std::move(model), {}, {}, {}, {}, {}});
  const robots::RobotModel& m = robot->model;
  const std::vector<std::vector<robots::CollisionPiece>> pieces = robots::collisionPieces(m, geometry);
  std::vector<bool> hasGeometry(m.numLinks(), false);
  for (int l = 0; l < m.numLinks(); ++l) {
    if (pieces[l].empty()) continue;
    hasGeometry[l] = true;
    LinkGeometry lg;
    lg.link = l;
    lg.firstPiece = static_cast<int>(robot->pieces.size());
    lg.numPieces = static_cast<int>(pieces[l].size());
    Aabb box;
    for (const robots::CollisionPiece& p : pieces[l]) {
      RobotPiece rp;
      rp.core = p.core;
      rp.radius = p.radius;
      rp.X_LP = p.X_LP;
      rp.center_L = p.X_LP * p.core->center();
      rp.sphereRadius = detail::padRadius(p.core->boundingRadius() + p.radius, rp.center_L);
      rp.obb_L = Obb::ofPiece(*p.core, p.radius).transformed(p.X_LP);
      rp.link = l;
      box.extend(Aabb::ofSphere(rp.center_L, rp.sphereRadius));
      robot->pieces.push_back(rp);
    }
    lg.center_L = box.center();
    double r = 0.0;
    for (int i = lg.firstPiece; i < lg.firstPiece + lg.numPieces; ++i) {
      const RobotPiece& rp = robot->pieces[i];
      r = std::max(r, (rp.center_L - lg.center_L).norm() + rp.sphereRadius);
    }
    lg.radius = detail::padRadius(r, lg.center_L);
    robot->links.push_back(lg);
  }
  robot->reach = linkReachSpheres(m, pieces);
  robot->adjacent = robots::adjacentLinkPairs(m, pieces);
  robot->rigid = rigidLinkPairs(m, hasGeometry);
  return robot;
}

WorldPiece makeWorldPiece(const robots::CollisionPiece& p, const Eigen::Isometry3d& X_WB, int body,
                          std::uint64_t uid) {
  WorldPiece w;
  w.core = p.core;
  w.radius = p.radius;
  w.X_WP = X_WB * p.X_LP;
  w.center_W = w.X_WP * p.core->center();
  w.sphereRadius = detail::padRadius(p.core->boundingRadius() + p.radius, w.center_W);
  // The box of the piece's vertices (tighter than the sphere's), grown by the radius and padding.
  for (const Eigen::Vector3d& v : p.core->vertices()) w.box.extend(w.X_WP * v);
  const double pad = p.radius + tol::kBoundingRelative * (p.core->boundingRadius() + p.radius + w.center_W.norm());
  w.box.lo.array() -= pad;
  w.box.hi.array() += pad;
  w.obb_W = Obb::ofPiece(*p.core, p.radius).transformed(w.X_WP);
  w.body = body;
  w.uid = uid;
  return w;
}

void finishPieceSet(PieceSet& set, BroadPhase broadPhase) {
  std::vector<Aabb> boxes;
  boxes.reserve(set.pieces.size());
  for (const WorldPiece& p : set.pieces) boxes.push_back(p.box);
  set.tree = AabbTree(boxes);
  if (broadPhase == BroadPhase::FclTree) set.fclTree = detail::makeExternalPieceTree(broadPhase, boxes);
}

/// The scene pieces of `old` plus those of the new scene `scene` (index `sceneIndex`) that pass
/// the reach filter; fills the scene's kept / dropped counts.
std::shared_ptr<const PieceSet> appendScenePieces(const PieceSet& old, const RobotData& robot, SceneData& scene,
                                                  int sceneIndex,
                                                  const std::vector<std::vector<robots::CollisionPiece>>& pieces,
                                                  double reachMargin, BroadPhase broadPhase) {
  auto set = std::make_shared<PieceSet>();
  set->pieces = old.pieces;
  set->bodies = old.bodies;
  for (int l = 0; l < scene.model.numLinks(); ++l) {
    if (pieces[l].empty()) continue;
    ++scene.linksWithGeometry;
    const int body = static_cast<int>(set->bodies.size());
    bool anyKept = false;
    for (const robots::CollisionPiece& p : pieces[l]) {
      WorldPiece w = makeWorldPiece(p, scene.X_WL[l], body, set->pieces.size());
      bool reachable = false;
      for (const ReachSphere& r : robot.reach) {
        if (r.valid && w.box.distance(r.center_W) - r.radius <= reachMargin) {
          reachable = true;
          break;
        }
      }
      if (!reachable) {
        ++scene.piecesDropped;
        continue;
      }
      ++scene.piecesKept;
      anyKept = true;
      set->pieces.push_back(std::move(w));
    }
    if (anyKept) {
      WorldBody b;
      b.ref.kind = BodyRef::Kind::SceneLink;
      b.ref.index = l;
      b.ref.scene = sceneIndex;
      b.name = "scene/" + scene.model.link(l).name;
      set->bodies.push_back(b);
    }
  }
  finishPieceSet(*set, broadPhase);
  return set;
}

std::shared_ptr<const PieceSet> buildObstaclePieces(const std::vector<std::shared_ptr<const ObstacleData>>& obstacles,
                                                    BroadPhase broadPhase) {
  auto set = std::make_shared<PieceSet>();
  for (const auto& o : obstacles) {
    const int body = static_cast<int>(set->bodies.size());
    WorldBody b;
    b.ref.kind = BodyRef::Kind::Obstacle;
    b.ref.index = o->id;
    b.name = "obstacle/" + o->source.name;
    set->bodies.push_back(b);
    for (std::size_t i = 0; i < o->pieces.size(); ++i) {
      const std::uint64_t uid = (static_cast<std::uint64_t>(o->id) << 24) | i;
      set->pieces.push_back(makeWorldPiece(o->pieces[i], o->source.X_WO, body, uid));
    }
  }
  finishPieceSet(*set, broadPhase);
  return set;
}

/// Self pairs of `robot` minus the adjacent and rigid ones (when asked) and the user's.
void buildSelfPairs(Snapshot& s, const WorldOptions& options) {
  const RobotData& robot = *s.robot;
  // Grids depend on the robot only: those of pairs already built are kept.
  std::map<std::pair<int, int>, std::shared_ptr<const detail::SelfPairGrid>> grids;
  for (const SelfPair& p : s.selfPairs) grids[{p.a, p.b}] = p.grid;
  std::set<std::pair<int, int>> adjacent(robot.adjacent.begin(), robot.adjacent.end());
  std::set<std::pair<int, int>> rigid(robot.rigid.begin(), robot.rigid.end());
  std::set<std::pair<int, int>> user(s.userDisabled.begin(), s.userDisabled.end());
  s.selfPairs.clear();
  s.selfCacheSize = 0;
  s.disabledAdjacent = 0;
  s.disabledRigid = 0;
  s.disabledByUser = 0;
  const int n = static_cast<int>(robot.links.size());
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      const std::pair<int, int> links(robot.links[a].link, robot.links[b].link);
      if (options.disableAdjacent && adjacent.count(links)) {
        ++s.disabledAdjacent;
        continue;
      }
      if (options.disableRigid && rigid.count(links)) {
        ++s.disabledRigid;
        continue;
      }
      if (user.count(links)) {
        ++s.disabledByUser;
        continue;
      }
      auto known = grids.find({a, b});
      s.selfPairs.push_back({a, b, s.selfCacheSize,
                             known != grids.end()    ? known->second
                             : options.selfPairGrids ? detail::SelfPairGrid::build(robot, a, b)
                                                     : nullptr});
      s.selfCacheSize += robot.links[a].numPieces * robot.links[b].numPieces;
    }
  }
}

std::pair<int, int> linkPairByName(const robots::RobotModel& model, const std::string& a, const std::string& b) {
  const int ia = model.linkIndex(a);
  const int ib = model.linkIndex(b);
  if (ia < 0) throw std::invalid_argument("robot '" + model.name() + "' has no link '" + a + "' (disabled pair)");
  if (ib < 0) throw std::invalid_argument("robot '" + model.name() + "' has no link '" + b + "' (disabled pair)");
  return {std::min(ia, ib), std::max(ia, ib)};
}

/// The narrow phase's own check of a pose (finite, a rotation within deep::tol::kOrthonormal),
/// made once when an obstacle is placed: isFree's narrow phase skips it (overlapsUnchecked).
void checkObstaclePose(const Eigen::Isometry3d& X_WO, const std::string& name) {
  deep::checkPose(X_WO, ("obstacle '" + name + "'").c_str());
}

}  // namespace

// --- World -----------------------------------------------------------------------------------

namespace {

/// Publishes a new snapshot (caller holds the mutex).
void publish(WorldState& st, std::shared_ptr<Snapshot> snap) {
  snap->excess = std::isnan(*st.excessSink) ? *st.excessSink
                                            : std::max(*st.excessSink, st.options.geometry.cylinderMaxDeviation);
  st.current = std::move(snap);
  st.generation.fetch_add(1, std::memory_order_acq_rel);
}

}  // namespace

World::World(robots::RobotModel robot, const WorldOptions& options) : state_(std::make_shared<WorldState>()) {
  if (!(options.reachMargin >= 0)) {
    throw std::invalid_argument("World: reachMargin must be >= 0, is " + std::to_string(options.reachMargin));
  }
  WorldState& st = *state_;
  st.options = options;
  st.uid = nextWorldUid();
  st.geometry = options.geometry;
  auto excess = std::make_shared<double>(0.0);
  if (!st.geometry.decomposer) {
    st.geometry.decomposer = makeDecomposer(options, excess);
  } else {
    *excess = std::numeric_limits<double>::quiet_NaN();  // a custom decomposer: unknown
  }
  auto snap = std::make_shared<Snapshot>();
  snap->robot = buildRobot(std::move(robot), st.geometry);
  robots::checkDisabledPairs(snap->robot->model, options.disabledPairs, "WorldOptions::disabledPairs");
  for (const robots::DisabledPair& p : options.disabledPairs) {
    snap->userDisabled.push_back(linkPairByName(snap->robot->model, p.link1, p.link2));
  }
  buildSelfPairs(*snap, options);
  {
    auto empty = std::make_shared<PieceSet>();
    finishPieceSet(*empty, options.broadPhase);
    snap->scenePieces = empty;
  }
  snap->obstaclePieces = buildObstaclePieces({}, options.broadPhase);
  // The decomposer keeps recording into `excess` for later scenes and obstacles.
  st.excessSink = excess;
  std::lock_guard<std::mutex> lock(st.mutex);
  publish(st, snap);
}

World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;
World::~World() = default;

int World::addScene(robots::RobotModel scene, const SceneOptions& options) {
  WorldState& st = *state_;
  std::lock_guard<std::mutex> lock(st.mutex);
  if (options.overridePose) scene.setBasePose(options.X_WS);
  Eigen::VectorXd q = options.q.size() == 0 ? scene.defaultConfiguration() : Eigen::VectorXd(options.q);
  try {
    robots::checkConfiguration(scene, q);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("scene '" + scene.name() + "': " + e.what());
  }
  std::vector<Eigen::Isometry3d> X_WL = robots::forwardKinematics(scene, q);
  auto data = std::make_shared<SceneData>(SceneData{std::move(scene), std::move(q), std::move(X_WL), 0, 0, 0});

  const std::vector<std::vector<robots::CollisionPiece>> pieces = robots::collisionPieces(data->model, st.geometry);
  auto snap = std::make_shared<Snapshot>(*st.current);
  const int index = static_cast<int>(snap->scenes.size());
  snap->scenePieces = appendScenePieces(*snap->scenePieces, *snap->robot, *data, index, pieces,
                                        st.options.reachMargin, st.options.broadPhase);
  snap->scenes.push_back(data);
  publish(st, snap);
  return static_cast<int>(snap->scenes.size()) - 1;
}

int World::addScene(robots::RobotModel scene, const Eigen::Isometry3d& X_WS) {
  SceneOptions options;
  options.overridePose = true;
  options.X_WS = X_WS;
  return addScene(std::move(scene), options);
}

int World::addObstacle(const Obstacle& obstacle) {
  WorldState& st = *state_;
  if (obstacle.name.empty()) throw std::invalid_argument("addObstacle: the obstacle has no name");
  checkObstaclePose(obstacle.X_WO, obstacle.name);
  std::lock_guard<std::mutex> lock(st.mutex);
  auto data = std::make_shared<ObstacleData>();
  data->source = obstacle;
  data->pieces = detail::piecesOfGeometry(obstacle.geometry, obstacle.mesh.get(), st.geometry,
                                          "obstacle '" + obstacle.name + "'");
  data->id = st.nextObstacleId++;
  auto snap = std::make_shared<Snapshot>(*st.current);
  snap->obstacles.push_back(data);
  snap->obstaclePieces = buildObstaclePieces(snap->obstacles, st.options.broadPhase);
  publish(st, snap);
  return data->id;
}

namespace {

std::size_t findObstacle(const Snapshot& s, int id) {
  for (std::size_t i = 0; i < s.obstacles.size(); ++i) {
    if (s.obstacles[i]->id == id) return i;
  }
  throw std::invalid_argument("no obstacle with id " + std::to_string(id));
}

}  // namespace

void World::removeObstacle(int id) {
  WorldState& st = *state_;
  std::lock_guard<std::mutex> lock(st.mutex);
  const std::size_t i = findObstacle(*st.current, id);
  auto snap = std::make_shared<Snapshot>(*st.current);
  snap->obstacles.erase(snap->obstacles.begin() + static_cast<std::ptrdiff_t>(i));
  snap->obstaclePieces = buildObstaclePieces(snap->obstacles, st.options.broadPhase);
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
  snap->obstaclePieces = buildObstaclePieces(snap->obstacles, st.options.broadPhase);
  publish(st, snap);
}

std::vector<int> World::obstacleIds() const {
  const auto snap = state_->snapshot();
  std::vector<int> ids;
  for (const auto& o : snap->obstacles) ids.push_back(o->id);
  return ids;
}

void World::disablePair(const std::string& linkA, const std::string& linkB) {
  WorldState& st = *state_;
  std::lock_guard<std::mutex> lock(st.mutex);
  auto snap = std::make_shared<Snapshot>(*st.current);
  snap->userDisabled.push_back(linkPairByName(snap->robot->model, linkA, linkB));
  buildSelfPairs(*snap, st.options);
  publish(st, snap);
}

const robots::RobotModel& World::robot() const { return state_->snapshot()->robot->model; }

int World::numScenes() const { return static_cast<int>(state_->snapshot()->scenes.size()); }

const robots::RobotModel& World::scene(int index) const {
  const auto snap = state_->snapshot();
  if (index < 0 || index >= static_cast<int>(snap->scenes.size())) {
    throw std::invalid_argument("no scene with index " + std::to_string(index));
  }
  return snap->scenes[index]->model;  // scenes are never removed: the data outlives the snapshot
}

const Eigen::VectorXd& World::sceneConfiguration(int index) const {
  const auto snap = state_->snapshot();
  if (index < 0 || index >= static_cast<int>(snap->scenes.size())) {
    throw std::invalid_argument("no scene with index " + std::to_string(index));
  }
  return snap->scenes[index]->q;
}

Obstacle World::obstacle(int id) const {
  const auto snap = state_->snapshot();
  return snap->obstacles[findObstacle(*snap, id)]->source;
}

std::vector<std::pair<int, int>> World::allowedSelfPairs() const {
  const auto snap = state_->snapshot();
  std::vector<std::pair<int, int>> out;
  for (const SelfPair& p : snap->selfPairs) out.emplace_back(snap->robot->links[p.a].link, snap->robot->links[p.b].link);
  return out;
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
  }
  throw std::invalid_argument("bodyName: no such body (index " + std::to_string(body.index) + ")");
}

World::Summary World::summaryCounts() const {
  const auto snap = state_->snapshot();
  Summary s;
  const RobotData& r = *snap->robot;
  s.robotLinks = r.model.numLinks();
  s.robotLinksWithGeometry = static_cast<int>(r.links.size());
  s.robotPieces = static_cast<int>(r.pieces.size());
  s.selfPairs = static_cast<int>(snap->selfPairs.size());
  s.selfPiecePairs = snap->selfCacheSize;
  s.disabledAdjacent = snap->disabledAdjacent;
  s.disabledRigid = snap->disabledRigid;
  s.disabledByUser = snap->disabledByUser;
  s.scenes = static_cast<int>(snap->scenes.size());
  for (const auto& sc : snap->scenes) {
    s.sceneLinksWithGeometry += sc->linksWithGeometry;
    s.scenePiecesKept += sc->piecesKept;
    s.scenePiecesDropped += sc->piecesDropped;
  }
  s.obstacles = static_cast<int>(snap->obstacles.size());
  s.obstaclePieces = static_cast<int>(snap->obstaclePieces->pieces.size());
  s.geometryExcess = snap->excess;
  return s;
}

std::string World::summary() const {
  const Summary s = summaryCounts();
  const auto snap = state_->snapshot();
  const robots::RobotModel& m = snap->robot->model;
  std::ostringstream out;
  out << "robot '" << m.name() << "': " << s.robotLinks << " links (" << s.robotLinksWithGeometry
      << " with geometry), " << m.numVariables() << " variables, " << s.robotPieces << " pieces\n";
  out << "self pairs: " << s.selfPairs << " link pairs checked (" << s.selfPiecePairs << " piece pairs), "
      << s.disabledAdjacent << " disabled as adjacent, " << s.disabledRigid << " as rigidly attached, "
      << s.disabledByUser << " by name (SRDF)\n";
  for (std::size_t i = 0; i < snap->scenes.size(); ++i) {
    const SceneData& sc = *snap->scenes[i];
    out << "scene " << i << " '" << sc.model.name() << "': " << sc.model.numLinks() << " links ("
        << sc.linksWithGeometry << " with geometry), pieces kept " << sc.piecesKept << ", dropped "
        << sc.piecesDropped << " (unreachable)\n";
  }
  out << "scene pieces: kept " << s.scenePiecesKept << ", dropped " << s.scenePiecesDropped
      << " (reach margin " << state_->options.reachMargin << " m)\n";
  out << "obstacles: " << s.obstacles << " (" << s.obstaclePieces << " pieces)\n";
  const long long worldPairs = static_cast<long long>(s.robotPieces) * (s.scenePiecesKept + s.obstaclePieces);
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
      << " self piece pairs; broad phase " << toString(state_->options.broadPhase) << "\n";
  char excess[64];
  std::snprintf(excess, sizeof excess, "%.3g", s.geometryExcess);
  out << "geometry excess (pieces beyond the original shapes): " << (std::isnan(s.geometryExcess) ? "unknown" : excess)
      << " m\n";
  return out.str();
}

}  // namespace deepcheck::checker
