// URDF loading: the real robots and scenes of ../shared, mimic joints, and one test per bad input.

#include "robots_test_util.h"

#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/package_path.h"
#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/robot_model.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace deepcheck::robots;
using deepcheck::robots::test::checkThrows;
using deepcheck::robots::test::haveShared;
using deepcheck::robots::test::sharedDir;
using deepcheck::robots::test::TempDir;

namespace {

std::string pandaUrdf() { return sharedDir() + "/robots/panda/moveit_resources_panda_description/urdf/panda.urdf"; }
std::string ur5Urdf() {
  return sharedDir() + "/robots/ur5/example-robot-data/robots/ur_description/urdf/ur5_robot.urdf";
}
std::string sceneUrdf(const std::string& name) {
  return sharedDir() + "/scenes/motion_bench_maker/configs/scenes/" + name + "/" + name + ".urdf";
}

LoadOptions rootsOnly(std::vector<std::string> roots) {
  LoadOptions o;
  o.packageRoots = std::move(roots);
  o.useRosPackagePath = false;
  return o;
}

std::vector<std::string> linkNames(const RobotModel& m) {
  std::vector<std::string> out;
  for (const Link& l : m.links()) out.push_back(l.name);
  return out;
}

/// A two-link robot whose joint has the given XML inside <joint>; the rest is valid.
std::string oneJointUrdf(const std::string& jointType, const std::string& inside) {
  return R"(<robot name="one">
  <link name="base"/>
  <link name="tip"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="j" type=")" +
         jointType + R"(">
    <parent link="base"/><child link="tip"/>)" +
         inside + R"(
  </joint>
</robot>)";
}

const char* kMimicUrdf = R"(<robot name="mimic">
  <link name="base"/>
  <link name="a"/>
  <link name="b"/>
  <link name="c"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="a"/>
    <origin xyz="0 0 0.5" rpy="0 0 0"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="j2" type="revolute">
    <parent link="a"/><child link="b"/>
    <origin xyz="0.4 0 0" rpy="0.3 0 0"/>
    <axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
    <mimic joint="j1" multiplier="2" offset="0.1"/>
  </joint>
  <joint name="j3" type="prismatic">
    <parent link="b"/><child link="c"/>
    <origin xyz="0.3 0 0" rpy="0 0 0"/>
    <axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
    <mimic joint="j2" multiplier="-0.5" offset="0.2"/>
  </joint>
</robot>)";

}  // namespace

BOOST_AUTO_TEST_SUITE(robots_urdf)

