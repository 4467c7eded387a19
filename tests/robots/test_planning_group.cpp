// SRDF planning groups: reading <group> elements, resolving joints, links, chains and subgroups
// to a robot's variables on a small robot where every answer is known, the Panda's groups of
// ../shared, and bad input.

#include "robots_test_util.h"

#include "deepcheck/robots/planning_group.h"
#include "deepcheck/robots/robot_model.h"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

using namespace deepcheck::robots;
using deepcheck::robots::test::checkThrows;
using deepcheck::robots::test::haveShared;
using deepcheck::robots::test::loadPanda;
using deepcheck::robots::test::sharedDir;
using deepcheck::robots::test::TempDir;

namespace {

/// A rail carrying a two-joint arm with a gripper, and a camera on a side branch:
///   world -rail (prismatic)-> cart -j1-> l1 -j2-> l2 -tool_joint (fixed)-> tool
///   tool -fa (prismatic)-> finger_a;  tool -fb (prismatic, mimics fa)-> finger_b
///   cart -pan (continuous)-> camera
const char* kRailUrdf = R"(<robot name="rail">
  <link name="world"/><link name="cart"/><link name="l1"/><link name="l2"/><link name="tool"/>
  <link name="finger_a"/><link name="finger_b"/><link name="camera"/>
  <joint name="rail" type="prismatic"><parent link="world"/><child link="cart"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j1" type="revolute"><parent link="cart"/><child link="l1"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="0.5 0 0"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="tool_joint" type="fixed"><parent link="l2"/><child link="tool"/><origin xyz="0.5 0 0"/></joint>
  <joint name="fa" type="prismatic"><parent link="tool"/><child link="finger_a"/>
    <axis xyz="0 1 0"/><limit lower="0" upper="0.04" effort="1" velocity="1"/></joint>
  <joint name="fb" type="prismatic"><parent link="tool"/><child link="finger_b"/>
    <axis xyz="0 -1 0"/><limit lower="0" upper="0.04" effort="1" velocity="1"/><mimic joint="fa"/></joint>
  <joint name="pan" type="continuous"><parent link="cart"/><child link="camera"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/></joint>
</robot>)";

/// Groups of every kind for kRailUrdf (the tests name the lines of some of them).
const char* kRailSrdf = R"(<?xml version="1.0"?>
<robot name="rail">
  <group name="arm">
    <chain base_link="cart" tip_link="tool"/>
  </group>
  <group name="gripper">
    <link name="finger_a"/>
    <link name="finger_b"/>
    <passive_joint name="fb"/>
  </group>
  <group name="mobile_arm">
    <chain base_link="world" tip_link="l2"/>
  </group>
  <group name="camera">
    <joint name="pan"/>
    <link name="world"/>
  </group>
  <group name="manipulator">
    <group name="arm"/>
    <group name="gripper"/>
  </group>
  <group name="everything">
    <group name="manipulator"/>
    <group name="arm"/>
    <group name="camera"/>
    <joint name="rail"/>
  </group>
  <group name="fixed_only">
    <joint name="tool_joint"/>
    <link name="finger_b"/>
  </group>
  <group name="empty">
  </group>
  <group name="one_link_chain">
    <chain base_link="l1" tip_link="l1"/>
  </group>
</robot>
)";

RobotModel loadRail() { return RobotModel::fromUrdfString(kRailUrdf, "", {}, "rail.urdf"); }

/// The variables of the named joints, ascending.
std::vector<int> variablesOf(const RobotModel& model, std::initializer_list<const char*> joints) {
  std::vector<int> v;
  for (const char* joint : joints) {
    const int index = model.variableIndex(joint);
    BOOST_REQUIRE_MESSAGE(index >= 0, joint << " is not a variable");
    v.push_back(index);
  }
  std::sort(v.begin(), v.end());
  return v;
}

void checkGroup(const RobotModel& model, const std::vector<SrdfGroup>& groups, const std::string& name,
                std::initializer_list<const char*> joints) {
  BOOST_TEST_CONTEXT("group " << name) {
    const std::vector<int> got = groupVariables(model, groups, name, "rail.srdf");
    const std::vector<int> expected = variablesOf(model, joints);
    BOOST_TEST(got == expected, boost::test_tools::per_element());
  }
}

/// SRDF text holding `groups` (the <group> elements) on its line 2 and after.
std::string srdfWith(const std::string& groups) { return "<robot name=\"rail\">\n" + groups + "\n</robot>\n"; }

