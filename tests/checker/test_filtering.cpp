// What never reaches the narrow phase: links without geometry, adjacent / rigid / disabled pairs,
// pieces far from each other; and what is dropped at load: scene pieces no link can reach.

#include "checker_test_util.h"
#include "reach.h"
#include "world_test_access.h"

#include "deepcheck/fcl_reference/fcl_backend.h"
#include "deepcheck/fcl_reference/fcl_broad_phase.h"
#include "deepcheck/checker/world.h"
#include "deepcheck/robots/collision_geometry.h"
#include "deepcheck/robots/kinematics.h"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <random>
#include <set>
#include <string>
#include <vector>

using namespace deepcheck;
using namespace deepcheck::checker;
using namespace deepcheck::checker::test;

namespace {

using LinkPair = std::pair<std::string, std::string>;

LinkPair ordered(std::string a, std::string b) {
  if (b < a) std::swap(a, b);
  return {a, b};
}

/// The (link, body) name pairs that reached the narrow phase over random configurations, with
/// both queries.
std::set<LinkPair> narrowPhasePairs(const World& world, int samples, unsigned seed) {
  std::set<LinkPair> seen;
  auto context = world.makeContext();
  setNarrowPhaseHook(world, [&](const NarrowPhaseEvent& e) {
    seen.insert(ordered(world.robot().link(e.linkA).name, world.bodyName(e.bodyB)));
  });
  std::mt19937 rng(seed);
  for (int i = 0; i < samples; ++i) {
    const Eigen::VectorXd q = randomConfiguration(world.robot(), rng);
    world.isFree(q, context);
    world.signedDistance(q, context);
  }
  setNarrowPhaseHook(world, {});
  return seen;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_filtering)

BOOST_AUTO_TEST_CASE(adjacent_and_rigid_pairs_of_the_arm) {
  World world(armRobot(), testWorldOptions());
  const robots::RobotModel& arm = world.robot();
  std::set<LinkPair> allowed;
  for (const auto& [a, b] : world.allowedSelfPairs()) allowed.insert(ordered(arm.link(a).name, arm.link(b).name));
  // Adjacent: base-link1, link1-link2, link2-link3 (through the geometry-less elbow), link3-tool;
  // link3-tool is rigid too. The 10 pairs of 5 links leave 6.
  const std::set<LinkPair> expected = {ordered("base", "link2"),  ordered("base", "link3"), ordered("base", "tool"),
                                       ordered("link1", "link3"), ordered("link1", "tool"), ordered("link2", "tool")};
  BOOST_TEST((allowed == expected));
  const World::Summary s = world.summaryCounts();
  BOOST_TEST(s.disabledAdjacent == 4);
  BOOST_TEST(s.disabledRigid == 0);
  std::vector<bool> hasGeometry(arm.numLinks(), true);
  hasGeometry[arm.linkIndex("elbow")] = false;
  const auto rigid = rigidLinkPairs(arm, hasGeometry);
  BOOST_TEST_REQUIRE(rigid.size() == 1u);
  BOOST_TEST((ordered(arm.link(rigid[0].first).name, arm.link(rigid[0].second).name) == ordered("link3", "tool")));
  // Without adjacency filtering, the rigid pair is still disabled, as rigid.
  WorldOptions options = testWorldOptions();
  options.disableAdjacent = false;
  World all(armRobot(), options);
  BOOST_TEST(all.summaryCounts().disabledRigid == 1);
  BOOST_TEST(all.summaryCounts().selfPairs == 9);
}

BOOST_AUTO_TEST_CASE(filtered_pairs_never_reach_the_narrow_phase) {
  WorldOptions options = testWorldOptions();
  options.disabledPairs = {{"tool", "base", robots::DisableReason::User}};
  World world(armRobot(), options);
  world.addObstacle(Obstacle::box("table", Eigen::Vector3d(1.2, 1.2, 0.05), translation(0.5, 0, 0.35)));
  const std::set<LinkPair> seen = narrowPhasePairs(world, 400, 5);
  for (const LinkPair& p : {ordered("base", "link1"), ordered("link1", "link2"), ordered("link2", "link3"),
                            ordered("link3", "tool"), ordered("base", "tool")}) {
    BOOST_TEST(seen.count(p) == 0u, p.first << " / " << p.second << " is filtered but reached the narrow phase");
  }
  for (const LinkPair& p : seen) {
    BOOST_TEST(p.first != "elbow");  // no geometry
    BOOST_TEST(p.second != "elbow");
  }
  // The allowed pairs do get there (the counter works).
  BOOST_TEST(seen.count(ordered("link1", "tool")) == 1u);
  BOOST_TEST(seen.count(ordered("link1", "obstacle/table")) + seen.count(ordered("link3", "obstacle/table")) > 0u);
  const auto allowed = world.allowedSelfPairs();
  BOOST_TEST(allowed.size() == 5u);  // 10 pairs of 5 links - 4 adjacent - 1 by name
  // Disabling later works too, and stops the pair at once.
  world.disablePair("link1", "tool");
  BOOST_TEST(narrowPhasePairs(world, 400, 5).count(ordered("link1", "tool")) == 0u);
  BOOST_TEST(world.summaryCounts().disabledByUser == 2);
}

BOOST_AUTO_TEST_CASE(adjacent_pairs_are_checked_when_asked) {
  WorldOptions options = testWorldOptions();
  options.disableAdjacent = false;
  World world(armRobot(), options);
  const std::set<LinkPair> seen = narrowPhasePairs(world, 200, 8);
  BOOST_TEST(seen.count(ordered("base", "link1")) == 1u);  // they touch at the joint: always near
  BOOST_TEST(world.summaryCounts().selfPairs == 9);        // the rigid link3-tool pair stays disabled
  // Touching at the joint: never free.
  BOOST_TEST(!world.isFree(Eigen::VectorXd::Zero(3)));
}

BOOST_AUTO_TEST_CASE(far_pieces_skip_the_narrow_phase) {
  World world(sliderRobot(0.2), testWorldOptions());
  world.addObstacle(Obstacle::box("far", Eigen::Vector3d(0.2, 0.2, 0.2), translation(0, 5, 0)));
  world.addObstacle(Obstacle::box("near", Eigen::Vector3d(0.2, 0.2, 0.2), translation(0.5, 0, 0)));
  auto context = world.makeContext();
  int farCalls = 0;
  setNarrowPhaseHook(world, [&](const NarrowPhaseEvent& e) { farCalls += world.bodyName(e.bodyB) == "obstacle/far"; });
  Eigen::VectorXd q(1);
  for (int k = 0; k <= 200; ++k) {
    q[0] = -1.0 + 0.01 * k;
    world.isFree(q, context);
    world.signedDistance(q, context);  // the near box is always nearer by far: the bound prunes
  }
  setNarrowPhaseHook(world, {});
  BOOST_TEST(farCalls == 0);
  BOOST_TEST(context.stats().narrowPhase > 0u);
  BOOST_TEST(context.stats().queries == 2 * 201u);
}

BOOST_AUTO_TEST_CASE(unreachable_scene_pieces_are_dropped) {
  // The slider's cube (edge 0.2) reaches |x| <= 2 + sqrt(3) * 0.1 from the origin.
  const std::string sceneXml =
      "<robot name='hall'><link name='root'/>"
      "<link name='near'><collision><origin xyz='1.5 0 0'/><geometry><box size='0.2 0.2 "
      "0.2'/></geometry></collision></link>"
      "<link name='far'><collision><origin xyz='0 4 0'/><geometry><box size='0.2 0.2 0.2'/></geometry></collision>"
      "<collision><origin xyz='0 -2.4 0'/><geometry><sphere radius='0.1'/></geometry></collision></link>"
      "<joint name='a' type='fixed'><parent link='root'/><child link='near'/></joint>"
      "<joint name='b' type='fixed'><parent link='root'/><child link='far'/></joint></robot>";
  // The sphere at y = -2.4 is 2.3 from the origin: 0.127 beyond the reach sphere (2.173):
  // dropped with the default 5 cm margin, kept with 20 cm.
  World world(sliderRobot(0.2), testWorldOptions());
  world.addScene(robots::RobotModel::fromUrdfString(sceneXml, ".", {}, "hall.urdf"));
  World::Summary s = world.summaryCounts();
  BOOST_TEST(s.scenePiecesKept == 1);
  BOOST_TEST(s.scenePiecesDropped == 2);
  BOOST_TEST(world.summary().find("dropped 2") != std::string::npos);
  // The FCL backend keeps every piece: it checks that dropping changed nothing.
  fcl_reference::FclWorld fcl(world);
  BOOST_TEST(fcl.numWorldObjects() == 3);
  Eigen::VectorXd q(1);
  for (int k = 0; k < 80; ++k) {
    q[0] = -2.0 + 0.05 * k + 0.013;  // never exactly touching (touching is a collision for us only)
    BOOST_TEST(world.isFree(q) == fcl.isFree(q), "x " << q[0]);
  }
  WorldOptions wide = testWorldOptions();
  wide.reachMargin = 0.2;
  World world2(sliderRobot(0.2), wide);
  world2.addScene(robots::RobotModel::fromUrdfString(sceneXml, ".", {}, "hall.urdf"));
  s = world2.summaryCounts();
  BOOST_TEST(s.scenePiecesKept == 2);
  BOOST_TEST(s.scenePiecesDropped == 1);
}

BOOST_AUTO_TEST_CASE(reach_spheres_contain_every_reachable_point) {
  std::vector<robots::RobotModel> robots;
  robots.push_back(armRobot());
  if (haveShared("reach spheres of the Panda")) robots.push_back(loadPanda());
  for (robots::RobotModel& model : robots) {
    Eigen::Isometry3d X_WR = translation(0.3, -0.2, 0.1);
    X_WR.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    model.setBasePose(X_WR);
    const auto pieces = robots::collisionPieces(model);
    const std::vector<ReachSphere> reach = linkReachSpheres(model, pieces);
    std::mt19937 rng(17);
    double worstSlack = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 500; ++i) {
      const std::vector<Eigen::Isometry3d> X_WL = robots::forwardKinematics(model, randomConfiguration(model, rng));
      for (int l = 0; l < model.numLinks(); ++l) {
        BOOST_TEST(reach[l].valid == !pieces[l].empty());
        for (const robots::CollisionPiece& p : pieces[l]) {
          for (const Eigen::Vector3d& v : p.core->vertices()) {
            const double slack = reach[l].radius - ((X_WL[l] * (p.X_LP * v)) - reach[l].center_W).norm() - p.radius;
            worstSlack = std::min(worstSlack, slack);
            BOOST_TEST(slack >= -1e-12, model.name() << " link " << model.link(l).name << " escapes its reach sphere");
          }
        }
      }
    }
  }
  // The arm's base never moves: its sphere is marked fixed.
  const robots::RobotModel arm = armRobot();
  BOOST_TEST(linkReachSpheres(arm, robots::collisionPieces(arm))[0].fixed);
  checkThrowsWith([&] { linkReachSpheres(arm, {}); }, "arm");
}

