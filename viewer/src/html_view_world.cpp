// viewOfWorld: the bodies of a World (robot links on tracks, scenes and obstacles fixed) and its
// closest pair along a sequence of configurations, densified for animation, with the body-level
// answer of that pair's bodies where they overlap (html_view.h).

#include "deepcheck/viewer/html_view.h"

#include "deepcheck/checker/body_distance.h"

#include "deepcheck/robots/format_number.h"
#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/mesh_loader.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace deepcheck::viewer {

using checker::AttachedObjectInfo;
using checker::BodyRef;
using checker::Contact;
using checker::DistanceResult;
using checker::Obstacle;
using checker::World;

namespace {

/// Meshes loaded once per file and scale.
class MeshStore {
 public:
  std::shared_ptr<const robots::TriangleMesh> get(const robots::Geometry& g) {
    const std::string key = g.meshPath + "|" + robots::formatNumber(g.meshScale.x()) + "," +
                            robots::formatNumber(g.meshScale.y()) + "," + robots::formatNumber(g.meshScale.z());
    auto& slot = meshes_[key];
    if (!slot) slot = std::make_shared<const robots::TriangleMesh>(robots::loadMesh(g.meshPath, g.meshScale));
    return slot;
  }

 private:
  std::map<std::string, std::shared_ptr<const robots::TriangleMesh>> meshes_;
};

ViewShape shapeOf(const robots::Geometry& g, const Eigen::Isometry3d& X_BG, MeshStore& meshes) {
  ViewShape s;
  s.geometry = g;
  s.X_BG = X_BG;
  if (g.type == robots::GeometryType::Mesh) s.mesh = meshes.get(g);
  return s;
}

/// Pieces of `body` among the world's pieces, moved from the world frame into the body frame.
std::vector<robots::CollisionPiece> piecesOf(const std::vector<World::WorldPieceRef>& all, const BodyRef& body,
                                             const Eigen::Isometry3d& X_WB) {
  std::vector<robots::CollisionPiece> out;
  const Eigen::Isometry3d X_BW = X_WB.inverse();
  for (const World::WorldPieceRef& p : all) {
    if (p.body != body) continue;
    out.push_back(p.piece);
    out.back().X_LP = X_BW * p.piece.X_LP;
  }
  return out;
}

void addScenes(const World& world, const std::vector<World::WorldPieceRef>& worldPieces,
               std::vector<ViewBody>& bodies) {
  for (int s = 0; s < world.numScenes(); ++s) {
    const robots::RobotModel& scene = world.scene(s);
    const std::vector<Eigen::Isometry3d> X_WL = robots::forwardKinematics(scene, world.sceneConfiguration(s));
    std::vector<std::vector<robots::CollisionPiece>> pieces(static_cast<std::size_t>(scene.numLinks()));
    for (int l = 0; l < scene.numLinks(); ++l) {
      BodyRef ref;
      ref.kind = BodyRef::Kind::SceneLink;
      ref.index = l;
      ref.scene = s;
      pieces[static_cast<std::size_t>(l)] = piecesOf(worldPieces, ref, X_WL[static_cast<std::size_t>(l)]);
    }
    for (ViewBody& b : linkBodies(scene, X_WL, pieces, "scene", "scene/")) bodies.push_back(std::move(b));
  }
}

void addObstacles(const World& world, const std::vector<World::WorldPieceRef>& worldPieces, MeshStore& meshes,
                  std::vector<ViewBody>& bodies) {
  for (const int id : world.obstacleIds()) {
    const Obstacle o = world.obstacle(id);
    ViewBody b;
    b.name = "obstacle/" + o.name;
    b.layer = "obstacle";
    b.X_WB = o.X_WO;
    if (o.geometry.type == robots::GeometryType::Mesh && o.mesh) {
      b.shapes.push_back(ViewShape{o.geometry, o.mesh, Eigen::Isometry3d::Identity()});
    } else {
      b.shapes.push_back(shapeOf(o.geometry, Eigen::Isometry3d::Identity(), meshes));
    }
    BodyRef ref;
    ref.kind = BodyRef::Kind::Obstacle;
    ref.index = id;
    b.pieces = piecesOf(worldPieces, ref, o.X_WO);
    bodies.push_back(std::move(b));
  }
}

/// The attached objects, each on a track of its own that follows its link (trackLink) at its
/// pose in the link frame (trackOffset).
void addAttached(const World& world, MeshStore& meshes, std::vector<ViewBody>& bodies, std::vector<int>& trackLink,
                 std::vector<Eigen::Isometry3d>& trackOffset) {
  for (const AttachedObjectInfo& a : world.attachedObjects()) {
    ViewBody b;
    b.name = "attached/" + a.object.name;
    b.layer = "attached";
    if (a.object.geometry.type == robots::GeometryType::Mesh && a.object.mesh) {
      b.shapes.push_back(ViewShape{a.object.geometry, a.object.mesh, Eigen::Isometry3d::Identity()});
    } else {
      b.shapes.push_back(shapeOf(a.object.geometry, Eigen::Isometry3d::Identity(), meshes));
    }
    const Eigen::Isometry3d X_OL = a.X_LO.inverse();
    for (const robots::CollisionPiece& p : a.pieces) {
      b.pieces.push_back(p);
      b.pieces.back().X_LP = X_OL * p.X_LP;  // into the object's frame
    }
    b.track = static_cast<int>(trackLink.size());
    trackLink.push_back(world.robot().linkIndex(a.link));
    trackOffset.push_back(a.X_LO);
    bodies.push_back(std::move(b));
  }
}

/// The configurations with frames added between them (WorldViewOptions::maxStep, maxFrames);
/// `waypoint` tells which are the given ones, `index` the waypoint each frame starts from.
struct Densified {
  std::vector<Eigen::VectorXd> q;
  std::vector<bool> waypoint;
  std::vector<int> index;
};

Densified densify(const std::vector<Eigen::VectorXd>& path, double maxStep, int maxFrames) {
  std::vector<long> steps(path.size() > 0 ? path.size() - 1 : 0, 1);
  long extra = 0;
  if (maxStep > 0.0 && std::isfinite(maxStep)) {
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
      const double delta = (path[i + 1] - path[i]).cwiseAbs().maxCoeff();
      steps[i] = std::max(1L, static_cast<long>(std::ceil(delta / maxStep)));
      extra += steps[i] - 1;
    }
  }
  const long budget = static_cast<long>(maxFrames) - static_cast<long>(path.size());
  if (extra > 0 && extra > budget) {
    for (long& s : steps) s = 1 + (budget > 0 ? (s - 1) * budget / extra : 0);
  }
  Densified d;
  for (std::size_t i = 0; i < path.size(); ++i) {
    d.q.push_back(path[i]);
    d.waypoint.push_back(true);
    d.index.push_back(static_cast<int>(i));
    if (i + 1 == path.size()) break;
    for (long k = 1; k < steps[i]; ++k) {
      const double t = static_cast<double>(k) / static_cast<double>(steps[i]);
      d.q.push_back((1.0 - t) * path[i] + t * path[i + 1]);
      d.waypoint.push_back(false);
      d.index.push_back(static_cast<int>(i));
    }
  }
  return d;
}