BOOST_AUTO_TEST_CASE(panda_structure) {
  if (!haveShared("panda_structure")) return;
  const RobotModel m = RobotModel::fromUrdfFile(pandaUrdf(), rootsOnly({sharedDir() + "/robots/panda"}));
  BOOST_TEST(m.name() == "panda");
  BOOST_TEST(m.numLinks() == 12);
  BOOST_TEST(m.numJoints() == 11);
  BOOST_TEST(m.numCollisionElements() == 11);
  const std::vector<std::string> links{"panda_link0", "panda_link1", "panda_link2",      "panda_link3",
                                       "panda_link4", "panda_link5", "panda_link6",      "panda_link7",
                                       "panda_link8", "panda_hand",  "panda_leftfinger", "panda_rightfinger"};
  BOOST_TEST(linkNames(m) == links, boost::test_tools::per_element());
  const std::vector<std::string> variables{"panda_joint1", "panda_joint2", "panda_joint3", "panda_joint4",
                                           "panda_joint5", "panda_joint6", "panda_joint7", "panda_finger_joint1"};
  BOOST_TEST(m.variableNames() == variables, boost::test_tools::per_element());
  BOOST_TEST(m.variableIndex("panda_joint4") == 3);
  BOOST_TEST(m.variableIndex("panda_finger_joint2") == -1);  // a mimic joint
  BOOST_TEST(m.variableIndex("panda_joint8") == -1);         // fixed
  BOOST_TEST(m.variableIndex("nope") == -1);

  // Limits as published in the URDF.
  BOOST_TEST(m.lowerLimits()[0] == -2.9671);
  BOOST_TEST(m.upperLimits()[0] == 2.9671);
  BOOST_TEST(m.lowerLimits()[3] == -3.1416);
  BOOST_TEST(m.upperLimits()[3] == 0.0873);
  BOOST_TEST(m.lowerLimits()[5] == -0.0873);
  BOOST_TEST(m.upperLimits()[5] == 3.8223);
  BOOST_TEST(m.lowerLimits()[7] == 0.0);
  BOOST_TEST(m.upperLimits()[7] == 0.04);

  // The right finger mimics the left one, with the URDF defaults (multiplier 1, offset 0).
  const Joint& finger2 = m.joint(m.jointIndex("panda_finger_joint2"));
  BOOST_TEST(finger2.isMimic());
  BOOST_TEST(finger2.mimicJoint == m.jointIndex("panda_finger_joint1"));
  BOOST_TEST(finger2.variable == 7);
  BOOST_TEST(finger2.multiplier == 1.0);
  BOOST_TEST(finger2.offset == 0.0);
  BOOST_TEST((finger2.axis - Eigen::Vector3d(0, -1, 0)).norm() == 0.0);

  // Joint i is the parent joint of link i + 1.
  for (int j = 0; j < m.numJoints(); ++j) {
    BOOST_TEST(m.joint(j).childLink == j + 1);
    BOOST_TEST(m.link(j + 1).parentJoint == j);
  }

  // Collision geometry: one mesh per link, resolved; the right finger's origin is turned by pi.
  const Link& right = m.link(m.linkIndex("panda_rightfinger"));
  BOOST_REQUIRE(right.collisions.size() == 1u);
  const Geometry& g = right.collisions[0].geometry;
  BOOST_TEST((g.type == GeometryType::Mesh));
  BOOST_TEST(g.meshUri == "package://moveit_resources_panda_description/meshes/collision/finger.stl");
  BOOST_TEST(fs::path(g.meshPath).is_absolute());
  BOOST_TEST(fs::exists(g.meshPath));
  const Eigen::Matrix3d Rz = Eigen::AngleAxisd(3.14159265359, Eigen::Vector3d::UnitZ()).matrix();
  BOOST_TEST((right.collisions[0].X_LG.linear() - Rz).norm() < 1e-12);
  BOOST_TEST(m.link(m.linkIndex("panda_link8")).collisions.empty());
}

