// End-to-end tests of `deepcheck check`: the binary is run with popen on URDF files and
// configurations written to temporary files; answers are compared with distances known in closed
// form (a cube on a slider against scene boxes), and the output format with the contract.

#include "tool_runner.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using namespace deepcheck::tool_test;

namespace {

/// Runs `deepcheck check <args>` with `input` on stdin.
Run runCheck(const Scratch& scratch, const std::string& args, const std::string& input) {
  return scratch.run("check " + args, input);
}

// A cube of edge 0.2 on a prismatic joint along x (centre at x = q) and a variable "lift" that
// moves it along z; a scene with a wall (x from 0.6 to 0.8) and a floor (top at z = -0.35).
const char* kRobot =
    "<robot name='slider'><link name='base'/><link name='carriage'/>"
    "<link name='cube'><collision><geometry><box size='0.2 0.2 0.2'/></geometry></collision></link>"
    "<joint name='slide' type='prismatic'><parent link='base'/><child link='carriage'/>"
    "<axis xyz='1 0 0'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>"
    "<joint name='lift' type='prismatic'><parent link='carriage'/><child link='cube'/>"
    "<axis xyz='0 0 1'/><limit lower='-1' upper='1' effort='1' velocity='1'/></joint></robot>";
const char* kScene =
    "<robot name='room'><link name='root'/>"
    "<link name='wall'><collision><origin xyz='0.7 0 0'/><geometry><box size='0.2 2 2'/></geometry></collision></link>"
    "<link name='floor'><collision><origin xyz='0 0 -0.45'/><geometry><box size='4 4 "
    "0.2'/></geometry></collision></link>"
    "<joint name='w' type='fixed'><parent link='root'/><child link='wall'/></joint>"
    "<joint name='f' type='fixed'><parent link='root'/><child link='floor'/></joint></robot>";

constexpr double kExact = 1e-9;

}  // namespace

BOOST_AUTO_TEST_SUITE(tool_check)

