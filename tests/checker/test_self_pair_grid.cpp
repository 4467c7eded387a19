// Certified-free self-pair grids (checker/src/self_pair_grid.h): isFree gives the same answer with
// and without them, on random configurations and on configurations packed around the cells of
// the grids' variables (cell boundaries, the limits, beyond the limits), and the grids are used.
// A box of several sub-motions is certified only when each of them is.

#include "checker_test_util.h"
#include "world_test_access.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/pair_filter.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace deepcheck;
using namespace deepcheck::checker;
using namespace deepcheck::checker::test;

namespace {

/// Random configurations, then ones that keep the other variables and sweep the two given ones
/// finely (many cells, their boundaries, the limits and a little beyond them).
std::vector<Eigen::VectorXd> configurations(const robots::RobotModel& m, int v0, int v1, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<Eigen::VectorXd> qs = randomConfigurations(m, 3000, rng);
  const Eigen::VectorXd base = randomConfiguration(m, rng);
  const int n = 90;
  for (int i = -2; i <= n + 2; ++i) {
    for (int j = -2; j <= n + 2; ++j) {
      Eigen::VectorXd q = base;
      q[v0] = m.lowerLimits()[v0] + (m.upperLimits()[v0] - m.lowerLimits()[v0]) * i / n;
      q[v1] = m.lowerLimits()[v1] + (m.upperLimits()[v1] - m.lowerLimits()[v1]) * j / n;
      qs.push_back(q);
    }
  }
  return qs;
}

/// The bundled arm with its SRDF's disabled pairs, grids built.
World bundledArm() {
  WorldOptions options = testWorldOptions();
  options.disabledPairs = robots::readSrdfDisabledPairs(bundledDataDir() + "/deepcheck_arm/srdf/deepcheck_arm.srdf");
  return World(robots::RobotModel::fromUrdfFile(bundledDataDir() + "/deepcheck_arm/urdf/deepcheck_arm.urdf",
                                                bundledLoadOptions()),
               options);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_self_pair_grid)

BOOST_AUTO_TEST_CASE(panda_same_answers_with_and_without_grids) {
  if (!haveShared("panda_same_answers_with_and_without_grids")) return;
  WorldOptions options = testWorldOptions();
  options.disabledPairs = robots::readSrdfDisabledPairs(
      sharedDir() + "/robots/panda/moveit_resources_panda_moveit_config/config/panda.srdf");
  World with(loadPanda(), options);
  World without(loadPanda(), options);
  disableSelfPairGrids(without);
  const std::string text = with.summary();
  BOOST_TEST(text.find("certified-free grid: 2") != std::string::npos, text);
  BOOST_TEST(without.summary().find("certified-free grid") == std::string::npos);
  // panda_joint6 and panda_joint7 move link7 and the hand relative to link5.
  const robots::RobotModel& m = with.robot();
  const std::vector<Eigen::VectorXd> qs =
      configurations(m, m.variableIndex("panda_joint6"), m.variableIndex("panda_joint7"), 17);
  QueryStats stats;
  const int colliding = compareIsFree(with, without, qs, "the grids", &stats);
  BOOST_TEST(colliding > 500);
  BOOST_TEST(colliding < static_cast<int>(qs.size()) - 500);
  BOOST_TEST(stats.certifiedSelf > qs.size());  // most queries skip both pairs
  BOOST_TEST(stats.selfNarrowPhase > 100u);     // and the rest are still checked
  // The grids survive a change of the pairs (kept, not rebuilt) and keep answering the same.
  with.disablePair("panda_link0", "panda_link5");
  without.disablePair("panda_link0", "panda_link5");
  BOOST_TEST(with.summary().find("certified-free grid: 2") != std::string::npos);
  compareIsFree(with, without, std::vector<Eigen::VectorXd>(qs.begin(), qs.begin() + 500), "the grids", &stats);
}

BOOST_AUTO_TEST_CASE(bundled_arm_same_answers_with_and_without_grids) {
  World with = bundledArm();
  World without = bundledArm();
  disableSelfPairGrids(without);
  BOOST_TEST(with.summary().find("certified-free grid") != std::string::npos);
  const robots::RobotModel& m = with.robot();
  const int n = m.numVariables();
  const std::vector<Eigen::VectorXd> qs = configurations(m, n - 2, n - 1, 23);
  QueryStats stats;
  const int colliding = compareIsFree(with, without, qs, "the grids", &stats);
  BOOST_TEST(stats.certifiedSelf > 0u);
  BOOST_TEST(colliding > 0);
}

// certifiedFreeWithin over the box of eight sub-motions q_l + s dq, |s| <= h (lanes along a
// motion, as the bound stage asks it) is true only when certifiedFreeAlong is true for every one,
// and it is true for some: on the bundled arm's grids, motions of random lengths from random
// configurations.
BOOST_AUTO_TEST_CASE(a_box_of_sub_motions_is_certified_only_when_each_is) {
  const World world = bundledArm();
  const robots::RobotModel& m = world.robot();
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int boxes = 0;
  int certified = 0;
  for (const detail::SelfPair& sp : selfPairsOf(world)) {
    if (sp.grid == nullptr) continue;
    for (int trial = 0; trial < 2000; ++trial) {
      const Eigen::VectorXd q1 = randomConfiguration(m, rng);
      const Eigen::VectorXd dq = (randomConfiguration(m, rng) - q1) * std::pow(u(rng), 3);
      const double h = 1.0 / 16.0;
      Eigen::VectorXd lower = Eigen::VectorXd::Constant(m.numVariables(), 1e300);
      Eigen::VectorXd upper = -lower;
      bool each = true;
      for (int l = 0; l < 8; ++l) {
        const Eigen::VectorXd q = q1 + (l + 0.5) / 8.0 * dq;
        each = each && sp.grid->certifiedFreeAlong(q, dq, h);
        lower = lower.cwiseMin(q);
        upper = upper.cwiseMax(q);
      }
      lower -= h * dq.cwiseAbs();
      upper += h * dq.cwiseAbs();
      const bool box = sp.grid->certifiedFreeWithin(lower, upper);
      BOOST_TEST((!box || each), "q1 = " << q1.transpose() << ", dq = " << dq.transpose());
      ++boxes;
      certified += box;
    }
  }
  BOOST_TEST(boxes > 0);
  BOOST_TEST(certified > boxes / 10);
}

// The block counts behind certifiedFreeWithin agree with the cells one by one: a box of one
// point answers as certifiedFree there, a box over the whole limits is free only when every cell
// is, and every point of a box found free lies in a free cell (the bundled arm's grids, random
// boxes).
BOOST_AUTO_TEST_CASE(a_box_is_free_only_when_its_cells_are) {
  const World world = bundledArm();
  const robots::RobotModel& m = world.robot();
  const Eigen::VectorXd span = m.upperLimits() - m.lowerLimits();
  std::mt19937 rng(37);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int free = 0;
  int blocked = 0;
  for (const detail::SelfPair& sp : selfPairsOf(world)) {
    if (sp.grid == nullptr) continue;
    const detail::SelfPairGrid& grid = *sp.grid;
    const Eigen::VectorXd whole = m.lowerLimits() + (1.0 - 1e-9) * span;
    BOOST_TEST(grid.certifiedFreeWithin(m.lowerLimits(), whole) == (grid.numFreeCells() == grid.numCells()));
    for (int trial = 0; trial < 2000; ++trial) {
      const Eigen::VectorXd q = randomConfiguration(m, rng);
      BOOST_TEST(grid.certifiedFreeWithin(q, q) == grid.certifiedFree(q));
      const Eigen::VectorXd lower = (q - 0.3 * std::pow(u(rng), 2) * span).cwiseMax(m.lowerLimits());
      const Eigen::VectorXd upper = (q + 0.3 * std::pow(u(rng), 2) * span).cwiseMin(whole);
      if (!grid.certifiedFreeWithin(lower, upper)) {
        ++blocked;
        continue;
      }
      ++free;
      for (int k = 0; k < 20; ++k) {
        Eigen::VectorXd p = q;
        for (Eigen::Index v = 0; v < p.size(); ++v) p[v] = lower[v] + u(rng) * (upper[v] - lower[v]);
        BOOST_TEST(grid.certifiedFree(p), "p = " << p.transpose());
      }
    }
  }
  BOOST_TEST(free > 0);
  BOOST_TEST(blocked > 0);
}

BOOST_AUTO_TEST_SUITE_END()
