// Worlds with many obstacles or links: obstacles added together (all or none), and self pairs
// found through the links' reach spheres (pairsWithinReach) instead of every pair of links.

#include "checker_test_util.h"

#include "deepcheck/robots/collision_geometry.h"
#include "deepcheck/robots/pair_filter.h"

#include "link_pairs.h"
#include "progress.h"
#include "reach.h"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace deepcheck;
using namespace deepcheck::checker;
using namespace deepcheck::checker::test;

namespace {

/// Two revolute arms (a 0.4 m box on each) with their bases `apart` metres apart along x, and a
/// cube on a prismatic joint (travel +-0.5 m) between them when `slider`.
robots::RobotModel twoArms(double apart, bool slider) {
  auto arm = [&](const std::string& n, double x) {
    return "<link name='" + n +
           "_base'><collision><geometry><box size='0.1 0.1 0.1'/></geometry></collision></link>"
           "<joint name='" +
           n + "_fix' type='fixed'><parent link='root'/><child link='" + n + "_base'/><origin xyz='" +
           robots::formatNumber(x) +
           " 0 0'/></joint>"
           "<link name='" +
           n +
           "_arm'><collision><origin xyz='0 0 0.25'/><geometry><box size='0.05 0.05 "
           "0.4'/></geometry></collision></link>"
           "<joint name='" +
           n + "_j' type='revolute'><parent link='" + n + "_base'/><child link='" + n +
           "_arm'/>"
           "<origin xyz='0 0 0.05'/><axis xyz='0 1 0'/><limit lower='-3' upper='3' effort='1' velocity='1'/></joint>";
  };
  std::string xml = "<robot name='two_arms'><link name='root'/>" + arm("left", -apart / 2) + arm("right", apart / 2);
  if (slider) {
    xml +=
        "<link name='cube'><collision><geometry><box size='0.1 0.1 0.1'/></geometry></collision></link>"
        "<joint name='slide' type='prismatic'><parent link='root'/><child link='cube'/><origin xyz='0 2 0'/>"
        "<axis xyz='1 0 0'/><limit lower='-0.5' upper='0.5' effort='1' velocity='1'/></joint>";
  }
  return robots::RobotModel::fromUrdfString(xml + "</robot>", ".", {}, "two_arms.urdf");
}

/// A random tree of n links: link i's parent is a random earlier link, its joint fixed or
/// revolute, and it has a box with probability `geometry` (else nothing).
robots::RobotModel randomTree(int n, double geometry, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::string xml = "<robot name='tree'>";
  for (int i = 0; i < n; ++i) {
    xml += "<link name='l" + std::to_string(i) + "'>";
    if (u(rng) < geometry) xml += "<collision><geometry><box size='0.1 0.1 0.1'/></geometry></collision>";
    xml += "</link>";
    if (i == 0) continue;
    const int parent = std::uniform_int_distribution<int>(0, i - 1)(rng);
    const bool fixed = u(rng) < 0.4;
    xml += "<joint name='j" + std::to_string(i) + "' type='" + (fixed ? "fixed" : "revolute") + "'><parent link='l" +
           std::to_string(parent) + "'/><child link='l" + std::to_string(i) + "'/><origin xyz='0.3 0 0'/>";
    if (!fixed) xml += "<axis xyz='0 0 1'/><limit lower='-1' upper='1' effort='1' velocity='1'/>";
    xml += "</joint>";
  }
  return robots::RobotModel::fromUrdfString(xml + "</robot>", ".", {}, "tree.urdf");
}

}  // namespace

BOOST_AUTO_TEST_SUITE(large_worlds)