BOOST_AUTO_TEST_CASE(ur5_structure) {
  if (!haveShared("ur5_structure")) return;
  const RobotModel m = RobotModel::fromUrdfFile(ur5Urdf(), rootsOnly({sharedDir() + "/robots/ur5"}));
  BOOST_TEST(m.numLinks() == 11);
  BOOST_TEST(m.numJoints() == 10);
  BOOST_TEST(m.numCollisionElements() == 8);
  BOOST_TEST(m.link(0).name == "world");
  // Depth first, children in file order: base_link's joints are shoulder_pan_joint (first in the
  // file) and base_link-base_fixed_joint (later), so "base" comes after the whole arm.
  const std::vector<std::string> links{"world",        "base_link",    "shoulder_link", "upper_arm_link",
                                       "forearm_link", "wrist_1_link", "wrist_2_link",  "wrist_3_link",
                                       "ee_link",      "tool0",        "base"};
  BOOST_TEST(linkNames(m) == links, boost::test_tools::per_element());
  const std::vector<std::string> variables{"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                                           "wrist_1_joint",      "wrist_2_joint",       "wrist_3_joint"};
  BOOST_TEST(m.variableNames() == variables, boost::test_tools::per_element());
  for (int v = 0; v < 6; ++v) {
    const double limit = v == 2 ? 3.14159265359 : 6.28318530718;
    BOOST_TEST(m.lowerLimits()[v] == -limit);
    BOOST_TEST(m.upperLimits()[v] == limit);
  }
  // ee_link has a box, offset along x.
  const Link& ee = m.link(m.linkIndex("ee_link"));
  BOOST_REQUIRE(ee.collisions.size() == 1u);
  BOOST_TEST((ee.collisions[0].geometry.type == GeometryType::Box));
  BOOST_TEST((ee.collisions[0].geometry.boxSize - Eigen::Vector3d::Constant(0.01)).norm() == 0.0);
  BOOST_TEST((ee.collisions[0].X_LG.translation() - Eigen::Vector3d(-0.01, 0, 0)).norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(scenes_structure_and_placement) {
  if (!haveShared("scenes_structure_and_placement")) return;
  const LoadOptions options = rootsOnly({sharedDir() + "/scenes"});

  const RobotModel kitchen = RobotModel::fromUrdfFile(sceneUrdf("kitchen"), options);
  BOOST_TEST(kitchen.numLinks() == 6);
  BOOST_TEST(kitchen.numJoints() == 5);
  BOOST_TEST(kitchen.numCollisionElements() == 5);
  const std::vector<std::string> kitchenLinks{
      "root", "cupboard", "dishwasher_door", "cupboard_door_l", "cupboard_door_r", "kitchen_counter"};
  BOOST_TEST(linkNames(kitchen) == kitchenLinks, boost::test_tools::per_element());
  const std::vector<std::string> kitchenVariables{"dishwasher_door_joint", "cupboard_door_l_joint",
                                                  "cupboard_door_r_joint"};
  BOOST_TEST(kitchen.variableNames() == kitchenVariables, boost::test_tools::per_element());
  BOOST_TEST(kitchen.lowerLimits()[0] == -1.57);
  BOOST_TEST(kitchen.upperLimits()[2] == 3.14);

  RobotModel bars = RobotModel::fromUrdfFile(sceneUrdf("table_bars"), options);
  const std::vector<std::string> barsLinks{"root", "shelves", "right_bars", "left_bars"};
  BOOST_TEST(linkNames(bars) == barsLinks, boost::test_tools::per_element());
  const std::vector<std::string> barsVariables{"right_bars_joint", "left_bars_joint"};
  BOOST_TEST(bars.variableNames() == barsVariables, boost::test_tools::per_element());
  BOOST_TEST(bars.lowerLimits()[0] == -0.35);
  BOOST_TEST(bars.upperLimits()[0] == 0.0);
  BOOST_TEST(bars.lowerLimits()[1] == 0.0);
  BOOST_TEST(bars.upperLimits()[1] == 0.35);
  BOOST_TEST((bars.joint(bars.jointIndex("right_bars_joint")).type == JointType::Prismatic));

  // Placed in the world: every link moves with the base; the bars slide along the scene's y.
  Eigen::Isometry3d X_WR = Eigen::Isometry3d::Identity();
  X_WR.translation() = Eigen::Vector3d(1.0 / 3.0, -0.7, 0.2);
  X_WR.linear() = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  bars.setBasePose(X_WR);
  const Eigen::Vector2d q(-0.2, 0.3);
  const auto X_WL = forwardKinematics(bars, q);
  BOOST_TEST(X_WL[0].isApprox(X_WR, 1e-15));
  const Eigen::Vector3d slide = X_WR.linear() * Eigen::Vector3d(0, -0.2, 0);
  BOOST_TEST((X_WL[2].translation() - (X_WR.translation() + slide)).norm() < 1e-14);

  Eigen::Isometry3d bad = Eigen::Isometry3d::Identity();
  bad.linear()(0, 0) = 2.0;
  checkThrows([&] { bars.setBasePose(bad); }, {"table_bars", "base pose"});
}

BOOST_AUTO_TEST_CASE(ros_package_path_is_read) {
  if (!haveShared("ros_package_path_is_read")) return;
  const char* previous = std::getenv("ROS_PACKAGE_PATH");
  const std::string saved = previous ? previous : "";
  ::setenv("ROS_PACKAGE_PATH", ("/nonexistent/deepcheck:" + sharedDir() + "/robots/panda").c_str(), 1);
  const RobotModel m = RobotModel::fromUrdfFile(pandaUrdf());  // no roots given
  BOOST_TEST(m.numCollisionElements() == 11);
  if (previous) {
    ::setenv("ROS_PACKAGE_PATH", saved.c_str(), 1);
  } else {
    ::unsetenv("ROS_PACKAGE_PATH");
  }
}

BOOST_AUTO_TEST_CASE(primitives_several_collisions_and_relative_meshes) {
  TempDir dir;
  dir.write("meshes/part.stl", "solid p\nendsolid p\n");  // only resolved here, never read
  const std::string urdf = dir.write("robot/r.urdf", R"(<robot name="prims">
  <link name="base">
    <visual><geometry><mesh filename="package://missing_visual_package/v.dae"/></geometry></visual>
    <collision name="first"><origin xyz="0 0 0.1" rpy="0 0 1.5707963267948966"/>
      <geometry><box size="0.2 0.4 0.6"/></geometry></collision>
    <collision><geometry><sphere radius="0.05"/></geometry></collision>
    <collision><origin xyz="1 2 3"/><geometry><cylinder radius="0.03" length="0.5"/></geometry></collision>
    <collision><geometry><mesh filename="../meshes/part.stl" scale="2 2 -1"/></geometry></collision>
    <collision><geometry><mesh filename="file://../meshes/part.stl"/></geometry></collision>
  </link>
</robot>)");
  const RobotModel m = RobotModel::fromUrdfFile(urdf, rootsOnly({}));
  BOOST_TEST(m.numLinks() == 1);
  BOOST_TEST(m.numVariables() == 0);
  const auto& c = m.link(0).collisions;
  BOOST_REQUIRE(c.size() == 5u);
  BOOST_TEST(c[0].name == "first");
  BOOST_TEST((c[0].geometry.type == GeometryType::Box));
  BOOST_TEST((c[0].geometry.boxSize - Eigen::Vector3d(0.2, 0.4, 0.6)).norm() == 0.0);
  BOOST_TEST((c[0].X_LG * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(0, 1, 0.1)).norm() < 1e-15);
  BOOST_TEST((c[1].geometry.type == GeometryType::Sphere));
  BOOST_TEST(c[1].geometry.radius == 0.05);
  BOOST_TEST((c[2].geometry.type == GeometryType::Cylinder));
  BOOST_TEST(c[2].geometry.radius == 0.03);
  BOOST_TEST(c[2].geometry.length == 0.5);
  BOOST_TEST((c[2].X_LG.translation() - Eigen::Vector3d(1, 2, 3)).norm() == 0.0);
  const std::string expected = (dir.path() / "meshes/part.stl").lexically_normal().string();
  BOOST_TEST(c[3].geometry.meshPath == expected);
  BOOST_TEST((c[3].geometry.meshScale - Eigen::Vector3d(2, 2, -1)).norm() == 0.0);
  BOOST_TEST(c[4].geometry.meshPath == expected);
}

BOOST_AUTO_TEST_CASE(package_xml_name_differs_from_folder) {
  TempDir dir;
  dir.write("roots/checkout_v2/package.xml",
            "<?xml version=\"1.0\"?>\n<package format=\"3\">\n  <name> my_robot </name>\n</package>\n");
  const std::string mesh = dir.write("roots/checkout_v2/meshes/a.stl", "solid a\nendsolid a\n");
  const std::string roots = (dir.path() / "roots").string();
  const UriResolution r = resolveUri("package://my_robot/meshes/a.stl", {roots}, "");
  BOOST_TEST(r.found());
  BOOST_TEST(r.path == fs::path(mesh).lexically_normal().string());
  // The root may be the package folder itself.
  const UriResolution self =
      resolveUri("package://my_robot/meshes/a.stl", {(dir.path() / "roots/checkout_v2").string()}, "");
  BOOST_TEST(self.path == fs::path(mesh).lexically_normal().string());
  // The plain rule comes first.
  const std::string plain = dir.write("roots/my_robot/meshes/a.stl", "solid a\nendsolid a\n");
  BOOST_TEST(resolveUri("package://my_robot/meshes/a.stl", {roots}, "").path ==
             fs::path(plain).lexically_normal().string());
  BOOST_TEST(!resolveUri("http://example.com/a.stl", {roots}, "").found());
}

BOOST_AUTO_TEST_CASE(mimic_chain_resolved) {
  const RobotModel m = RobotModel::fromUrdfString(kMimicUrdf, "", rootsOnly({}), "mimic.urdf");
  BOOST_TEST(m.numVariables() == 1);
  BOOST_TEST(m.variableNames()[0] == "j1");
  const Joint& j2 = m.joint(m.jointIndex("j2"));
  const Joint& j3 = m.joint(m.jointIndex("j3"));
  BOOST_TEST(j2.variable == 0);
  BOOST_TEST(j3.variable == 0);
  BOOST_TEST(j2.mimicJoint == m.jointIndex("j1"));
  BOOST_TEST(j3.mimicJoint == m.jointIndex("j2"));
  // j2 = 2 q + 0.1; j3 = -0.5 j2 + 0.2 = -q + 0.15.
  BOOST_TEST(j2.multiplier == 2.0);
  BOOST_TEST(j2.offset == 0.1);
  BOOST_TEST(j3.multiplier == -1.0);
  BOOST_TEST(std::abs(j3.offset - 0.15) < 1e-15);

  // Forward kinematics agrees with the chain written out by hand.
  const double q = 0.37;
  const auto X_WL = forwardKinematics(m, Eigen::VectorXd::Constant(1, q));
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translate(Eigen::Vector3d(0, 0, 0.5)).rotate(Eigen::AngleAxisd(q, Eigen::Vector3d::UnitZ()));
  X.translate(Eigen::Vector3d(0.4, 0, 0)).rotate(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()));
  X.rotate(Eigen::AngleAxisd(2 * q + 0.1, Eigen::Vector3d::UnitY()));
  X.translate(Eigen::Vector3d(0.3, 0, 0)).translate(Eigen::Vector3d(-q + 0.15, 0, 0));
  BOOST_TEST(X_WL[m.linkIndex("c")].isApprox(X, 1e-14));
}

BOOST_AUTO_TEST_CASE(links_with_visuals_are_marked) {
  // The visual's contents are not read (a missing mesh is fine); only that it is there.
  const RobotModel m = RobotModel::fromUrdfString(
      R"(<robot name="v"><link name="drawn"><visual><geometry><mesh filename="missing.stl"/></geometry></visual></link>
      <link name="both"><visual><geometry><box size="1 1 1"/></geometry></visual>
        <collision><geometry><box size="1 1 1"/></geometry></collision></link>
      <link name="bare"/>
      <joint name="a" type="fixed"><parent link="drawn"/><child link="both"/></joint>
      <joint name="b" type="fixed"><parent link="drawn"/><child link="bare"/></joint></robot>)",
      "", rootsOnly({}));
  BOOST_TEST(m.link(m.linkIndex("drawn")).hasVisual);
  BOOST_TEST(m.link(m.linkIndex("drawn")).collisions.empty());
  BOOST_TEST(m.link(m.linkIndex("both")).hasVisual);
  BOOST_TEST(!m.link(m.linkIndex("bare")).hasVisual);
}

BOOST_AUTO_TEST_CASE(continuous_joint_limits) {
  const RobotModel m =
      RobotModel::fromUrdfString(oneJointUrdf("continuous", R"(<axis xyz="0 0 2"/>)"), "", rootsOnly({}));
  BOOST_TEST(m.numVariables() == 1);
  BOOST_TEST(m.lowerLimits()[0] == -M_PI);
  BOOST_TEST(m.upperLimits()[0] == M_PI);
  BOOST_TEST((m.joint(0).axis - Eigen::Vector3d::UnitZ()).norm() == 0.0);  // normalized
  BOOST_TEST(m.defaultConfiguration()[0] == 0.0);
}

BOOST_AUTO_TEST_CASE(floating_joint_fixed_on_request) {
  LoadOptions options = rootsOnly({});
  options.fixFloatingJoints = true;
  const RobotModel m = RobotModel::fromUrdfString(oneJointUrdf("floating", R"(<origin xyz="1 2 3"/>)"), "", options);
  BOOST_TEST(m.numVariables() == 0);
  BOOST_TEST((m.joint(0).type == JointType::Fixed));
  BOOST_TEST(m.joint(0).urdfType == "floating");
  const auto X_WL = forwardKinematics(m, Eigen::VectorXd(0));
  BOOST_TEST((X_WL[1].translation() - Eigen::Vector3d(1, 2, 3)).norm() == 0.0);
}

// ---- bad input: one test each, checking the message ----

BOOST_AUTO_TEST_CASE(error_missing_urdf_file) {
  TempDir dir;
  const std::string path = (dir.path() / "no_such_robot.urdf").string();
  checkThrows([&] { RobotModel::fromUrdfFile(path); }, {path, "does not exist"});
}

BOOST_AUTO_TEST_CASE(error_malformed_xml) {
  TempDir dir;
  const std::string path = dir.write("broken.urdf", "<robot name=\"x\">\n  <link name=\"a\">\n</robot>\n");
  checkThrows([&] { RobotModel::fromUrdfFile(path, rootsOnly({})); }, {"broken.urdf", "malformed XML", "line"});
}

BOOST_AUTO_TEST_CASE(error_text_that_is_not_utf8) {
  // A UTF-8 lead byte cut off by the end of the text made TinyXML read past the end of the buffer
  // (found by fuzz_urdf); such text, NUL bytes and other invalid UTF-8 are rejected first.
  const std::string truncated = "<robot name=\"a\"><link name=\"b\xe1";
  checkThrows([&] { RobotModel::fromUrdfString(truncated, "", rootsOnly({}), "cut.urdf"); },
              {"cut.urdf", "line 1, byte 29 (0xE1): not UTF-8"});
  const std::string nul = std::string("<robot name=\"a\">\n<link name=\"b") + '\0' + "\"/></robot>";
  checkThrows([&] { RobotModel::fromUrdfString(nul, "", rootsOnly({}), "nul.urdf"); },
              {"nul.urdf", "line 2, byte 30 (0x00): a NUL byte"});
  const std::string overlong = "<robot name=\"\xc0\xae\"><link name=\"b\"/></robot>";
  checkThrows([&] { RobotModel::fromUrdfString(overlong, "", rootsOnly({}), "overlong.urdf"); },
              {"overlong.urdf", "byte 13 (0xC0): not UTF-8"});
  checkThrows([&] { deepcheck::robots::parseSrdfDisabledPairs("<robot name=\"\xed\xa0\x80\"/>", "surrogate.srdf"); },
              {"surrogate.srdf", "byte 13 (0xED): not UTF-8"});
  // Valid multi-byte names load.
  const RobotModel ok =
      RobotModel::fromUrdfString("<robot name=\"r\xc3\xa9\xe2\x82\xac\"><link name=\"\xf0\x9f\xa4\x96\"/></robot>", "",
                                 rootsOnly({}), "utf8.urdf");
  BOOST_TEST(ok.name() == "r\xc3\xa9\xe2\x82\xac");
}

BOOST_AUTO_TEST_CASE(error_joint_closes_a_loop) {
  // urdfdom accepts a joint whose child is its own parent or an ancestor of it, and a link with two
  // parent joints; walking the tree then recursed until the stack overflowed (found by fuzz_urdf).
  const std::string self = R"(<robot name="x"><link name="a"/><link name="b"/>
    <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
    <joint name="j2" type="fixed"><parent link="a"/><child link="a"/></joint></robot>)";
  checkThrows([&] { RobotModel::fromUrdfString(self, "", rootsOnly({}), "self.urdf"); },
              {"self.urdf", "joint 'j2' closes a loop: its child link 'a' is also its parent or an ancestor"});
  const std::string cycle = R"(<robot name="x"><link name="a"/><link name="b"/><link name="c"/>
    <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
    <joint name="j2" type="fixed"><parent link="b"/><child link="c"/></joint>
    <joint name="j3" type="fixed"><parent link="c"/><child link="b"/></joint></robot>)";
  checkThrows([&] { RobotModel::fromUrdfString(cycle, "", rootsOnly({}), "cycle.urdf"); },
              {"cycle.urdf", "link 'b' is the child of two joints, 'j1' and 'j3'"});
  const std::string ring = R"(<robot name="x"><link name="a"/><link name="b"/><link name="c"/>
    <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
    <joint name="j2" type="fixed"><parent link="b"/><child link="a"/></joint>
    <joint name="j3" type="fixed"><parent link="b"/><child link="c"/></joint></robot>)";
  checkThrows([&] { RobotModel::fromUrdfString(ring, "", rootsOnly({}), "ring.urdf"); },
              {"ring.urdf", "closes a loop"});
}

