// World construction: the robot, its scenes and self pairs, and the world's changes other than
// obstacles (world_obstacles.cpp). The queries are in world_is_free.cpp and world_distance.cpp,
// the description in world_summary.cpp.

#include "deepcheck/checker/world.h"

#include "progress.h"
#include "self_pair_grid_cache.h"
#include "world_internal.h"

#include "deepcheck/geometry/pair_frame.h"
#include "deepcheck/robots/format_number.h"
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

using detail::buildObstaclePieces;
using detail::finishPieceSet;
using detail::LinkGeometry;
using detail::makeWorldPiece;
using detail::ObstacleData;
using detail::PieceSet;
using detail::publish;
using detail::RobotData;
using detail::RobotPiece;
using detail::SceneData;
using detail::SelfPair;
using detail::Snapshot;
using detail::WorldBody;
using detail::WorldPiece;
using detail::WorldState;

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

/// robots::collisionPieces of `model`, with a progress line per mesh made into pieces once the
/// step runs long (`what` names the model in it).
std::vector<std::vector<robots::CollisionPiece>> piecesWithProgress(const robots::RobotModel& model,
                                                                    const robots::CollisionGeometryOptions& geometry,
                                                                    std::ostream* out, const std::string& what) {
  std::size_t total = 0;
  for (int l = 0; l < model.numLinks(); ++l) {
    for (const auto& c : model.link(l).collisions) total += c.geometry.type == robots::GeometryType::Mesh;
  }
  detail::Progress progress(out, what + ": meshes made into pieces", total, tol::kProgressQuietSeconds);
  std::size_t meshes = 0;
  robots::CollisionGeometryOptions counted = geometry;
  counted.decomposer = [&](const robots::TriangleMesh& mesh) {
    std::vector<geometry::ConvexPolytope> polytopes =
        geometry.decomposer ? geometry.decomposer(mesh) : robots::convexHullDecomposer(mesh);
    progress.update(++meshes);
    return polytopes;
  };
  return robots::collisionPieces(model, counted);
}

std::shared_ptr<const RobotData> buildRobot(robots::RobotModel model, const robots::CollisionGeometryOptions& geometry,
                                            std::ostream* progress) {
  auto robot = std::make_shared<RobotData>(RobotData{std::move(model), {}, {}, {}, {}, nullptr});
  const robots::RobotModel& m = robot->model;
  const std::vector<std::vector<robots::CollisionPiece>> pieces =
      piecesWithProgress(m, geometry, progress, "robot '" + m.name() + "'");
  std::vector<bool> hasGeometry(m.numLinks(), false);
  for (int l = 0; l < m.numLinks(); ++l) {
    if (pieces[l].empty()) continue;
    hasGeometry[l] = true;
    detail::appendLinkGeometry(*robot, l, -1, pieces[l], Eigen::Isometry3d::Identity());
  }
  robot->reach = linkReachSpheres(m, pieces);
  robot->linkPairs = std::make_shared<const LinkPairIndex>(m, hasGeometry);
  return robot;
}

}  // namespace

