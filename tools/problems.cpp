// deepcheck problems: planning problems generated as MotionBenchMaker generates them (a varied
// planning scene, a start and a goal by collision-free inverse kinematics), written to a folder.

#include "common.h"
#include "load_world.h"
#include "subcommands.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/problems/problem_generation.h"
#include "deepcheck/robots/moveit_scene.h"
#include "deepcheck/robots/random_configuration.h"
#include "deepcheck/robots/robot_model.h"

#include <ompl/util/Console.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace deepcheck::tools {

namespace {

const char kProblemsUsage[] =
    "usage: deepcheck problems --robot URDF [--srdf FILE [--group NAME]] [--lock JOINT=VALUE]...\n"
    "                          [--package-path DIR]... --scene SCENE.yaml|SCENE.urdf\n"
    "                          --variation VARIATION.yaml --queries QUERIES.yaml --robot-config ROBOT.yaml\n"
    "                          [--frame-alias NAME=LINK]... [--tip LINK] [--ee-offset \"x y z qx qy qz qw\"]\n"
    "                          [--count N] [--seed S] [--max-attempts N] --out DIR\n"
    "\n"
    "Generates N planning problems as MotionBenchMaker does: the scene varied as the variation file\n"
    "says, a goal (and a start, when the query file has start_queries) by collision-free inverse\n"
    "kinematics of the tip at an object-relative query pose; without start queries the start is the\n"
    "robot configuration file's default state. Invalid draws are resampled.\n"
    "\n"
    "  --robot URDF          the robot\n"
    "  --srdf FILE           disable the self-collision pairs of this SRDF (one file: the problem\n"
    "                        files record one)\n"
    "  --group NAME          plan only the SRDF's planning group NAME (e.g. panda_arm); the other\n"
    "                        variables are held at the robot configuration file's values\n"
    "  --lock JOINT=VALUE    hold JOINT at VALUE (rad or m; repeatable; overrides the file's value)\n"
    "  --package-path DIR    search DIR for package:// URIs (repeatable)\n"
    "  --scene FILE          the nominal MoveIt planning scene (YAML), or a scene URDF: its links\n"
    "                        become objects named as the links, in the robot's root frame, posed\n"
    "                        for every draw at joint values drawn within their limits (doors,\n"
    "                        sliding parts), as MotionBenchMaker does\n"
    "  --variation FILE      MotionBenchMaker variation file\n"
    "  --queries FILE        MotionBenchMaker query file\n"
    "  --robot-config FILE   MotionBenchMaker robot file (its robot_state is the start)\n"
    "  --frame-alias N=LINK  the scene's frame N is the robot's link LINK (repeatable)\n"
    "  --tip LINK            the end effector (default panda_hand)\n"
    "  --ee-offset POSE      the query frame in the tip frame, x y z qx qy qz qw (default, for\n"
    "                        panda_hand: the query's x axis along the hand's z, 0 0 0 0 -0.70710678 0 0.70710678)\n"
    "  --count N             problems to write (default 10)\n"
    "  --seed S              of every random draw (default 0): the same seed gives the same problems\n"
    "  --max-attempts N      varied scenes tried per problem before giving up (default 100)\n"
    "  --out DIR             output folder (created); existing problem files are overwritten\n"
    "\n"
    "Output, for problem k (4 digits): DIR/scene_k.yaml, the varied scene (a planning scene the\n"
    "--scene option reads), and DIR/problem_k.txt, lines of the form\n"
    "  scene scene_k.yaml\n"
    "  variables NAME...        the robot's variables, in the order of the values below\n"
    "  start V...               the start configuration\n"
    "  goal V...                the goal configuration\n"
    "  goal_query OBJECT_TAG    and, when there was one, start_query OBJECT_TAG\n"
    "  goal_pose x y z qx qy qz qw   the tip's target pose in the world\n"
    "Lines starting with # are comments. Progress goes to standard output.\n";

/// "x y z qx qy qz qw" (spaces or commas) as a pose.
Eigen::Isometry3d parsePose(const std::string& text, const std::string& option) {
  std::string spaced = text;
  for (char& c : spaced) {
    if (c == ',') c = ' ';
  }
  std::istringstream in(spaced);
  std::vector<double> v;
  for (std::string word; in >> word;) v.push_back(parseValue(word, option));
  if (v.size() != 7) throw UsageError(option + " needs 7 numbers (x y z qx qy qz qw), got '" + text + "'");
  return robots::poseFromQuaternion(Eigen::Vector3d(v[0], v[1], v[2]), v[3], v[4], v[5], v[6]);
}

std::string numbers(const Eigen::VectorXd& q) {
  std::ostringstream out;
  out << std::setprecision(17);
  for (Eigen::Index i = 0; i < q.size(); ++i) out << (i ? " " : "") << q[i];
  return out.str();
}

void writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw InputError("cannot write '" + path.string() + "'");
}

