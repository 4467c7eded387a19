// Objects attached to robot links: attaching, detaching, and the robot data of a snapshot with
// its attached objects (world.h, header comment).
//
// An attached object is one more robot geometry (LinkGeometry with `attached` set) on the link
// carrying it, after the links' own: its pieces are posed by the link's forward kinematics in
// every query, its gradients are that link's, and its self pairs are made by buildSelfPairs
// (world.cpp). The robot's own data (WorldState::robot) never changes: World::robot() stays valid.

#include "deepcheck/checker/world.h"

#include "near_matches.h"
#include "world_internal.h"

#include "deepcheck/geometry/pair_frame.h"
#include "deepcheck/robots/kinematics.h"

#include <algorithm>
#include <stdexcept>

namespace deepcheck::checker {

using detail::AttachedData;
using detail::ObstacleData;
using detail::Snapshot;
using detail::WorldState;

namespace detail {

void attachToRobot(Snapshot& s, const std::shared_ptr<const RobotData>& own) {
  if (s.attached.empty()) {
    s.robot = own;
    return;
  }
  auto robot = std::make_shared<RobotData>(*own);
  for (std::size_t k = 0; k < s.attached.size(); ++k) {
    const AttachedData& a = *s.attached[k];
    appendLinkGeometry(*robot, a.link, static_cast<int>(k), a.pieces, a.X_LO);
  }
  // The reach spheres of the links holding objects, grown to hold them (reach.h).
  std::vector<std::vector<robots::CollisionPiece>> pieces(static_cast<std::size_t>(robot->model.numLinks()));
  for (const RobotPiece& p : robot->pieces) {
    pieces[static_cast<std::size_t>(p.link)].push_back(robots::CollisionPiece{p.core, p.radius, p.X_LP, ""});
  }
  robot->reach = linkReachSpheres(robot->model, pieces);
  s.robot = robot;
}

}  // namespace detail

namespace {

int linkOf(const robots::RobotModel& model, const std::string& name, const std::string& what) {
  const int l = model.linkIndex(name);
  if (l >= 0) return l;
  std::vector<std::string> names;
  for (const robots::Link& link : model.links()) names.push_back(link.name);
  throw std::invalid_argument(what + ": robot '" + model.name() + "' has no link '" + name + "'" +
                              detail::nearMatchesText(name, names));
}

std::size_t findAttached(const Snapshot& s, const std::string& name, const std::string& what) {
  std::vector<std::string> names;
  for (std::size_t k = 0; k < s.attached.size(); ++k) {
    if (s.attached[k]->source.name == name) return k;
    names.push_back(s.attached[k]->source.name);
  }
  throw std::invalid_argument(what + ": no attached object is named '" + name + "'" +
                              detail::nearMatchesText(name, names));
}

/// The link's pose in the world with the robot at q (empty: its default configuration).
Eigen::Isometry3d linkPose(const robots::RobotModel& model, int link, const Eigen::VectorXd& q) {
  const Eigen::VectorXd at = q.size() == 0 ? model.defaultConfiguration() : q;
  robots::checkConfiguration(model, at);
  return robots::forwardKinematics(model, at)[static_cast<std::size_t>(link)];
}

/// The attached data of `object` on `link` (its pieces already made), checked against `s`.
std::shared_ptr<AttachedData> makeAttached(const Snapshot& s, const std::string& link, const Obstacle& object,
                                           const AttachOptions& options, std::vector<robots::CollisionPiece> pieces) {
  const robots::RobotModel& model = s.robot->model;
  const std::string what = "attach '" + object.name + "'";
  if (object.name.empty()) throw std::invalid_argument("attach: the object has no name");
  for (const auto& a : s.attached) {
    if (a->source.name == object.name) throw std::invalid_argument(what + ": an object of that name is attached");
  }
  geometry::checkPose(object.X_WO, what.c_str());
  auto data = std::make_shared<AttachedData>();
  data->source = object;
  data->link = linkOf(model, link, what);
  for (const std::string& t : options.touchLinks) data->touchLinks.push_back(linkOf(model, t, what + " touch link"));
  data->X_LO = options.worldFrame ? linkPose(model, data->link, options.q).inverse() * object.X_WO : object.X_WO;
  data->pieces = std::move(pieces);
  return data;
}

/// Publishes `snap` with `s.attached` changed: robot data, self pairs and masks made again.
void publishAttached(WorldState& st, std::shared_ptr<Snapshot> snap) {
  detail::attachToRobot(*snap, st.robot);
  detail::reclaimScenePieces(*snap, st.options.reachMargin, st.options.externalBroadPhase.get());
  detail::rebuildSelfPairs(*snap, st.options);
  detail::publish(st, std::move(snap));
}

}  // namespace

void World::attach(const std::string& link, const Obstacle& object, const AttachOptions& options) {
  WorldState& st = *state_;
  {
    std::lock_guard<std::mutex> lock(st.mutex);  // the decomposer records into shared state
    std::vector<robots::CollisionPiece> pieces = detail::piecesOfGeometry(
        object.geometry, object.mesh.get(), st.geometry, "attached object '" + object.name + "'");
    auto snap = std::make_shared<Snapshot>(*st.current);
    snap->attached.push_back(makeAttached(*snap, link, object, options, std::move(pieces)));
    publishAttached(st, std::move(snap));
  }
  detail::reportFixedPairs(*this, st);  // an object on a link that no joint moves
}

void World::attachObstacle(int id, const std::string& link, const AttachOptions& options) {
  WorldState& st = *state_;
  std::lock_guard<std::mutex> lock(st.mutex);
  auto snap = std::make_shared<Snapshot>(*st.current);
  auto it = std::find_if(snap->obstacles.begin(), snap->obstacles.end(), [&](const auto& o) { return o->id == id; });
  if (it == snap->obstacles.end())
    throw std::invalid_argument("attachObstacle: no obstacle with id " + std::to_string(id));
  AttachOptions inWorld = options;
  inWorld.worldFrame = true;
  snap->attached.push_back(makeAttached(*snap, link, (*it)->source, inWorld, (*it)->pieces));
  snap->obstacles.erase(it);
  snap->obstaclePieces = detail::buildObstaclePieces(snap->obstacles, st.options.externalBroadPhase.get());
  publishAttached(st, std::move(snap));
}

int World::detach(const std::string& name, bool keepAsObstacle, const Eigen::VectorXd& q) {
  WorldState& st = *state_;
  std::lock_guard<std::mutex> lock(st.mutex);
  auto snap = std::make_shared<Snapshot>(*st.current);
  const std::size_t k = findAttached(*snap, name, "detach");
  const AttachedData& a = *snap->attached[k];
  int id = -1;
  if (keepAsObstacle) {
    auto data = std::make_shared<ObstacleData>();
    data->source = a.source;
    data->source.X_WO = linkPose(st.robot->model, a.link, q) * a.X_LO;
    data->pieces = a.pieces;
    data->id = id = st.nextObstacleId++;
    snap->obstacles.push_back(data);
    snap->obstaclePieces = detail::buildObstaclePieces(snap->obstacles, st.options.externalBroadPhase.get());
  }
  snap->attached.erase(snap->attached.begin() + static_cast<std::ptrdiff_t>(k));
  publishAttached(st, std::move(snap));
  return id;
}

std::vector<AttachedObjectInfo> World::attachedObjects() const {
  const auto snap = state_->snapshot();
  std::vector<AttachedObjectInfo> out;
  for (const auto& a : snap->attached) {
    AttachedObjectInfo info;
    info.object = a->source;
    info.link = snap->robot->model.link(a->link).name;
    info.X_LO = a->X_LO;
    for (const int t : a->touchLinks) info.touchLinks.push_back(snap->robot->model.link(t).name);
    for (robots::CollisionPiece p : a->pieces) {
      p.X_LP = a->X_LO * p.X_LP;
      info.pieces.push_back(std::move(p));
    }
    out.push_back(std::move(info));
  }
  return out;
}

}  // namespace deepcheck::checker