namespace detail {

void appendLinkGeometry(RobotData& robot, int link, int attached, const std::vector<robots::CollisionPiece>& pieces,
                        const Eigen::Isometry3d& X_LB) {
  LinkGeometry lg;
  lg.link = link;
  lg.attached = attached;
  lg.firstPiece = static_cast<int>(robot.pieces.size());
  lg.numPieces = static_cast<int>(pieces.size());
  Aabb box;
  for (const robots::CollisionPiece& p : pieces) {
    RobotPiece rp;
    rp.core = p.core;
    rp.radius = p.radius;
    rp.X_LP = X_LB * p.X_LP;
    rp.center_L = rp.X_LP * p.core->center();
    rp.sphereRadius = detail::padRadius(p.core->boundingRadius() + p.radius, rp.center_L);
    rp.obb_L = Obb::ofPiece(*p.core, p.radius).transformed(rp.X_LP);
    rp.link = link;
    rp.group = static_cast<int>(robot.links.size());
    box.extend(Aabb::ofSphere(rp.center_L, rp.sphereRadius));
    robot.pieces.push_back(rp);
  }
  lg.center_L = box.center();
  double r = 0.0;
  for (int i = lg.firstPiece; i < lg.firstPiece + lg.numPieces; ++i) {
    const RobotPiece& rp = robot.pieces[i];
    r = std::max(r, (rp.center_L - lg.center_L).norm() + rp.sphereRadius);
  }
  lg.radius = detail::padRadius(r, lg.center_L);
  robot.links.push_back(lg);
  std::vector<int>& chain = robot.chains.emplace_back();
  const robots::RobotModel& m = robot.model;
  for (int l = link; m.link(l).parentJoint >= 0; l = m.link(l).parentLink) {
    const int j = m.link(l).parentJoint;
    if (m.joint(j).moves() && m.joint(j).variable >= 0) chain.push_back(j);
  }
}

WorldPiece makeWorldPiece(const robots::CollisionPiece& p, const Eigen::Isometry3d& X_WB, int body, std::uint64_t uid) {
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

void finishPieceSet(PieceSet& set, const PieceTreeFactory* external) {
  std::vector<Aabb> boxes;
  boxes.reserve(set.pieces.size());
  for (const WorldPiece& p : set.pieces) boxes.push_back(p.box);
  set.tree = AabbTree(boxes);
  set.external = external != nullptr && !boxes.empty() ? external->build(boxes) : nullptr;
}

}  // namespace detail

namespace {

/// The scene pieces of `old` plus those of the new scene `scene` (index `sceneIndex`) that pass
/// the reach filter; fills the scene's kept / dropped counts.
std::shared_ptr<const PieceSet> appendScenePieces(const PieceSet& old, const RobotData& robot, SceneData& scene,
                                                  int sceneIndex,
                                                  const std::vector<std::vector<robots::CollisionPiece>>& pieces,
                                                  double reachMargin, const PieceTreeFactory* external) {
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
      if (!detail::reachable(robot.reach, w.box, reachMargin)) {
        ++scene.piecesDropped;
        scene.dropped.push_back({l, std::move(w)});
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
  finishPieceSet(*set, external);
  return set;
}

/// Counts the disabled link pairs of `s` by reason (adjacent before rigid before by name), over
/// the pairs of links with geometry; returns the pairs disabled by name only (allowed collisions).
std::set<std::pair<int, int>> countDisabledPairs(Snapshot& s, const WorldOptions& options) {
  const RobotData& robot = *s.robot;
  const LinkPairIndex& index = *robot.linkPairs;
  const long long adjacentAndRigid = options.disableAdjacent ? index.numAdjacentAndRigid() : 0;
  s.disabledAdjacent = static_cast<int>(options.disableAdjacent ? index.numAdjacent() : 0);
  s.disabledRigid = static_cast<int>(options.disableRigid ? index.numRigid() - adjacentAndRigid : 0);
  std::set<std::pair<int, int>> byName;
  for (const auto& [a, b] : detail::allowedLinkPairs(s)) {
    if ((options.disableAdjacent && index.adjacent(a, b)) || (options.disableRigid && index.rigid(a, b))) continue;
    byName.insert({a, b});
  }
  s.disabledByUser = static_cast<int>(byName.size());
  return byName;
}

/// True when the attached object of robot geometry a may not touch robot geometry b (a link's or
/// another attached object's): b is on its link, a touch link, rigidly attached to its link (with
/// disableRigid), or the pair is allowed by name.
bool attachedPairDisabled(const Snapshot& s, const WorldOptions& options, int a, int b) {
  const RobotData& robot = *s.robot;
  const detail::AttachedData& object = *s.attached[static_cast<std::size_t>(robot.links[a].attached)];
  const int other = robot.links[b].link;
  if (other == object.link) return true;
  if (std::find(object.touchLinks.begin(), object.touchLinks.end(), other) != object.touchLinks.end()) return true;
  if (options.disableRigid && robot.linkPairs->rigid(object.link, other)) return true;
  return detail::allowedByName(s.allowed, detail::groupAliases(s, a), detail::groupAliases(s, b));
}

/// Self pairs of the attached objects (robot geometries from `first` on) with every robot
/// geometry before them, unless disabled (attachedPairDisabled). No reach filter, no grid.
void addAttachedSelfPairs(Snapshot& s, const WorldOptions& options, int first) {
  const RobotData& robot = *s.robot;
  for (int a = first; a < static_cast<int>(robot.links.size()); ++a) {
    for (int b = 0; b < a; ++b) {
      if (attachedPairDisabled(s, options, a, b)) continue;
      s.selfPairs.push_back({b, a, s.selfCacheSize, nullptr});
      s.selfCacheSize += robot.links[a].numPieces * robot.links[b].numPieces;
    }
  }
}

/// Self pairs of `robot` that can come within the reach margin (reach.h), minus the adjacent and
/// rigid ones (when asked) and the user's.
void buildSelfPairs(Snapshot& s, const WorldOptions& options) {
  const RobotData& robot = *s.robot;
  // Grids depend on the robot only: those of pairs already built are kept.
  std::map<std::pair<int, int>, std::shared_ptr<const detail::SelfPairGrid>> grids;
  for (const SelfPair& p : s.selfPairs) grids[{p.a, p.b}] = p.grid;
  const std::set<std::pair<int, int>> byName = countDisabledPairs(s, options);
  const LinkPairIndex& index = *robot.linkPairs;
  auto disabled = [&](int a, int b) {
    return (options.disableAdjacent && index.adjacent(a, b)) || (options.disableRigid && index.rigid(a, b)) ||
           byName.count({a, b}) > 0;
  };
  std::vector<int> links;
  for (const LinkGeometry& g : robot.links) {
    if (g.attached < 0) links.push_back(g.link);
  }
  s.selfPairs.clear();
  s.selfCacheSize = 0;
  const std::vector<std::pair<int, int>> reachable = pairsWithinReach(robot.reach, links, options.reachMargin);
  detail::Progress progress(options.progress, "robot '" + robot.model.name() + "': self pairs", reachable.size(),
                            tol::kProgressQuietSeconds);
  const detail::SelfPairGridCache gridCache = detail::SelfPairGridCache::besideDecompositionCache(options);
  for (std::size_t k = 0; k < reachable.size(); ++k) {
    progress.update(k);
    const auto [a, b] = reachable[k];
    if (disabled(links[a], links[b])) continue;
    auto known = grids.find({a, b});
    s.selfPairs.push_back({a, b, s.selfCacheSize,
                           known != grids.end() ? known->second
                           : s.shortcuts.selfPairGrids
                               ? detail::SelfPairGrid::build(robot, a, b, &gridCache, options.progress)
                               : nullptr});
    s.selfCacheSize += robot.links[a].numPieces * robot.links[b].numPieces;
  }
  const long long n = static_cast<long long>(links.size());
  const long long disabledPairs = static_cast<long long>(s.disabledAdjacent) + s.disabledRigid + s.disabledByUser;
  s.unreachablePairs = static_cast<int>(n * (n - 1) / 2 - disabledPairs - static_cast<long long>(s.selfPairs.size()));
  addAttachedSelfPairs(s, options, static_cast<int>(links.size()));
}

std::pair<int, int> linkPairByName(const robots::RobotModel& model, const std::string& a, const std::string& b) {
  const int ia = model.linkIndex(a);
  const int ib = model.linkIndex(b);
  if (ia < 0) throw std::invalid_argument("robot '" + model.name() + "' has no link '" + a + "' (disabled pair)");
  if (ib < 0) throw std::invalid_argument("robot '" + model.name() + "' has no link '" + b + "' (disabled pair)");
  return {std::min(ia, ib), std::max(ia, ib)};
}

}  // namespace

// --- World -----------------------------------------------------------------------------------

namespace detail {

void publish(WorldState& st, std::shared_ptr<Snapshot> snap) {
  buildAllowedMasks(*snap);
  snap->excess =
      std::isnan(*st.excessSink) ? *st.excessSink : std::max(*st.excessSink, st.options.geometry.cylinderMaxDeviation);
  st.current = std::move(snap);
  st.generation.fetch_add(1, std::memory_order_acq_rel);
}

void rebuildSelfPairs(Snapshot& s, const WorldOptions& options) { buildSelfPairs(s, options); }

bool reachable(const std::vector<ReachSphere>& reach, const Aabb& box, double margin) {
  for (const ReachSphere& r : reach) {
    if (r.valid && box.distance(r.center_W) - r.radius <= margin) return true;
  }
  return false;
}

namespace {

/// The index of scene link `link`'s body in `set` (scene `scene`), made when it has none yet.
int sceneBody(PieceSet& set, const SceneData& data, int scene, int link) {
  for (std::size_t b = 0; b < set.bodies.size(); ++b) {
    const BodyRef& ref = set.bodies[b].ref;
    if (ref.kind == BodyRef::Kind::SceneLink && ref.scene == scene && ref.index == link) return static_cast<int>(b);
  }
  WorldBody body;
  body.ref.kind = BodyRef::Kind::SceneLink;
  body.ref.index = link;
  body.ref.scene = scene;
  body.name = "scene/" + data.model.link(link).name;
  set.bodies.push_back(body);
  return static_cast<int>(set.bodies.size()) - 1;
}

}  // namespace

void reclaimScenePieces(Snapshot& s, double reachMargin, const PieceTreeFactory* external) {
  std::shared_ptr<PieceSet> set;
  for (std::size_t k = 0; k < s.scenes.size(); ++k) {
    const SceneData& old = *s.scenes[k];
    const auto reached = [&](const DroppedPiece& d) { return reachable(s.robot->reach, d.piece.box, reachMargin); };
    if (std::none_of(old.dropped.begin(), old.dropped.end(), reached)) continue;
    if (set == nullptr) set = std::make_shared<PieceSet>(*s.scenePieces);
    auto data = std::make_shared<SceneData>(old);
    data->dropped.clear();
    for (const DroppedPiece& d : old.dropped) {
      if (!reached(d)) {
        data->dropped.push_back(d);
        continue;
      }
      WorldPiece w = d.piece;
      w.body = sceneBody(*set, *data, static_cast<int>(k), d.link);
      w.uid = set->pieces.size();
      set->pieces.push_back(std::move(w));
      ++data->piecesKept;
      --data->piecesDropped;
    }
    s.scenes[k] = data;
  }
  if (set == nullptr) return;
  finishPieceSet(*set, external);
  s.scenePieces = set;
}

}  // namespace detail

World::World(robots::RobotModel robot, const WorldOptions& options) : state_(std::make_shared<WorldState>()) {
  if (!(options.reachMargin >= 0)) {
    throw std::invalid_argument("World: reachMargin must be >= 0, is " + robots::formatNumber(options.reachMargin));
  }
  WorldState& st = *state_;
  st.options = options;
  st.uid = nextWorldUid();
  st.geometry = options.geometry;
  auto excess = std::make_shared<double>(0.0);
  if (!st.geometry.decomposer) {
    st.geometry.decomposer =
        robots::meshDecomposer({options.decompose, options.decomposition, options.decompositionCacheDir}, excess);
  } else {
    *excess = std::numeric_limits<double>::quiet_NaN();  // a custom decomposer: unknown
  }
  auto snap = std::make_shared<Snapshot>();
  snap->robot = buildRobot(std::move(robot), st.geometry, options.progress);
  st.robot = snap->robot;
  robots::checkDisabledPairs(snap->robot->model, options.disabledPairs, "WorldOptions::disabledPairs");
  for (const robots::DisabledPair& p : options.disabledPairs) {
    // An SRDF's disabled pairs are allowed collisions like any other (world_allowed.cpp).
    snap->allowed.pairs.insert(std::minmax(p.link1, p.link2));
  }
  buildSelfPairs(*snap, options);
  {
    auto empty = std::make_shared<PieceSet>();
    finishPieceSet(*empty, options.externalBroadPhase.get());
    snap->scenePieces = empty;
  }
  snap->obstaclePieces = buildObstaclePieces({}, options.externalBroadPhase.get());
  // The decomposer keeps recording into `excess` for later scenes and obstacles.
  st.excessSink = excess;
  std::lock_guard<std::mutex> lock(st.mutex);
  publish(st, snap);
}

World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;
World::~World() = default;

int World::addScene(robots::RobotModel scene, const SceneSpec& placement) {
  const int index = addSceneLocked(std::move(scene), placement);
  detail::reportFixedPairs(*this, *state_);
  return index;
}

int World::addSceneLocked(robots::RobotModel scene, const SceneSpec& options) {
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
  auto data = std::make_shared<SceneData>(SceneData{std::move(scene), std::move(q), std::move(X_WL), 0, 0, 0, {}});

  const std::vector<std::vector<robots::CollisionPiece>> pieces =
      piecesWithProgress(data->model, st.geometry, st.options.progress, "scene '" + data->model.name() + "'");
  auto snap = std::make_shared<Snapshot>(*st.current);
  const int index = static_cast<int>(snap->scenes.size());
  snap->scenePieces = appendScenePieces(*snap->scenePieces, *snap->robot, *data, index, pieces, st.options.reachMargin,
                                        st.options.externalBroadPhase.get());
  snap->scenes.push_back(data);
  publish(st, snap);
  return static_cast<int>(snap->scenes.size()) - 1;
}

int World::addScene(robots::RobotModel scene, const Eigen::Isometry3d& X_WS) {
  SceneSpec placement;
  placement.overridePose = true;
  placement.X_WS = X_WS;
  return addScene(std::move(scene), placement);
}

void World::disablePair(const std::string& linkA, const std::string& linkB) {
  WorldState& st = *state_;
  std::lock_guard<std::mutex> lock(st.mutex);
  auto snap = std::make_shared<Snapshot>(*st.current);
  linkPairByName(snap->robot->model, linkA, linkB);  // both must be robot links
  snap->allowed.pairs.insert(std::minmax(linkA, linkB));
  buildSelfPairs(*snap, st.options);
  publish(st, snap);
}

const robots::RobotModel& World::robot() const { return state_->robot->model; }

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

std::vector<std::pair<int, int>> World::allowedSelfPairs() const {
  const auto snap = state_->snapshot();
  std::vector<std::pair<int, int>> out;
  for (const SelfPair& p : snap->selfPairs) {
    const LinkGeometry& a = snap->robot->links[p.a];
    const LinkGeometry& b = snap->robot->links[p.b];
    if (a.attached < 0 && b.attached < 0) out.emplace_back(a.link, b.link);
  }
  return out;
}

std::uint64_t World::version() const { return state_->generation.load(std::memory_order_acquire); }

}  // namespace deepcheck::checker