/// groupVariables of group `name` of `srdf` (read as "bad.srdf") on the rail robot.
std::vector<int> railGroup(const std::string& srdf, const std::string& name) {
  return groupVariables(loadRail(), parseSrdfGroups(srdf, "bad.srdf"), name, "bad.srdf");
}

}  // namespace

BOOST_AUTO_TEST_SUITE(planning_group)

BOOST_AUTO_TEST_CASE(parse_keeps_every_element_in_file_order) {
  const std::vector<SrdfGroup> groups = parseSrdfGroups(kRailSrdf, "rail.srdf");
  BOOST_REQUIRE_EQUAL(groups.size(), 9u);
  BOOST_TEST(groups[0].name == "arm");
  BOOST_TEST(groups[0].line == 3);
  BOOST_REQUIRE_EQUAL(groups[0].chains.size(), 1u);
  BOOST_TEST(groups[0].chains[0].first == "cart");
  BOOST_TEST(groups[0].chains[0].second == "tool");
  BOOST_TEST(groups[1].name == "gripper");
  BOOST_TEST(groups[1].line == 6);
  BOOST_TEST(groups[1].links == (std::vector<std::string>{"finger_a", "finger_b"}), boost::test_tools::per_element());
  BOOST_TEST(groups[1].joints.empty());  // <passive_joint> is not a group joint
  BOOST_TEST(groups[3].joints == std::vector<std::string>{"pan"}, boost::test_tools::per_element());
  BOOST_TEST(groups[3].links == std::vector<std::string>{"world"}, boost::test_tools::per_element());
  BOOST_TEST(groups[5].name == "everything");
  BOOST_TEST(groups[5].line == 22);
  BOOST_TEST(groups[5].subgroups == (std::vector<std::string>{"manipulator", "arm", "camera"}),
             boost::test_tools::per_element());
  BOOST_TEST(groups[5].joints == std::vector<std::string>{"rail"}, boost::test_tools::per_element());
  BOOST_TEST(groups[7].name == "empty");
  BOOST_TEST(
      (groups[7].joints.empty() && groups[7].links.empty() && groups[7].chains.empty() && groups[7].subgroups.empty()));
}

BOOST_AUTO_TEST_CASE(resolves_joints_links_chains_and_subgroups) {
  const RobotModel model = loadRail();
  BOOST_REQUIRE_EQUAL(model.numVariables(), 5);  // rail, j1, j2, fa, pan (fb mimics fa)
  const std::vector<SrdfGroup> groups = parseSrdfGroups(kRailSrdf, "rail.srdf");
  // A chain: the joints below its base link, down to its tip; not the base's parent joint
  // (rail), and the fixed tool_joint moves nothing.
  checkGroup(model, groups, "arm", {"j1", "j2"});
  checkGroup(model, groups, "mobile_arm", {"rail", "j1", "j2"});
  // Links give their parent joints; fb is a mimic of fa, so it adds no variable.
  checkGroup(model, groups, "gripper", {"fa"});
  // The root link has no parent joint.
  checkGroup(model, groups, "camera", {"pan"});
  checkGroup(model, groups, "manipulator", {"j1", "j2", "fa"});
  // arm reached twice (directly and through manipulator) is not a cycle.
  checkGroup(model, groups, "everything", {"rail", "j1", "j2", "fa", "pan"});
}

BOOST_AUTO_TEST_CASE(reads_a_file) {
  TempDir dir;
  const std::string path = dir.write("rail.srdf", kRailSrdf);
  const std::vector<SrdfGroup> groups = readSrdfGroups(path);
  BOOST_REQUIRE_EQUAL(groups.size(), 9u);
  BOOST_TEST(groupVariables(loadRail(), groups, "arm", path) == variablesOf(loadRail(), {"j1", "j2"}),
             boost::test_tools::per_element());
  checkThrows([&] { readSrdfGroups((dir.path() / "missing.srdf").string()); }, {"missing.srdf", "cannot open"});
}

