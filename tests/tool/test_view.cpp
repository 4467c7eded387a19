// End-to-end tests of `deepcheck view`: the pages of a path, a configuration, a decomposition and
// a pd case file carry the right data (decoded from the page and compared with the library and
// `deepcheck pd`), and bad inputs are named with no page written. The browser test of the pages
// is tests/viewer/.

#include "tool_runner.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/robot_model.h"

#include <boost/test/unit_test.hpp>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

using namespace deepcheck;
using tool_test::kData;
using tool_test::quote;
using tool_test::Run;
using tool_test::Scratch;

namespace {

const std::string kUrdf = kData + "/deepcheck_arm/urdf/deepcheck_arm.urdf";
const std::string kSrdf = kData + "/deepcheck_arm/srdf/deepcheck_arm.srdf";
const std::string kWorld = " --robot " + quote(kUrdf) + " --srdf " + quote(kSrdf) + " --scene " +
                           quote(kData + "/scenes/shelf.urdf") + " --package-path " + quote(kData);
const std::string kStart = "0 -0.4 0 -1.6 0 1.2 0";
const std::string kGoal = "1.05 0.75 -1.17 -1.30 0.05 -0.07 -2.79";

/// The text of the JSON string field `"name":"..."` (the first one in the page).
std::string field(const std::string& page, const std::string& name) {
  const std::string key = "\"" + name + "\":\"";
  const std::size_t at = page.find(key);
  BOOST_TEST_REQUIRE(at != std::string::npos, "no field " << name);
  const std::size_t begin = at + key.size();
  return page.substr(begin, page.find('"', begin) - begin);
}

/// A number field `"name":N` (the first one).
int intField(const std::string& page, const std::string& name) {
  const std::string key = "\"" + name + "\":";
  const std::size_t at = page.find(key);
  BOOST_TEST_REQUIRE(at != std::string::npos, "no field " << name);
  return std::stoi(page.substr(at + key.size()));
}

std::vector<double> decodeFloat64(const std::string& b64) {
  std::string bytes;
  unsigned buffer = 0;
  int bits = 0;
  for (const char c : b64) {
    const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char* p = c == '=' ? nullptr : std::strchr(digits, c);
    if (!p) break;
    buffer = (buffer << 6) | static_cast<unsigned>(p - digits);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes += static_cast<char>((buffer >> bits) & 0xFF);
    }
  }
  std::vector<double> out(bytes.size() / 8);
  std::memcpy(out.data(), bytes.data(), out.size() * 8);
  return out;
}

checker::World shelfWorld() {
  robots::LoadOptions load;
  load.packageRoots = {kData};
  checker::WorldOptions options;
  options.disabledPairs = robots::readSrdfDisabledPairs(kSrdf);
  checker::World world(robots::RobotModel::fromUrdfFile(kUrdf, load), options);
  world.addScene(robots::RobotModel::fromUrdfFile(kData + "/scenes/shelf.urdf", load));
  return world;
}

Eigen::VectorXd configuration(const std::string& text) {
  std::vector<double> v;
  for (const std::string& f : tool_test::fields(text)) v.push_back(std::stod(f));
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

/// The page must not load anything: no script, style or image source outside it.
void checkSelfContained(const std::string& page) {
  BOOST_TEST(page.find("<script src") == std::string::npos);
  BOOST_TEST(page.find("<link") == std::string::npos);
  BOOST_TEST(page.find("THREE.OrbitControls") != std::string::npos);  // inlined with three.js
  BOOST_TEST(page.find("@DEEPCHECK_") == std::string::npos);          // every marker filled
}

}  // namespace

BOOST_AUTO_TEST_SUITE(tool_view)