BOOST_AUTO_TEST_CASE(error_urdfdom_rejects) {
  // Well-formed XML, but the joint names a link that does not exist.
  const std::string xml = R"(<robot name="x"><link name="a"/>
    <joint name="j" type="fixed"><parent link="a"/><child link="ghost"/></joint></robot>)";
  checkThrows([&] { RobotModel::fromUrdfString(xml, "", rootsOnly({}), "ghost.urdf"); },
              {"ghost.urdf", "urdfdom", "ghost"});
}

BOOST_AUTO_TEST_CASE(error_missing_mesh_lists_searched_places) {
  TempDir dir;
  const std::string rootA = (dir.path() / "rootA").string();
  const std::string rootB = (dir.path() / "rootB").string();
  fs::create_directories(dir.path() / "rootA/my_pkg/meshes");
  fs::create_directories(dir.path() / "rootB");
  const std::string urdf = dir.write("r.urdf", R"(<robot name="r"><link name="arm_link">
    <collision><geometry><mesh filename="package://my_pkg/meshes/arm.stl"/></geometry></collision>
  </link></robot>)");
  checkThrows(
      [&] {
        RobotModel::fromUrdfFile(urdf, rootsOnly({rootA, rootB}));
      },
      {urdf, "arm_link", "package://my_pkg/meshes/arm.stl", (fs::path(rootA) / "my_pkg/meshes/arm.stl").string(),
       (fs::path(rootB) / "my_pkg/meshes/arm.stl").string()});

  // A plain relative path names the place it was looked for.
  const std::string rel = dir.write("s.urdf", R"(<robot name="s"><link name="l">
    <collision><geometry><mesh filename="meshes/nothing.obj"/></geometry></collision>
  </link></robot>)");
  checkThrows([&] { RobotModel::fromUrdfFile(rel, rootsOnly({})); },
              {"s.urdf", "link 'l'", "meshes/nothing.obj", (dir.path() / "meshes/nothing.obj").string()});
}