BOOST_AUTO_TEST_CASE(reads_several_files) {
  // Groups of two files in file order; a group both define alike is read once.
  TempDir dir;
  const std::string a = dir.write("a.srdf", srdfWith("<group name=\"arm\"><joint name=\"j1\"/></group>"));
  const std::string b = dir.write("b.srdf", srdfWith("<group name=\"cam\"><joint name=\"pan\"/></group>\n"
                                                     "<group name=\"arm\"><joint name=\"j1\"/></group>"));
  const std::vector<SrdfGroup> groups = readSrdfGroups(std::vector<std::string>{a, b});
  BOOST_REQUIRE_EQUAL(groups.size(), 2u);
  BOOST_TEST(groups[0].name == "arm");
  BOOST_TEST(groups[1].name == "cam");
  const RobotModel model = planningGroupModel(loadRail(), std::vector<std::string>{a, b}, "cam", {});
  BOOST_TEST(model.numVariables() == 1);
  // Defined differently: both files, both lines and the group are named.
  const std::string c = dir.write("c.srdf", srdfWith("\n<group name=\"arm\"><joint name=\"j2\"/></group>"));
  checkThrows(
      [&] {
        readSrdfGroups(std::vector<std::string>{a, c});
      },
      {"c.srdf', line 3", "a.srdf', line 2", "'arm'", "differently"});
  BOOST_TEST(srdfSourceName({a, c}) == a + ", " + c);
}

