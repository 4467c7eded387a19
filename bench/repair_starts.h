#pragma once
// The start-repair benchmarks' shared setup (repair_bench, push_out_body_bench): the bundled arm in
// a bundled scene, and its slightly colliding random starts.

#include "deepcheck/checker/world.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/validity.h"
#include "deepcheck/robots/random_configuration.h"

#include <Eigen/Core>

#include <memory>
#include <random>
#include <string>
#include <vector>

namespace deepcheck::bench {

/// The bundled arm (robots/data, with its SRDF) in the bundled scene `scene`.
inline std::shared_ptr<checker::World> bundledArmWorld(const std::string& scene) {
  const std::string data = std::string(DEEPCHECK_SOURCE_DIR) + "/robots/data";
  planners::SetupOptions options;
  options.packageRoots = {data};
  options.useRosPackagePath = false;
  options.srdf = data + "/deepcheck_arm/srdf/deepcheck_arm.srdf";
  return planners::loadWorld(data + "/deepcheck_arm/urdf/deepcheck_arm.urdf", {data + "/scenes/" + scene + ".urdf"},
                             options);
}

/// `count` random configurations drawn with `rng` whose signed distance lies in [-maxDepth, 0).
inline std::vector<Eigen::VectorXd> penetratingStarts(const checker::World& world, int count, double maxDepth,
                                                      std::mt19937_64& rng) {
  std::vector<Eigen::VectorXd> starts;
  while (static_cast<int>(starts.size()) < count) {
    const Eigen::VectorXd q = robots::randomConfiguration(world.robot(), rng);
    const double sd = planners::signedDistanceUpTo(world, q, 1e-3);
    if (sd < 0.0 && sd >= -maxDepth) starts.push_back(q);
  }
  return starts;
}

}  // namespace deepcheck::bench
