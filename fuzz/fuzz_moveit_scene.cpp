// Fuzz harness: a MoveIt planning-scene YAML document (the bytes, as text) through the robots
// loader (moveit_scene.h), then placed in the world through a two-link robot with the frame
// alias world=base. Bad input must end in std::invalid_argument naming the problem (the loader's
// documented error), never a crash or another exception; what loads must be well formed
// (positive finite sizes, rigid finite poses), else the harness aborts. Relative mesh paths are
// resolved against a folder that does not exist and no package root is searched, so no mesh
// file is found or opened.

#include "harness_support.h"

#include "deepcheck/robots/moveit_scene.h"
#include "deepcheck/robots/robot_model.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace {

using deepcheck::robots::GeometryType;
using deepcheck::robots::SceneShape;

const deepcheck::robots::RobotModel& robot() {
  static const deepcheck::robots::RobotModel model = deepcheck::robots::RobotModel::fromUrdfString(
      R"(<robot name="fuzz">
           <link name="base"/><link name="tip"/>
           <joint name="j" type="revolute"><parent link="base"/><child link="tip"/>
             <origin xyz="0 0 0.5"/><axis xyz="0 0 1"/>
             <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
         </robot>)",
      "", {}, "fuzz_robot.urdf");
  return model;
}

using deepcheck::fuzz::rigid;

bool wellFormed(const SceneShape& s) {
  const auto& g = s.geometry;
  switch (g.type) {
    case GeometryType::Box: return (g.boxSize.array() > 0.0).all() && g.boxSize.allFinite();
    case GeometryType::Sphere: return g.radius > 0.0 && std::isfinite(g.radius);
    case GeometryType::Cylinder:
      return g.radius > 0.0 && g.length > 0.0 && std::isfinite(g.radius) && std::isfinite(g.length);
    case GeometryType::Mesh:
      return s.mesh ? !s.mesh->empty() && g.meshPath.empty() : !g.meshPath.empty();
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string yaml(reinterpret_cast<const char*>(data), size);
  deepcheck::robots::SceneLoadOptions options;
  options.useRosPackagePath = false;
  try {
    const auto scene = deepcheck::robots::parsePlanningScene(yaml, "/nonexistent-deepcheck-fuzz",
                                                             options, "fuzz.yaml");
    for (const auto& object : scene.objects) {
      for (const SceneShape& shape : object.shapes) {
        if (!wellFormed(shape) || !rigid(shape.X_FS)) std::abort();
      }
    }
    const auto poses = deepcheck::robots::shapeWorldPoses(
        scene, robot(), robot().defaultConfiguration(), {{"world", "base"}});
    for (const auto& objectPoses : poses) {
      for (const Eigen::Isometry3d& X_WS : objectPoses) {
        if (!rigid(X_WS)) std::abort();
      }
    }
  } catch (const std::invalid_argument&) {
    // Rejected input: the loader's documented error.
  }
  return 0;
}