BOOST_AUTO_TEST_CASE(error_unknown_package) {
  TempDir dir;
  const std::string root = (dir.path() / "ws").string();
  fs::create_directories(root);
  const std::string xml = R"(<robot name="r"><link name="l">
    <collision><geometry><mesh filename="package://no_such_package/m.stl"/></geometry></collision>
  </link></robot>)";
  checkThrows([&] { RobotModel::fromUrdfString(xml, "", rootsOnly({root}), "u.urdf"); },
              {"u.urdf", "link 'l'", "package 'no_such_package'", (fs::path(root) / "no_such_package/m.stl").string()});
  // No roots at all: the message names the library's option (not a command-line flag) and the
  // environment variables.
  checkThrows([&] { RobotModel::fromUrdfString(xml, "", rootsOnly({}), "u.urdf"); },
              {"no package roots", "LoadOptions::packageRoots", "ROS_PACKAGE_PATH"});
}

BOOST_AUTO_TEST_CASE(error_mimic_cycle) {
  const std::string xml = R"(<robot name="cyc">
  <link name="base"/><link name="a"/><link name="b"/>
  <joint name="ja" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="jb"/></joint>
  <joint name="jb" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="ja"/></joint>
</robot>)";
  checkThrows([&] { RobotModel::fromUrdfString(xml, "", rootsOnly({}), "cyc.urdf"); },
              {"cyc.urdf", "cycle", "'ja'", "'jb'"});
  // Mimic of a joint that does not exist.
  checkThrows(
      [&] {
        RobotModel::fromUrdfString(
            oneJointUrdf(
                "revolute",
                R"(<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="phantom"/>)"),
            "", rootsOnly({}), "m.urdf");
      },
      {"m.urdf", "joint 'j'", "phantom"});
}

