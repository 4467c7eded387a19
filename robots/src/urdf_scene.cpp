// A scene described as a URDF, as a planning scene at one configuration (moveit_scene.h).

#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/moveit_scene.h"

#include <string>
#include <vector>

namespace deepcheck::robots {

PlanningScene planningSceneFromUrdf(const RobotModel& scene, const Eigen::Ref<const Eigen::VectorXd>& q,
                                    const std::string& frameId) {
  const std::vector<Eigen::Isometry3d> X_FL = forwardKinematics(scene, q);
  PlanningScene out;
  out.source = scene.source();
  for (int l = 0; l < scene.numLinks(); ++l) {
    const Link& link = scene.link(l);
    if (link.collisions.empty()) continue;
    SceneObject object;
    object.id = link.name;
    object.frameId = frameId;
    for (std::size_t c = 0; c < link.collisions.size(); ++c) {
      SceneShape shape;
      shape.geometry = link.collisions[c].geometry;
      shape.X_FS = X_FL[static_cast<std::size_t>(l)] * link.collisions[c].X_LG;
      shape.name = "collision " + std::to_string(c) + " of link " + link.name;
      object.shapes.push_back(shape);
    }
    out.objects.push_back(object);
  }
  return out;
}

}  // namespace deepcheck::robots
