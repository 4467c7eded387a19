// World::isFreeBatch answers isFree for every column, with the AVX2 bound stage (where the
// processor has it) and with the baseline one (forced through world_test_access.h), which certify
// the same configurations: on random configurations, on eight states spread along straight
// motions and on short motions near obstacles, for the Panda in the shelf and the kitchen, the
// bundled arm in the shelf, among tilted thin boards and among obstacles (with an attached
// object, without a broad phase), and a robot with every kind of joint; for every batch size; two
// threads with their own contexts; bad shapes, and poses that leave the doubles, throw as isFree
// does. World::isClearBatch answers isClear likewise, for demands with and without a base
// clearance, and throws for bad demands. The batch kinematics of both builds agree with
// robots::forwardKinematics, bit for bit with each other.

#include "batch_kinematics.h"
#include "checker_test_util.h"
#include "world_test_access.h"

#include "deepcheck/checker/world.h"
#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/srdf.h"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <random>
#include <string>
#include <thread>
#include <vector>

using namespace deepcheck;
using namespace deepcheck::checker;
using namespace deepcheck::checker::test;

namespace {

/// `random` random configurations; `motions` straight motions between two random configurations,
/// eight states spread along each (as a planner's motion check asks); `shortMotions` short motions
/// (24 states 0.01 apart) from random starts, which graze obstacles.
std::vector<Eigen::VectorXd> configurations(const robots::RobotModel& m, int random, int motions, int shortMotions,
                                            unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<Eigen::VectorXd> qs = randomConfigurations(m, random, rng);
  for (int k = 0; k < motions; ++k) {
    const Eigen::VectorXd a = randomConfiguration(m, rng);
    const Eigen::VectorXd b = randomConfiguration(m, rng);
    for (int s = 0; s < 8; ++s) qs.push_back(a + (s + 0.5) / 8.0 * (b - a));
  }
  std::normal_distribution<double> g(0.0, 1.0);
  for (int k = 0; k < shortMotions; ++k) {
    const Eigen::VectorXd q = randomConfiguration(m, rng);
    Eigen::VectorXd step(q.size());
    for (int v = 0; v < q.size(); ++v) step[v] = g(rng);
    step *= 0.01 / step.cwiseAbs().maxCoeff();
    for (int s = 0; s < 24; ++s) qs.push_back(q + s * step);
  }
  return qs;
}

struct Tally {
  int colliding = 0;
  std::uint64_t certified = 0;
};

/// isFreeBatch on qs in consecutive batches of `width` (the last one shorter) against isFree,
/// one context each (with a demand: isClearBatch against isClear); the bound stage in its
/// baseline build when `baseline`.
Tally compareBatches(const World& world, const std::vector<Eigen::VectorXd>& qs, int width, bool baseline,
                     const ClearanceDemand* demand = nullptr) {
  forceBatchBaseline(world, baseline);
  World::Context batch = world.makeContext();
  World::Context single = world.makeContext();
  Tally t;
  const int vars = world.robot().numVariables();
  for (std::size_t first = 0; first < qs.size(); first += width) {
    const int n = static_cast<int>(std::min<std::size_t>(width, qs.size() - first));
    Eigen::MatrixXd m(vars, n);
    for (int l = 0; l < n; ++l) m.col(l) = qs[first + l];
    bool free[8];
    if (demand != nullptr) {
      world.isClearBatch(m, free, batch, *demand);
    } else {
      world.isFreeBatch(m, free, batch);
    }
    for (int l = 0; l < n; ++l) {
      const bool reference =
          demand != nullptr ? world.isClear(qs[first + l], single, *demand) : world.isFree(qs[first + l], single);
      BOOST_CHECK_MESSAGE(free[l] == reference, "q = " << qs[first + l].transpose() << ": batch " << free[l]
                                                       << ", one by one " << reference
                                                       << (baseline ? " (baseline)" : ""));
      t.colliding += !reference;
    }
  }
  t.certified = batch.stats().batchCertified;
  BOOST_TEST(batch.stats().queries == qs.size());  // one per configuration, certified or not
  forceBatchBaseline(world, false);
  return t;
}

/// Both builds of the bound stage on qs: isFree's (isClear's) answers, the same configurations
/// certified.
Tally compareBothBuilds(const World& world, const std::vector<Eigen::VectorXd>& qs, int width = 8,
                        const ClearanceDemand* demand = nullptr) {
  const Tally avx2 = compareBatches(world, qs, width, false, demand);
  const Tally baseline = compareBatches(world, qs, width, true, demand);
  BOOST_TEST(avx2.certified == baseline.certified);
  BOOST_TEST(avx2.colliding == baseline.colliding);
  return avx2;
}

World pandaWorld(const robots::RobotModel& scene) {
  WorldOptions options = testWorldOptions();
  options.disabledPairs = robots::readSrdfDisabledPairs(
      sharedDir() + "/robots/panda/moveit_resources_panda_moveit_config/config/panda.srdf");
  World world(loadPanda(), options);
  world.addScene(scene);
  return world;
}

robots::RobotModel bundledShelf() {
  return robots::RobotModel::fromUrdfFile(bundledDataDir() + "/scenes/shelf.urdf", bundledLoadOptions());
}

World armWorld(BroadPhase broadPhase = BroadPhase::AabbTree) {
  WorldOptions options = testWorldOptions();
  options.broadPhase = broadPhase;
  options.disabledPairs = robots::readSrdfDisabledPairs(bundledDataDir() + "/deepcheck_arm/srdf/deepcheck_arm.srdf");
  return World(robots::RobotModel::fromUrdfFile(bundledDataDir() + "/deepcheck_arm/urdf/deepcheck_arm.urdf",
                                                bundledLoadOptions()),
               options);
}

/// Every lane of `poses` against robots::forwardKinematics of its column (lanes past qs.cols()
/// repeat the last one): link poses and link geometry centres within 1e-12.
template <class L>
void checkPoses(const robots::RobotModel& model, const detail::RobotData& robot, const Eigen::MatrixXd& qs,
                const detail::BatchPosesT<L>& poses) {
  for (int lane = 0; lane < detail::kLanes; ++lane) {
    const Eigen::Index col = std::min<Eigen::Index>(lane, qs.cols() - 1);
    const std::vector<Eigen::Isometry3d> X_WL = robots::forwardKinematics(model, qs.col(col));
    BOOST_TEST(poses.finite[lane]);
    for (int k = 0; k < model.numLinks(); ++k) {
      for (int i = 0; i < 9; ++i) {
        BOOST_TEST(std::abs(poses.links[k].R[i][lane] - X_WL[k].linear()(i / 3, i % 3)) < 1e-12);
      }
      for (int i = 0; i < 3; ++i) BOOST_TEST(std::abs(poses.links[k].t[i][lane] - X_WL[k].translation()[i]) < 1e-12);
    }
    for (std::size_t g = 0; g < robot.links.size(); ++g) {
      const Eigen::Vector3d c = X_WL[robot.links[g].link] * robot.links[g].center_L;
      const detail::LanePointT<L>& p = poses.linkCenter[g];
      BOOST_TEST((Eigen::Vector3d(p.x[lane], p.y[lane], p.z[lane]) - c).norm() < 1e-12);
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_is_free_batch)

BOOST_AUTO_TEST_CASE(batch_kinematics_agree_with_forward_kinematics) {
  robots::RobotModel model = everyJointRobot();
  Eigen::Isometry3d base = translation(0.4, -0.2, 0.1);
  base.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -1, 2).normalized()).toRotationMatrix();
  model.setBasePose(base);
  const World world(model, testWorldOptions());
  const detail::RobotData& robot = *robotOf(world);
  std::mt19937 rng(57);
  std::uniform_real_distribution<double> u(-20.0, 20.0);  // several turns, and far slides
  for (int round = 0; round < 50; ++round) {
    const int n = 1 + round % 8;
    Eigen::MatrixXd qs(model.numVariables(), n);
    for (int v = 0; v < qs.rows(); ++v) {
      for (int l = 0; l < n; ++l) qs(v, l) = u(rng);
    }
    detail::BatchPosesT<detail::BaselineLanes> baseline;
    detail::batchForwardKinematics(robot, qs, baseline);
    checkPoses(model, robot, qs, baseline);
    if (!detail::batchAvx2Available()) continue;
    detail::BatchPosesT<detail::Avx2Lanes> avx2;
    detail::batchForwardKinematics(robot, qs, avx2);
    checkPoses(model, robot, qs, avx2);
    for (std::size_t k = 0; k < avx2.links.size(); ++k) {  // the same bits
      for (int l = 0; l < detail::kLanes; ++l) BOOST_TEST(avx2.links[k].t[0][l] == baseline.links[k].t[0][l]);
    }
  }
}

BOOST_AUTO_TEST_CASE(panda_shelf_batches_answer_as_is_free) {
  if (!haveShared("panda_shelf_batches_answer_as_is_free")) return;
  const World world = pandaWorld(bundledShelf());
  const std::vector<Eigen::VectorXd> qs = configurations(world.robot(), 4000, 300, 100, 51);
  const Tally t = compareBothBuilds(world, qs);
  BOOST_TEST(t.colliding > 500);
  BOOST_TEST(t.colliding < static_cast<int>(qs.size()) - 500);
  BOOST_TEST(t.certified > 100u);  // the bound stage answers some configurations itself
}

BOOST_AUTO_TEST_CASE(panda_kitchen_batches_answer_as_is_free) {
  if (!haveShared("panda_kitchen_batches_answer_as_is_free")) return;
  const World world = pandaWorld(loadKitchen());
  const std::vector<Eigen::VectorXd> qs = configurations(world.robot(), 2000, 200, 60, 52);
  const Tally t = compareBothBuilds(world, qs);
  BOOST_TEST(t.colliding > 300);
  BOOST_TEST(t.colliding < static_cast<int>(qs.size()) - 300);
}

BOOST_AUTO_TEST_CASE(arm_shelf_batches_answer_as_is_free) {
  World world = armWorld();
  world.addScene(bundledShelf());
  const std::vector<Eigen::VectorXd> qs = configurations(world.robot(), 3000, 300, 100, 53);
  const Tally t = compareBothBuilds(world, qs);
  BOOST_TEST(t.colliding > 300);
  BOOST_TEST(t.colliding < static_cast<int>(qs.size()) - 300);
  BOOST_TEST(t.certified > 100u);
}

BOOST_AUTO_TEST_CASE(arm_obstacles_and_attached_object_batches_answer_as_is_free) {
  World world = armWorld();
  addCrateBallPost(world);
  const std::vector<Eigen::VectorXd> qs = configurations(world.robot(), 1500, 150, 60, 54);
  compareBothBuilds(world, qs);
  // An attached box adds a link geometry (and self pairs); then an obstacle moves.
  const std::string tip = world.robot().links().back().name;
  world.attach(tip, Obstacle::box("tool", Eigen::Vector3d(0.05, 0.05, 0.25), translation(0, 0, 0.1)));
  compareBothBuilds(world, qs);
  world.setObstaclePose(world.obstacleIds().front(), translation(-0.3, 0.3, 0.5));
  const Tally t = compareBothBuilds(world, qs);
  BOOST_TEST(t.colliding > 100);
  BOOST_TEST(t.certified > 100u);
}

// Thin boards turned about two axes, whose world boxes are far larger than they are: a piece's
// sphere is often beyond a board's oriented box but within its world box, where the bound stage's
// float test against the oriented box decides.
BOOST_AUTO_TEST_CASE(tilted_boards_batches_answer_as_is_free) {
  World world = armWorld();
  const Eigen::Vector3d at[3] = {{0.7, 0.0, 0.4}, {-0.5, 0.55, 0.5}, {0.0, -0.75, 0.3}};
  for (int k = 0; k < 3; ++k) {
    Eigen::Isometry3d X = translation(at[k].x(), at[k].y(), at[k].z());
    X.linear() =
        (Eigen::AngleAxisd(0.7 + 0.4 * k, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()))
            .toRotationMatrix();
    world.addObstacle(Obstacle::box("board" + std::to_string(k), Eigen::Vector3d(0.8, 0.02, 0.6), X));
  }
  const Tally t = compareBothBuilds(world, configurations(world.robot(), 1500, 150, 60, 60));
  BOOST_TEST(t.colliding > 100);
  BOOST_TEST(t.certified > 100u);
}

BOOST_AUTO_TEST_CASE(every_joint_kind_batches_answer_as_is_free) {
  // Skew revolute and prismatic axes, a mimic joint, a fixed joint and a rotated base, among
  // obstacles: the batch's own kinematics feed the bound stage.
  robots::RobotModel model = everyJointRobot();
  Eigen::Isometry3d base = translation(0.1, -0.1, 0.0);
  base.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(0, 0, 1)).toRotationMatrix();
  model.setBasePose(base);
  World world(model, testWorldOptions());
  world.addObstacle(Obstacle::box("wall", Eigen::Vector3d(0.1, 1.0, 1.0), translation(0.6, 0.0, 0.3)));
  world.addObstacle(Obstacle::sphere("ball", 0.15, translation(-0.3, 0.4, 0.3)));
  const Tally t = compareBothBuilds(world, configurations(world.robot(), 2000, 150, 60, 59));
  BOOST_TEST(t.colliding > 100);
  BOOST_TEST(t.certified > 100u);
}

