// End-to-end tests of `deepcheck plan`: the bundled arm through the bundled shelf, the path file
// checked line by line against the checker, and the errors of bad command lines and inputs.

#include "tool_runner.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/robot_model.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

using namespace deepcheck;
using tool_test::kData;
using tool_test::quote;
using tool_test::Run;
using tool_test::Scratch;

namespace {

/// The options naming the bundled arm and one bundled scene.
std::string armIn(const std::string& scene) {
  return " --robot " + quote(kData + "/deepcheck_arm/urdf/deepcheck_arm.urdf") + " --srdf " +
         quote(kData + "/deepcheck_arm/srdf/deepcheck_arm.srdf") + " --scene " +
         quote(kData + "/scenes/" + scene + ".urdf") + " --package-path " + quote(kData);
}
const std::string kWorld = armIn("shelf");
const std::string kStart = " --start 0 -0.4 0 -1.6 0 1.2 0";
const std::string kGoal = " --goal 1.05 0.75 -1.17 -1.30 0.05 -0.07 -2.79";

/// The world `kWorld` names (the bundled arm with its SRDF in the shelf), to check paths with.
std::unique_ptr<checker::World> armInTheShelf() {
  robots::LoadOptions load;
  load.packageRoots = {kData};
  load.useRosPackagePath = false;
  checker::WorldOptions options;
  options.disabledPairs = robots::readSrdfDisabledPairs(kData + "/deepcheck_arm/srdf/deepcheck_arm.srdf");
  auto world = std::make_unique<checker::World>(
      robots::RobotModel::fromUrdfFile(kData + "/deepcheck_arm/urdf/deepcheck_arm.urdf", load), options);
  world->addScene(robots::RobotModel::fromUrdfFile(kData + "/scenes/shelf.urdf", load));
  return world;
}

/// Runs `deepcheck plan <args>` in the scratch folder (also its decomposition cache).
Run plan(const Scratch& scratch, const std::string& args) { return scratch.run("plan" + args); }

}  // namespace

BOOST_AUTO_TEST_SUITE(tool_plan)

BOOST_AUTO_TEST_CASE(plans_through_the_shelf_and_every_waypoint_is_free) {
  Scratch scratch;
  const std::string out = scratch.path("path.txt");
  const Run r = plan(scratch, kWorld + kStart + kGoal + " --seed 3 --time 10 --out " + quote(out));
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(r.err.find("certified") != std::string::npos, r.err);
  const std::unique_ptr<checker::World> armWorld = armInTheShelf();
  const checker::World& world = *armWorld;
  std::ifstream in(out);
  std::string line;
  std::vector<Eigen::VectorXd> waypoints;
  while (std::getline(in, line)) {
    std::istringstream values(line);
    std::vector<double> q;
    double v;
    while (values >> v) q.push_back(v);
    BOOST_TEST_REQUIRE(q.size() == 7u, "line '" << line << "'");
    waypoints.push_back(Eigen::Map<Eigen::VectorXd>(q.data(), 7));
    BOOST_TEST(world.isFree(waypoints.back()), "waypoint '" << line << "'");
  }
  BOOST_TEST_REQUIRE(waypoints.size() >= 2u);
  BOOST_TEST((waypoints.front() -
              Eigen::Map<const Eigen::VectorXd>(std::vector<double>{0, -0.4, 0, -1.6, 0, 1.2, 0}.data(), 7))
                 .norm() < 1e-12);
  // Every motion, at 0.005 rad.
  for (std::size_t i = 0; i + 1 < waypoints.size(); ++i) {
    const int steps = static_cast<int>(std::ceil((waypoints[i + 1] - waypoints[i]).norm() / 0.005));
    for (int k = 1; k < steps; ++k) {
      BOOST_TEST(world.isFree(waypoints[i] + (double(k) / steps) * (waypoints[i + 1] - waypoints[i])));
    }
  }
}

BOOST_AUTO_TEST_CASE(rrt_star_with_the_clearance_objective_plans_and_certifies) {
  // The table problem (its straight motion is free): RRT* with the clearance objective uses its
  // whole time, then the path is simplified and certified like any other.
  Scratch scratch;
  const std::string out = scratch.path("path.txt");
  const Run r = plan(scratch, armIn("table") + kStart + " --goal -0.14 0.61 0.24 -0.77 -0.14 1.77 -2.23" +
                                  " --planner RRT* --objective clearance --time 1 --seed 2 --out " + quote(out));
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(r.err.find("RRTstar") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("certified") != std::string::npos, r.err);
  std::ifstream in(out);
  std::string line;
  int lines = 0;
  while (std::getline(in, line)) ++lines;
  BOOST_TEST(lines >= 2);
}

