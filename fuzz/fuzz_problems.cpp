// Fuzz harness: MotionBenchMaker's problem files (problems/problem_generation.h), the files
// `deepcheck problems` reads. The same bytes are read as each of the three: a variation file
// (applied to a two-object scene, World included), a query file (each query's pose put in that
// scene on the bundled arm, and its IK tolerances made), a robot configuration (made a
// configuration of the bundled arm). Bad input must end in std::invalid_argument naming the file
// (the readers' documented error), never a crash or another exception (a yaml-cpp exception
// escaping included); what is accepted must be finite, rigid and within the arm's limits.

#include "harness_support.h"

#include "deepcheck/problems/problem_generation.h"
#include "deepcheck/robots/moveit_scene.h"
#include "deepcheck/robots/robot_model.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace problems = deepcheck::problems;
namespace robots = deepcheck::robots;

const robots::RobotModel& arm() { return deepcheck::fuzz::bundledArm(); }

/// Objects "box" and "can" on the arm's base link.
const robots::PlanningScene& scene() {
  static const robots::PlanningScene s = robots::parsePlanningScene(
      "world:\n  collision_objects:\n"
      "    - header: {frame_id: base_link}\n      id: box\n      primitives: [{type: box, dimensions: [0.2, 0.2, "
      "0.2]}]\n"
      "      primitive_poses: [{position: [0.5, 0, 0.3], orientation: [0, 0, 0, 1]}]\n"
      "    - header: {frame_id: base_link}\n      id: can\n"
      "      primitives: [{type: cylinder, dimensions: [0.1, 0.03]}]\n"
      "      primitive_poses: [{position: [0.4, 0.2, 0.3], orientation: [0, 0.707106781186548, 0, "
      "0.707106781186548]}]\n",
      ".", {}, "fuzz_scene.yaml");
  return s;
}

using deepcheck::fuzz::rigid;

void require(bool ok, const char* what) { deepcheck::fuzz::require(ok, "problem files", what); }

void variations(const std::string& yaml, std::size_t seed) {
  std::vector<problems::SceneVariation> v;
  try {
    v = problems::parseSceneVariations(yaml, "fuzz_variation.yaml");
  } catch (const std::invalid_argument&) {
    return;
  }
  for (const problems::SceneVariation& x : v) {
    require(x.position.allFinite() && x.orientation.allFinite() && (x.position.array() >= 0).all() &&
                (x.orientation.array() >= 0).all(),
            "a variation's widths are negative or not finite");
  }
  std::mt19937_64 rng(seed);
  try {
    const robots::PlanningScene varied = problems::varyScene(scene(), v, rng, "fuzz_variation.yaml");
    for (const auto& object : varied.objects) {
      for (const auto& shape : object.shapes) require(rigid(shape.X_FS), "a varied shape's pose is not rigid");
    }
  } catch (const std::invalid_argument&) {
    // An object the scene does not have.
  }
}

void queries(const std::string& yaml) {
  problems::QuerySet set;
  try {
    set = problems::parseQueries(yaml, "fuzz_queries.yaml");
  } catch (const std::invalid_argument&) {
    return;
  }
  require(!set.goal.empty(), "a query set without goal queries");
  const Eigen::VectorXd q = arm().defaultConfiguration();
  for (const auto* list : {&set.start, &set.goal}) {
    for (const problems::ObjectQuery& query : *list) {
      require(rigid(query.offset), "a query offset is not rigid");
      require((query.positionTolerance.array() > 0).all() && query.positionTolerance.allFinite() &&
                  (query.orientationTolerance.array() > 0).all() && query.orientationTolerance.allFinite(),
              "a query tolerance is not positive and finite");
      const robots::IkOptions ik = problems::queryIkOptions(query, {}, Eigen::Isometry3d::Identity());
      require(std::isfinite(ik.orientationTolerance) && ik.positionBox.allFinite(), "IK tolerances not finite");
      try {
        require(rigid(problems::queryPose(scene(), query, arm(), q, {}, Eigen::Isometry3d::Identity())),
                "a query pose is not rigid");
      } catch (const std::invalid_argument&) {
        // An object the scene does not have.
      }
    }
  }
}

void robotConfig(const std::string& yaml) {
  problems::RobotConfig config;
  try {
    config = problems::parseRobotConfig(yaml, "fuzz_robot.yaml");
  } catch (const std::invalid_argument&) {
    return;
  }
  require(config.jointNames.size() == config.jointPositions.size(), "names and positions of different sizes");
  try {
    const Eigen::VectorXd q = problems::configurationOf(arm(), config);
    require(q.size() == arm().numVariables() && q.allFinite(), "a configuration of the wrong size or not finite");
    require((q.array() >= arm().lowerLimits().array()).all() && (q.array() <= arm().upperLimits().array()).all(),
            "a configuration outside the limits");
  } catch (const std::invalid_argument&) {
    // A joint the arm does not have.
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string yaml(reinterpret_cast<const char*>(data), size);
  variations(yaml, size);
  queries(yaml);
  robotConfig(yaml);
  return 0;
}