BOOST_AUTO_TEST_CASE(without_a_broad_phase_batches_answer_as_is_free) {
  World world = armWorld(BroadPhase::None);
  world.addScene(bundledShelf());
  addCrateBallPost(world);
  const Tally t = compareBothBuilds(world, configurations(world.robot(), 800, 80, 40, 58));
  BOOST_TEST(t.colliding > 100);
  BOOST_TEST(t.certified > 100u);
}

BOOST_AUTO_TEST_CASE(every_batch_size_answers_as_is_free) {
  World world = armWorld();
  world.addScene(bundledShelf());
  const std::vector<Eigen::VectorXd> qs = configurations(world.robot(), 400, 40, 20, 55);
  for (int width = 1; width <= 8; ++width) compareBothBuilds(world, qs, width);
  // Columns of a larger matrix (a Ref with an outer stride).
  Eigen::MatrixXd all(world.robot().numVariables(), 12);
  for (int l = 0; l < 12; ++l) all.col(l) = qs[l];
  bool free[8];
  world.isFreeBatch(all.middleCols(3, 7), free);
  for (int l = 0; l < 7; ++l) BOOST_TEST(free[l] == world.isFree(qs[3 + l]));
}

/// A demand of `base` plus `scale` times random link and self bounds (up to 1 and 2 m).
ClearanceDemand randomDemand(const robots::RobotModel& m, double base, double scale, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ClearanceDemand d;
  d.base = base;
  d.scale = scale;
  d.link = Eigen::VectorXd::NullaryExpr(m.numLinks(), [&] { return u(rng); });
  d.self = Eigen::MatrixXd::NullaryExpr(m.numLinks(), m.numLinks(), [&] { return 2.0 * u(rng); });
  return d;
}

