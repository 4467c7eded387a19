#pragma once
// The real robots of the shared data folder (../shared: tests that use them skip without it), as
// the planners suites load them.

#include "deepcheck/planners/setup.h"

#include "common/test_paths.h"

#include <string>

namespace deepcheck::planners::test {

/// A robot's URDF and the set-up options that load it.
struct SharedRobot {
  std::string urdf;
  SetupOptions options;
};

/// The UR5 (joints of +-2 pi) with its SRDF.
inline SharedRobot sharedUr5() {
  const std::string dir = deepcheck::test::sharedDir() + "/robots/ur5";
  const std::string description = dir + "/example-robot-data/robots/ur_description";
  SharedRobot r;
  r.urdf = description + "/urdf/ur5_robot.urdf";
  r.options.packageRoots = {dir};
  r.options.useRosPackagePath = false;
  r.options.srdf = description + "/srdf/ur5.srdf";
  return r;
}

/// The Panda, all its joints.
inline SharedRobot sharedPanda() {
  const std::string dir = deepcheck::test::sharedDir() + "/robots/panda";
  SharedRobot r;
  r.urdf = dir + "/moveit_resources_panda_description/urdf/panda.urdf";
  r.options.packageRoots = {dir};
  r.options.useRosPackagePath = false;
  return r;
}

}  // namespace deepcheck::planners::test
