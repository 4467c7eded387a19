#pragma once
// Helpers shared by the checker test files: small URDF robots with known geometry, the shared
// data folder (Panda, kitchen), random configurations and exception-message checks.

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/format_number.h"
#include "deepcheck/robots/robot_model.h"

#include "common/random_configurations.h"
#include "common/test_paths.h"

#include <boost/test/unit_test.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace deepcheck::checker::test {

using deepcheck::test::bundledDataDir;
using deepcheck::test::haveShared;
using deepcheck::test::sharedDir;

/// Decomposition cache of the test runs (in the build folder, so reruns are fast).
inline std::string testCacheDir() {
#ifdef DEEPCHECK_BINARY_DIR
  return std::string(DEEPCHECK_BINARY_DIR) + "/checker_test_cache";
#else
  return "";
#endif
}

inline WorldOptions testWorldOptions() {
  WorldOptions o;
  o.decompositionCacheDir = testCacheDir();
  return o;
}

/// A slider: a cube of edge `edge` on a prismatic joint along x (variable "slide", limits
/// [-2, 2]); its centre is at (q, 0, 0).
inline robots::RobotModel sliderRobot(double edge) {
  const std::string e = robots::formatNumber(edge);  // std::to_string keeps 6 decimals only
  const std::string xml =
      "<robot name='slider'>"
      "<link name='base'/>"
      "<link name='cube'><collision><geometry><box size='" +
      e + " " + e + " " + e +
      "'/></geometry></collision></link>"
      "<joint name='slide' type='prismatic'><parent link='base'/><child link='cube'/>"
      "<axis xyz='1 0 0'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>"
      "</robot>";
  return robots::RobotModel::fromUrdfString(xml, ".", {}, "slider.urdf");
}

/// A 3-joint arm: base box; link1 (box) on a revolute z joint; link2 (box) on a revolute y joint;
/// link3 (box) on a revolute y joint with a tool sphere rigidly attached by a fixed joint; and a
/// link without geometry in between (link2 -> elbow (no geometry) -> link3).
inline robots::RobotModel armRobot() {
  const std::string xml = R"(
<robot name='arm'>
  <link name='base'><collision><origin xyz='0 0 0.05'/><geometry><box size='0.3 0.3 0.1'/></geometry></collision></link>
  <link name='link1'><collision><origin xyz='0 0 0.2'/><geometry><box size='0.1 0.1 0.4'/></geometry></collision></link>
  <joint name='j1' type='revolute'><parent link='base'/><child link='link1'/><origin xyz='0 0 0.1'/>
    <axis xyz='0 0 1'/><limit lower='-3' upper='3' effort='1' velocity='1'/></joint>
  <link name='link2'><collision><origin xyz='0 0 0.15'/><geometry><box size='0.08 0.08 0.3'/></geometry></collision></link>
  <joint name='j2' type='revolute'><parent link='link1'/><child link='link2'/><origin xyz='0 0 0.4'/>
    <axis xyz='0 1 0'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>
  <link name='elbow'/>
  <joint name='elbow_fixed' type='fixed'><parent link='link2'/><child link='elbow'/><origin xyz='0 0 0.3'/></joint>
  <link name='link3'><collision><origin xyz='0 0 0.125'/><geometry><cylinder radius='0.03' length='0.25'/></geometry></collision></link>
  <joint name='j3' type='revolute'><parent link='elbow'/><child link='link3'/>
    <axis xyz='0 1 0'/><limit lower='-2.5' upper='2.5' effort='1' velocity='1'/></joint>
  <link name='tool'><collision><geometry><sphere radius='0.05'/></geometry></collision></link>
  <joint name='tool_fixed' type='fixed'><parent link='link3'/><child link='tool'/><origin xyz='0 0 0.3'/></joint>
</robot>)";
  return robots::RobotModel::fromUrdfString(xml, ".", {}, "arm.urdf");
}

using deepcheck::test::randomConfiguration;
using deepcheck::test::randomConfigurations;

inline Eigen::Isometry3d translation(double x, double y, double z) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}

/// Two sliders in series along x carrying a cube, and a box obstacle at the origin: q = (1e308,
/// 1e308) poses the cube beyond the doubles, though each value is finite.
inline World sliderPairWorld() {
  const std::string xml =
      "<robot name='far'>"
      "<link name='base'/><link name='mid'/>"
      "<link name='cube'><collision><geometry><box size='0.1 0.1 0.1'/></geometry></collision></link>"
      "<joint name='slide1' type='prismatic'><parent link='base'/><child link='mid'/>"
      "<axis xyz='1 0 0'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>"
      "<joint name='slide2' type='prismatic'><parent link='mid'/><child link='cube'/>"
      "<axis xyz='1 0 0'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>"
      "</robot>";
  World world(robots::RobotModel::fromUrdfString(xml, ".", {}, "far.urdf"), testWorldOptions());
  world.addObstacle(Obstacle::box("box", Eigen::Vector3d(0.2, 0.2, 0.2), translation(0, 0, 0)));
  return world;
}

/// A tetrahedron of edge 0.3 along the axes, corner at the origin, as a triangle mesh.
inline robots::TriangleMesh tetrahedronMesh() {
  robots::TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {0.3, 0, 0}, {0, 0.3, 0}, {0, 0, 0.3}};
  mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return mesh;
}