BOOST_AUTO_TEST_CASE(clear_batches_answer_as_is_clear) {
  // The bound stage with every pair's margin (a certified motion's first level asks it so), on
  // the bundled arm among obstacles with an attached object, and in the shelf.
  World world = armWorld();
  addCrateBallPost(world);
  world.attach(world.robot().links().back().name,
               Obstacle::box("tool", Eigen::Vector3d(0.05, 0.05, 0.25), translation(0, 0, 0.1)));
  std::mt19937 rng(61);
  const std::vector<Eigen::VectorXd> qs = configurations(world.robot(), 1200, 120, 40, 60);
  std::uint64_t certified = 0;
  int notClear = 0;
  for (const auto& [base, scale] : std::vector<std::pair<double, double>>{{0.0, 0.0}, {0.0, 0.05}, {0.01, 0.2}}) {
    const ClearanceDemand d = randomDemand(world.robot(), base, scale, rng);
    BOOST_TEST_CONTEXT("base " << base << ", scale " << scale) {
      const Tally t = compareBothBuilds(world, qs, 8, &d);
      certified += t.certified;
      notClear += t.colliding;
    }
  }
  world.addScene(bundledShelf());
  const ClearanceDemand d = randomDemand(world.robot(), 0.0, 0.1, rng);
  const Tally t = compareBothBuilds(world, qs, 5, &d);
  BOOST_TEST(t.colliding > 300);
  BOOST_TEST(certified + t.certified > 300u);  // the bound stage answers some itself
  BOOST_TEST(notClear > 300);
}