ViewContact contactOf(const Contact& c) {
  return ViewContact{c.distance, c.pointA, c.pointB, c.normal, c.nameA, c.nameB};
}

/// The body A of a contact: its robot link, or the attached object named by nameA (attached
/// objects are told apart by name, as World::attachedObjects lists them).
BodyRef bodyA(const Contact& c, const std::vector<AttachedObjectInfo>& attached) {
  BodyRef a;
  a.kind = BodyRef::Kind::RobotLink;
  a.index = c.linkA;
  for (std::size_t i = 0; i < attached.size(); ++i) {
    if (c.nameA == "attached/" + attached[i].object.name) {
      a.kind = BodyRef::Kind::Attached;
      a.scene = static_cast<int>(i);
    }
  }
  return a;
}

}  // namespace

std::vector<ViewBody> linkBodies(const robots::RobotModel& model, const std::vector<Eigen::Isometry3d>& X_WL,
                                 const std::vector<std::vector<robots::CollisionPiece>>& pieces,
                                 const std::string& layer, const std::string& namePrefix) {
  if (X_WL.size() != static_cast<std::size_t>(model.numLinks()) || pieces.size() != X_WL.size()) {
    throw std::invalid_argument("linkBodies: one pose and one piece list per link of '" + model.name() + "' expected");
  }
  MeshStore meshes;
  std::vector<ViewBody> bodies;
  for (int l = 0; l < model.numLinks(); ++l) {
    const robots::Link& link = model.link(l);
    if (link.collisions.empty() && pieces[static_cast<std::size_t>(l)].empty()) continue;
    ViewBody b;
    b.name = namePrefix + link.name;
    b.layer = layer;
    b.X_WB = X_WL[static_cast<std::size_t>(l)];
    for (const robots::CollisionElement& e : link.collisions) b.shapes.push_back(shapeOf(e.geometry, e.X_LG, meshes));
    b.pieces = pieces[static_cast<std::size_t>(l)];
    bodies.push_back(std::move(b));
  }
  return bodies;
}