BOOST_AUTO_TEST_CASE(known_distances_and_gradients) {
  Scratch s;
  const std::string robot = s.write("slider.urdf", kRobot);
  const std::string scene = s.write("room.urdf", kScene);
  // (x, z): wall distance 0.5 - x, floor distance z + 0.25.
  const std::vector<std::pair<double, double>> qs = {{0.0, 0.0}, {0.4, 0.1}, {-0.3, -0.2}, {0.55, 0.0}, {0.0, -0.3}};
  std::string input = "# x z\n\n";
  for (const auto& [x, z] : qs) input += formatNumber(x) + " " + formatNumber(z) + "\n";
  const Run r = runCheck(s, "--robot " + robot + " --scene " + scene + " --gradient", input);
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const std::vector<std::string> out = lines(r.out);
  BOOST_TEST_REQUIRE(out.size() == qs.size());
  for (std::size_t i = 0; i < qs.size(); ++i) {
    const auto [x, z] = qs[i];
    const double wall = 0.5 - x;
    const double floor = z + 0.25;
    const std::vector<std::string> f = fields(out[i]);
    BOOST_TEST_REQUIRE(f.size() == 11u, out[i]);
    const double sd = number(f[0]);
    BOOST_TEST(std::abs(sd - std::min(wall, floor)) < kExact, out[i]);
    BOOST_TEST(f[1] == "cube");
    BOOST_TEST(f[2] == (wall < floor ? "scene/wall" : "scene/floor"));
    // The scene triple is the same (the scene is nearest); one link has no self pair.
    BOOST_TEST(number(f[3]) == sd);
    BOOST_TEST(f[4] == f[1]);
    BOOST_TEST(f[5] == f[2]);
    BOOST_TEST((f[6] == "inf" && f[7] == "none" && f[8] == "none"), out[i]);
    const double gx = number(f[9]);
    const double gz = number(f[10]);
    BOOST_TEST(std::abs(gx - (wall < floor ? -1.0 : 0.0)) < 1e-9, out[i]);
    BOOST_TEST(std::abs(gz - (wall < floor ? 0.0 : 1.0)) < 1e-9, out[i]);
  }
  const std::vector<std::string> err = lines(r.err);
  BOOST_TEST_REQUIRE(!err.empty());
  BOOST_TEST(err.back().rfind("configurations 5 total_us ", 0) == 0u, err.back());
  BOOST_TEST(r.err.find("robot 'slider'") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(scene_pose_and_no_gradient) {
  Scratch s;
  const std::string robot = s.write("slider.urdf", kRobot);
  const std::string scene = s.write("room.urdf", kScene);
  // The room turned half a turn about z and raised by 0.05: the wall is now at x -0.8 .. -0.6,
  // the floor top at -0.30.
  const Run r = runCheck(s, "--robot=" + robot + " --scene " + scene + " --scene-pose 0 0 0.05 0 0 3.141592653589793",
                         "-0.2 0.3\n0.3 0\n");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const std::vector<std::string> out = lines(r.out);
  BOOST_TEST_REQUIRE(out.size() == 2u);
  std::vector<std::string> f = fields(out[0]);
  BOOST_TEST_REQUIRE(f.size() == 9u);                 // three triples, no gradient
  BOOST_TEST(std::abs(number(f[0]) - 0.3) < kExact);  // wall: -0.3 - (-0.6)
  BOOST_TEST(f[2] == "scene/wall");
  f = fields(out[1]);
  BOOST_TEST(std::abs(number(f[0]) - 0.2) < kExact);  // floor: -0.1 - (-0.3)
  BOOST_TEST(f[2] == "scene/floor");
}

BOOST_AUTO_TEST_CASE(self_pairs_and_srdf) {
  // Two cubes on one slider each; the SRDF disables their pair, leaving no pair at all.
  Scratch s;
  const std::string robot = s.write(
      "pair.urdf",
      "<robot name='pair'><link name='base'/>"
      "<link name='a'><collision><geometry><box size='0.2 0.2 0.2'/></geometry></collision></link>"
      "<link name='b'><collision><geometry><box size='0.2 0.2 0.2'/></geometry></collision></link>"
      "<joint name='ja' type='prismatic'><parent link='base'/><child link='a'/><axis xyz='1 0 0'/>"
      "<limit lower='-2' upper='2' effort='1' velocity='1'/></joint>"
      "<joint name='jb' type='prismatic'><parent link='base'/><child link='b'/><origin xyz='0 0 0'/><axis xyz='1 0 0'/>"
      "<limit lower='-2' upper='2' effort='1' velocity='1'/></joint></robot>");
  // Both hang from the base (geometry-less): adjacent through it, so disabled by default.
  Run r = runCheck(s, "--robot " + robot, "0 1\n");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(lines(r.out).at(0) == "inf none none inf none none inf none none");
  BOOST_TEST(r.err.find("0 link pairs checked") != std::string::npos, r.err);
  // An SRDF for another robot's links is an error naming the link.
  const std::string srdf =
      s.write("bad.srdf", "<robot name='pair'><disable_collisions link1='a' link2='zzz' reason='Never'/></robot>");
  r = runCheck(s, "--robot " + robot + " --srdf " + srdf, "0 1\n");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("zzz") != std::string::npos, r.err);
}

BOOST_AUTO_TEST_CASE(several_srdf_files) {
  // A robot's groups and its disabled pairs in separate files (as the PR2's are): both are read.
  // Two cubes on sliders from a base with geometry: only the pair (a, b) is not adjacent.
  Scratch s;
  const std::string robot = s.write(
      "pair.urdf",
      "<robot name='pair'><link name='base'><collision><origin xyz='0 0 -1'/><geometry><box size='0.1 0.1 0.1'/>"
      "</geometry></collision></link>"
      "<link name='a'><collision><geometry><box size='0.2 0.2 0.2'/></geometry></collision></link>"
      "<link name='b'><collision><origin xyz='0 0.5 0'/><geometry><box size='0.2 0.2 "
      "0.2'/></geometry></collision></link>"
      "<joint name='ja' type='prismatic'><parent link='base'/><child link='a'/><axis xyz='1 0 0'/>"
      "<limit lower='-2' upper='2' effort='1' velocity='1'/></joint>"
      "<joint name='jb' type='prismatic'><parent link='base'/><child link='b'/><axis xyz='1 0 0'/>"
      "<limit lower='-2' upper='2' effort='1' velocity='1'/></joint></robot>");
  const std::string groups =
      s.write("groups.srdf", "<robot name='pair'>\n<group name='a_only'><joint name='ja'/></group>\n</robot>");
  const std::string pairs = s.write("pairs.srdf",
                                    "<robot name='pair'><disable_collisions link1='a' link2='b' reason='Common'/>\n"
                                    "<group name='a_only'><joint name='ja'/></group></robot>");
  Run r = runCheck(s, "--robot " + robot + " --srdf " + groups, "0 0\n");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(r.err.find("1 link pairs checked") != std::string::npos, r.err);
  // The group of the first file, the pair of the second (which defines the group alike).
  r = runCheck(s, "--robot " + robot + " --srdf " + groups + " --srdf " + pairs + " --group a_only", "0\n");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(r.err.find("0 link pairs checked") != std::string::npos, r.err);
  // A group two files define differently: an error naming both files and the group.
  const std::string other =
      s.write("other.srdf", "<robot name='pair'>\n\n<group name='a_only'><joint name='jb'/></group></robot>");
  r = runCheck(s, "--robot " + robot + " --srdf " + groups + " --srdf " + other + " --group a_only", "0\n");
  BOOST_TEST(r.status == 1);
  for (const std::string& word :
       {other + "', line 3", groups + "', line 2", std::string("'a_only'"), std::string("differently")}) {
    BOOST_TEST(r.err.find(word) != std::string::npos, word << ": " << r.err);
  }
}

BOOST_AUTO_TEST_CASE(values_outside_the_joint_limits) {
  Scratch s;
  const std::string robot = s.write("slider.urdf", kRobot);
  const std::string scene = s.write("room.urdf", kScene);
  // Refused: the line, the joint, the value and the limits (slide in [-2, 2], lift in [-1, 1]).
  Run r = runCheck(s, "--robot " + robot + " --scene " + scene, "0 0\n3 0\n");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.out.empty());
  BOOST_TEST(r.err.find("line 2: the configuration is outside the joint limits: joint 'slide' = 3 m is above its "
                        "upper limit 2 m (limits [-2, 2] m)") != std::string::npos,
             r.err);
  // Clamped with --clamp-to-limits: the answers at the limits, one warning line naming each joint.
  r = runCheck(s, "--robot " + robot + " --scene " + scene + " --clamp-to-limits", "3 0\n-5 7\n0 -1\n");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const Run atLimits = runCheck(s, "--robot " + robot + " --scene " + scene, "2 0\n-2 1\n0 -1\n");
  BOOST_TEST(r.out == atLimits.out);
  BOOST_TEST(r.err.find("deepcheck check: warning: values clamped to the joint limits of 'lift', 'slide'\n") !=
                 std::string::npos,
             r.err);
  BOOST_TEST(r.err.find("warning") == r.err.rfind("warning"), r.err);
  BOOST_TEST(atLimits.err.find("warning") == std::string::npos, atLimits.err);
  // A continuous joint has no limits: any value is taken as it is.
  const std::string wheel = s.write("wheel.urdf",
                                    "<robot name='wheel'><link name='base'/>"
                                    "<link name='rim'><collision><origin xyz='1 0 0'/><geometry><box size='0.2 0.2 "
                                    "0.2'/></geometry></collision></link>"
                                    "<joint name='spin' type='continuous'><parent link='base'/><child "
                                    "link='rim'/><axis xyz='0 0 1'/></joint></robot>");
  r = runCheck(s, "--robot " + wheel + " --scene " + scene, "7\n-12.5\n");
  BOOST_TEST(r.status == 0, r.err);
  BOOST_TEST(r.err.find("warning") == std::string::npos, r.err);
  // 4.0 rad is the angle 4.0 - 2 pi (robots/joint_angles.h): the same answers, digit for digit.
  char normalized[64];
  std::snprintf(normalized, sizeof normalized, "%.17g\n", 4.0 - 2.0 * M_PI);
  r = runCheck(s, "--robot " + wheel + " --scene " + scene, "4.0\n");
  const Run same = runCheck(s, "--robot " + wheel + " --scene " + scene, normalized);
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(r.out == same.out);
}