BOOST_AUTO_TEST_CASE(bad_demands_throw_in_a_clear_batch) {
  World world = armWorld();
  const int vars = world.robot().numVariables();
  const int links = world.robot().numLinks();
  bool clear[8];
  std::mt19937 rng(62);
  ClearanceDemand d = randomDemand(world.robot(), 0.0, 0.1, rng);
  d.link = Eigen::VectorXd::Zero(links + 1);
  checkThrowsWith([&] { world.isClearBatch(Eigen::MatrixXd::Zero(vars, 3), clear, d); },
                  std::to_string(links + 1) + " link entries");
  d = randomDemand(world.robot(), -0.01, 0.1, rng);
  checkThrowsWith([&] { world.isClearBatch(Eigen::MatrixXd::Zero(vars, 3), clear, d); }, "-0.01");
  addCrateBallPost(world);  // pairs to read the link entries for
  d = randomDemand(world.robot(), 0.0, 0.1, rng);
  d.link.setConstant(-1.0);
  checkThrowsWith([&] { world.isClearBatch(Eigen::MatrixXd::Zero(vars, 3), clear, d); }, "-0.1");
  checkThrowsWith([&] { world.isClearBatch(Eigen::MatrixXd::Zero(vars, 9), clear, d); }, "isClearBatch");
}