BOOST_AUTO_TEST_CASE(error_nan_in_origin) {
  checkThrows(
      [&] {
        RobotModel::fromUrdfString(oneJointUrdf("fixed", R"(<origin xyz="0 nan 0" rpy="0 0 0"/>)"), "", rootsOnly({}),
                                   "nan.urdf");
      },
      {"nan.urdf", "joint 'j'", "origin", "non-finite"});
  // In a collision origin: names the link and the collision element.
  const std::string xml = R"(<robot name="r"><link name="body">
    <collision><geometry><sphere radius="1"/></geometry></collision>
    <collision><origin xyz="0 0 0" rpy="inf 0 0"/><geometry><sphere radius="1"/></geometry></collision>
  </link></robot>)";
  checkThrows([&] { RobotModel::fromUrdfString(xml, "", rootsOnly({}), "inf.urdf"); },
              {"inf.urdf", "link 'body'", "collision 1", "rpy", "non-finite"});
  // In a limit.
  checkThrows(
      [&] {
        RobotModel::fromUrdfString(
            oneJointUrdf("revolute", R"(<axis xyz="0 0 1"/><limit lower="-1" upper="NaN" effort="1" velocity="1"/>)"),
            "", rootsOnly({}), "lim.urdf");
      },
      {"lim.urdf", "joint 'j'", "upper", "non-finite"});
}

