// A MoveIt planning scene in a World: every shape of every collision object becomes an obstacle,
// posed once through the robot's links (robots::shapeWorldPoses); every shape of every attached
// object is attached to its link where it is at the scene's configuration; the scene's allowed
// collisions are allowed. Built on World's public API only.

#include "deepcheck/checker/world.h"

#include <cstddef>
#include <string>
#include <vector>

namespace deepcheck::checker {

namespace {

/// The obstacle of one shape: its geometry (a cone's pyramid in memory) at X_WS.
Obstacle obstacleOfShape(const robots::SceneShape& shape, const std::string& name, const Eigen::Isometry3d& X_WS) {
  Obstacle o;
  o.name = name;
  o.geometry = shape.geometry;
  o.mesh = shape.mesh;
  o.X_WO = X_WS;
  return o;
}

/// The obstacle name of shape k of an object of `count` shapes.
std::string shapeName(const std::string& id, std::size_t k, std::size_t count) {
  return count == 1 ? id : id + "/" + std::to_string(k);
}

/// The robot link `name` stands for: its frame alias, or itself.
std::string aliased(const robots::FrameAliases& aliases, const std::string& name) {
  const auto it = aliases.find(name);
  return it == aliases.end() ? name : it->second;
}

/// Attaches every shape of every attached object of `scene` where it is at configuration q.
void attachAll(World& world, const robots::PlanningScene& scene, const PlanningSceneOptions& options,
               const Eigen::VectorXd& q) {
  robots::PlanningScene objects;
  objects.source = scene.source;
  for (const robots::AttachedObject& a : scene.attached) objects.objects.push_back(a.object);
  const auto poses = robots::shapeWorldPoses(objects, world.robot(), q, options.frameAliases);
  for (std::size_t i = 0; i < scene.attached.size(); ++i) {
    const robots::AttachedObject& a = scene.attached[i];
    AttachOptions placement;
    placement.worldFrame = true;
    placement.q = q;
    for (const std::string& t : a.touchLinks) placement.touchLinks.push_back(aliased(options.frameAliases, t));
    const std::vector<robots::SceneShape>& shapes = a.object.shapes;
    for (std::size_t k = 0; k < shapes.size(); ++k) {
      const Obstacle o = obstacleOfShape(shapes[k], shapeName(a.object.id, k, shapes.size()), poses[i][k]);
      try {
        world.attach(aliased(options.frameAliases, a.linkName), o, placement);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("planning scene '" + scene.source + "', line " + std::to_string(a.line) + ": " +
                                    e.what());
      }
    }
  }
}

/// Allows the scene's allowed collisions (names: robot links, object ids).
void allowAll(World& world, const robots::PlanningScene& scene) {
  try {
    for (const auto& [a, b] : scene.allowed.pairs) world.allowCollision(a, b);
    for (const std::string& name : scene.allowed.always) world.allowCollisionsWith(name);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("planning scene '" + scene.source + "', allowed collisions: " + e.what());
  }
}

}  // namespace

std::vector<int> World::addPlanningScene(const robots::PlanningScene& scene, const PlanningSceneOptions& options) {
  const Eigen::VectorXd q = options.q.size() == 0 ? robot().defaultConfiguration() : options.q;
  // Every frame is resolved before anything is added: a bad frame leaves the world unchanged.
  const auto poses = robots::shapeWorldPoses(scene, robot(), q, options.frameAliases);
  std::vector<Obstacle> obstacles;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const robots::SceneObject& object = scene.objects[i];
    for (std::size_t k = 0; k < object.shapes.size(); ++k) {
      obstacles.push_back(
          obstacleOfShape(object.shapes[k], shapeName(object.id, k, object.shapes.size()), poses[i][k]));
    }
  }
  // All at once: one change of the world, and none added when a shape cannot become pieces.
  // Fixed pairs are reported once the scene's own allowed collisions are in.
  const bool reports = setFixedPairReports(false);
  try {
    std::vector<int> ids = addObstacles(obstacles);
    attachAll(*this, scene, options, q);
    allowAll(*this, scene);
    setFixedPairReports(reports);
    return ids;
  } catch (...) {
    setFixedPairReports(reports);
    throw;
  }
}

}  // namespace deepcheck::checker
