#include "deepcheck/fcl_reference/fcl_backend.h"

#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/mesh_loader.h"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <map>
#include <stdexcept>
#include <tuple>

namespace deepcheck::fcl_reference {
namespace {

using GeometryPtr = std::shared_ptr<fcl::CollisionGeometryd>;
using MeshKey = std::tuple<std::string, double, double, double>;

GeometryPtr meshGeometry(const robots::TriangleMesh& mesh) {
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  model->beginModel();
  model->addSubModel(mesh.vertices, triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

/// The FCL geometry of a URDF geometry (meshes shared through `meshes`).
GeometryPtr fclGeometry(const robots::Geometry& g, const robots::TriangleMesh* inMemory,
                        std::map<MeshKey, GeometryPtr>& meshes, const std::string& what) {
  switch (g.type) {
    case robots::GeometryType::Box:
      return std::make_shared<fcl::Boxd>(g.boxSize);
    case robots::GeometryType::Sphere:
      return std::make_shared<fcl::Sphered>(g.radius);
    case robots::GeometryType::Cylinder:
      return std::make_shared<fcl::Cylinderd>(g.radius, g.length);
    case robots::GeometryType::Mesh: {
      if (inMemory != nullptr) return meshGeometry(*inMemory);
      const MeshKey key(g.meshPath, g.meshScale.x(), g.meshScale.y(), g.meshScale.z());
      auto it = meshes.find(key);
      if (it != meshes.end()) return it->second;
      try {
        return meshes[key] = meshGeometry(robots::loadMesh(g.meshPath, g.meshScale));
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("FclWorld: " + what + ": " + e.what());
      }
    }
  }
  throw std::invalid_argument("FclWorld: " + what + ": unknown geometry type");
}

}  // namespace

struct FclWorld::Impl {
  struct RobotObject {
    std::unique_ptr<fcl::CollisionObjectd> object;
    int link = -1;
    Eigen::Isometry3d X_LG = Eigen::Isometry3d::Identity();
  };
  struct WorldObject {
    std::unique_ptr<fcl::CollisionObjectd> object;
    std::string name;
  };

  robots::RobotModel robot;
  std::vector<RobotObject> robotObjects;         // grouped by link
  std::vector<std::pair<int, int>> linkObjects;  // per link: [first, end) in robotObjects
  std::vector<std::pair<int, int>> selfPairs;    // allowed link pairs
  std::vector<WorldObject> worldObjects;
  fcl::DynamicAABBTreeCollisionManagerd manager;
  std::vector<Eigen::Isometry3d> X_WL;

  explicit Impl(robots::RobotModel model) : robot(std::move(model)) {}

  void pose(const Eigen::Ref<const Eigen::VectorXd>& q) {
    robots::forwardKinematics(robot, q, X_WL);
    for (RobotObject& r : robotObjects) {
      const Eigen::Isometry3d X_WG = X_WL[r.link] * r.X_LG;
      r.object->setTransform(X_WG.linear(), X_WG.translation());
      r.object->computeAABB();
    }
  }

  const std::string& nameOf(fcl::CollisionObjectd* o) const {
    return worldObjects[reinterpret_cast<std::intptr_t>(o->getUserData())].name;
  }
};

namespace {

struct CollideData {
  bool hit = false;
};

bool collideCallback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
  auto* d = static_cast<CollideData*>(data);
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::collide(o1, o2, request, result);
  if (result.isCollision()) d->hit = true;
  return d->hit;
}

struct DistanceData {
  double best = std::numeric_limits<double>::infinity();
  fcl::CollisionObjectd* bestWorld = nullptr;
};

bool distanceCallback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data, double& dist) {
  auto* d = static_cast<DistanceData*>(data);
  fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  fcl::distance(o1, o2, request, result);
  if (result.min_distance < d->best) {
    d->best = result.min_distance;
    // The manager's object is the first argument; the query (robot) object the second.
    d->bestWorld = o1;
  }
  dist = d->best;
  return false;
}

}  // namespace

FclWorld::FclWorld(const checker::World& world) : impl_(std::make_unique<Impl>(world.robot())) {
  Impl& m = *impl_;
  std::map<MeshKey, GeometryPtr> meshes;
  m.linkObjects.assign(m.robot.numLinks(), {0, 0});
  for (int l = 0; l < m.robot.numLinks(); ++l) {
    const robots::Link& link = m.robot.link(l);
    m.linkObjects[l].first = static_cast<int>(m.robotObjects.size());
    for (std::size_t c = 0; c < link.collisions.size(); ++c) {
      Impl::RobotObject r;
      r.link = l;
      r.X_LG = link.collisions[c].X_LG;
      r.object = std::make_unique<fcl::CollisionObjectd>(
          fclGeometry(link.collisions[c].geometry, nullptr, meshes, "link '" + link.name + "'"));
      m.robotObjects.push_back(std::move(r));
    }
    m.linkObjects[l].second = static_cast<int>(m.robotObjects.size());
  }
  m.selfPairs = world.allowedSelfPairs();

  auto addWorldObject = [&](GeometryPtr geometry, const Eigen::Isometry3d& X_WG, const std::string& name) {
    Impl::WorldObject w;
    w.object = std::make_unique<fcl::CollisionObjectd>(std::move(geometry));
    w.object->setTransform(X_WG.linear(), X_WG.translation());
    w.object->computeAABB();
    w.object->setUserData(reinterpret_cast<void*>(static_cast<std::intptr_t>(m.worldObjects.size())));
    w.name = name;
    m.worldObjects.push_back(std::move(w));
  };
  for (int s = 0; s < world.numScenes(); ++s) {
    const robots::RobotModel& scene = world.scene(s);
    const std::vector<Eigen::Isometry3d> X_WL = robots::forwardKinematics(scene, world.sceneConfiguration(s));
    for (int l = 0; l < scene.numLinks(); ++l) {
      const robots::Link& link = scene.link(l);
      for (const robots::CollisionElement& e : link.collisions) {
        addWorldObject(fclGeometry(e.geometry, nullptr, meshes, "scene link '" + link.name + "'"), X_WL[l] * e.X_LG,
                       "scene/" + link.name);
      }
    }
  }
  for (int id : world.obstacleIds()) {
    const checker::Obstacle o = world.obstacle(id);
    addWorldObject(fclGeometry(o.geometry, o.mesh.get(), meshes, "obstacle '" + o.name + "'"), o.X_WO,
                   "obstacle/" + o.name);
  }
  std::vector<fcl::CollisionObjectd*> raw;
  for (Impl::WorldObject& w : m.worldObjects) raw.push_back(w.object.get());
  m.manager.registerObjects(raw);
  m.manager.setup();
}

FclWorld::~FclWorld() = default;
FclWorld::FclWorld(FclWorld&&) noexcept = default;
FclWorld& FclWorld::operator=(FclWorld&&) noexcept = default;

int FclWorld::numRobotObjects() const { return static_cast<int>(impl_->robotObjects.size()); }
int FclWorld::numWorldObjects() const { return static_cast<int>(impl_->worldObjects.size()); }

bool FclWorld::isFree(const Eigen::Ref<const Eigen::VectorXd>& q) {
  Impl& m = *impl_;
  m.pose(q);
  CollideData data;
  for (Impl::RobotObject& r : m.robotObjects) {
    m.manager.collide(r.object.get(), &data, collideCallback);
    if (data.hit) return false;
  }
  for (const auto& [a, b] : m.selfPairs) {
    for (int i = m.linkObjects[a].first; i < m.linkObjects[a].second; ++i) {
      for (int j = m.linkObjects[b].first; j < m.linkObjects[b].second; ++j) {
        fcl::CollisionObjectd* oa = m.robotObjects[i].object.get();
        fcl::CollisionObjectd* ob = m.robotObjects[j].object.get();
        if (!oa->getAABB().overlap(ob->getAABB())) continue;
        if (collideCallback(oa, ob, &data)) return false;
      }
    }
  }
  return true;
}

FclDistanceResult FclWorld::distance(const Eigen::Ref<const Eigen::VectorXd>& q) {
  FclDistanceResult out;
  if (!isFree(q)) {
    out.colliding = true;
    out.distance = 0.0;
    return out;
  }
  Impl& m = *impl_;  // posed by isFree
  for (Impl::RobotObject& r : m.robotObjects) {
    DistanceData data;
    data.best = out.distance;
    m.manager.distance(r.object.get(), &data, distanceCallback);
    if (data.bestWorld != nullptr && data.best < out.distance) {
      out.distance = data.best;
      out.nameA = m.robot.link(r.link).name;
      out.nameB = m.nameOf(data.bestWorld);
    }
  }
  for (const auto& [a, b] : m.selfPairs) {
    for (int i = m.linkObjects[a].first; i < m.linkObjects[a].second; ++i) {
      for (int j = m.linkObjects[b].first; j < m.linkObjects[b].second; ++j) {
        fcl::CollisionObjectd* oa = m.robotObjects[i].object.get();
        fcl::CollisionObjectd* ob = m.robotObjects[j].object.get();
        if (oa->getAABB().distance(ob->getAABB()) >= out.distance) continue;
        fcl::DistanceRequestd request;
        fcl::DistanceResultd result;
        fcl::distance(oa, ob, request, result);
        if (result.min_distance < out.distance) {
          out.distance = result.min_distance;
          out.nameA = m.robot.link(a).name;
          out.nameB = m.robot.link(b).name;
        }
      }
    }
  }
  return out;
}

}  // namespace deepcheck::fcl_reference