BOOST_AUTO_TEST_CASE(bad_shapes_throw_naming_the_sizes) {
  World world = armWorld();
  const int vars = world.robot().numVariables();
  bool free[9];
  checkThrowsWith([&] { world.isFreeBatch(Eigen::MatrixXd::Zero(vars, 0), free); }, "x 0");
  checkThrowsWith([&] { world.isFreeBatch(Eigen::MatrixXd::Zero(vars, 9), free); }, "x 9");
  checkThrowsWith([&] { world.isFreeBatch(Eigen::MatrixXd::Zero(vars + 1, 3), free); },
                  std::to_string(vars + 1) + " x 3");
  World other = armWorld();
  World::Context foreign = other.makeContext();
  checkThrowsWith([&] { world.isFreeBatch(Eigen::MatrixXd::Zero(vars, 2), free, foreign); }, "another world");
}

BOOST_AUTO_TEST_CASE(two_threads_with_their_own_contexts_give_the_same_answers) {
  World world = armWorld();
  world.addScene(bundledShelf());
  const std::vector<Eigen::VectorXd> qs = configurations(world.robot(), 1600, 100, 40, 56);
  std::vector<char> reference(qs.size());
  for (std::size_t i = 0; i < qs.size(); ++i) reference[i] = world.isFree(qs[i]);
  const int vars = world.robot().numVariables();
  std::vector<std::vector<char>> answers(2, std::vector<char>(qs.size()));
  auto run = [&](int t) {
    World::Context context = world.makeContext();
    for (std::size_t first = 0; first + 8 <= qs.size(); first += 8) {
      Eigen::MatrixXd m(vars, 8);
      for (int l = 0; l < 8; ++l) m.col(l) = qs[first + l];
      bool free[8];
      world.isFreeBatch(m, free, context);
      for (int l = 0; l < 8; ++l) answers[t][first + l] = free[l];
    }
  };
  std::thread a(run, 0), b(run, 1);
  a.join();
  b.join();
  const std::size_t full = qs.size() / 8 * 8;
  for (int t = 0; t < 2; ++t) {
    BOOST_TEST(std::equal(reference.begin(), reference.begin() + full, answers[t].begin()));
  }
}

BOOST_AUTO_TEST_CASE(poses_far_out_answer_or_throw_as_is_free) {
  World world = sliderPairWorld();
  // Each value finite, their sum not: isFree reports it; so does the batch, whatever lane it is in.
  Eigen::MatrixXd qs(2, 3);
  qs << 0.5, 1e308, 0.0, 0.0, 1e308, 0.0;
  checkThrowsWith([&] { world.isFree(qs.col(1)); }, "not finite");
  bool free[4];
  checkThrowsWith([&] { world.isFreeBatch(qs, free); }, "not finite");
  // A value that is not finite: both throw naming it.
  qs(0, 1) = std::numeric_limits<double>::quiet_NaN();
  checkThrowsWith([&] { world.isFree(qs.col(1)); }, "slide1");
  checkThrowsWith([&] { world.isFreeBatch(qs, free); }, "slide1");
  // Finite but far: the cube at 1e30 (free), and travels of 1e20 that cancel, leaving the cube on
  // the box (colliding; in floats the lanes' poses would be meaningless there).
  Eigen::MatrixXd far(2, 4);
  far << 1e30, 1e20, -3e18, 0.5, 0.0, -1e20, 3e18, 0.0;
  world.isFreeBatch(far, free);
  for (int l = 0; l < 4; ++l) BOOST_TEST(free[l] == world.isFree(far.col(l)), "lane " << l);
  BOOST_TEST(free[0]);
  BOOST_TEST(!free[1]);
  BOOST_TEST(!free[2]);
  BOOST_TEST(free[3]);
}

BOOST_AUTO_TEST_SUITE_END()