void writeProblem(const std::filesystem::path& dir, int index, const problems::Problem& p,
                  const robots::RobotModel& robot) {
  std::ostringstream k;
  k << std::setw(4) << std::setfill('0') << index;
  const std::string scene = "scene_" + k.str() + ".yaml";
  writeText(dir / scene, robots::writePlanningScene(p.scene));
  std::ostringstream out;
  out << "# deepcheck problem " << index << " (deepcheck problems)\n";
  out << "scene " << scene << "\nvariables";
  for (const std::string& name : robot.variableNames()) out << " " << name;
  out << "\nstart " << numbers(p.start) << "\ngoal " << numbers(p.goal) << "\ngoal_query " << p.goalQuery << "\n";
  if (!p.startQuery.empty()) out << "start_query " << p.startQuery << "\n";
  const Eigen::Quaterniond q(p.goalPose.rotation());
  Eigen::VectorXd pose(7);
  pose << p.goalPose.translation(), q.x(), q.y(), q.z(), q.w();
  out << "goal_pose " << numbers(pose) << "\n";
  writeText(dir / ("problem_" + k.str() + ".txt"), out.str());
}

struct ProblemsArgs {
  std::string robot, srdf, group, scene, variation, queries, robotConfig, out;
  std::map<std::string, double> locks;
  PackageRoots packages;
  problems::ProblemOptions options;
  int count = 10;
};

ProblemsArgs takeArgs(std::vector<std::string>& args) {
  ProblemsArgs a;
  a.robot = takeSingleOption(args, "--robot");
  a.srdf = takeSingleOption(args, "--srdf");
  a.group = takeSingleOption(args, "--group");
  a.locks = takeLocks(args);
  a.packages = takePackageRoots(args);
  a.scene = takeSingleOption(args, "--scene");
  a.variation = takeSingleOption(args, "--variation");
  a.queries = takeSingleOption(args, "--queries");
  a.robotConfig = takeSingleOption(args, "--robot-config");
  a.options.frameAliases = takeFrameAliases(args);
  a.options.tipLink = takeSingleOption(args, "--tip", "panda_hand");
  a.options.eeOffset = parsePose(
      takeSingleOption(args, "--ee-offset", "0 0 0 0 -0.70710678118654752 0 0.70710678118654752"), "--ee-offset");
  a.count = static_cast<int>(parseCount(takeSingleOption(args, "--count", "10"), "--count", 1, 1000000));
  a.options.seed =
      parseCount(takeSingleOption(args, "--seed", "0"), "--seed", 0, std::numeric_limits<std::uint64_t>::max());
  a.options.maxAttempts =
      static_cast<int>(parseCount(takeSingleOption(args, "--max-attempts", "100"), "--max-attempts", 1, 1000000));
  a.out = takeSingleOption(args, "--out");
  rejectUnknownOptions(args);
  if (!args.empty()) throw UsageError("unexpected argument '" + args.front() + "'");
  for (const auto& [value, name] : {std::pair{a.robot, "--robot"},
                                    {a.scene, "--scene"},
                                    {a.variation, "--variation"},
                                    {a.queries, "--queries"},
                                    {a.robotConfig, "--robot-config"},
                                    {a.out, "--out"}}) {
    if (value.empty()) throw UsageError(std::string("option ") + name + " is required");
  }
  if (!a.group.empty() && a.srdf.empty())
    throw UsageError("--group " + a.group + " needs --srdf: the planning groups are the SRDF's");
  sceneKind(a.scene);  // a known extension, or a UsageError naming the file
  return a;
}