BOOST_AUTO_TEST_CASE(path_page_has_a_frame_per_waypoint_with_the_worlds_signed_distance) {
  Scratch scratch;
  const std::string path = scratch.write("path.txt", "# start, goal\n" + kStart + "\n\n" + kGoal + "\n");
  const std::string out = scratch.path("view.html");
  const Run r = scratch.run("view" + kWorld + " --path " + quote(path) + " --step 0 --out " + quote(out));
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const std::string page = tool_test::readText(out);
  checkSelfContained(page);
  BOOST_TEST(intField(page, "count") >= 1);
  const std::string frames = page.substr(page.find("\"frames\":"));
  BOOST_TEST_REQUIRE(intField(frames, "count") == 2);
  BOOST_TEST(field(frames, "waypoint") == "11");
  const std::vector<double> values = decodeFloat64(field(frames, "value"));
  BOOST_TEST_REQUIRE(values.size() == 2u);
  const checker::World world = shelfWorld();
  BOOST_TEST(values[0] == world.signedDistance(configuration(kStart)).closest.distance);
  BOOST_TEST(values[1] == world.signedDistance(configuration(kGoal)).closest.distance);
  // Every robot link with geometry follows a track.
  BOOST_TEST(intField(frames, "tracks") == world.summaryCounts().robotLinksWithGeometry);
}

BOOST_AUTO_TEST_CASE(path_is_densified_by_step_with_the_waypoints_kept) {
  Scratch scratch;
  const std::string path = scratch.write("path.txt", kStart + "\n" + kGoal + "\n");
  const std::string out = scratch.path("view.html");
  const Run r = scratch.run("view" + kWorld + " --path " + quote(path) + " --step 0.1 --out " + quote(out));
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const std::string page = tool_test::readText(out);
  const std::string frames = page.substr(page.find("\"frames\":"));
  // The largest joint motion is |-2.79 - 0| = 2.79 rad: ceil(27.9) = 28 steps, 29 frames.
  BOOST_TEST(intField(frames, "count") == 29);
  const std::string waypoints = field(frames, "waypoint");
  BOOST_TEST(waypoints == "1" + std::string(27, '0') + "1");
}

