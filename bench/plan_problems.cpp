// The planning problems of plan_bench and plan_certify (plan_problems.h), and how the Panda's
// start and goal were picked.

#include "plan_problems.h"

#include "format.h"

#include "deepcheck/planners/path_tools.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/robots/kinematics.h"

#include <ompl/base/ScopedState.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

// The Panda's start and goal (see problems(); printed by --pick-panda-endpoints, rounded to 1e-4).
#define PANDA_KITCHEN_START 2.3235, -0.7332, -0.7202, -1.0283, -1.0430, 1.9942, 0.8179, 0.0350
#define PANDA_KITCHEN_GOAL 0.6441, -1.7750, -1.3077, -2.4067, -0.8443, 3.7595, -0.7133, 0.0350
#define PANDA_TABLE_BARS_START 1.1207, 0.3870, -1.5234, -1.4975, -0.8731, 2.3007, 0.2042, 0.0350
#define PANDA_TABLE_BARS_GOAL 0.6831, 0.5868, -0.9187, -2.1369, -2.5455, 2.2887, -2.3964, 0.0350

namespace deepcheck::bench {

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace dp = deepcheck::planners;

namespace {

Eigen::VectorXd vec(std::initializer_list<double> values) {
  Eigen::VectorXd q(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double v : values) q[i++] = v;
  return q;
}

std::string sourceDir() { return DEEPCHECK_SOURCE_DIR; }

/// The first configuration found, from seeded random starts refined by damped least squares on
/// the fingertip position (panda_hand origin + 0.1034 m along its z), within 1 cm of `target`, at
/// least 2 cm from everything by our signed distance, and free for FCL. Finger at 0.035 m.
Eigen::VectorXd pickEndpoint(const deepcheck::checker::World& world,
                             deepcheck::fcl_reference::FclStateValidityChecker& fcl, const Eigen::Vector3d& target,
                             std::mt19937& rng, int* attemptsOut) {
  const auto& model = world.robot();
  const int n = model.numVariables();
  const int hand = model.linkIndex("panda_hand");
  const int finger = model.variableIndex("panda_finger_joint1");
  const Eigen::Vector3d tip(0.0, 0.0, 0.1034);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int attempt = 1; attempt <= 5000; ++attempt) {
    Eigen::VectorXd q(n);
    for (int i = 0; i < n; ++i) {
      q[i] = model.lowerLimits()[i] + unit(rng) * (model.upperLimits()[i] - model.lowerLimits()[i]);
    }
    q[finger] = 0.035;
    double err = 1e9;
    for (int it = 0; it < 200 && err > 0.002; ++it) {
      const auto X = deepcheck::robots::forwardKinematics(model, q);
      const Eigen::Vector3d e = target - X[hand] * tip;
      err = e.norm();
      Eigen::Matrix3Xd J = deepcheck::robots::pointJacobian(model, X, hand, tip);
      J.col(finger).setZero();
      const double lambda = 0.05;
      const Eigen::Matrix3d A = J * J.transpose() + lambda * lambda * Eigen::Matrix3d::Identity();
      Eigen::VectorXd dq = J.transpose() * A.ldlt().solve(e);
      const double m = dq.cwiseAbs().maxCoeff();
      if (m > 0.2) dq *= 0.2 / m;
      q = (q + dq).cwiseMax(model.lowerLimits()).cwiseMin(model.upperLimits());
    }
    const Eigen::Vector3d reached = deepcheck::robots::forwardKinematics(model, q)[hand] * tip;
    if ((reached - target).norm() > 0.01) continue;
    const auto d = world.signedDistance(q);
    if (!d.found || d.closest.distance < 0.02) continue;
    if (!fcl.isFree(q)) continue;
    *attemptsOut = attempt;
    return q;
  }
  throw std::runtime_error("no endpoint found near the target");
}

}  // namespace

/// The table_bars scene is placed 0.3 m in front of the Panda (+x): the shelves' front edge
/// (the bars) is at x = -0.06 in the scene's frame, so at the identity the robot's base would be
/// inside them. MotionBenchMaker's own robot placement for this scene is in its problem files,
/// which ../shared does not include.
Eigen::Isometry3d tableBarsPose() {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(0.3, 0.0, 0.0);
  return X;
}

