#pragma once
// Helpers shared by the robots test files: the robots they load, where ../shared is, and (from
// tests/common) temporary folders and checks of exception messages.

#include "common/check_throws.h"
#include "common/temp_dir.h"
#include "common/test_paths.h"

#include "deepcheck/robots/robot_model.h"

#include <string>

namespace deepcheck::robots::test {

using deepcheck::test::checkThrows;
using deepcheck::test::haveShared;
using deepcheck::test::sharedDir;
using deepcheck::test::TempDir;

/// The Panda of the shared data folder (call only when haveShared()).
inline RobotModel loadPanda() {
  LoadOptions o;
  o.packageRoots = {sharedDir() + "/robots/panda"};
  o.useRosPackagePath = false;
  return RobotModel::fromUrdfFile(sharedDir() + "/robots/panda/moveit_resources_panda_description/urdf/panda.urdf", o);
}

/// The bundled arm (robots/data), ROS_PACKAGE_PATH ignored.
inline RobotModel loadBundledArm() {
  LoadOptions o;
  o.packageRoots = {deepcheck::test::bundledDataDir()};
  o.useRosPackagePath = false;
  return RobotModel::fromUrdfFile(deepcheck::test::bundledDataDir() + "/deepcheck_arm/urdf/deepcheck_arm.urdf", o);
}

}  // namespace deepcheck::robots::test