BOOST_AUTO_TEST_CASE(panda_groups_of_its_moveit_config) {
  if (!haveShared("panda_groups_of_its_moveit_config")) return;
  const RobotModel panda = loadPanda();
  const std::string srdf = sharedDir() + "/robots/panda/moveit_resources_panda_moveit_config/config/panda.srdf";
  const std::vector<SrdfGroup> groups = readSrdfGroups(srdf);
  BOOST_REQUIRE_EQUAL(groups.size(), 3u);

  std::vector<int> arm;
  for (int k = 1; k <= 7; ++k) arm.push_back(panda.variableIndex("panda_joint" + std::to_string(k)));
  BOOST_TEST(groupVariables(panda, groups, "panda_arm", srdf) == arm, boost::test_tools::per_element());

  // panda_finger_joint2 mimics panda_finger_joint1: the hand moves one variable.
  BOOST_REQUIRE(panda.joint(panda.jointIndex("panda_finger_joint2")).isMimic());
  const std::vector<int> hand{panda.variableIndex("panda_finger_joint1")};
  BOOST_TEST(groupVariables(panda, groups, "hand", srdf) == hand, boost::test_tools::per_element());

  std::vector<int> all(panda.numVariables());
  for (int v = 0; v < panda.numVariables(); ++v) all[v] = v;
  BOOST_TEST(groupVariables(panda, groups, "panda_arm_hand", srdf) == all, boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(malformed_groups_are_rejected_when_read) {
  checkThrows([] { parseSrdfGroups("<robot>\n<group name=\"a\">\n</robot>", "bad.srdf"); },
              {"SRDF 'bad.srdf'", "malformed XML at line 3"});
  checkThrows([] { parseSrdfGroups("<robt/>", "bad.srdf"); }, {"bad.srdf", "root element"});
  checkThrows([] { parseSrdfGroups(srdfWith("<group>\n<joint name=\"j1\"/>\n</group>"), "bad.srdf"); },
              {"SRDF 'bad.srdf'", "line 2", "<group> without name"});
  checkThrows(
      [] { parseSrdfGroups(srdfWith("<group name=\"g\">\n<chain base_link=\"cart\"/>\n</group>"), "bad.srdf"); },
      {"SRDF 'bad.srdf'", "line 3", "group 'g'", "<chain> without tip_link"});
  checkThrows([] { parseSrdfGroups(srdfWith("<group name=\"g\">\n<chain tip_link=\"l2\"/>\n</group>"), "bad.srdf"); },
              {"bad.srdf", "line 3", "group 'g'", "<chain> without base_link"});
  checkThrows([] { parseSrdfGroups(srdfWith("<group name=\"g\">\n<joint nam=\"j1\"/>\n</group>"), "bad.srdf"); },
              {"bad.srdf", "line 3", "group 'g'", "<joint> without name"});
  checkThrows([] { parseSrdfGroups(srdfWith("<group name=\"g\">\n<joints name=\"j1\"/>\n</group>"), "bad.srdf"); },
              {"bad.srdf", "line 3", "group 'g'", "<joints>"});
  checkThrows(
      [] {
        parseSrdfGroups(srdfWith("<group name=\"g\"><joint name=\"j1\"/></group>\n"
                                 "<group name=\"g\"><joint name=\"j2\"/></group>"),
                        "bad.srdf");
      },
      {"bad.srdf", "line 3", "group 'g'", "defined twice", "line 2"});
}

BOOST_AUTO_TEST_CASE(unresolvable_groups_are_rejected) {
  checkThrows([] { railGroup(kRailSrdf, "legs"); },
              {"SRDF 'bad.srdf'", "no group 'legs'", "'arm'", "'gripper'", "'one_link_chain'"});
  checkThrows([] { railGroup(srdfWith(""), "arm"); }, {"bad.srdf", "no group 'arm'", "defines no group"});
  checkThrows([] { railGroup(srdfWith("<group name=\"g\">\n<joint name=\"j9\"/></group>"), "g"); },
              {"bad.srdf", "line 2", "group 'g'", "joint 'j9'", "robot 'rail' (rail.urdf)"});
  checkThrows([] { railGroup(srdfWith("<group name=\"g\">\n<link name=\"l9\"/></group>"), "g"); },
              {"bad.srdf", "line 2", "group 'g'", "link 'l9'"});
  checkThrows(
      [] { railGroup(srdfWith("<group name=\"g\">\n<chain base_link=\"cart\" tip_link=\"l9\"/></group>"), "g"); },
      {"bad.srdf", "line 2", "group 'g'", "link 'l9'"});
  // Reversed, and across branches: base_link is not an ancestor of tip_link.
  checkThrows([] { railGroup(srdfWith("<group name=\"g\">\n<chain base_link=\"l2\" tip_link=\"l1\"/></group>"), "g"); },
              {"bad.srdf", "line 2", "group 'g'", "base_link='l2' tip_link='l1'", "not an ancestor"});
  checkThrows(
      [] { railGroup(srdfWith("<group name=\"g\"><chain base_link=\"camera\" tip_link=\"tool\"/></group>"), "g"); },
      {"bad.srdf", "line 2", "group 'g'", "'camera' is not an ancestor of 'tool'"});
  checkThrows([] { railGroup(srdfWith("<group name=\"g\">\n<group name=\"arms\"/></group>"), "g"); },
              {"bad.srdf", "line 2", "group 'g'", "subgroup 'arms'"});
}

BOOST_AUTO_TEST_CASE(subgroup_cycles_are_rejected) {
  const std::string cycle = srdfWith(
      "<group name=\"a\"><group name=\"b\"/></group>\n"
      "<group name=\"b\"><joint name=\"j1\"/><group name=\"c\"/></group>\n"
      "<group name=\"c\"><group name=\"a\"/></group>\n"
      "<group name=\"d\"><group name=\"b\"/></group>");
  checkThrows([&] { railGroup(cycle, "a"); }, {"bad.srdf", "line 4", "group 'c'", "cycle: a -> b -> c -> a"});
  checkThrows([&] { railGroup(cycle, "d"); }, {"bad.srdf", "line 2", "group 'a'", "cycle: b -> c -> a -> b"});
  checkThrows([] { railGroup(srdfWith("<group name=\"self\"><group name=\"self\"/></group>"), "self"); },
              {"bad.srdf", "line 2", "group 'self'", "cycle: self -> self"});
}

BOOST_AUTO_TEST_CASE(groups_that_move_nothing_are_rejected) {
  checkThrows([] { railGroup(kRailSrdf, "fixed_only"); },
              {"SRDF 'bad.srdf'", "line 28", "group 'fixed_only'", "moves no variable", "tool_joint, fb"});
  checkThrows([] { railGroup(kRailSrdf, "empty"); },
              {"bad.srdf", "line 32", "group 'empty'", "moves no variable", "no joint"});
  checkThrows([] { railGroup(kRailSrdf, "one_link_chain"); },
              {"bad.srdf", "line 34", "group 'one_link_chain'", "moves no variable"});
}

BOOST_AUTO_TEST_CASE(deeply_nested_subgroups_are_resolved) {
  // Each group holds the next as its subgroup; the last one holds j2. Following one group per
  // call-stack frame this deep would risk overflowing the stack.
  constexpr int kDepth = 200000;
  std::vector<SrdfGroup> groups(kDepth);
  for (int k = 0; k < kDepth; ++k) {
    groups[k].name = "g" + std::to_string(k);
    groups[k].line = k + 2;
    if (k + 1 < kDepth) groups[k].subgroups = {"g" + std::to_string(k + 1)};
  }
  groups.back().joints = {"j2"};
  const RobotModel model = loadRail();
  BOOST_TEST(groupVariables(model, groups, "g0", "deep.srdf") == variablesOf(model, {"j2"}),
             boost::test_tools::per_element());
  groups.back().subgroups = {"g0"};
  checkThrows([&] { groupVariables(model, groups, "g0", "deep.srdf"); },
              {"deep.srdf", "line " + std::to_string(kDepth + 1), "cycle: g0 -> g1 -> g2 -> "});
}

BOOST_AUTO_TEST_SUITE_END()
