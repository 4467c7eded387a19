#pragma once
// The hard cases of body penetration depth as robots and scenes, shared by the checker
// and planners suites: a gantry carrying a box tool, a slab of two touching boxes and a U of three
// boxes, each one scene link (one body of several pieces).

#include "deepcheck/robots/format_number.h"
#include "deepcheck/robots/robot_model.h"

#include <Eigen/Core>

#include <string>

namespace deepcheck::test {

/// A box collision element of `size` centred at `at` (URDF).
inline std::string boxCollision(const Eigen::Vector3d& size, const Eigen::Vector3d& at) {
  auto v = [](const Eigen::Vector3d& x) {
    return robots::formatNumber(x.x()) + " " + robots::formatNumber(x.y()) + " " + robots::formatNumber(x.z());
  };
  return "<collision><origin xyz='" + v(at) + "'/><geometry><box size='" + v(size) + "'/></geometry></collision>";
}

/// A gantry: prismatic x, y, z (variables 0 to 2, links without geometry, limits +-1), then
/// revolute z and y joints (variables 3 and 4, limits +-3.1) carrying the link "tool" whose
/// collision elements are `toolCollisions` (URDF). With the angles at 0 the tool frame is at
/// (x, y, z) with the world's axes.
inline robots::RobotModel gantryRobot(const std::string& toolCollisions) {
  auto joint = [](const std::string& name, const std::string& type, const std::string& parent, const std::string& child,
                  const std::string& axis, double limit) {
    const std::string l = robots::formatNumber(limit);
    return "<joint name='" + name + "' type='" + type + "'><parent link='" + parent + "'/><child link='" + child +
           "'/><axis xyz='" + axis + "'/><limit lower='-" + l + "' upper='" + l + "' effort='1' velocity='1'/></joint>";
  };
  const std::string xml =
      "<robot name='gantry'><link name='base'/><link name='lx'/><link name='ly'/>"
      "<link name='lz'/><link name='lr'/><link name='tool'>" +
      toolCollisions + "</link>" + joint("x", "prismatic", "base", "lx", "1 0 0", 1) +
      joint("y", "prismatic", "lx", "ly", "0 1 0", 1) + joint("z", "prismatic", "ly", "lz", "0 0 1", 1) +
      joint("rz", "revolute", "lz", "lr", "0 0 1", 3.1) + joint("ry", "revolute", "lr", "tool", "0 1 0", 3.1) +
      "</robot>";
  return robots::RobotModel::fromUrdfString(xml, ".", {}, "gantry.urdf");
}

inline Eigen::VectorXd gantryQ(double x, double y, double z, double rz = 0.0, double ry = 0.0) {
  Eigen::VectorXd q(5);
  q << x, y, z, rz, ry;
  return q;
}

/// The tool of the hard cases: a box 0.06 (x) by 0.1 by 0.1 centred on the tool frame.
inline std::string toolBox() { return boxCollision({0.06, 0.1, 0.1}, {0, 0, 0}); }

/// A scene of one link `link` made of the given collision elements.
inline robots::RobotModel sceneOf(const std::string& link, const std::string& collisions) {
  return robots::RobotModel::fromUrdfString(
      "<robot name='scene'><link name='" + link + "'>" + collisions + "</link></robot>", ".", {}, "scene.urdf");
}

/// The slab: two boxes 0.4 x 0.4 x 0.1 touching along x = 0, top face at z = 0.
inline std::string slabCollisions() {
  return boxCollision({0.4, 0.4, 0.1}, {-0.2, 0, -0.05}) + boxCollision({0.4, 0.4, 0.1}, {0.2, 0, -0.05});
}

/// The U: a bottom plate z in [-0.04, 0] and two walls x in +-[0.025, 0.065], z in [0, 0.1]: a
/// channel 0.05 wide, narrower than the 0.06 tool.
inline std::string uCollisions() {
  return boxCollision({0.13, 0.2, 0.04}, {0, 0, -0.02}) + boxCollision({0.04, 0.2, 0.1}, {-0.045, 0, 0.05}) +
         boxCollision({0.04, 0.2, 0.1}, {0.045, 0, 0.05});
}

}  // namespace deepcheck::test