BOOST_AUTO_TEST_CASE(links_with_visual_but_no_collision_geometry) {
  Scratch s;
  const std::string scene = s.write("room.urdf", kScene);
  // Drawn with visuals only: free everywhere, so the links are named in one warning line.
  const std::string drawn =
      s.write("drawn.urdf",
              "<robot name='drawn'><link name='base'><visual><geometry><box size='1 1 1'/></geometry></visual></link>"
              "<link name='arm'><visual><geometry><box size='0.2 0.2 0.2'/></geometry></visual></link>"
              "<joint name='slide' type='prismatic'><parent link='base'/><child link='arm'/><axis xyz='1 0 0'/>"
              "<limit lower='-2' upper='2' effort='1' velocity='1'/></joint></robot>");
  Run r = runCheck(s, "--robot " + drawn + " --scene " + scene, "0.7\n");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(r.err.find("deepcheck check: warning: robot 'drawn' has no collision geometry at all: links with "
                        "<visual> but no <collision> geometry, not checked: 'base', 'arm'\n") != std::string::npos,
             r.err);
  BOOST_TEST(r.err.find("warning") == r.err.rfind("warning"), r.err);
  // Some links with collision geometry: only the visual-only ones are named.
  const std::string half =
      s.write("half.urdf",
              "<robot name='half'><link name='base'><visual><geometry><box size='1 1 1'/></geometry></visual></link>"
              "<link name='arm'><visual><geometry><box size='0.2 0.2 0.2'/></geometry></visual>"
              "<collision><geometry><box size='0.2 0.2 0.2'/></geometry></collision></link>"
              "<joint name='slide' type='prismatic'><parent link='base'/><child link='arm'/><axis xyz='1 0 0'/>"
              "<limit lower='-2' upper='2' effort='1' velocity='1'/></joint></robot>");
  r = runCheck(s, "--robot " + half + " --scene " + scene, "0\n");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(r.err.find("deepcheck check: warning: robot 'half': links with <visual> but no <collision> geometry, "
                        "not checked: 'base'\n") != std::string::npos,
             r.err);
  // Collision geometry everywhere: no warning.
  r = runCheck(s, "--robot " + s.write("slider.urdf", kRobot) + " --scene " + scene, "0 0\n");
  BOOST_TEST(r.err.find("warning") == std::string::npos, r.err);
}