BOOST_AUTO_TEST_CASE(bad_command_lines_and_inputs_are_named) {
  Scratch scratch;
  const std::string out = " --out " + quote(scratch.path("p.txt"));
  Run r = plan(scratch, kWorld + kStart + kGoal);  // no --out
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("--out") != std::string::npos, r.err);
  r = plan(scratch, kWorld + kStart + kGoal + out + " --planner RRTDisconnect");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("RRTDisconnect") != std::string::npos, r.err);
  r = plan(scratch, kWorld + " --start 0 0 0" + kGoal + out);  // 3 values for 7 joints
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("start") != std::string::npos, r.err);
  r = plan(scratch, kWorld + kStart + kGoal + out + " --objective fastest");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("fastest") != std::string::npos, r.err);
  // The goal inside the shelf's board: in collision, the pair named, and no planning without repair.
  r = plan(scratch, kWorld + kStart + " --goal 0 1.2 0 0 0 0 0" + out);
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("goal configuration is in collision") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("link6 and scene/shelf") != std::string::npos, r.err);
  // A goal outside the joint limits: the joint, its value and the limit.
  r = plan(scratch, kWorld + kStart + " --goal 0 3 0 0 0 0 0" + out);
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("joint 'joint2' = 3 rad is above its upper limit 2.0944 rad") != std::string::npos, r.err);
  r = plan(scratch, kWorld + " --start 0 -0.4 0 -1.6 0 1.2 -3.1" + kGoal + out + " --repair-start");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("joint 'joint7' = -3.1 rad is below its lower limit -3.05433 rad") != std::string::npos, r.err);
  // --repair-margin: only with --repair-start, in metres >= 0.
  r = plan(scratch, kWorld + kStart + kGoal + out + " --repair-margin 0.002");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.err.find("--repair-start") != std::string::npos, r.err);
  r = plan(scratch, kWorld + kStart + kGoal + out + " --repair-start --repair-margin -1");
  BOOST_TEST(r.status == 2);
}

BOOST_AUTO_TEST_CASE(clamp_to_limits_clamps_the_start_and_warns_once) {
  // joint7 at -3.1, below its lower limit -3.05433: refused, naming the limits; clamped with the
  // option, the path then starting at the limit.
  Scratch scratch;
  const std::string out = scratch.path("path.txt");
  const std::string start = " --start 0 -0.4 0 -1.6 0 1.2 -3.1";
  Run r = plan(scratch, kWorld + start + kGoal + " --out " + quote(out));
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("(limits [-3.05433, 3.05433] rad); --clamp-to-limits clamps it") != std::string::npos, r.err);
  r = plan(scratch, kWorld + start + kGoal + " --clamp-to-limits --seed 3 --time 10 --out " + quote(out));
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(
      r.err.find("deepcheck plan: warning: values clamped to the joint limits of 'joint7'\n") != std::string::npos,
      r.err);
  BOOST_TEST(r.err.find("warning") == r.err.rfind("warning"), r.err);  // one line
  std::ifstream in(out);
  std::vector<double> first(7);
  for (double& v : first) in >> v;
  const robots::RobotModel arm = armInTheShelf()->robot();
  BOOST_TEST(first[6] == arm.lowerLimits()[6]);
}

BOOST_AUTO_TEST_CASE(a_continuous_joint_takes_any_angle) {
  // No limits to refuse: 7 rad is planned from as the same angle in [-pi, pi], without a warning.
  Scratch scratch;
  const std::string robot =
      scratch.write("wheel.urdf",
                    "<robot name='wheel'><link name='base'/><link name='rim'><collision><origin xyz='1 0 0'/><geometry>"
                    "<box size='0.2 0.2 0.2'/></geometry></collision></link><joint name='spin' type='continuous'>"
                    "<parent link='base'/><child link='rim'/><axis xyz='0 0 1'/></joint></robot>");
  const std::string out = scratch.path("path.txt");
  const Run r = plan(scratch, " --robot " + quote(robot) + " --start 7 --goal 0 --seed 1 --out " + quote(out));
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(r.err.find("warning") == std::string::npos, r.err);
  std::ifstream in(out);
  double first = 0.0;
  in >> first;
  BOOST_TEST(std::abs(first - (7.0 - 2.0 * M_PI)) < 1e-12);
}