// The broad phases (static AABB tree, none, and FCL's dynamic tree as the external one) only
// choose which world pieces reach the bounding tests: isFree answers the same with each, and
// signedDistance finds the same separation (each query cold, so a pair's distance does not depend
// on what was measured before).
BOOST_AUTO_TEST_CASE(broad_phases_give_the_same_answers) {
  const robots::LoadOptions load = bundledLoadOptions();
  const std::string urdf = bundledDataDir() + "/deepcheck_arm/urdf/deepcheck_arm.urdf";
  std::vector<std::pair<std::string, WorldOptions>> phases(3, {"", testWorldOptions()});
  phases[0].first = toString(BroadPhase::AabbTree);
  phases[1].first = "fcl (external)";
  phases[1].second.externalBroadPhase = fcl_reference::fclBroadPhase();
  phases[2].first = toString(BroadPhase::None);
  phases[2].second.broadPhase = BroadPhase::None;
  std::vector<World> worlds;
  for (const auto& [name, options] : phases) {
    World& w = worlds.emplace_back(robots::RobotModel::fromUrdfFile(urdf, load), options);
    w.addScene(robots::RobotModel::fromUrdfFile(bundledDataDir() + "/scenes/shelf.urdf", load));
    addCrateBallPost(w);
  }
  std::mt19937 rng(19);
  const std::vector<Eigen::VectorXd> qs = randomConfigurations(worlds[0].robot(), 1500, rng);
  for (std::size_t k = 1; k < worlds.size(); ++k) {
    const std::string name = "broad phase " + phases[k].first;
    const int colliding = compareIsFree(worlds[k], worlds[0], qs, name + " (without: the AABB tree)", nullptr);
    BOOST_TEST(colliding > 100);
    BOOST_TEST(colliding < static_cast<int>(qs.size()) - 100);
    auto reference = worlds[0].makeContext();
    auto other = worlds[k].makeContext();
    int separated = 0;
    for (std::size_t i = 0; i < 300; ++i) {
      reference.resetCaches();
      other.resetCaches();
      const DistanceResult a = worlds[0].signedDistance(qs[i], reference);
      const DistanceResult b = worlds[k].signedDistance(qs[i], other);
      BOOST_TEST_REQUIRE(a.found);
      BOOST_TEST_REQUIRE(b.found);
      if (a.closest.distance <= 0.0) continue;
      ++separated;
      BOOST_TEST(b.closest.distance == a.closest.distance, name << ", q " << qs[i].transpose());
    }
    BOOST_TEST(separated > 100);
  }
}