BOOST_AUTO_TEST_CASE(error_floating_joint_rejected) {
  checkThrows([&] { RobotModel::fromUrdfString(oneJointUrdf("floating", ""), "", rootsOnly({}), "f.urdf"); },
              {"f.urdf", "joint 'j'", "floating", "fixFloatingJoints"});
  checkThrows(
      [&] {
        RobotModel::fromUrdfString(oneJointUrdf("planar", R"(<axis xyz="0 0 1"/>)"), "", rootsOnly({}), "p.urdf");
      },
      {"p.urdf", "joint 'j'", "planar"});
}

BOOST_AUTO_TEST_CASE(error_zero_axis_and_bad_limits) {
  checkThrows(
      [&] {
        RobotModel::fromUrdfString(
            oneJointUrdf("prismatic", R"(<axis xyz="0 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>)"),
            "", rootsOnly({}), "axis.urdf");
      },
      {"axis.urdf", "joint 'j'", "axis", "zero"});
  checkThrows(
      [&] {
        RobotModel::fromUrdfString(
            oneJointUrdf("revolute", R"(<axis xyz="0 0 1"/><limit lower="1" upper="-1" effort="1" velocity="1"/>)"), "",
            rootsOnly({}), "order.urdf");
      },
      {"order.urdf", "joint 'j'", "lower limit"});
}

BOOST_AUTO_TEST_CASE(error_bad_primitive) {
  const std::string xml = R"(<robot name="r"><link name="plate">
    <collision><geometry><box size="0.1 0 0.1"/></geometry></collision>
  </link></robot>)";
  checkThrows([&] { RobotModel::fromUrdfString(xml, "", rootsOnly({}), "b.urdf"); },
              {"b.urdf", "link 'plate'", "collision 0", "box size"});
}

BOOST_AUTO_TEST_SUITE_END()
