// The MotionBenchMaker scenes of mbm_bench and their generated problems (mbm_problems.h).

#include "mbm_problems.h"

#include "plan_problems.h"

#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/random_configuration.h"
#include "deepcheck/robots/robot_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace deepcheck::bench {

namespace dp = deepcheck::planners;

namespace {

std::string mbmDir() { return sharedDir() + "/scenes/motion_bench_maker/configs"; }

/// x y z qx qy qz qw as a pose; the quaternion, written with 3 digits, normalised.
Eigen::Isometry3d pose(const std::array<double, 7>& v) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  X.linear() = Eigen::Quaterniond(v[6], v[3], v[4], v[5]).normalized().toRotationMatrix();
  return X;
}

/// A scene of ../shared's MotionBenchMaker folder `dir` from its file names there, its base_offset
/// and ee_offset.
MbmScene sceneOf(const std::string& name, const std::string& dir, const std::string& scene,
                 const std::string& variation, const std::string& queries, const std::array<double, 7>& base,
                 const std::array<double, 7>& ee) {
  const std::string d = mbmDir() + "/scenes/" + dir + "/";
  return {name, d + scene, d + variation, d + queries, pose(base), pose(ee)};
}

/// Every object of `scene` moved by X in the world frame (the objects' frame is the robot's base).
void moveAll(robots::PlanningScene& scene, const Eigen::Isometry3d& X) {
  for (robots::SceneObject& object : scene.objects) {
    object.X_FO = X * object.X_FO;
    for (robots::SceneShape& shape : object.shapes) shape.X_FS = X * shape.X_FS;
  }
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

robots::RobotModel loadSceneUrdf(const MbmScene& scene) {
  robots::LoadOptions load;
  load.packageRoots = pandaOptions().packageRoots;
  load.useRosPackagePath = false;
  return robots::RobotModel::fromUrdfFile(scene.scene, load);
}

/// The links of a scene URDF at configuration q as planning-scene objects in frame base_link,
/// moved by the scene's base_offset.
robots::PlanningScene linksAsScene(const robots::RobotModel& model, const Eigen::VectorXd& q, const MbmScene& scene) {
  robots::PlanningScene out = robots::planningSceneFromUrdf(model, q, "base_link");
  moveAll(out, scene.baseOffset);
  return out;
}

}  // namespace

std::vector<MbmScene> mbmScenes() {
  // base_offset and ee_offset of MotionBenchMaker's configs/problems/<name>_panda.yaml.
  const std::array<double, 7> ee{0, 0, -0.08, -0.271, -0.653, -0.271, 0.653};
  return {sceneOf("bookshelf_small", "bookshelf", "scene_small.yaml", "variation_small.yaml", "all_queries_small.yaml",
                  {0.2, 0, -0.7, 0, 0, 0, 1}, ee),
          sceneOf("bookshelf_tall", "bookshelf", "scene_tall.yaml", "variation_tall.yaml", "all_queries_tall.yaml",
                  {0.3, 0, -0.7, 0, 0, 0, 1}, ee),
          sceneOf("bookshelf_thin", "bookshelf", "scene_thin.yaml", "variation_thin.yaml", "all_queries_thin.yaml",
                  {-0.1, 0, -0.7, 0, 0, 0, 1}, ee),
          sceneOf("cage", "cage", "scene_cage.yaml", "variation_cage.yaml", "queries_cage.yaml",
                  {0, 0, -0.18, 0, 0, 0, 1}, {0.13, -0.13, 0.11, 0, 0, 0.924, 0.383}),
          sceneOf("box", "box", "scene_box.yaml", "variation_box.yaml", "hard_queries_box.yaml",
                  {-0.15, 0, -1.02, 0, 0, 0, 1}, {0, 0, -0.08, -0.653, -0.271, -0.653, 0.271}),
          sceneOf("table_pick", "table", "scene_table.yaml", "variation_table.yaml", "queries_pick_table.yaml",
                  {0.1, 0.1, -0.5, 0, 0, 0, 1}, ee),
          sceneOf("kitchen", "kitchen", "kitchen.urdf", "variation.yaml", "hard_queries.yaml",
                  {0.2, 0.4, -0.7, 0, 0, 0, 1}, {0.2, 0.2, 0.03, -0.271, -0.653, -0.271, 0.653}),
          sceneOf("table_bars", "table_bars", "table_bars.urdf", "variation.yaml", "single_arm_queries.yaml",
                  {0.6, 0, -0.6, 0, 0, 0, 1}, {0.29, -0.29, 0.35, -0.271, -0.653, -0.271, 0.653})};
}

