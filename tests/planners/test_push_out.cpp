// Push-out (start/goal repair) against the random-jiggle baseline, on the bundled arm and scenes.

#include "bundled.h"

#include "deepcheck/planners/push_out.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/validity.h"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace dp = deepcheck::planners;
using dp::test::bundledWorld;
using dp::test::randomConfiguration;

namespace {

/// Random configurations of `world` whose signed distance is in [-maxDepth, 0): slightly colliding
/// starts, with the scene or with the robot itself.
std::vector<Eigen::VectorXd> penetratingConfigurations(const deepcheck::checker::World& world, int count,
                                                       double maxDepth, std::mt19937_64& rng) {
  std::vector<Eigen::VectorXd> out;
  while (static_cast<int>(out.size()) < count) {
    const Eigen::VectorXd q = randomConfiguration(world.robot(), rng);
    const double sd = dp::signedDistanceUpTo(world, q, 0.0 + 1e-3);
    if (sd < 0.0 && sd >= -maxDepth) out.push_back(q);
  }
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(planners_push_out)

BOOST_AUTO_TEST_CASE(valid_input_is_returned_unchanged) {
  const auto world = bundledWorld("shelf");
  const dp::PushOut pushOut(world);
  const Eigen::VectorXd start = dp::test::suggestedStart();
  const dp::PushOutResult r = pushOut.run(start);
  BOOST_TEST(r.status == dp::PushOutStatus::AlreadyValid);
  BOOST_TEST(r.jointMotion == 0.0);
  BOOST_TEST((r.q == start));
}

// A table sunk 3 mm into the base, which no joint moves: no push-out can help; the result says
// which pair blocks and how to allow it, and once allowed the start is valid.
BOOST_AUTO_TEST_CASE(a_pair_no_joint_moves_is_named_with_how_to_allow_it) {
  const auto world = dp::loadWorld(dp::test::armUrdf(), {}, dp::test::bundledOptions());
  double bottom = std::numeric_limits<double>::infinity();
  for (const deepcheck::robots::CollisionPiece& p : world->linkPieces(world->robot().linkIndex("base_link"))) {
    for (const Eigen::Vector3d& v : p.core->vertices()) bottom = std::min(bottom, (p.X_LP * v).z() - p.radius);
  }
  Eigen::Isometry3d X_WT = Eigen::Isometry3d::Identity();
  X_WT.translation() = Eigen::Vector3d(0, 0, bottom + 0.003 - 0.025);
  world->addObstacle(deepcheck::checker::Obstacle::box("table", Eigen::Vector3d(1.0, 1.0, 0.05), X_WT));
  const dp::PushOutResult r = dp::PushOut(world).run(dp::test::suggestedStart());
  BOOST_TEST(!r.success());
  BOOST_TEST(r.reason.find("the link base_link is moved by no joint") != std::string::npos, r.reason);
  BOOST_TEST(r.reason.find("--allow-collision base_link:obstacle/table") != std::string::npos, r.reason);
  world->allowCollision("base_link", "table");
  const dp::PushOutResult allowed = dp::PushOut(world).run(dp::test::suggestedStart());
  BOOST_TEST(allowed.status == dp::PushOutStatus::AlreadyValid);
  BOOST_TEST(allowed.reason.empty());
}

BOOST_AUTO_TEST_CASE(bad_input_is_rejected_with_its_name) {
  const auto world = bundledWorld("shelf");
  dp::PushOutOptions options;
  options.damping = -1.0;
  BOOST_CHECK_EXCEPTION(dp::PushOut(world, {}, options), std::invalid_argument, [](const std::invalid_argument& e) {
    return std::string(e.what()).find("damping") != std::string::npos;
  });
  dp::ValidityOptions validity;
  validity.penetrationTolerance = std::nan("");
  BOOST_CHECK_EXCEPTION(dp::PushOut(world, validity), std::invalid_argument, [](const std::invalid_argument& e) {
    return std::string(e.what()).find("penetrationTolerance") != std::string::npos;
  });
  const dp::PushOut pushOut(world);
  Eigen::VectorXd q = dp::test::suggestedStart();
  q[3] = std::nan("");
  BOOST_CHECK_EXCEPTION(pushOut.run(q), std::invalid_argument, [](const std::invalid_argument& e) {
    return std::string(e.what()).find("joint4") != std::string::npos;
  });
  BOOST_CHECK_THROW(pushOut.run(Eigen::VectorXd::Zero(3)), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(too_deep_is_left_alone) {
  const auto world = bundledWorld("shelf");
  std::mt19937_64 rng(7);
  dp::PushOutOptions options;
  options.maxDepth = 0.01;
  const dp::PushOut pushOut(world, {}, options);
  // A configuration penetrating more than 1 cm.
  for (int i = 0; i < 100000; ++i) {
    const Eigen::VectorXd q = randomConfiguration(world->robot(), rng);
    const double sd = dp::signedDistanceUpTo(*world, q, 1.0);
    if (sd < -0.02) {
      const dp::PushOutResult r = pushOut.run(q);
      BOOST_TEST(r.status == dp::PushOutStatus::TooDeep);
      BOOST_TEST((r.q == q));
      return;
    }
  }
  BOOST_FAIL("no configuration penetrating more than 2 cm found");
}

BOOST_AUTO_TEST_CASE(joint_limits_are_respected_and_a_start_outside_them_is_clamped) {
  const auto world = bundledWorld("shelf");
  const dp::PushOut pushOut(world);
  const auto& model = world->robot();
  Eigen::VectorXd q = dp::test::suggestedStart();
  q[1] = model.upperLimits()[1] + 0.3;
  const dp::PushOutResult r = pushOut.run(q);
  BOOST_TEST(r.success());
  BOOST_TEST(r.q[1] <= model.upperLimits()[1]);
  BOOST_TEST(r.jointMotion >= 0.3 - 1e-12);
}

// A start penetrating up to 2 cm is repaired in >= 99 % of seeded trials, with less joint
// motion than the random-jiggle baseline.
BOOST_AUTO_TEST_CASE(repairs_starts_penetrating_up_to_2cm_with_less_motion_than_jiggle) {
  constexpr int kTrialsPerScene = 100;
  constexpr double kMaxDepth = 0.02;
  int trials = 0;
  int pushSuccess = 0;
  int both = 0;
  double pushMotion = 0.0;
  double jiggleMotion = 0.0;
  double pushWorkspace = 0.0;
  double jiggleWorkspace = 0.0;
  for (const std::string scene : {"table", "shelf", "narrow_passage"}) {
    const auto world = bundledWorld(scene);
    std::mt19937_64 rng(1234);
    const std::vector<Eigen::VectorXd> starts = penetratingConfigurations(*world, kTrialsPerScene, kMaxDepth, rng);
    const dp::PushOut pushOut(world);
    for (const Eigen::VectorXd& q : starts) {
      ++trials;
      const dp::PushOutResult p = pushOut.run(q);
      const dp::PushOutResult j = dp::jiggle(*world, {}, q, {}, rng);
      if (p.success()) {
        ++pushSuccess;
        BOOST_TEST(dp::isConfigurationValid(*world, p.q, {}));
        BOOST_TEST(((p.q.array() >= world->robot().lowerLimits().array()).all() &&
                    (p.q.array() <= world->robot().upperLimits().array()).all()));
      }
      if (j.success()) {
        BOOST_TEST(dp::isConfigurationValid(*world, j.q, {}));
      }
      if (p.success() && j.success()) {
        ++both;
        pushMotion += p.jointMotion;
        jiggleMotion += j.jointMotion;
        pushWorkspace += dp::maxLinkDisplacement(world->robot(), q, p.q);
        jiggleWorkspace += dp::maxLinkDisplacement(world->robot(), q, j.q);
      }
    }
  }
  BOOST_TEST(pushSuccess >= 0.99 * trials);
  BOOST_TEST(both > trials / 2);
  BOOST_TEST(pushMotion < jiggleMotion);
  BOOST_TEST(pushWorkspace < jiggleWorkspace);
}

BOOST_AUTO_TEST_SUITE_END()