std::string pandaUrdf() { return sharedDir() + "/robots/panda/moveit_resources_panda_description/urdf/panda.urdf"; }
std::string mbmScene(const std::string& name) {
  return sharedDir() + "/scenes/motion_bench_maker/configs/scenes/" + name + "/" + name + ".urdf";
}

dp::SetupOptions pandaOptions() {
  dp::SetupOptions o;
  o.packageRoots = {sharedDir() + "/robots/panda", sharedDir() + "/scenes"};
  o.useRosPackagePath = false;
  o.srdf = sharedDir() + "/robots/panda/moveit_resources_panda_moveit_config/config/panda.srdf";
  return o;
}

std::string sharedDir() { return DEEPCHECK_SHARED_DIR; }
bool haveShared() { return std::filesystem::is_directory(sharedDir() + "/robots/panda"); }

std::vector<Problem> problems() {
  std::vector<Problem> list;
  const std::string data = sourceDir() + "/robots/data";
  dp::SetupOptions arm;
  arm.packageRoots = {data};
  arm.useRosPackagePath = false;
  arm.srdf = data + "/deepcheck_arm/srdf/deepcheck_arm.srdf";
  const Eigen::VectorXd armStart = vec({0, -0.4, 0, -1.6, 0, 1.2, 0});
  const std::string readme = "robots/data/README.md, Suggested planning problems";
  list.push_back({"table",
                  data + "/deepcheck_arm/urdf/deepcheck_arm.urdf",
                  arm,
                  {data + "/scenes/table.urdf"},
                  armStart,
                  vec({-0.14, 0.61, 0.24, -0.77, -0.14, 1.77, -2.23}),
                  false,
                  readme});
  list.push_back({"shelf",
                  data + "/deepcheck_arm/urdf/deepcheck_arm.urdf",
                  arm,
                  {data + "/scenes/shelf.urdf"},
                  armStart,
                  vec({1.05, 0.75, -1.17, -1.30, 0.05, -0.07, -2.79}),
                  false,
                  readme});
  list.push_back({"narrow_passage",
                  data + "/deepcheck_arm/urdf/deepcheck_arm.urdf",
                  arm,
                  {data + "/scenes/narrow_passage.urdf"},
                  armStart,
                  vec({-0.40, 1.72, -0.40, 1.79, 0.31, 1.50, 0.59}),
                  false,
                  readme});
  // Panda: 8 variables (panda_joint1..7, panda_finger_joint1; finger 2 mimics finger 1). The
  // MotionBenchMaker configs give end-effector poses relative to scene objects, not joint
  // values; the configurations below were found by `plan_bench --pick-panda-endpoints`
  // (pickEndpoints(): damped least squares on the fingertip position from seeded random
  // configurations, std::mt19937 seed 1, first solution within 1 cm that is at least 2 cm from
  // everything by our signed distance and free for FCL). Targets, world frame (Panda at the
  // origin):
  //   kitchen (URDF pose, as the checker tests): start (0.45, 0.2, 1.0), above the counter under
  //     the cupboard; goal (0.2, -0.5, 0.6), in front of the dishwasher (MotionBenchMaker's
  //     "FrontEasy" goal offset; its start, in the cupboard at z 1.5, is out of the Panda's reach
  //     from the origin);
  //   table_bars (at tableBarsPose()): MotionBenchMaker's queries.yaml "ArmAboveShelfR" ->
  //     "ArmBelowShelfR": shelves + (0.35, -0.2, 0.7) -> shelves + (0.35, -0.2, 0.25), above and
  //     below the middle shelf.
  list.push_back({"panda_kitchen",
                  pandaUrdf(),
                  pandaOptions(),
                  {mbmScene("kitchen")},
                  vec({PANDA_KITCHEN_START}),
                  vec({PANDA_KITCHEN_GOAL}),
                  true,
                  "picked by --pick-panda-endpoints (seed 1)"});
  list.push_back({"panda_table_bars",
                  pandaUrdf(),
                  pandaOptions(),
                  {dp::SceneSpec(mbmScene("table_bars"), tableBarsPose())},
                  vec({PANDA_TABLE_BARS_START}),
                  vec({PANDA_TABLE_BARS_GOAL}),
                  true,
                  "picked by --pick-panda-endpoints (seed 1)"});
  return list;
}

