// A MoveIt planning scene in a World: every shape of every collision object becomes an obstacle,
// posed once through the robot's links (robots::shapeWorldPoses). Built on World's public API only.

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

}  // namespace

std::vector<int> World::addPlanningScene(const robots::PlanningScene& scene, const PlanningSceneOptions& options) {
  const Eigen::VectorXd q = options.q.size() == 0 ? robot().defaultConfiguration() : options.q;
  // Every frame is resolved before anything is added: a bad frame leaves the world unchanged.
  const auto poses = robots::shapeWorldPoses(scene, robot(), q, options.frameAliases);
  std::vector<Obstacle> obstacles;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const robots::SceneObject& object = scene.objects[i];
    for (std::size_t k = 0; k < object.shapes.size(); ++k) {
      const std::string name = object.shapes.size() == 1 ? object.id : object.id + "/" + std::to_string(k);
      obstacles.push_back(obstacleOfShape(object.shapes[k], name, poses[i][k]));
    }
  }
  // All at once: one change of the world, and none added when a shape cannot become pieces.
  return addObstacles(obstacles);
}

}  // namespace deepcheck::checker