/// The nominal scene; for a scene URDF also the draw of its joints (options.drawScene).
robots::PlanningScene loadNominal(const ProblemsArgs& a, const robots::RobotModel& robot,
                                  problems::ProblemOptions& options) {
  if (sceneKind(a.scene) == SceneKind::PlanningScene) {
    robots::SceneLoadOptions sceneOptions;
    sceneOptions.packageRoots = a.packages.commandLine;
    return robots::loadPlanningScene(a.scene, sceneOptions);
  }
  robots::LoadOptions load;
  load.packageRoots = a.packages.commandLine;
  auto model = std::make_shared<const robots::RobotModel>(robots::RobotModel::fromUrdfFile(a.scene, load));
  const std::string frame = robot.link(0).name;
  options.drawScene = [model, frame](std::mt19937_64& rng) {
    return robots::planningSceneFromUrdf(*model, robots::randomConfiguration(*model, rng), frame);
  };
  return robots::planningSceneFromUrdf(*model, model->defaultConfiguration(), frame);
}

int runProblems(std::vector<std::string> args) {
  ProblemsArgs a = takeArgs(args);
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  planners::SetupOptions setup;
  setup.packageRoots = a.packages.commandLine;
  setup.srdf = a.srdf;
  const problems::RobotConfig config = problems::loadRobotConfig(a.robotConfig);
  setup.group = a.group;
  setup.lockedVariables = a.locks;
  if (!a.group.empty()) {
    robots::LoadOptions load;
    load.packageRoots = a.packages.commandLine;
    const auto outside =
        problems::lockedOutsideGroup(robots::RobotModel::fromUrdfFile(a.robot, load), config, a.srdf, a.group);
    setup.lockedVariables.insert(outside.begin(), outside.end());  // --lock's values first
  }
  const auto world = planners::loadWorld(a.robot, {}, setup);
  const auto ss = planners::makeSimpleSetup(world, setup);
  const robots::PlanningScene nominal = loadNominal(a, world->robot(), a.options);
  const auto variations = problems::loadSceneVariations(a.variation);
  const auto queries = problems::loadQueries(a.queries);
  std::vector<std::string> notes;
  a.options.start = problems::configurationOf(world->robot(), config, &notes);
  for (const std::string& note : notes) std::fprintf(stderr, "note: %s\n", note.c_str());
  const std::filesystem::path dir(a.out);
  std::filesystem::create_directories(dir);
  problems::generateProblems(
      *world, *planners::validityCheckerOf(*ss), nominal, variations, queries, a.options, a.count,
      [&](int index, const problems::Problem& p) {
        writeProblem(dir, index, p, world->robot());
        std::printf("problem %d/%d: goal %s%s%s, %d scene(s) drawn, goal error %.3g m %.3g rad\n", index + 1, a.count,
                    p.goalQuery.c_str(), p.startQuery.empty() ? "" : ", start ", p.startQuery.c_str(), p.attempts,
                    p.goalError.position, p.goalError.orientation);
        std::fflush(stdout);
      },
      a.variation);
  std::printf("wrote %d problems to %s\n", a.count, dir.string().c_str());
  return 0;
}

}  // namespace

const Subcommand kProblemsCommand = {"problems", "generate planning problems from a scene, variations and queries",
                                     kProblemsUsage, runProblems};

}  // namespace deepcheck::tools