BOOST_AUTO_TEST_CASE(bad_input_and_command_lines) {
  Scratch s;
  const std::string robot = s.write("slider.urdf", kRobot);
  const std::string scene = s.write("room.urdf", kScene);
  // Wrong number of values: exit 1, the line named, nothing on stdout.
  Run r = runCheck(s, "--robot " + robot, "0 0\n0.1\n");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.out.empty());
  BOOST_TEST(r.err.find("line 2") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("2 variables") != std::string::npos, r.err);
  r = runCheck(s, "--robot " + robot, "0 nan\n");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("line 1") != std::string::npos, r.err);
  // Command-line errors: exit 2 with the usage.
  for (const std::string& args : {std::string(""), "--robot " + robot + " --scene-pose 0 0 0 0 0 0",
                                  "--robot " + robot + " --scene " + scene + " --scene-pose 0 0 0 0 0",
                                  "--robot " + robot + " --scene " + scene + " --scene-pose 0 0 0 0 0 x",
                                  "--robot " + robot + " --frobnicate", "--robot " + robot + " --robot " + robot}) {
    r = runCheck(s, args, "");
    BOOST_TEST(r.status == 2, "args '" << args << "': " << r.err);
    BOOST_TEST(r.err.find("usage: deepcheck check") != std::string::npos);
  }
  // A missing file: exit 1 naming it.
  r = runCheck(s, "--robot " + (s.dir / "none.urdf").string(), "");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("none.urdf") != std::string::npos, r.err);
}

