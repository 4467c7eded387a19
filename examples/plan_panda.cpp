// Plan the Franka Emika Panda's arm (MoveIt's panda description, meshes through assimp, its SRDF's
// disabled pairs and its panda_arm planning group) in MotionBenchMaker's kitchen, both from ../shared when present: the
// Panda's collision meshes are convex-decomposed on first use and cached on disk.
//
//   example_plan_panda [SHARED_DIR] [OUT_FILE] [CACHE_DIR]
//
// SHARED_DIR holds robots/panda and scenes/motion_bench_maker (default: ../shared beside the
// repository, compiled in); without it the example says so and exits with status 0. OUT_FILE is
// the path file (default panda_path.txt), CACHE_DIR the decomposition cache (default: the
// library's, under $XDG_CACHE_HOME or ~/.cache).

#include "report.h"

#include <deepcheck/planners/setup.h>

#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

int main(int argc, char** argv) {
  const std::string shared = argc > 1 ? argv[1] : DEEPCHECK_SHARED_DIR;
  const std::string out = argc > 2 ? argv[2] : "panda_path.txt";
  const std::string cache = argc > 3 ? argv[3] : "";
  const std::string panda = shared + "/robots/panda";
  const std::string kitchen = shared + "/scenes/motion_bench_maker/configs/scenes/kitchen/kitchen.urdf";
  if (!std::filesystem::is_directory(panda) || !std::filesystem::is_regular_file(kitchen)) {
    std::printf("skipped: no Panda and kitchen under %s (robots/panda, scenes/motion_bench_maker)\n", shared.c_str());
    return 0;
  }
  ompl::RNG::setSeed(1);  // before any OMPL object: reproducible samples
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  try {
    // 1. package://moveit_resources_panda_description/... resolves under robots/panda, the
    //    kitchen's package:// meshes under scenes/. The Panda's visual-quality collision meshes are
    //    decomposed into convex pieces once (a few seconds each) and read from the cache after.
    deepcheck::planners::SetupOptions options;
    options.packageRoots = {panda, shared + "/scenes"};
    options.srdf = panda + "/moveit_resources_panda_moveit_config/config/panda.srdf";
    // Plan the SRDF's panda_arm group, as MoveIt does: the seven arm joints; the fingers are held
    // 0.035 m open (finger 2 mimics finger 1).
    options.group = "panda_arm";
    options.lockedVariables = {{"panda_finger_joint1", 0.035}};
    options.world.decompositionCacheDir = cache;  // "": the default directory
    const auto loadStart = std::chrono::steady_clock::now();
    auto ss = deepcheck::planners::makeSimpleSetup(panda + "/moveit_resources_panda_description/urdf/panda.urdf",
                                                   {kitchen}, options);
    std::printf("loaded in        %.2f s (robot, kitchen, convex pieces)\n",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - loadStart).count());

    // 2. Above the counter under the cupboard -> in front of the dishwasher (bench/plan_bench.cpp
    //    says how these were picked). The group's 7 variables, panda_joint1..7, in radians.
    Eigen::VectorXd start(7), goal(7);
    start << 2.3235, -0.7332, -0.7202, -1.0283, -1.0430, 1.9942, 0.8179;
    goal << 0.6441, -1.7750, -1.3077, -2.4067, -0.8443, 3.7595, -0.7133;
    deepcheck::planners::setStartAndGoal(*ss, start, goal);

    // 3. Plan, shortcut, certify every motion with the clearance motion validator, report.
    return example::planCertifyAndWrite(*ss, 20.0, out) ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
