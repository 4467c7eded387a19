#pragma once
// Random configurations for the checker and kinematics suites: std::mt19937 with
// std::uniform_real_distribution per variable (the suites' seeds were chosen with these
// sequences). The planners suite and the pair filter use robots/random_configuration.h instead.

#include "deepcheck/robots/robot_model.h"

#include <Eigen/Core>

#include <random>
#include <vector>

namespace deepcheck::test {

/// A uniformly random configuration within the limits.
inline Eigen::VectorXd randomConfiguration(const robots::RobotModel& model, std::mt19937& rng) {
  Eigen::VectorXd q(model.numVariables());
  for (int v = 0; v < q.size(); ++v) {
    std::uniform_real_distribution<double> u(model.lowerLimits()[v], model.upperLimits()[v]);
    q[v] = u(rng);
  }
  return q;
}

/// n uniformly random configurations within the limits.
inline std::vector<Eigen::VectorXd> randomConfigurations(const robots::RobotModel& model, int n, std::mt19937& rng) {
  std::vector<Eigen::VectorXd> qs;
  for (int i = 0; i < n; ++i) qs.push_back(randomConfiguration(model, rng));
  return qs;
}

}  // namespace deepcheck::test