BOOST_AUTO_TEST_CASE(locked_joints_and_planning_groups) {
  // The cube's lift held at 0.1 (by --lock, or as the joint outside the SRDF group "slide_only"
  // held at its --lock value): configurations are the slide alone, the floor 0.35 below.
  Scratch s;
  const std::string robot = s.write("slider.urdf", kRobot);
  const std::string scene = s.write("room.urdf", kScene);
  const std::string srdf =
      s.write("slider.srdf",
              "<robot name='slider'>\n<group name='slide_only'><joint name='slide'/></group>\n"
              "<group name='both'><group name='slide_only'/><joint name='lift'/></group>\n</robot>");
  for (const std::string& how :
       {std::string("--lock lift=0.1"), "--srdf " + srdf + " --group slide_only --lock lift=0.1"}) {
    const Run r = runCheck(s, "--robot " + robot + " --scene " + scene + " --gradient " + how, "0\n0.4\n");
    BOOST_TEST_REQUIRE(r.status == 0, how << ": " << r.err);
    const std::vector<std::string> out = lines(r.out);
    BOOST_TEST_REQUIRE(out.size() == 2u);
    for (std::size_t i = 0; i < 2; ++i) {
      const std::vector<std::string> f = fields(out[i]);
      BOOST_TEST_REQUIRE(f.size() == 10u, out[i]);  // three triples and one gradient component
      BOOST_TEST(std::abs(number(f[0]) - std::min(0.5 - 0.4 * static_cast<double>(i), 0.35)) < kExact, out[i]);
    }
  }
  // Without --lock the joint outside the group is held at its default, 0: the floor 0.25 below.
  Run r = runCheck(s, "--robot " + robot + " --scene " + scene + " --srdf " + srdf + " --group slide_only", "0\n");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(std::abs(number(fields(lines(r.out).at(0)).at(0)) - 0.25) < kExact, r.out);
  // Two values where the group has one: the count is named.
  r = runCheck(s, "--robot " + robot + " --srdf " + srdf + " --group slide_only", "0 0\n");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("1 variables") != std::string::npos, r.err);
  // Errors naming the group, the joint, the value.
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"--srdf " + srdf + " --group nosuch", "group 'nosuch'"},
      {"--srdf " + srdf + " --group slide_only --lock slide=0", "it is a variable of group 'slide_only'"},
      {"--lock lift=5", "outside its limits [-1, 1]"},
      {"--lock cube=0", "cannot lock 'cube'"},
      {"--srdf " + srdf + " --group both --lock lift=0", "a variable of group 'both'"}};
  for (const auto& [args, message] : bad) {
    r = runCheck(s, "--robot " + robot + " " + args, "0\n");
    BOOST_TEST(r.status == 1, args);
    BOOST_TEST(r.err.find(message) != std::string::npos, args << ": " << r.err);
  }
  r = runCheck(s, "--robot " + robot + " --srdf " + srdf + " --group nosuch", "0\n");
  BOOST_TEST(r.err.find("slide_only") != std::string::npos, r.err);  // the groups the file has
  // Command-line errors: exit 2.
  for (const std::string& args : {std::string("--group slide_only"), std::string("--lock lift"),
                                  std::string("--lock lift=x"), std::string("--lock lift=0 --lock lift=0.1")}) {
    r = runCheck(s, "--robot " + robot + " " + args, "0\n");
    BOOST_TEST(r.status == 2, args << ": " << r.err);
  }
}