ViewScene viewOfWorld(const World& world, const std::vector<Eigen::VectorXd>& configurations,
                      const WorldViewOptions& options) {
  const robots::RobotModel& robot = world.robot();
  if (configurations.empty()) throw std::invalid_argument("viewOfWorld: no configuration given");
  for (std::size_t i = 0; i < configurations.size(); ++i) {
    try {
      robots::checkConfiguration(robot, configurations[i]);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("viewOfWorld: configuration " + std::to_string(i) + ": " + e.what());
    }
  }
  for (const std::string& name : options.hiddenLinks) {
    if (robot.linkIndex(name) < 0) {
      throw std::invalid_argument("viewOfWorld: robot '" + robot.name() + "' has no link '" + name + "'");
    }
  }
  ViewScene scene;
  scene.title = options.title;
  scene.caption = options.caption;

  std::vector<std::vector<robots::CollisionPiece>> pieces;
  for (int l = 0; l < robot.numLinks(); ++l) pieces.push_back(world.linkPieces(l));
  scene.bodies = linkBodies(robot, robots::forwardKinematics(robot, configurations.front()), pieces, "robot", "");
  std::vector<int> trackLink;  // robot link of each track
  for (ViewBody& b : scene.bodies) {
    b.track = static_cast<int>(trackLink.size());
    trackLink.push_back(robot.linkIndex(b.name));
    b.visible = std::find(options.hiddenLinks.begin(), options.hiddenLinks.end(), b.name) == options.hiddenLinks.end();
  }
  std::vector<Eigen::Isometry3d> trackOffset(trackLink.size(), Eigen::Isometry3d::Identity());
  MeshStore meshes;
  addAttached(world, meshes, scene.bodies, trackLink, trackOffset);
  scene.numTracks = static_cast<int>(trackLink.size());
  const std::vector<World::WorldPieceRef> worldPieces = world.worldPieces();
  addScenes(world, worldPieces, scene.bodies);
  addObstacles(world, worldPieces, meshes, scene.bodies);

  const std::vector<AttachedObjectInfo> attached = world.attachedObjects();
  const Densified path = densify(configurations, options.maxStep, options.maxFrames);
  auto context = world.makeContext();
  std::vector<Eigen::Isometry3d> X_WL;
  for (std::size_t f = 0; f < path.q.size(); ++f) {
    ViewFrame frame;
    robots::forwardKinematics(robot, path.q[f], X_WL);
    for (std::size_t t = 0; t < trackLink.size(); ++t) {
      frame.poses.push_back(X_WL[static_cast<std::size_t>(trackLink[t])] * trackOffset[t]);
    }
    frame.waypoint = path.waypoint[f];
    const int w = path.index[f];
    frame.label = frame.waypoint ? "waypoint " + std::to_string(w)
                                 : "between waypoints " + std::to_string(w) + " and " + std::to_string(w + 1);
    const DistanceResult r = world.signedDistance(path.q[f], context);
    frame.hasContact = r.found;
    if (r.found) {
      frame.contact = contactOf(r.closest);
      frame.value = r.closest.distance;
    }
    if (r.found && r.closest.distance < 0.0) {
      const World::BodyContact body = world.bodySignedDistance(path.q[f], bodyA(r.closest, attached), r.closest.bodyB);
      frame.hasBodyContact = true;
      frame.bodyContact = contactOf(body.contact);
    }
    scene.frames.push_back(std::move(frame));
  }
  return scene;
}

void writeHtmlView(const World& world, const std::vector<Eigen::VectorXd>& configurations, const std::string& file,
                   const WorldViewOptions& options) {
  writeHtmlView(viewOfWorld(world, configurations, options), file);
}

}  // namespace deepcheck::viewer
