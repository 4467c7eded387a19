// A UR5 bolted to a table (a robot cell as MoveIt describes it): the planning scene
// robots/data/scenes/ur5_table.yaml holds the table, a crate on it and a post, and an
// allowed-collision matrix that allows the bolted pair (base_link against the table). The robot
// plans from one side of the crate to the other; the clearance it prints is the arm's, not the
// base's 3 mm overlap with the table it stands on.
//
//   example_ur5_on_table [SHARED_DIR] [OUT_FILE] [CACHE_DIR]
//
// SHARED_DIR holds robots/ur5 (example-robot-data's UR5; default: ../shared beside the
// repository, compiled in); without it the example says so and exits with status 0. OUT_FILE is
// the path file (default ur5_path.txt), CACHE_DIR the decomposition cache of the UR5's meshes
// (default: the library's, under $XDG_CACHE_HOME or ~/.cache).

#include "report.h"

#include <deepcheck/checker/world.h>
#include <deepcheck/robots/moveit_scene.h>
#include <deepcheck/planners/setup.h>

#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

int main(int argc, char** argv) {
  const std::string shared = argc > 1 ? argv[1] : DEEPCHECK_SHARED_DIR;
  const std::string out = argc > 2 ? argv[2] : "ur5_path.txt";
  const std::string cache = argc > 3 ? argv[3] : "";
  const std::string ur5 = shared + "/robots/ur5";
  const std::string urdf = ur5 + "/example-robot-data/robots/ur_description/urdf/ur5_robot.urdf";
  if (!std::filesystem::is_regular_file(urdf)) {
    std::printf("skipped: no UR5 under %s (robots/ur5)\n", shared.c_str());
    return 0;
  }
  ompl::RNG::setSeed(1);  // before any OMPL object: reproducible samples
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  try {
    // 1. The robot alone, then the cell. Reports of pairs no joint can change are held back until
    //    the scene's allowed pairs are in, so only a pair the scene does not allow is reported.
    deepcheck::planners::SetupOptions options;
    options.packageRoots = {ur5};
    options.srdf = ur5 + "/example-robot-data/robots/ur_description/srdf/ur5.srdf";
    options.world.decompositionCacheDir = cache;  // "": the default directory
    const auto world = deepcheck::planners::loadWorld(urdf, {}, options);
    const bool reports = world->setFixedPairReports(false);
    const auto scene = deepcheck::robots::loadPlanningScene(DEEPCHECK_DATA_DIR "/scenes/ur5_table.yaml");
    world->addPlanningScene(scene);  // its objects, and its allowed_collision_matrix
    world->setFixedPairReports(reports);
    for (const auto& [a, b] : world->allowedCollisions())
      std::printf("allowed          %s - %s\n", a.c_str(), b.c_str());

    // 2. From the left of the crate to its right, reaching over it. The UR5's 6 joints, radians.
    auto ss = deepcheck::planners::makeSimpleSetup(world, options);
    Eigen::VectorXd start(6), goal(6);
    start << 1.2, -1.0, 1.2, -1.8, -1.57, 0.0;
    goal << -1.2, -1.0, 1.2, -1.8, -1.57, 0.0;
    deepcheck::planners::setStartAndGoal(*ss, start, goal);

    // 3. Plan, shortcut, certify every motion with the clearance motion validator, report.
    return example::planCertifyAndWrite(*ss, 10.0, out) ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
