#pragma once
// What the planning-scene harnesses share: a two-link robot whose root is `base`, and the checks
// every loaded scene must pass (well-formed shapes, rigid poses, world poses through the robot).

#include "harness_support.h"

#include "deepcheck/robots/moveit_scene.h"
#include "deepcheck/robots/robot_model.h"

#include <cmath>
#include <cstddef>

namespace deepcheck::fuzz {

/// Links base and tip (tip 0.5 m above base, on a revolute joint about z), loaded once.
inline const robots::RobotModel& twoLinkRobot() {
  static const robots::RobotModel model = robots::RobotModel::fromUrdfString(
      R"(<robot name="fuzz">
           <link name="base"/><link name="tip"/>
           <joint name="j" type="revolute"><parent link="base"/><child link="tip"/>
             <origin xyz="0 0 0.5"/><axis xyz="0 0 1"/>
             <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
         </robot>)",
      "", {}, "fuzz_robot.urdf");
  return model;
}

/// Positive finite sizes; a mesh either a file path or an in-memory mesh that is not empty.
inline bool wellFormed(const robots::SceneShape& s) {
  const auto& g = s.geometry;
  switch (g.type) {
    case robots::GeometryType::Box:
      return (g.boxSize.array() > 0.0).all() && g.boxSize.allFinite();
    case robots::GeometryType::Sphere:
      return g.radius > 0.0 && std::isfinite(g.radius);
    case robots::GeometryType::Cylinder:
      return g.radius > 0.0 && g.length > 0.0 && std::isfinite(g.radius) && std::isfinite(g.length);
    case robots::GeometryType::Mesh:
      return s.mesh ? !s.mesh->empty() && g.meshPath.empty() : !g.meshPath.empty();
  }
  return false;
}

/// Every shape (of the objects and of the attached objects) well formed with a rigid pose, and
/// every world pose through twoLinkRobot (frame alias world=base) rigid; aborts otherwise. The
/// world poses may throw std::invalid_argument (a frame that is no link).
inline void requireWellFormed(const robots::PlanningScene& scene) {
  auto check = [](const robots::SceneObject& object) {
    for (const robots::SceneShape& shape : object.shapes) {
      require(wellFormed(shape) && rigid(shape.X_FS), "planning scene", "a shape that is not well formed");
    }
  };
  for (const auto& object : scene.objects) check(object);
  for (const auto& attached : scene.attached) check(attached.object);
  const auto poses =
      robots::shapeWorldPoses(scene, twoLinkRobot(), twoLinkRobot().defaultConfiguration(), {{"world", "base"}});
  for (const auto& objectPoses : poses) {
    for (const Eigen::Isometry3d& X_WS : objectPoses)
      require(rigid(X_WS), "planning scene", "a world pose that is not rigid");
  }
}

/// The counts of objects, attached objects and shapes of `a` and `b` are equal.
inline bool sameCounts(const robots::PlanningScene& a, const robots::PlanningScene& b) {
  if (a.objects.size() != b.objects.size() || a.attached.size() != b.attached.size()) return false;
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    if (a.objects[i].shapes.size() != b.objects[i].shapes.size()) return false;
  }
  return true;
}

}  // namespace deepcheck::fuzz