BOOST_AUTO_TEST_CASE(bundled_arm_in_the_shelf) {
  // The project's own arm and shelf: runs on a fresh clone.
  Scratch s;
  const std::string data = std::string(DEEPCHECK_SOURCE_DIR) + "/robots/data";
  const std::string args = "--robot " + quote(data + "/deepcheck_arm/urdf/deepcheck_arm.urdf") + " --srdf " +
                           quote(data + "/deepcheck_arm/srdf/deepcheck_arm.srdf") + " --scene " +
                           quote(data + "/scenes/shelf.urdf") + " --package-path " + quote(data) + " --gradient";
  // The arm straight up (clear of the shelf), and bent forward into it.
  const Run r = runCheck(s, args, "0 0 0 0 0 0 0\n0 1.2 0 0 0 0 0\n");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const std::vector<std::string> out = lines(r.out);
  BOOST_TEST_REQUIRE(out.size() == 2u);
  for (const std::string& line : out) BOOST_TEST(fields(line).size() == 9u + 7u, line);
  BOOST_TEST(number(fields(out[0])[0]) > 0.0, out[0]);
  BOOST_TEST(number(fields(out[1])[0]) < 0.0, out[1]);
  BOOST_TEST(fields(out[1])[2] == "scene/shelf", out[1]);
  // Straight up, the nearest pair is the wrist (link5, link7, a few centimetres apart in every
  // configuration); the scene clearance, reported apart, is far larger.
  const std::vector<std::string> up = fields(out[0]);
  BOOST_TEST((up[1] == "link5" && up[2] == "link7"), out[0]);
  BOOST_TEST(up[5] == "scene/shelf", out[0]);
  BOOST_TEST(number(up[3]) > 0.2, out[0]);
  BOOST_TEST(number(up[6]) == number(up[0]), out[0]);
  BOOST_TEST((up[7] == "link5" && up[8] == "link7"), out[0]);
  // Bent into the shelf: the overall minimum is the scene's, the self clearance still the wrist's.
  const std::vector<std::string> bent = fields(out[1]);
  BOOST_TEST(number(bent[3]) == number(bent[0]), out[1]);
  BOOST_TEST(number(bent[6]) > 0.0, out[1]);
}

BOOST_AUTO_TEST_CASE(damaged_decomposition_cache_entries_are_recomputed_with_a_note) {
  // The bundled arm's meshes go through the scratch folder's decomposition cache. Each entry is
  // then replaced by a directory, then by garbage: the answers stay the same, exit status 0, and
  // stderr says what was wrong with the cache.
  Scratch s;
  const std::string data = std::string(DEEPCHECK_SOURCE_DIR) + "/robots/data";
  const std::string args =
      "--robot " + quote(data + "/deepcheck_arm/urdf/deepcheck_arm.urdf") + " --package-path " + quote(data);
  const std::string input = "0 0.3 0 -1 0 0.5 0\n";
  const Run first = runCheck(s, args, input);
  BOOST_TEST_REQUIRE(first.status == 0, first.err);
  const fs::path cache = fs::path(s.path("cache")) / "deepcheck";
  std::vector<fs::path> entries;
  for (const auto& e : fs::directory_iterator(cache)) entries.push_back(e.path());
  BOOST_TEST_REQUIRE(!entries.empty());
  for (const fs::path& e : entries) {
    fs::remove(e);
    fs::create_directory(e);
  }
  Run r = runCheck(s, args, input);
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(r.out == first.out);
  BOOST_TEST(r.err.find("deepcheck: decomposition cache: " + entries.front().string()) != std::string::npos, r.err);
  BOOST_TEST(r.err.find("not a regular file") != std::string::npos, r.err);
  for (const fs::path& e : entries) {
    fs::remove(e);
    std::ofstream(e, std::ios::binary) << std::string(100, 'x');  // long enough to have a checksum
  }
  r = runCheck(s, args, input);
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(r.out == first.out);
  BOOST_TEST(r.err.find("checksum mismatch") != std::string::npos, r.err);
}

BOOST_AUTO_TEST_CASE(package_roots_from_ros_package_path) {
  // The arm's meshes are package:// URIs: found through ROS_PACKAGE_PATH alone, and not found
  // (exit 1, the URI named) when no root holds them.
  Scratch s;
  const std::string data = std::string(DEEPCHECK_SOURCE_DIR) + "/robots/data";
  const std::string args = "check --robot " + quote(data + "/deepcheck_arm/urdf/deepcheck_arm.urdf");
  Run r = s.run(args, "0 0 0 0 0 0 0\n", "ROS_PACKAGE_PATH=" + quote(s.path("nothing") + ":" + data));
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(lines(r.out).size() == 1u);
  r = s.run(args, "0 0 0 0 0 0 0\n", "ROS_PACKAGE_PATH= AMENT_PREFIX_PATH=");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("package://deepcheck_arm/") != std::string::npos, r.err);
}