// The link pair index answers and counts as the pair lists it replaces (adjacentLinkPairs,
// rigidLinkPairs) on random trees, hubs without geometry included.
BOOST_AUTO_TEST_CASE(link_pair_index_equals_the_pair_lists) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 300; ++trial) {
    const robots::RobotModel model = randomTree(2 + trial % 30, trial % 3 == 0 ? 0.3 : 0.7, rng);
    const auto pieces = robots::collisionPieces(model, robots::CollisionGeometryOptions());
    std::vector<bool> hasGeometry(model.numLinks());
    for (int l = 0; l < model.numLinks(); ++l) hasGeometry[l] = !pieces[l].empty();
    const auto adjacentList = robots::adjacentLinkPairs(model, pieces);
    const auto rigidList = rigidLinkPairs(model, hasGeometry);
    const std::set<std::pair<int, int>> adjacent(adjacentList.begin(), adjacentList.end());
    const std::set<std::pair<int, int>> rigid(rigidList.begin(), rigidList.end());
    const LinkPairIndex index(model, hasGeometry);
    long long both = 0;
    for (int a = 0; a < model.numLinks(); ++a) {
      for (int b = a + 1; b < model.numLinks(); ++b) {
        if (!hasGeometry[a] || !hasGeometry[b]) continue;
        BOOST_TEST(index.adjacent(a, b) == (adjacent.count({a, b}) > 0),
                   "trial " << trial << " links " << a << ", " << b);
        BOOST_TEST(index.adjacent(b, a) == index.adjacent(a, b));
        BOOST_TEST(index.rigid(a, b) == (rigid.count({a, b}) > 0), "trial " << trial << " links " << a << ", " << b);
        both += adjacent.count({a, b}) > 0 && rigid.count({a, b}) > 0;
      }
    }
    BOOST_TEST(index.numAdjacent() == static_cast<long long>(adjacent.size()), "trial " << trial);
    BOOST_TEST(index.numRigid() == static_cast<long long>(rigid.size()), "trial " << trial);
    BOOST_TEST(index.numAdjacentAndRigid() == both, "trial " << trial);
  }
}

// addObstacles: ids in order, the same answers as adding one by one, and a bad obstacle anywhere
// in the list leaves the world as it was, with an error naming it.
BOOST_AUTO_TEST_CASE(obstacles_added_together) {
  World one(armRobot(), testWorldOptions());
  World together(armRobot(), testWorldOptions());
  std::vector<Obstacle> obstacles;
  for (int i = 0; i < 50; ++i) {
    obstacles.push_back(Obstacle::box("b" + std::to_string(i), Eigen::Vector3d(0.05, 0.05, 0.05),
                                      translation(0.3 + 0.02 * i, -0.4 + 0.016 * i, 0.1 + 0.015 * i)));
  }
  std::vector<int> ids;
  for (const Obstacle& o : obstacles) ids.push_back(one.addObstacle(o));
  BOOST_TEST((together.addObstacles(obstacles) == ids));
  std::mt19937 rng(5);
  for (const Eigen::VectorXd& q : randomConfigurations(one.robot(), 200, rng)) {
    BOOST_TEST(one.isFree(q) == together.isFree(q));
    BOOST_TEST(one.signedDistance(q).closest.distance == together.signedDistance(q).closest.distance);
  }
  std::vector<Obstacle> bad = {obstacles[0], obstacles[1]};
  bad.push_back(Obstacle::sphere("negative", -1.0, translation(0, 0, 0)));
  checkThrowsWith([&] { together.addObstacles(bad); }, "negative");
  BOOST_TEST(together.obstacleIds().size() == obstacles.size());
  bad.back() = Obstacle::box("", Eigen::Vector3d::Ones(), translation(0, 0, 0));
  checkThrowsWith([&] { together.addObstacles(bad); }, "no name");
  BOOST_TEST(together.obstacleIds().size() == obstacles.size());
}

// The mesh file size limit is the world's option: a mesh over it is refused naming the option,
// and raising it loads the mesh.
BOOST_AUTO_TEST_CASE(mesh_file_size_limit_is_a_world_option) {
  const std::string mesh = bundledDataDir() + "/deepcheck_arm/meshes/link4.stl";
  WorldOptions options = testWorldOptions();
  options.geometry.meshLoad.maxFileBytes = 100;
  World small(armRobot(), options);
  checkThrowsWith([&] { small.addObstacle(Obstacle::meshFile("m", mesh, translation(2, 0, 0))); },
                  "MeshLoadOptions::maxFileBytes = 100");
  options.geometry.meshLoad.maxFileBytes = std::uintmax_t{1} << 30;
  World large(armRobot(), options);
  BOOST_TEST(large.addObstacle(Obstacle::meshFile("m", mesh, translation(2, 0, 0))) >= 0);
}

