// The MotionBenchMaker scenes of mbm_bench and their generated problems (mbm_problems.h).

#include "mbm_problems.h"

#include "plan_problems.h"

#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/robot_model.h"

#include <cmath>
#include <stdexcept>

namespace deepcheck::bench {

namespace dp = deepcheck::planners;

namespace {

std::string mbmDir() { return sharedDir() + "/scenes/motion_bench_maker/configs"; }

/// A scene of ../shared's MotionBenchMaker folder `dir` from its file names there.
MbmScene sceneOf(const std::string& name, const std::string& dir, const std::string& scene,
                 const std::string& variation, const std::string& queries) {
  const std::string d = mbmDir() + "/scenes/" + dir + "/";
  return {name, d + scene, d + variation, d + queries, Eigen::Isometry3d::Identity()};
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// The links of a scene URDF with collision geometry as planning-scene objects in frame
/// base_link, posed at the scene's default configuration placed at X_WS.
robots::PlanningScene sceneFromUrdf(const MbmScene& scene) {
  robots::LoadOptions load;
  load.packageRoots = pandaOptions().packageRoots;
  load.useRosPackagePath = false;
  const robots::RobotModel model = robots::RobotModel::fromUrdfFile(scene.scene, load);
  const std::vector<Eigen::Isometry3d> X_WL = robots::forwardKinematics(model, model.defaultConfiguration());
  robots::PlanningScene out;
  out.source = scene.scene;
  for (int l = 0; l < model.numLinks(); ++l) {
    const robots::Link& link = model.link(l);
    if (link.collisions.empty()) continue;
    robots::SceneObject object;
    object.id = link.name;
    object.frameId = "base_link";
    for (std::size_t c = 0; c < link.collisions.size(); ++c) {
      robots::SceneShape shape;
      shape.geometry = link.collisions[c].geometry;
      shape.X_FS = scene.X_WS * X_WL[static_cast<std::size_t>(l)] * link.collisions[c].X_LG;
      shape.name = "collision " + std::to_string(c) + " of link " + link.name;
      object.shapes.push_back(shape);
    }
    // The object's pose is its first shape's (problem_generation.h): queries are relative to it.
    out.objects.push_back(object);
  }
  return out;
}

}  // namespace

std::vector<MbmScene> mbmScenes() {
  std::vector<MbmScene> list{
      sceneOf("bookshelf_small", "bookshelf", "scene_small.yaml", "variation_small.yaml", "all_queries_small.yaml"),
      sceneOf("bookshelf_tall", "bookshelf", "scene_tall.yaml", "variation_tall.yaml", "all_queries_tall.yaml"),
      sceneOf("bookshelf_thin", "bookshelf", "scene_thin.yaml", "variation_thin.yaml", "all_queries_thin.yaml"),
      sceneOf("cage", "cage", "scene_cage.yaml", "variation_cage.yaml", "queries_cage.yaml"),
      sceneOf("box", "box", "scene_box.yaml", "variation_box.yaml", "hard_queries_box.yaml"),
      sceneOf("table_pick", "table", "scene_table.yaml", "variation_table.yaml", "queries_pick_table.yaml"),
      sceneOf("kitchen", "kitchen", "kitchen.urdf", "variation.yaml", "hard_queries.yaml"),
      sceneOf("table_bars", "table_bars", "table_bars.urdf", "variation.yaml", "single_arm_queries.yaml")};
  list.back().X_WS = tableBarsPose();
  return list;
}

robots::FrameAliases pandaFrameAliases() { return {{"base_link", "panda_link0"}}; }

robots::PlanningScene loadNominalScene(const MbmScene& scene) {
  if (endsWith(scene.scene, ".urdf")) return sceneFromUrdf(scene);
  robots::SceneLoadOptions options;
  options.packageRoots = pandaOptions().packageRoots;
  options.useRosPackagePath = false;
  return robots::loadPlanningScene(scene.scene, options);
}

dp::ProblemOptions pandaProblemOptions(const robots::RobotModel& panda, std::uint64_t seed,
                                       std::vector<std::string>* notes) {
  dp::ProblemOptions o;
  o.tipLink = "panda_hand";
  o.eeOffset = Eigen::Isometry3d::Identity();
  o.eeOffset.linear() = Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  o.frameAliases = pandaFrameAliases();
  o.start = dp::configurationOf(panda, dp::loadRobotConfig(mbmDir() + "/robots/panda.yaml"), notes);
  o.seed = seed;
  return o;
}

std::vector<dp::Problem> generateMbmProblems(const MbmScene& scene, checker::World& world,
                                             const dp::StateValidityChecker& checker, const dp::ProblemOptions& options,
                                             int count, const dp::ProblemProgress& progress) {
  const robots::PlanningScene nominal = loadNominalScene(scene);
  const auto variations = dp::loadSceneVariations(scene.variation);
  const auto queries = dp::loadQueries(scene.queries);
  return dp::generateProblems(world, checker, nominal, variations, queries, options, count, progress, scene.variation);
}

void placeScene(checker::World& world, const robots::PlanningScene& scene) {
  for (int id : world.obstacleIds()) world.removeObstacle(id);
  checker::PlanningSceneOptions placement;
  placement.frameAliases = pandaFrameAliases();
  world.addPlanningScene(scene, placement);
}

}  // namespace deepcheck::bench
