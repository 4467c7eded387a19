#pragma once
// The bundled arm and scenes (robots/data) for the planners suite, loaded once per process, the
// suggested planning problems of robots/data/README.md.

#include "deepcheck/checker/world.h"
#include "deepcheck/planners/push_out.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/robots/random_configuration.h"

#include <Eigen/Core>

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <cstdint>
#include <map>
#include <memory>
#include <ostream>
#include <random>
#include <string>

namespace deepcheck::planners {
/// For Boost.Test messages.
inline std::ostream& operator<<(std::ostream& out, PushOutStatus status) { return out << toString(status); }
}  // namespace deepcheck::planners

namespace deepcheck::planners::test {

/// OMPL's uniform sampler of a RealVectorStateSpace drawing from its own pinned seed instead of
/// OMPL's global seed sequence: two plans on the same seed draw the same samples.
class SeededSampler : public ompl::base::RealVectorStateSampler {
 public:
  SeededSampler(const ompl::base::StateSpace* space, std::uint_fast32_t seed)
      : ompl::base::RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

inline std::string dataDir() { return std::string(DEEPCHECK_SOURCE_DIR) + "/robots/data"; }
inline std::string armUrdf() { return dataDir() + "/deepcheck_arm/urdf/deepcheck_arm.urdf"; }
inline std::string armSrdf() { return dataDir() + "/deepcheck_arm/srdf/deepcheck_arm.srdf"; }
inline std::string sceneUrdf(const std::string& name) { return dataDir() + "/scenes/" + name + ".urdf"; }

/// Package path and SRDF of the bundled arm; ROS_PACKAGE_PATH ignored.
inline SetupOptions bundledOptions() {
  SetupOptions options;
  options.packageRoots = {dataDir()};
  options.useRosPackagePath = false;
  options.srdf = armSrdf();
  return options;
}

/// The arm in one bundled scene ("" for none), loaded once and shared (queries are const).
inline std::shared_ptr<const checker::World> bundledWorld(const std::string& scene) {
  static std::map<std::string, std::shared_ptr<const checker::World>> cache;
  auto it = cache.find(scene);
  if (it != cache.end()) return it->second;
  std::vector<SceneSpec> scenes;
  if (!scene.empty()) scenes.emplace_back(sceneUrdf(scene));
  auto world = loadWorld(armUrdf(), scenes, bundledOptions());
  cache[scene] = world;
  return world;
}

/// Seeded random configurations, the same with every standard library.
using robots::randomConfiguration;
using robots::uniform01;

/// robots/data/README.md, "Suggested planning problems".
inline Eigen::VectorXd suggestedStart() {
  Eigen::VectorXd q(7);
  q << 0, -0.4, 0, -1.6, 0, 1.2, 0;
  return q;
}
inline Eigen::VectorXd suggestedGoal(const std::string& scene) {
  Eigen::VectorXd q(7);
  if (scene == "table") {
    q << -0.14, 0.61, 0.24, -0.77, -0.14, 1.77, -2.23;
  } else if (scene == "shelf") {
    q << 1.05, 0.75, -1.17, -1.30, 0.05, -0.07, -2.79;
  } else {
    q << -0.40, 1.72, -0.40, 1.79, 0.31, 1.50, 0.59;
  }
  return q;
}

}  // namespace deepcheck::planners::test