// Links whose reach spheres never come within the margin are not paired; within it, and with a
// link on a prismatic joint (whose sphere holds within its limits only), they are.
BOOST_AUTO_TEST_CASE(self_pairs_within_reach) {
  WorldOptions options = testWorldOptions();
  options.disableAdjacent = true;
  // Arms 3 m apart: reach spheres of radius ~0.5 never meet. The cross pairs but the bases (adjacent
  // through the geometry-less root) are left out.
  World far(twoArms(3.0, false), options);
  BOOST_TEST(far.allowedSelfPairs().empty());
  BOOST_TEST(far.summaryCounts().unreachablePairs == 3);
  BOOST_TEST(far.summary().find("3 never within reach") != std::string::npos);
  // Arms 0.9 m apart: the arms can touch, and are checked.
  World near(twoArms(0.9, false), options);
  BOOST_TEST(near.summaryCounts().unreachablePairs < 3);
  BOOST_TEST(!near.allowedSelfPairs().empty());
  // An infinite margin keeps every pair.
  options.reachMargin = std::numeric_limits<double>::infinity();
  World all(twoArms(3.0, false), options);
  BOOST_TEST(all.summaryCounts().unreachablePairs == 0);
  BOOST_TEST(all.allowedSelfPairs().size() == 3u);
  // The prismatic cube is paired with every link but the bases it is adjacent to (its sphere
  // holds within its limits only).
  options.reachMargin = tol::kDefaultReachMargin;
  World slider(twoArms(3.0, true), options);
  const robots::RobotModel& m = slider.robot();
  const int cube = m.linkIndex("cube");
  int cubePairs = 0;
  for (const auto& [a, b] : slider.allowedSelfPairs()) cubePairs += (a == cube || b == cube);
  BOOST_TEST(cubePairs == 2);
}

// pairsWithinReach against every pair, on random spheres, some of which hold within limits only.
BOOST_AUTO_TEST_CASE(pairs_within_reach_equal_brute_force) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 40;
    std::vector<ReachSphere> spheres(n + 3);
    std::vector<int> links;
    for (int l = 3; l < n + 3; ++l) {  // links 0..2 have no sphere
      spheres[l].valid = true;
      spheres[l].center_W = Eigen::Vector3d(4 * u(rng), 4 * u(rng), 4 * u(rng));
      spheres[l].radius = 0.5 * u(rng);
      spheres[l].withinLimitsOnly = u(rng) < 0.1;
      links.push_back(l);
    }
    const double margin = 0.2 * u(rng);
    std::vector<std::pair<int, int>> expected;
    for (int i = 0; i < n; ++i) {
      for (int j = i + 1; j < n; ++j) {
        const ReachSphere& a = spheres[links[i]];
        const ReachSphere& b = spheres[links[j]];
        if (a.withinLimitsOnly || b.withinLimitsOnly ||
            (a.center_W - b.center_W).norm() - a.radius - b.radius <= margin) {
          expected.emplace_back(i, j);
        }
      }
    }
    BOOST_TEST((pairsWithinReach(spheres, links, margin) == expected), "trial " << trial);
  }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(construction_progress)

// Nothing while the step is within its quiet time; then lines with the count, and a closing line;
// a null stream is silent.
BOOST_AUTO_TEST_CASE(lines_only_past_the_quiet_time) {
  std::ostringstream quiet;
  {
    detail::Progress p(&quiet, "self pairs", 10, 3600.0);
    for (std::size_t k = 0; k < 10; ++k) p.update(k);
  }
  BOOST_TEST(quiet.str().empty());
  std::ostringstream loud;
  {
    detail::Progress p(&loud, "self pairs", 10, 0.0);
    p.update(3);
  }
  BOOST_TEST(loud.str().find("deepcheck: self pairs 3/10 (") == 0u, loud.str());
  BOOST_TEST(loud.str().find(" left)\n") != std::string::npos, loud.str());  // the estimate of the rest
  BOOST_TEST(loud.str().find("deepcheck: self pairs done (") != std::string::npos, loud.str());
  std::ostringstream unknown;
  {
    detail::Progress p(&unknown, "meshes", 0, 0.0);
    p.update(7);
  }
  BOOST_TEST(unknown.str().find("deepcheck: meshes 7 (") == 0u, unknown.str());
  BOOST_TEST(unknown.str().find("left") == std::string::npos, unknown.str());  // no total, no estimate
  detail::Progress silent(nullptr, "x", 1, 0.0);
  silent.update(1);
}

BOOST_AUTO_TEST_SUITE_END()