BOOST_AUTO_TEST_CASE(a_continuous_joint_is_planned_the_short_way_through_pi) {
  // From 3.0 to -3.0 rad: 2 pi - 6 = 0.283 rad through pi, not 6 rad through 0. The path file's
  // values are in (-pi, pi]; the turns between its lines, taken the short way, add up to 0.283.
  Scratch scratch;
  const std::string robot =
      scratch.write("wheel.urdf",
                    "<robot name='wheel'><link name='base'/><link name='rim'><collision><origin xyz='1 0 0'/><geometry>"
                    "<box size='0.2 0.2 0.2'/></geometry></collision></link><joint name='spin' type='continuous'>"
                    "<parent link='base'/><child link='rim'/><axis xyz='0 0 1'/></joint></robot>");
  const std::string out = scratch.path("path.txt");
  const Run r = plan(scratch, " --robot " + quote(robot) + " --start 3.0 --goal -3.0 --seed 1 --out " + quote(out));
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(r.err.find("length 0.2832 rad") != std::string::npos, r.err);
  std::ifstream in(out);
  std::vector<double> values;
  for (double x = 0.0; in >> x;) values.push_back(x);
  BOOST_TEST_REQUIRE(values.size() >= 2u);
  double travel = 0.0;
  for (std::size_t i = 0; i + 1 < values.size(); ++i) {
    BOOST_TEST((values[i] > -M_PI && values[i] <= M_PI));
    travel += std::abs(std::remainder(values[i + 1] - values[i], 2.0 * M_PI));
  }
  BOOST_TEST(std::abs(travel - (2.0 * M_PI - 6.0)) < 1e-9);
  BOOST_TEST(values.back() == -3.0);
  // Informed planners with path length: OMPL's own informed sampler takes no SO2 component, the
  // project's objective falls back to one that does.
  for (const std::string planner : {"BIT*", "InformedRRT*"}) {
    const Run informed = plan(scratch, " --robot " + quote(robot) + " --start 3.0 --goal -3.0 --seed 1 --planner " +
                                           quote(planner) + " --objective length --time 0.5 --out " + quote(out));
    BOOST_TEST(informed.status == 0, planner + ": " + informed.err);
  }
}

BOOST_AUTO_TEST_CASE(a_robot_drawn_with_visuals_only_is_named_in_a_warning) {
  // No collision geometry: every path is free, which the warning line says is not a finding.
  Scratch scratch;
  const std::string robot = scratch.write(
      "drawn.urdf",
      "<robot name='drawn'><link name='base'/><link name='arm'><visual><geometry><box size='0.2 0.2 0.2'/></geometry>"
      "</visual></link><joint name='slide' type='prismatic'><parent link='base'/><child link='arm'/>"
      "<axis xyz='1 0 0'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint></robot>");
  const Run r = plan(
      scratch, " --robot " + quote(robot) + " --start 0 --goal 1 --seed 1 --out " + quote(scratch.path("path.txt")));
  BOOST_TEST(r.status == 0, r.err);
  BOOST_TEST(r.err.find("deepcheck plan: warning: robot 'drawn' has no collision geometry at all: links with "
                        "<visual> but no <collision> geometry, not checked: 'arm'\n") != std::string::npos,
             r.err);
}

BOOST_AUTO_TEST_CASE(a_repaired_start_gets_the_margin_and_the_report_splits_scene_and_self_clearance) {
  // The shelf goal turned about joint 1 until the hand is 2 to 10 mm into the compartment's wall.
  const std::unique_ptr<checker::World> armWorld = armInTheShelf();
  const checker::World& world = *armWorld;
  std::vector<double> start = {1.05, 0.75, -1.17, -1.30, 0.05, -0.07, -2.79};
  const double joint1 = start[0];
  double sd = 1.0;
  for (double turn = 0.0; turn < 0.6 && !(sd < -0.002); turn += 0.002) {
    start[0] = joint1 + turn;
    sd = world.signedDistance(Eigen::Map<const Eigen::VectorXd>(start.data(), 7)).closest.distance;
  }
  BOOST_TEST_REQUIRE(sd < -0.002);
  BOOST_TEST_REQUIRE(sd > -0.010);
  std::string startArg = " --start";
  for (double v : start) startArg += " " + tool_test::formatNumber(v);
  Scratch scratch;
  const Run r = plan(scratch, kWorld + startArg + " --goal 0 -0.4 0 -1.6 0 1.2 0 --repair-start --repair-margin 0.002" +
                                  " --seed 4 --time 10 --out " + quote(scratch.path("path.txt")));
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  // "repair start: Repaired, moved X rad, signed distance now Y m (margin 0.002 m)"
  const std::string key = "repair start: Repaired, moved ";
  const std::size_t at = r.err.find(key);
  BOOST_TEST_REQUIRE(at != std::string::npos, r.err);
  const std::size_t now = r.err.find("signed distance now ", at);
  BOOST_TEST_REQUIRE(now != std::string::npos, r.err);
  BOOST_TEST(std::stod(r.err.substr(now + 20)) > 0.002, r.err);
  BOOST_TEST(r.err.find("(margin 0.002 m)") != std::string::npos, r.err);
  // The path: scene and self clearance, each with its pair; the planning time with a unit that
  // shows it (never "0.000 s").
  BOOST_TEST(r.err.find("scene clearance ") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("scene/shelf)") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("self clearance ") != std::string::npos, r.err);
  const std::size_t after = r.err.find("Exact solution after ");
  BOOST_TEST_REQUIRE(after != std::string::npos, r.err);
  const std::string duration = r.err.substr(after + 21, r.err.find('\n', after) - after - 21);
  BOOST_TEST(std::stod(duration) > 0.0, duration);
  const std::string unit = duration.substr(duration.find(' ') + 1);
  BOOST_TEST((unit == "us" || unit == "ms" || unit == "s"), duration);
}

BOOST_AUTO_TEST_SUITE_END()
