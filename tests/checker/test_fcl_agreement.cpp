// Agreement with the FCL reference backend (original meshes, exact primitives) on random
// configurations: a configuration FCL finds colliding is never reported free; a false alarm
// (ours colliding, FCL free) is allowed only within the geometry excess of the pieces (cylinder
// prisms, decomposition concavity); on free configurations our distance is at most FCL's and at
// least FCL's minus that excess. Both bodies of a pair may stick out of their original shapes,
// so the tolerance of a pair is twice the world's largest excess.

#include "checker_test_util.h"

#include "deepcheck/fcl_reference/fcl_backend.h"
#include "deepcheck/checker/world.h"
#include "deepcheck/robots/pair_filter.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>

using namespace deepcheck;
using namespace deepcheck::checker;
using namespace deepcheck::checker::test;

namespace {

/// FCL's mesh distance takes milliseconds: the distance cross-check runs on the first this many
/// free configurations of each world (the boolean check runs on all).
constexpr int kMaxDistanceChecks = 400;

/// FCL's distances between meshes and primitives come from its own GJK on triangles; they agree
/// with exact distances to about this (metres).
constexpr double kFclAccuracy = 1e-6;

struct Agreement {
  int samples = 0;
  int fclColliding = 0;
  int missed = 0;       ///< FCL colliding, ours free: must be 0
  int falseAlarms = 0;  ///< ours colliding, FCL free
  int falseAlarmsBeyondExcess = 0;
  double worstFalseAlarm = 0.0;  ///< largest FCL distance of a false alarm
  int distanceChecks = 0;
};

Agreement compare(const World& world, int samples, unsigned seed, bool distances) {
  fcl_reference::FclWorld fcl(world);
  auto context = world.makeContext();
  const double excess = 2 * world.summaryCounts().geometryExcess;  // both bodies of the pair
  BOOST_TEST_REQUIRE(!std::isnan(excess));
  std::mt19937 rng(seed);
  Agreement a;
  for (int i = 0; i < samples; ++i) {
    const Eigen::VectorXd q = randomConfiguration(world.robot(), rng);
    const bool ours = world.isFree(q, context);
    const bool theirs = fcl.isFree(q);
    ++a.samples;
    a.fclColliding += !theirs;
    if (!theirs && ours) {
      ++a.missed;
      BOOST_ERROR("FCL finds q = " << q.transpose() << " colliding; reported free");
    }
    const bool checkDistance = distances && theirs && ours && a.distanceChecks < kMaxDistanceChecks;
    if (!checkDistance && theirs == ours) continue;
    const fcl_reference::FclDistanceResult reference = theirs ? fcl.distance(q) : fcl_reference::FclDistanceResult{};
    if (theirs && !ours) {
      ++a.falseAlarms;
      a.worstFalseAlarm = std::max(a.worstFalseAlarm, reference.distance);
      if (reference.distance > excess + kFclAccuracy) ++a.falseAlarmsBeyondExcess;
    }
    if (checkDistance) {
      const DistanceResult r = world.signedDistance(q, context);
      BOOST_TEST(r.closest.distance <= reference.distance + kFclAccuracy,
                 "q " << q.transpose() << ": sd " << r.closest.distance << " (" << r.closest.nameA << " / "
                      << r.closest.nameB << ") above FCL's " << reference.distance << " (" << reference.nameA << " / "
                      << reference.nameB << ")");
      BOOST_TEST(r.closest.distance >= reference.distance - excess - kFclAccuracy,
                 "q " << q.transpose() << ": sd " << r.closest.distance << " below FCL's " << reference.distance
                      << " by more than the excess " << excess);
      ++a.distanceChecks;
    }
  }
  return a;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_fcl_agreement)

BOOST_AUTO_TEST_CASE(arm_with_primitives_and_a_mesh) {
  World world(armRobot(), testWorldOptions());
  addCrateBallPost(world);
  world.addObstacle(Obstacle::fromMesh("tetra", tetrahedronMesh(), translation(-0.4, 0.3, 0.2)));
  const Agreement a = compare(world, 3000, 31, true);
  BOOST_TEST(a.missed == 0);
  BOOST_TEST(a.falseAlarmsBeyondExcess == 0);
  BOOST_TEST(a.fclColliding > 300);  // both outcomes are well represented
  BOOST_TEST(a.fclColliding < a.samples - 300);
  BOOST_TEST(a.distanceChecks == kMaxDistanceChecks);
}

BOOST_AUTO_TEST_CASE(bundled_arm_in_the_shelf) {
  WorldOptions options = testWorldOptions();
  options.disabledPairs = robots::readSrdfDisabledPairs(bundledDataDir() + "/deepcheck_arm/srdf/deepcheck_arm.srdf");
  World world(robots::RobotModel::fromUrdfFile(bundledDataDir() + "/deepcheck_arm/urdf/deepcheck_arm.urdf",
                                               bundledLoadOptions()),
              options);
  world.addScene(robots::RobotModel::fromUrdfFile(bundledDataDir() + "/scenes/shelf.urdf", bundledLoadOptions()));
  const Agreement a = compare(world, 2000, 33, true);
  BOOST_TEST(a.missed == 0);
  BOOST_TEST(a.falseAlarmsBeyondExcess == 0);
  BOOST_TEST(a.fclColliding > 100);
  BOOST_TEST(a.fclColliding < a.samples - 100);
}

BOOST_AUTO_TEST_CASE(panda_in_the_kitchen) {
  if (!haveShared("panda_in_the_kitchen")) return;
  World world(loadPanda(), testWorldOptions());
  world.addScene(loadKitchen());
  const Agreement a = compare(world, 2000, 32, true);
  BOOST_TEST(a.missed == 0);
  BOOST_TEST(a.falseAlarmsBeyondExcess == 0);
  BOOST_TEST(a.fclColliding > 200);
  BOOST_TEST(a.fclColliding < a.samples - 200);
}

BOOST_AUTO_TEST_SUITE_END()