BOOST_AUTO_TEST_CASE(panda_in_the_kitchen) {
  const std::string shared = DEEPCHECK_SHARED_DIR;
  if (!fs::is_directory(shared + "/robots")) {
    BOOST_TEST_MESSAGE("skipped panda_in_the_kitchen: the shared data folder (../shared) is absent");
    return;
  }
  Scratch s;
  const std::string args =
      "--robot " + quote(shared + "/robots/panda/moveit_resources_panda_description/urdf/panda.urdf") + " --srdf " +
      quote(shared + "/robots/panda/moveit_resources_panda_moveit_config/config/panda.srdf") + " --scene " +
      quote(shared + "/scenes/motion_bench_maker/configs/scenes/kitchen/kitchen.urdf") + " --package-path " +
      quote(shared + "/robots/panda") + " --package-path " + quote(shared + "/scenes");
  // The Panda's ready pose (clear), then its arm folded down into the counter.
  const Run r = runCheck(s, args, "0 -0.785 0 -2.356 0 1.571 0.785 0.035\n1.0 1.2 0 -0.5 0 1.0 0 0.02\n");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const std::vector<std::string> out = lines(r.out);
  BOOST_TEST_REQUIRE(out.size() == 2u);
  BOOST_TEST(number(fields(out[0])[0]) > 0.0, out[0]);
  BOOST_TEST(number(fields(out[1])[0]) < 0.0, out[1]);
  BOOST_TEST(fields(out[1])[2].rfind("scene/", 0) == 0u, out[1]);
  BOOST_TEST(r.err.find("scene 0 'kitchen'") != std::string::npos, r.err);
}

// A robot whose base (moved by no joint) is sunk 0.05 into the floor: reported once after
// loading with the option that allows it; --allow-collision removes the pair from the answers;
// bad names and bad syntax are errors.
BOOST_AUTO_TEST_CASE(allow_collision_and_the_fixed_pair_report) {
  Scratch s;
  std::string robotXml = kRobot;
  robotXml.replace(robotXml.find("<link name='base'/>"), std::string("<link name='base'/>").size(),
                   "<link name='base'><collision><origin xyz='0 0 -0.3'/><geometry><box size='0.2 0.2 0.2'/>"
                   "</geometry></collision></link>");
  const std::string robot = s.write("bolted.urdf", robotXml);
  const std::string scene = s.write("room.urdf", kScene);
  const std::string world = "--robot " + robot + " --scene " + scene;
  const Run sunk = runCheck(s, world, "0 0.3\n");
  BOOST_TEST_REQUIRE(sunk.status == 0, sunk.err);
  BOOST_TEST(sunk.err.find("warning: base and scene/floor are -0.05 m apart in every configuration (no joint moves "
                           "base): every configuration collides; allow it with --allow-collision base:scene/floor") !=
                 std::string::npos,
             sunk.err);
  BOOST_TEST(std::abs(number(fields(lines(sunk.out).at(0))[0]) + 0.05) < kExact, sunk.out);

  const Run allowed = runCheck(s, world + " --allow-collision base:floor", "0 0.3\n");
  BOOST_TEST_REQUIRE(allowed.status == 0, allowed.err);
  BOOST_TEST(allowed.err.find("warning") == std::string::npos, allowed.err);
  const std::vector<std::string> f = fields(lines(allowed.out).at(0));
  BOOST_TEST(std::abs(number(f[0]) - 0.5) < kExact, allowed.out);  // the cube to the wall
  BOOST_TEST(f[2] == "scene/wall");

  const Run typo = runCheck(s, world + " --allow-collision base:flor", "0 0\n");
  BOOST_TEST(typo.status == 1);
  BOOST_TEST(typo.err.find("--allow-collision base:flor: allowCollision: no robot link, attached object, scene link or "
                           "obstacle is named 'flor'; near matches: 'floor'") != std::string::npos,
             typo.err);
  const Run syntax = runCheck(s, world + " --allow-collision base", "0 0\n");
  BOOST_TEST(syntax.status == 2);
  BOOST_TEST(syntax.err.find("--allow-collision needs A:B") != std::string::npos, syntax.err);
  const Run anything = runCheck(s, world + " --allow-collision base:*", "0 0.3\n");
  BOOST_TEST_REQUIRE(anything.status == 0, anything.err);
  BOOST_TEST(fields(lines(anything.out).at(0))[2] == "scene/wall");
}

BOOST_AUTO_TEST_SUITE_END()