robots::FrameAliases pandaFrameAliases() { return {{"base_link", "panda_link0"}}; }

dp::SetupOptions pandaArmOptions() {
  static const dp::SetupOptions options = [] {
    dp::SetupOptions o = pandaOptions();
    robots::LoadOptions load;
    load.packageRoots = o.packageRoots;
    load.useRosPackagePath = false;
    o.group = "panda_arm";
    o.lockedVariables =
        problems::lockedOutsideGroup(robots::RobotModel::fromUrdfFile(pandaUrdf(), load),
                                     problems::loadRobotConfig(mbmDir() + "/robots/panda.yaml"), o.srdf, o.group);
    return o;
  }();
  return options;
}

robots::PlanningScene loadNominalScene(const MbmScene& scene, problems::SceneDraw* draw) {
  if (endsWith(scene.scene, ".urdf")) {
    auto model = std::make_shared<const robots::RobotModel>(loadSceneUrdf(scene));
    if (draw != nullptr) {
      *draw = [model, scene](std::mt19937_64& rng) {
        return linksAsScene(*model, robots::randomConfiguration(*model, rng), scene);
      };
    }
    return linksAsScene(*model, model->defaultConfiguration(), scene);
  }
  robots::SceneLoadOptions options;
  options.packageRoots = pandaOptions().packageRoots;
  options.useRosPackagePath = false;
  robots::PlanningScene out = robots::loadPlanningScene(scene.scene, options);
  moveAll(out, scene.baseOffset);
  return out;
}

problems::ProblemOptions pandaProblemOptions(const MbmScene& scene, const robots::RobotModel& panda, std::uint64_t seed,
                                             std::vector<std::string>* notes) {
  problems::ProblemOptions o;
  o.tipLink = "panda_link8";
  o.eeOffset = scene.eeOffset;
  o.frameAliases = pandaFrameAliases();
  o.start = problems::configurationOf(panda, problems::loadRobotConfig(mbmDir() + "/robots/panda.yaml"), notes);
  o.seed = seed;
  return o;
}

std::vector<problems::Problem> generateMbmProblems(const MbmScene& scene, checker::World& world,
                                                   const dp::StateValidityChecker& checker,
                                                   const problems::ProblemOptions& options, int count,
                                                   const problems::ProblemProgress& progress) {
  problems::ProblemOptions drawing = options;
  const robots::PlanningScene nominal = loadNominalScene(scene, &drawing.drawScene);
  const auto variations = problems::loadSceneVariations(scene.variation);
  const auto queries = problems::loadQueries(scene.queries);
  return problems::generateProblems(world, checker, nominal, variations, queries, drawing, count, progress,
                                    scene.variation);
}

void placeScene(checker::World& world, const robots::PlanningScene& scene) {
  for (int id : world.obstacleIds()) world.removeObstacle(id);
  checker::PlanningSceneOptions placement;
  placement.frameAliases = pandaFrameAliases();
  world.addPlanningScene(scene, placement);
}

std::vector<MbmScene> selectScenes(const std::vector<std::string>& wanted, Usage usage) {
  const std::vector<MbmScene> all = mbmScenes();
  if (wanted.empty()) return all;
  std::vector<MbmScene> out;
  for (const std::string& w : wanted) {
    auto it = std::find_if(all.begin(), all.end(), [&](const MbmScene& s) { return s.name == w; });
    if (it == all.end()) usage("unknown scene '" + w + "'");
    out.push_back(*it);
  }
  return out;
}

}  // namespace deepcheck::bench
