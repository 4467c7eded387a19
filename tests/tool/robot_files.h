#pragma once
// The robot and scene files of the tool tests: the bundled arm (robots/data) and, from the shared
// data folder (test::haveShared says whether it is there), the Panda and MotionBenchMaker's small
// bookshelf; and the world the library builds from such files, to compare the program with.

#include "common/test_paths.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/moveit_scene.h"
#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/robot_model.h"

#include <string>

namespace deepcheck::tool_test {

inline std::string armUrdf() { return test::bundledDataDir() + "/deepcheck_arm/urdf/deepcheck_arm.urdf"; }
inline std::string armSrdf() { return test::bundledDataDir() + "/deepcheck_arm/srdf/deepcheck_arm.srdf"; }

inline std::string pandaDir() { return test::sharedDir() + "/robots/panda"; }
inline std::string pandaUrdf() { return pandaDir() + "/moveit_resources_panda_description/urdf/panda.urdf"; }
inline std::string pandaSrdf() { return pandaDir() + "/moveit_resources_panda_moveit_config/config/panda.srdf"; }
inline std::string bookshelfScene() {
  return test::sharedDir() + "/scenes/motion_bench_maker/configs/scenes/bookshelf/scene_small.yaml";
}

/// The robot of `urdf` with the SRDF's pairs disabled, `packageRoot` its only package root;
/// with the objects of the planning scene `scene` when it is not empty.
inline checker::World libraryWorld(const std::string& urdf, const std::string& srdf, const std::string& packageRoot,
                                   const std::string& scene = "", const robots::FrameAliases& aliases = {}) {
  robots::LoadOptions load;
  load.packageRoots = {packageRoot};
  load.useRosPackagePath = false;
  checker::WorldOptions options;
  options.disabledPairs = robots::readSrdfDisabledPairs(srdf);
  checker::World world(robots::RobotModel::fromUrdfFile(urdf, load), options);
  if (!scene.empty()) {
    checker::PlanningSceneOptions placement;
    placement.frameAliases = aliases;
    world.addPlanningScene(robots::loadPlanningScene(scene), placement);
  }
  return world;
}

}  // namespace deepcheck::tool_test