std::shared_ptr<og::SimpleSetup> makeFclSetup(
    const og::SimpleSetup& ours, const deepcheck::checker::World& world,
    std::shared_ptr<deepcheck::fcl_reference::FclStateValidityChecker>* checkerOut) {
  auto space = dp::makeStateSpace(world.robot());
  space->setLongestValidSegmentFraction(ours.getStateSpace()->getLongestValidSegmentFraction());
  auto ss = std::make_shared<og::SimpleSetup>(space);
  auto checker = std::make_shared<deepcheck::fcl_reference::FclStateValidityChecker>(ss->getSpaceInformation(), world);
  ss->setStateValidityChecker(checker);
  if (checkerOut != nullptr) *checkerOut = checker;
  return ss;
}

void setEndpoints(og::SimpleSetup& ss, const Eigen::VectorXd& start, const Eigen::VectorXd& goal) {
  ob::ScopedState<> s(ss.getStateSpace());
  ob::ScopedState<> g(ss.getStateSpace());
  dp::copyToState(start, s.get());
  dp::copyToState(goal, g.get());
  ss.setStartAndGoalStates(s, g);
}

int pickPandaEndpoints() {
  if (!haveShared()) {
    std::fprintf(stderr, "plan_bench: ../shared is absent (%s): nothing to pick\n", sharedDir().c_str());
    return 1;
  }
  struct Target {
    std::string name;
    std::vector<dp::SceneSpec> scenes;
    Eigen::Vector3d start, goal;
  };
  const Eigen::Vector3d shelves = tableBarsPose().translation();
  const std::vector<Target> targets{{"panda_kitchen", {mbmScene("kitchen")}, {0.45, 0.2, 1.0}, {0.2, -0.5, 0.6}},
                                    {"panda_table_bars",
                                     {dp::SceneSpec(mbmScene("table_bars"), tableBarsPose())},
                                     shelves + Eigen::Vector3d(0.35, -0.2, 0.7),
                                     shelves + Eigen::Vector3d(0.35, -0.2, 0.25)}};
  for (const Target& t : targets) {
    auto world = dp::loadWorld(pandaUrdf(), t.scenes, pandaOptions());
    auto ss = dp::makeSimpleSetup(world);
    std::shared_ptr<deepcheck::fcl_reference::FclStateValidityChecker> fcl;
    auto fss = makeFclSetup(*ss, *world, &fcl);
    std::mt19937 rng(1);
    int a1 = 0, a2 = 0;
    const Eigen::VectorXd qs = pickEndpoint(*world, *fcl, t.start, rng, &a1);
    const Eigen::VectorXd qg = pickEndpoint(*world, *fcl, t.goal, rng, &a2);
    // Is the straight motion free? (Then the problem would be trivial.)
    og::PathGeometric straight(fss->getSpaceInformation());
    ob::ScopedState<> s(fss->getStateSpace()), g(fss->getStateSpace());
    dp::copyToState(qs, s.get());
    dp::copyToState(qg, g.get());
    straight.append(s.get());
    straight.append(g.get());
    const dp::PathCheck check = dp::checkPathFine(straight, [&](const Eigen::VectorXd& q) { return fcl->isFree(q); });
    auto print = [](const Eigen::VectorXd& q) {
      std::string out;
      for (int i = 0; i < q.size(); ++i) out += (i ? ", " : "") + fmt(q[i], "%.4f");
      return out;
    };
    std::printf("%s: start %s (attempt %d, clearance %.4f m)\n", t.name.c_str(), print(qs).c_str(), a1,
                world->signedDistance(qs).closest.distance);
    std::printf("%s: goal  %s (attempt %d, clearance %.4f m)\n", t.name.c_str(), print(qg).c_str(), a2,
                world->signedDistance(qg).closest.distance);
    std::printf("%s: straight-line motion %s\n", t.name.c_str(),
                check.valid ? "FREE (trivial problem)" : "in collision (good)");
  }
  return 0;
}

}  // namespace deepcheck::bench