BOOST_AUTO_TEST_CASE(configuration_page_has_one_frame) {
  Scratch scratch;
  const std::string out = scratch.path("view.html");
  const Run r = scratch.run("view" + kWorld + " --config " + kStart + " --hide link3 --out " + quote(out));
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const std::string page = tool_test::readText(out);
  BOOST_TEST(intField(page.substr(page.find("\"frames\":")), "count") == 1);
  BOOST_TEST(page.find("\"name\":\"link3\",\"layer\":\"robot\",\"visible\":false") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(planning_scene_objects_are_shown_as_obstacles) {
  Scratch scratch;
  const std::string scene =
      scratch.write("crate.yaml",
                    "world:\n  collision_objects:\n    - header: {frame_id: world}\n"
                    "      id: crate\n"
                    "      primitives: [{type: box, dimensions: [0.2, 0.2, 0.2]}]\n"
                    "      primitive_poses: [{position: [0.6, 0, 0.1], orientation: [0, 0, 0, 1]}]\n");
  const std::string out = scratch.path("view.html");
  const Run r = scratch.run("view --robot " + quote(kUrdf) + " --package-path " + quote(kData) + " --scene " +
                            quote(scene) + " --frame-alias world=base_link --out " + quote(out));
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const std::string page = tool_test::readText(out);
  BOOST_TEST(page.find("\"name\":\"obstacle/crate\",\"layer\":\"obstacle\"") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(decompose_page_shows_the_mesh_pieces_and_report) {
  Scratch scratch;
  const std::string out = scratch.path("view.html");
  const Run r =
      scratch.run("view --decompose " + quote(kData + "/deepcheck_arm/meshes/hand.stl") + " --out " + quote(out));
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const std::string page = tool_test::readText(out);
  checkSelfContained(page);
  BOOST_TEST(page.find("concavity") != std::string::npos);
  BOOST_TEST(page.find("\"type\":\"mesh\"") != std::string::npos);
  BOOST_TEST(intField(page.substr(page.find("\"pieces\":")), "count") >= 1);
}

BOOST_AUTO_TEST_CASE(pd_page_has_a_frame_per_query_with_the_answers_of_deepcheck_pd) {
  Scratch scratch;
  const std::string cases =
      "shape cube 8\n-1 -1 -1\n1 -1 -1\n-1 1 -1\n1 1 -1\n-1 -1 1\n1 -1 1\n-1 1 1\n1 1 1\n"
      "shape tetra 4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
      "query cube 0 0 0 1 0 0 0 tetra 0.5 0.2 0.3 1 0 0 0\n"
      "query cube 0 0 0 1 0 0 0 tetra 3 0 0 1 0 0 0\n";
  const std::string file = scratch.write("cases.txt", cases);
  const std::string out = scratch.path("view.html");
  const Run r = scratch.run("view --pd " + quote(file) + " --out " + quote(out));
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const Run pd = scratch.run("pd", cases);
  BOOST_TEST_REQUIRE(pd.status == 0, pd.err);
  const std::vector<std::string> answers = tool_test::lines(pd.out);
  const std::string page = tool_test::readText(out);
  const std::string frames = page.substr(page.find("\"frames\":"));
  BOOST_TEST_REQUIRE(intField(frames, "count") == 2);
  const std::vector<double> values = decodeFloat64(field(frames, "value"));
  BOOST_TEST_REQUIRE(values.size() == 2u);
  BOOST_TEST(values[0] == tool_test::number(tool_test::fields(answers[0])[0]));
  BOOST_TEST(values[1] == tool_test::number(tool_test::fields(answers[1])[0]));
  BOOST_TEST(values[0] < 0.0);
  BOOST_TEST(values[1] > 0.0);
  // A and B of each query, and B's answer (a ghost).
  BOOST_TEST(intField(frames, "tracks") == 3);
}

BOOST_AUTO_TEST_CASE(bad_inputs_are_named_and_no_page_is_written) {
  Scratch scratch;
  const std::string out = scratch.path("view.html");
  const auto fails = [&](const std::string& args, int status, const std::string& message) {
    const Run r = scratch.run("view" + args + " --out " + quote(out));
    BOOST_TEST(r.status == status, args << ": " << r.err);
    BOOST_TEST(r.err.find(message) != std::string::npos, args << ": " << r.err);
    BOOST_TEST(!std::filesystem::exists(out), args);
  };
  const std::string shortPath = scratch.write("short.txt", kStart + "\n0 1 2 3 4 5\n");
  fails(kWorld + " --path " + quote(shortPath), 1,
        "short.txt: line 2: 6 values, robot 'deepcheck_arm' has 7 variables");
  const std::string nanPath = scratch.write("nan.txt", kStart + "\n\n0 0 nan 0 0 0 0\n");
  fails(kWorld + " --path " + quote(nanPath), 1, "nan.txt: line 3: 'nan' is not a finite number");
  fails(kWorld + " --config 0 0 nan 0 0 0 0", 2, "--config needs a finite number, got 'nan'");
  fails(kWorld + " --config 0 0 0", 1, "--config has 3 values, robot 'deepcheck_arm' has 7 variables");
  fails(kWorld + " --hide link9", 1, "robot 'deepcheck_arm' has no link 'link9'");
  const std::string srdf = scratch.write(
      "bad.srdf",
      "<robot name=\"deepcheck_arm\"><disable_collisions link1=\"link1\" link2=\"gripper\" reason=\"Never\"/></robot>");
  fails(" --robot " + quote(kUrdf) + " --package-path " + quote(kData) + " --srdf " + quote(srdf), 1, "gripper");
  fails(kWorld + " --path " + quote(scratch.path("missing.txt")), 1, "cannot read the path file");
  fails(kWorld + " --config " + kStart + " --path " + quote(shortPath), 2, "--config and --path exclude each other");
  fails(" --pd " + quote(scratch.write("bad_cases.txt", "shape a 1\n0 0 nan\n")), 1, "bad_cases.txt: line 2");
  fails(" --decompose " + quote(scratch.path("none.stl")), 1, "none.stl");
  const Run noOut = scratch.run("view" + kWorld);
  BOOST_TEST(noOut.status == 2);
  BOOST_TEST(noOut.err.find("option --out is required") != std::string::npos, noOut.err);
}

BOOST_AUTO_TEST_SUITE_END()