// DistanceOptions::worldPairs / selfPairs: each kind alone gives the minimum over that kind, and
// the smaller of the two is the full minimum.
BOOST_AUTO_TEST_CASE(distance_over_world_pairs_or_self_pairs_only) {
  robots::LoadOptions load = bundledLoadOptions();
  World world(robots::RobotModel::fromUrdfFile(bundledDataDir() + "/deepcheck_arm/urdf/deepcheck_arm.urdf", load),
              testWorldOptions());
  world.addScene(robots::RobotModel::fromUrdfFile(bundledDataDir() + "/scenes/shelf.urdf", load));
  auto context = world.makeContext();
  std::mt19937 rng(5);
  int selfNearest = 0;
  int worldNearest = 0;
  for (int i = 0; i < 300; ++i) {
    const Eigen::VectorXd q = randomConfiguration(world.robot(), rng);
    DistanceOptions worldOnly;
    worldOnly.selfPairs = false;
    DistanceOptions selfOnly;
    selfOnly.worldPairs = false;
    // Each query cold: a penetration depth depends on the warm start (deep.h), and a warm start
    // left by the previous query would make the three measure the same pair differently.
    auto cold = [&](const DistanceOptions& options) {
      context.resetCaches();
      return world.signedDistance(q, context, options);
    };
    const DistanceResult all = cold(DistanceOptions{});
    const DistanceResult w = cold(worldOnly);
    const DistanceResult s = cold(selfOnly);
    BOOST_TEST_REQUIRE(all.found);
    BOOST_TEST(w.found);
    BOOST_TEST(s.found);
    BOOST_TEST((w.closest.bodyB.kind != BodyRef::Kind::RobotLink));
    BOOST_TEST((s.closest.bodyB.kind == BodyRef::Kind::RobotLink));
    BOOST_TEST(std::min(w.closest.distance, s.closest.distance) == all.closest.distance);
    (s.closest.distance < w.closest.distance ? selfNearest : worldNearest)++;
  }
  BOOST_TEST(selfNearest > 10);
  BOOST_TEST(worldNearest > 10);
  DistanceOptions none;
  none.worldPairs = false;
  none.selfPairs = false;
  BOOST_TEST(!world.signedDistance(Eigen::VectorXd::Zero(7), context, none).found);
}

BOOST_AUTO_TEST_SUITE_END()
