// End-to-end tests of `deepcheck info` on the bundled arm (robots/data): the binary is run with
// popen and its text output is read back.

#include "tool_runner.h"

#include "deepcheck/robots/planning_group.h"
#include "deepcheck/robots/robot_model.h"
#include "deepcheck/robots/srdf.h"

#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

using namespace deepcheck::tool_test;
namespace fs = std::filesystem;
namespace robots = deepcheck::robots;

namespace {

const std::string kArm = kData + "/deepcheck_arm/urdf/deepcheck_arm.urdf";

/// Runs `deepcheck info <args>` (each argument one word) with an empty stdin.
Run runInfo(const Scratch& scratch, const std::vector<std::string>& args) {
  return scratch.run("info " + quoteAll(args));
}

/// The lines of `text` after the line equal to `heading`, up to the next blank line.
std::vector<std::string> section(const std::string& text, const std::string& heading) {
  std::istringstream in(text);
  std::vector<std::string> lines;
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (inside && line.empty()) break;
    if (inside) lines.push_back(line);
    if (line == heading) inside = true;
  }
  return lines;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(tool_info)

BOOST_AUTO_TEST_CASE(bundled_arm) {
  Scratch scratch;
  const Run r = runInfo(scratch, {kArm, "--package-path", kData, "--samples", "2000"});
  BOOST_REQUIRE_MESSAGE(r.status == 0, "exit " << r.status << ": " << r.err);
  BOOST_TEST(r.out.find("robot 'deepcheck_arm'") != std::string::npos);
  BOOST_TEST(r.out.find("12 links (11 with collision geometry), 11 joints, 7 variables") != std::string::npos);

  // The 7 variables, in configuration order, with their limits.
  const std::vector<std::string> vars = section(r.out, "variables (configuration order):");
  BOOST_REQUIRE_EQUAL(vars.size(), 8u);  // a header and 7 rows
  const std::regex row(R"(\s*(\d+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s*)");
  for (int v = 0; v < 7; ++v) {
    std::smatch m;
    BOOST_REQUIRE_MESSAGE(std::regex_match(vars[v + 1], m, row), "bad row: " << vars[v + 1]);
    BOOST_TEST(std::stoi(m[1]) == v);
    BOOST_TEST(m[2].str() == "joint" + std::to_string(v + 1));
    BOOST_TEST(m[3].str() == "revolute");
    BOOST_TEST(std::stod(m[4]) == -std::stod(m[5]));
    BOOST_TEST(std::stod(m[5]) > 2.0);
  }

  // Links with their element and piece counts; the flange has neither. link1's mesh is not
  // convex: the checker decomposes it into several pieces.
  const std::vector<std::string> links = section(r.out, "links:");
  BOOST_REQUIRE_EQUAL(links.size(), 13u);
  BOOST_TEST(std::regex_match(links[9], std::regex(R"(\s*8\s+flange\s+link7\s+flange_joint\s+0\s+0\s*)")), links[9]);
  std::smatch link1;
  BOOST_TEST_REQUIRE(
      std::regex_match(links[2], link1, std::regex(R"(\s*1\s+link1\s+base_link\s+joint1\s+1\s+(\d+)\s*)")), links[2]);
  BOOST_TEST(std::stoi(link1[1]) > 1);

  std::smatch summary;
  BOOST_REQUIRE(std::regex_search(r.out, summary, std::regex(R"((\d+) convex pieces)")));
  BOOST_TEST(section(r.out, "pieces:").size() == std::stoul(summary[1]));
  BOOST_TEST(r.out.find("finger.stl") != std::string::npos);

  // Pair counts: 55 pairs of the 11 links with geometry, 10 adjacent ones, the rest balanced.
  std::smatch m;
  BOOST_REQUIRE(std::regex_search(r.out, m, std::regex(R"(links with geometry: (\d+), link pairs: (\d+))")));
  BOOST_TEST(m[1].str() == "11");
  BOOST_TEST(m[2].str() == "55");
  BOOST_REQUIRE(std::regex_search(
      r.out, m, std::regex(R"(disabled: (\d+) \(Adjacent (\d+), Default (\d+), Always (\d+), Never (\d+)\))")));
  const int disabled = std::stoi(m[1]);
  BOOST_TEST(std::stoi(m[2]) == 10);
  BOOST_TEST(std::stoi(m[2]) + std::stoi(m[3]) + std::stoi(m[4]) + std::stoi(m[5]) == disabled);
  BOOST_REQUIRE(std::regex_search(r.out, m, std::regex(R"(remaining \(checked\): (\d+))")));
  BOOST_TEST(std::stoi(m[1]) + disabled == 55);
  BOOST_TEST(std::stoi(m[1]) > 0);
}

BOOST_AUTO_TEST_CASE(pieces_are_the_checkers_through_the_same_cache) {
  // info decomposes the meshes as check does, through the same cache: its piece count is the one
  // check's summary gives, more than one hull per mesh (the arm's links are not convex), and
  // check finds every decomposition in the cache info filled.
  Scratch scratch(Scratch::Cache::Empty);
  const Run info = runInfo(scratch, {kArm, "--package-path", kData, "--samples", "0"});
  BOOST_REQUIRE_MESSAGE(info.status == 0, "exit " << info.status << ": " << info.err);
  std::smatch m;
  BOOST_REQUIRE(std::regex_search(info.out, m, std::regex(R"((\d+) collision elements, (\d+) convex pieces)")));
  const int elements = std::stoi(m[1]);
  const int pieces = std::stoi(m[2]);
  BOOST_TEST(pieces > elements);
  BOOST_TEST(section(info.out, "pieces:").size() == static_cast<std::size_t>(pieces));
  int perLink = 0;
  for (const std::string& row : section(info.out, "links:")) {
    const std::vector<std::string> f = fields(row);
    if (f.size() == 6 && f[0] != "index") perLink += std::stoi(f[5]);
  }
  BOOST_TEST(perLink == pieces);

  const fs::path cache = fs::path(scratch.path("cache")) / "deepcheck";
  std::vector<fs::path> entries;
  for (const auto& e : fs::directory_iterator(cache)) entries.push_back(e.path());
  BOOST_TEST(!entries.empty());
  const Run check = scratch.run("check --robot " + quote(kArm) + " --package-path " + quote(kData), "0 0 0 0 0 0 0\n");
  BOOST_REQUIRE_MESSAGE(check.status == 0, "exit " << check.status << ": " << check.err);
  BOOST_REQUIRE(std::regex_search(check.err, m, std::regex(R"(robot 'deepcheck_arm': .* (\d+) pieces)")));
  BOOST_TEST(std::stoi(m[1]) == pieces);
  std::size_t after = 0;
  for (const auto& e : fs::directory_iterator(cache)) after += e.is_regular_file() ? 1 : 0;
  BOOST_TEST(after == entries.size(), "check added cache entries: info did not use the same cache");
}

BOOST_AUTO_TEST_CASE(writes_srdf) {
  Scratch scratch;
  const std::string srdf = scratch.path("arm.srdf");
  const Run r =
      runInfo(scratch, {kArm, "--package-path=" + kData, "--samples", "500", "--seed", "3", "--write-srdf", srdf});
  BOOST_REQUIRE_MESSAGE(r.status == 0, "exit " << r.status << ": " << r.err);
  const std::string text = readText(srdf);
  BOOST_TEST(text.find("<robot name=\"deepcheck_arm\">") != std::string::npos);
  BOOST_TEST(text.find("<disable_collisions link1=\"base_link\" link2=\"link1\" reason=\"Adjacent\"/>") !=
             std::string::npos);
  BOOST_TEST(text.find("<disable_collisions link1=\"link7\" link2=\"hand\" reason=\"Adjacent\"/>") !=
             std::string::npos);
  BOOST_TEST(text.find("500 random samples, seed 3") != std::string::npos);
  BOOST_TEST(r.out.find("disabled pairs, 1 planning groups)") != std::string::npos, r.out);
  // The file is a usable SRDF: its default group is the chain from the root to the hand (where
  // the fingers branch off), and it reads back to the pairs written.
  const std::vector<robots::SrdfGroup> groups = robots::readSrdfGroups(srdf);
  BOOST_REQUIRE_EQUAL(groups.size(), 1u);
  BOOST_TEST(groups[0].name == robots::kDefaultGroupName);
  BOOST_REQUIRE_EQUAL(groups[0].chains.size(), 1u);
  BOOST_TEST(groups[0].chains[0].first == "base_link");
  BOOST_TEST(groups[0].chains[0].second == "hand");
  robots::LoadOptions load;
  load.packageRoots = {kData};
  const robots::RobotModel arm = robots::RobotModel::fromUrdfFile(kArm, load);
  BOOST_TEST(robots::groupVariables(arm, groups, groups[0].name, srdf).size() == 7u);
  BOOST_TEST(!robots::readSrdfDisabledPairs(srdf).empty());
  const Run check = scratch.run("check --robot " + quote(kArm) + " --package-path " + quote(kData) + " --srdf " +
                                    quote(srdf) + " --group " + robots::kDefaultGroupName,
                                "0 0 0 0 0 0 0\n");
  BOOST_TEST(check.status == 0, check.err);
}

BOOST_AUTO_TEST_CASE(write_srdf_keeps_the_groups_and_virtual_joint_of_srdf) {
  Scratch scratch;
  const std::string given =
      scratch.write("given.srdf",
                    "<robot name='deepcheck_arm'>\n"
                    "  <group name='shoulder'><chain base_link='base_link' tip_link='link2'/></group>\n"
                    "  <group name='wrist'><joint name='joint6'/><joint name='joint7'/>"
                    "<group name='shoulder'/></group>\n"
                    "  <virtual_joint name='v' type='fixed' parent_frame='world' child_link='base_link'/>\n"
                    "</robot>\n");
  const std::string written = scratch.path("written.srdf");
  const Run r = runInfo(scratch, {kArm, "--package-path", kData, "--samples", "0", "--srdf", given, "--group", "wrist",
                                  "--write-srdf", written});
  BOOST_REQUIRE_MESSAGE(r.status == 0, r.err);
  const std::vector<robots::SrdfGroup> groups = robots::readSrdfGroups(written);
  BOOST_REQUIRE_EQUAL(groups.size(), 2u);
  BOOST_TEST(groups[0].name == "shoulder");
  BOOST_TEST(groups[1].joints == (std::vector<std::string>{"joint6", "joint7"}));
  BOOST_TEST(groups[1].subgroups == std::vector<std::string>{"shoulder"});
  // The same groups as the given file: both files together are no conflict.
  BOOST_TEST(robots::readSrdfGroups(std::vector<std::string>{given, written}).size() == 2u);
  const std::vector<robots::SrdfVirtualJoint> joints = robots::readSrdfVirtualJoints(written);
  BOOST_REQUIRE_EQUAL(joints.size(), 1u);
  BOOST_TEST(joints[0].parentFrame == "world");
  BOOST_TEST(joints[0].childLink == "base_link");
}

BOOST_AUTO_TEST_CASE(locked_joints_and_a_planning_group) {
  Scratch scratch;
  const std::string srdf =
      scratch.write("arm_group.srdf",
                    "<robot name='deepcheck_arm'>\n"
                    "  <group name='shoulder'><chain base_link='base_link' tip_link='link2'/></group>\n"
                    "</robot>\n");
  // --lock: joint7 leaves the variables and is listed as held.
  Run r = runInfo(scratch, {kArm, "--package-path", kData, "--samples", "0", "--lock", "joint7=0.5"});
  BOOST_REQUIRE_MESSAGE(r.status == 0, r.err);
  BOOST_TEST(section(r.out, "variables (configuration order):").size() == 7u);  // a header and 6 rows
  const std::vector<std::string> held = section(r.out, "locked joints:");
  BOOST_REQUIRE_EQUAL(held.size(), 1u);
  BOOST_TEST(held[0] == "  joint7 (revolute) held at 0.5");
  // --group: joint1 and joint2 move; joints 3 to 7 are held at their defaults.
  r = runInfo(scratch, {kArm, "--package-path", kData, "--samples", "0", "--srdf", srdf, "--group", "shoulder"});
  BOOST_REQUIRE_MESSAGE(r.status == 0, r.err);
  const std::vector<std::string> vars = section(r.out, "variables (configuration order):");
  BOOST_REQUIRE_EQUAL(vars.size(), 3u);
  BOOST_TEST(vars[1].find("joint1") != std::string::npos);
  BOOST_TEST(vars[2].find("joint2") != std::string::npos);
  BOOST_TEST(section(r.out, "locked joints:").size() == 5u);
  // Errors: the group without its SRDF (usage), an unknown group (named, with the file's groups).
  BOOST_TEST(runInfo(scratch, {kArm, "--group", "shoulder"}).status == 2);
  r = runInfo(scratch, {kArm, "--package-path", kData, "--samples", "0", "--srdf", srdf, "--group", "elbow"});
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("elbow") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("shoulder") != std::string::npos, r.err);
}

BOOST_AUTO_TEST_CASE(bad_input) {
  Scratch scratch;
  // A missing file: exit 1, one error line naming it.
  const Run missing = runInfo(scratch, {kData + "/no_such_robot.urdf"});
  BOOST_TEST(missing.status == 1);
  BOOST_TEST(missing.err.find("deepcheck info:") == 0u);
  BOOST_TEST(missing.err.find("no_such_robot.urdf") != std::string::npos);
  // An unresolvable package: exit 1, naming the URI.
  const Run package = runInfo(scratch, {kArm, "--samples", "0"});
  if (package.status != 0) {  // unless ROS_PACKAGE_PATH happens to hold robots/data
    BOOST_TEST(package.status == 1);
    BOOST_TEST(package.err.find("package://deepcheck_arm/meshes/") != std::string::npos);
  }
  // Bad command lines: exit 2.
  BOOST_TEST(runInfo(scratch, {}).status == 2);
  BOOST_TEST(runInfo(scratch, {kArm, "--samples", "many"}).status == 2);
  BOOST_TEST(runInfo(scratch, {kArm, "--bogus"}).status == 2);
  BOOST_TEST(runInfo(scratch, {kArm, kArm}).status == 2);
}

BOOST_AUTO_TEST_SUITE_END()