/// The arm's obstacles in the agreement and gradient tests: a tilted crate, a ball and a post.
inline void addCrateBallPost(World& world) {
  Eigen::Isometry3d tilted = translation(0.35, 0.1, 0.55);
  tilted.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  world.addObstacle(Obstacle::box("crate", Eigen::Vector3d(0.2, 0.3, 0.25), tilted));
  world.addObstacle(Obstacle::sphere("ball", 0.12, translation(-0.3, -0.25, 0.7)));
  world.addObstacle(Obstacle::cylinder("post", 0.05, 0.6, translation(0.0, 0.45, 0.4)));
}

/// isFree of `with` (a fast path on: `feature`) against `without` (off) on `qs`, one fresh context
/// each: every answer must agree. Returns how many of qs are colliding; the two contexts' counters
/// in *withStats and *withoutStats (when not null).
inline int compareIsFree(const World& with, const World& without, const std::vector<Eigen::VectorXd>& qs,
                         const std::string& feature, QueryStats* withStats, QueryStats* withoutStats = nullptr) {
  auto a = with.makeContext();
  auto b = without.makeContext();
  int colliding = 0;
  for (const Eigen::VectorXd& q : qs) {
    const bool fast = with.isFree(q, a);
    const bool reference = without.isFree(q, b);
    BOOST_CHECK_MESSAGE(fast == reference, "q = " << q.transpose() << ": isFree " << fast << " with " << feature << ", "
                                                  << reference << " without");
    colliding += !reference;
  }
  if (withStats != nullptr) *withStats = a.stats();
  if (withoutStats != nullptr) *withoutStats = b.stats();
  return colliding;
}

/// Checks that `f` throws std::invalid_argument whose message contains `needle`.
inline void checkThrowsWith(const std::function<void()>& f, const std::string& needle) {
  try {
    f();
    BOOST_ERROR("expected std::invalid_argument mentioning '" << needle << "'");
  } catch (const std::invalid_argument& e) {
    BOOST_TEST(std::string(e.what()).find(needle) != std::string::npos,
               "message '" << e.what() << "' should mention '" << needle << "'");
  }
}

inline robots::LoadOptions bundledLoadOptions() {
  robots::LoadOptions o;
  o.packageRoots = {bundledDataDir()};
  o.useRosPackagePath = false;
  return o;
}

inline std::string pandaUrdf() {
  return sharedDir() + "/robots/panda/moveit_resources_panda_description/urdf/panda.urdf";
}
inline std::string pandaPackageRoot() { return sharedDir() + "/robots/panda"; }
inline std::string kitchenUrdf() {
  return sharedDir() + "/scenes/motion_bench_maker/configs/scenes/kitchen/kitchen.urdf";
}
inline std::string scenesPackageRoot() { return sharedDir() + "/scenes"; }

inline robots::RobotModel loadPanda() {
  robots::LoadOptions o;
  o.packageRoots = {pandaPackageRoot()};
  o.useRosPackagePath = false;
  return robots::RobotModel::fromUrdfFile(pandaUrdf(), o);
}

/// The kitchen, placed so the Panda (at the origin) stands in front of the counter.
inline robots::RobotModel loadKitchen() {
  robots::LoadOptions o;
  o.packageRoots = {scenesPackageRoot()};
  o.useRosPackagePath = false;
  return robots::RobotModel::fromUrdfFile(kitchenUrdf(), o);
}

/// Every joint kind: a revolute joint about a skew axis, a prismatic one along a skew axis, a
/// continuous one about -x, a mimic of the first (multiplier 2, offset 0.3), a fixed one; the
/// origins rotated.
inline robots::RobotModel everyJointRobot() {
  const std::string box = "<collision><geometry><box size='0.1 0.2 0.3'/></geometry></collision>";
  auto link = [&](const std::string& name) { return "<link name='" + name + "'>" + box + "</link>"; };
  auto joint = [](const std::string& name, const std::string& type, const std::string& parent, const std::string& child,
                  const std::string& xyz, const std::string& rpy, const std::string& axis, const std::string& extra) {
    return "<joint name='" + name + "' type='" + type + "'><parent link='" + parent + "'/><child link='" + child +
           "'/><origin xyz='" + xyz + "' rpy='" + rpy + "'/><axis xyz='" + axis +
           "'/><limit lower='-3' upper='3' effort='1' velocity='1'/>" + extra + "</joint>";
  };
  const std::string xml = "<robot name='every'><link name='base'/>" + link("a") + link("b") + link("c") + link("d") +
                          link("e") + joint("j1", "revolute", "base", "a", "0.1 0 0.2", "0.3 -0.2 0.1", "1 2 3", "") +
                          joint("j2", "prismatic", "a", "b", "0 0.3 0", "0 0 0.5", "0 1 1", "") +
                          joint("j3", "continuous", "b", "c", "0.2 0 0", "0.1 0.2 0.3", "-1 0 0", "") +
                          joint("j4", "revolute", "c", "d", "0 0 0.25", "0 0 0", "0 0.6 0.8",
                                "<mimic joint='j1' multiplier='2' offset='0.3'/>") +
                          joint("j5", "fixed", "d", "e", "0.05 0.05 0.05", "1 0 0", "1 0 0", "") + "</robot>";
  return robots::RobotModel::fromUrdfString(xml, ".", {}, "every.urdf");
}

}  // namespace deepcheck::checker::test
