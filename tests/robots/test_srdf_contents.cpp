// SRDF contents beyond disabled pairs (srdf.h): virtual joints, groups written back, the default
// chain group, and the virtual joint's parent frame as a frame alias (moveit_scene.h).
#include "deepcheck/robots/moveit_scene.h"
#include "deepcheck/robots/planning_group.h"
#include "deepcheck/robots/srdf.h"

#include "robots_test_util.h"

#include <boost/test/unit_test.hpp>

#include <string>
#include <vector>

namespace deepcheck::robots {
namespace {

using test::checkThrows;

/// A base with two arms of two revolute joints each, the first arm ending in a fixed tool.
const char* kTwoArms = R"(<robot name="two_arms">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="tool"/><link name="r1"/><link name="r2"/>
  <joint name="jl1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="jl2" type="revolute"><parent link="l1"/><child link="l2"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="jt" type="fixed"><parent link="l2"/><child link="tool"/></joint>
  <joint name="jr1" type="revolute"><parent link="base"/><child link="r1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="jr2" type="revolute"><parent link="r1"/><child link="r2"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>)";

}  // namespace

BOOST_AUTO_TEST_SUITE(robots_srdf_contents)

BOOST_AUTO_TEST_CASE(groups_and_virtual_joints_round_trip) {
  SrdfContents contents;
  SrdfGroup arm;
  arm.name = "arm & hand";
  arm.joints = {"j1", "j2"};
  arm.links = {"hand"};
  arm.chains = {{"base_link", "link7"}};
  arm.subgroups = {"fingers"};
  SrdfGroup fingers;
  fingers.name = "fingers";
  fingers.joints = {"finger_joint"};
  contents.groups = {arm, fingers};
  contents.virtualJoints = {{"v", "floating", "odom_combined", "base_link", 0}};
  contents.pairs = {{"a", "b", DisableReason::Never}};
  const std::string text = srdfText("robot", contents, "groups");
  const std::vector<SrdfGroup> groups = parseSrdfGroups(text, "memory");
  BOOST_REQUIRE_EQUAL(groups.size(), 2u);
  BOOST_TEST(groups[0].name == arm.name);
  BOOST_TEST(groups[0].joints == arm.joints);
  BOOST_TEST(groups[0].links == arm.links);
  BOOST_TEST((groups[0].chains == arm.chains));
  BOOST_TEST(groups[0].subgroups == arm.subgroups);
  BOOST_TEST(groups[1].joints == fingers.joints);
  const std::vector<SrdfVirtualJoint> joints = parseSrdfVirtualJoints(text, "memory");
  BOOST_REQUIRE_EQUAL(joints.size(), 1u);
  BOOST_TEST(joints[0].name == "v");
  BOOST_TEST(joints[0].type == "floating");
  BOOST_TEST(joints[0].parentFrame == "odom_combined");
  BOOST_TEST(joints[0].childLink == "base_link");
  BOOST_TEST(parseSrdfDisabledPairs(text, "memory").size() == 1u);
  // Groups come first, as MoveIt writes them.
  BOOST_TEST(text.find("<group name=\"arm &amp; hand\">") < text.find("<virtual_joint"));
  BOOST_TEST(text.find("<virtual_joint") < text.find("<disable_collisions"));
}

BOOST_AUTO_TEST_CASE(bad_virtual_joints_name_file_and_line) {
  checkThrows(
      [] {
        parseSrdfVirtualJoints("<robot>\n<virtual_joint name='v' type='fixed' child_link='b'/>\n</robot>", "x.srdf");
      },
      {"SRDF 'x.srdf', line 2", "<virtual_joint> without parent_frame"});
  checkThrows(
      [] {
        parseSrdfVirtualJoints(
            "<robot>\n\n<virtual_joint name='v' type='hinge' parent_frame='w' child_link='b'/></robot>", "x.srdf");
      },
      {"line 3", "'v' has type 'hinge' (known: fixed, floating, planar)"});
  checkThrows([] { parseSrdfVirtualJoints("<robt/>", "x.srdf"); }, {"SRDF 'x.srdf'"});
}

BOOST_AUTO_TEST_CASE(default_group_is_the_longest_chain) {
  const RobotModel arm = test::loadBundledArm();
  const SrdfGroup group = defaultChainGroup(arm);
  BOOST_TEST(group.name == kDefaultGroupName);
  BOOST_REQUIRE_EQUAL(group.chains.size(), 1u);
  BOOST_TEST(group.chains[0].first == "base_link");
  BOOST_TEST(group.chains[0].second == "hand");  // where the fixed fingers branch off
  BOOST_TEST(groupVariables(arm, {group}, group.name, "default").size() == 7u);
  // Two arms of equal length branch apart at the base: the first arm, to its tool.
  const RobotModel twoArms = RobotModel::fromUrdfString(kTwoArms, ".");
  const SrdfGroup first = defaultChainGroup(twoArms);
  BOOST_TEST(first.chains.at(0).second == "tool");
  BOOST_TEST(groupVariables(twoArms, {first}, first.name, "default").size() == 2u);
  const RobotModel still = RobotModel::fromUrdfString("<robot name='still'><link name='a'/></robot>", ".");
  checkThrows([&] { defaultChainGroup(still); }, {"robot 'still' has no moving joint"});
}

BOOST_AUTO_TEST_CASE(virtual_joint_frame_aliases_the_root) {
  const RobotModel arm = test::loadBundledArm();
  const std::vector<SrdfVirtualJoint> joints = {{"v", "fixed", "world", "base_link", 1},
                                                {"w", "fixed", "world", "link1", 2},
                                                {"l", "fixed", "link2", "base_link", 3}};
  const FrameAliases aliases = withVirtualJointAliases({}, joints, arm);
  BOOST_TEST(aliases.size() == 1u);  // link2 names a link; the second "world" comes too late
  BOOST_TEST(aliases.at("world") == "base_link");
  const FrameAliases own = withVirtualJointAliases({{"world", "link3"}}, joints, arm);
  BOOST_TEST(own.at("world") == "link3");
}

BOOST_AUTO_TEST_SUITE_END()

}  // namespace deepcheck::robots
