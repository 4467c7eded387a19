// Concurrent queries on one World give the answers of sequential ones. Run these under
// ThreadSanitizer too (DEEPCHECK_TSAN, see checker/CMakeLists.txt).

#include "checker_test_util.h"

#include "deepcheck/checker/world.h"

#include <boost/test/unit_test.hpp>

#include <atomic>
#include <random>
#include <thread>
#include <vector>

using namespace deepcheck;
using namespace deepcheck::checker;
using namespace deepcheck::checker::test;

namespace {

constexpr int kThreads = 4;

struct Answer {
  bool free = false;
  double distance = 0.0;
  std::string nameA;
  std::string nameB;
  Eigen::VectorXd gradient;
};

/// Answers for `qs` in order, with one context (made here) or the thread's own (explicit = false).
std::vector<Answer> answers(const World& world, const std::vector<Eigen::VectorXd>& qs, bool explicitContext) {
  std::vector<Answer> out;
  auto context = world.makeContext();
  DistanceOptions options;
  options.gradient = true;
  for (const Eigen::VectorXd& q : qs) {
    Answer a;
    a.free = explicitContext ? world.isFree(q, context) : world.isFree(q);
    const DistanceResult r =
        explicitContext ? world.signedDistance(q, context, options) : world.signedDistance(q, options);
    a.distance = r.closest.distance;
    a.nameA = r.closest.nameA;
    a.nameB = r.closest.nameB;
    a.gradient = r.closest.gradient;
    out.push_back(a);
  }
  return out;
}

void checkSame(const std::vector<Answer>& got, const std::vector<Answer>& expected, int thread) {
  BOOST_TEST_REQUIRE(got.size() == expected.size());
  int differences = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    // Same sequence, same warm starts: bit-identical answers.
    differences += got[i].free != expected[i].free || got[i].distance != expected[i].distance ||
                   got[i].nameA != expected[i].nameA || got[i].nameB != expected[i].nameB ||
                   got[i].gradient != expected[i].gradient;
  }
  BOOST_TEST(differences == 0, "thread " << thread << ": " << differences << " answers differ");
}

World makeWorld() {
  World world(armRobot(), testWorldOptions());
  world.addObstacle(Obstacle::box("crate", Eigen::Vector3d(0.2, 0.3, 0.25), translation(0.35, 0.1, 0.55)));
  world.addObstacle(Obstacle::sphere("ball", 0.12, translation(-0.3, -0.25, 0.7)));
  world.addObstacle(Obstacle::cylinder("post", 0.05, 0.6, translation(0.0, 0.45, 0.4)));
  return world;
}

/// A random walk: consecutive configurations close together, as motion validation makes.
std::vector<Eigen::VectorXd> walk(const robots::RobotModel& model, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> step(0.0, 0.05);
  std::vector<Eigen::VectorXd> qs{randomConfiguration(model, rng)};
  for (int i = 1; i < n; ++i) {
    Eigen::VectorXd q = qs.back();
    for (int v = 0; v < q.size(); ++v) {
      q[v] = std::clamp(q[v] + step(rng), model.lowerLimits()[v], model.upperLimits()[v]);
    }
    qs.push_back(q);
  }
  return qs;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_concurrency)

BOOST_AUTO_TEST_CASE(threads_match_sequential_answers) {
  const World world = makeWorld();
  const std::vector<Eigen::VectorXd> qs = walk(world.robot(), 600, 21);
  const std::vector<Answer> sequential = answers(world, qs, true);
  int colliding = 0;
  for (const Answer& a : sequential) colliding += !a.free;
  BOOST_TEST(colliding > 30);
  BOOST_TEST(colliding < 570);
  std::vector<std::vector<Answer>> results(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    // Half the threads pass their own context, half use the thread's own (thread_local) one.
    threads.emplace_back([&, t] { results[t] = answers(world, qs, t % 2 == 0); });
  }
  for (std::thread& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t) checkSame(results[t], sequential, t);
}

BOOST_AUTO_TEST_CASE(panda_in_the_kitchen_from_threads) {
  if (!haveShared("panda_in_the_kitchen_from_threads")) return;
  World world(loadPanda(), testWorldOptions());
  world.addScene(loadKitchen());
  const std::vector<Eigen::VectorXd> qs = walk(world.robot(), 300, 22);
  const std::vector<Answer> sequential = answers(world, qs, true);
  std::vector<std::vector<Answer>> results(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) threads.emplace_back([&, t] { results[t] = answers(world, qs, t % 2 == 1); });
  for (std::thread& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t) checkSame(results[t], sequential, t);
}

BOOST_AUTO_TEST_CASE(changes_while_queries_run) {
  // One thread moves an obstacle back and forth between two poses while others query. Every
  // answer must be one of the two worlds' answers (a query runs on one snapshot, never a mix).
  World world = makeWorld();
  const int moving =
      world.addObstacle(Obstacle::box("door", Eigen::Vector3d(0.05, 1.6, 1.2), translation(0.3, 0, 0.6)));
  const Eigen::Isometry3d open = translation(3.0, 0, 0.6);
  const Eigen::Isometry3d closed = translation(0.3, 0, 0.6);
  std::mt19937 rng(23);
  const std::vector<Eigen::VectorXd> qs = randomConfigurations(world.robot(), 200, rng);
  // Reference answers of both worlds (fresh contexts, isFree only: exact booleans).
  auto freshIsFree = [&](const Eigen::VectorXd& q) {
    auto context = world.makeContext();
    return world.isFree(q, context);
  };
  std::vector<bool> freeClosed, freeOpen;
  for (const auto& q : qs) freeClosed.push_back(freshIsFree(q));
  world.setObstaclePose(moving, open);
  for (const auto& q : qs) freeOpen.push_back(freshIsFree(q));
  int differing = 0;
  for (std::size_t i = 0; i < qs.size(); ++i) differing += freeClosed[i] != freeOpen[i];
  BOOST_TEST(differing > 10);

  std::atomic<bool> stop{false};
  std::atomic<int> mismatches{0};
  std::atomic<int> queries{0};
  std::thread mover([&] {
    for (int i = 0; i < 200; ++i) world.setObstaclePose(moving, i % 2 ? open : closed);
    stop = true;
  });
  std::vector<std::thread> readers;
  for (int t = 0; t < kThreads - 1; ++t) {
    readers.emplace_back([&, t] {
      auto context = world.makeContext();
      // Until the mover is done, and at least one pass over the configurations.
      for (std::size_t i = t; !stop || i < qs.size(); ++i) {
        const std::size_t k = i % qs.size();
        const bool free = world.isFree(qs[k], context);
        if (free != freeClosed[k] && free != freeOpen[k]) ++mismatches;
        world.signedDistance(qs[k], context);
        ++queries;
      }
    });
  }
  mover.join();
  for (std::thread& th : readers) th.join();
  BOOST_TEST(mismatches == 0);
  BOOST_TEST(queries > 0);
}

BOOST_AUTO_TEST_CASE(attaching_while_queries_run) {
  // One thread attaches a rod to the tool and detaches it, over and over, while others query.
  // Every answer must be one of the two worlds' answers (a query runs on one snapshot).
  World world = makeWorld();
  const Obstacle rod = Obstacle::box("rod", Eigen::Vector3d(0.12, 0.12, 1.0), translation(0, 0, 0.4));
  std::mt19937 rng(29);
  const std::vector<Eigen::VectorXd> qs = randomConfigurations(world.robot(), 200, rng);
  auto freshIsFree = [&](const Eigen::VectorXd& q) {
    auto context = world.makeContext();
    return world.isFree(q, context);
  };
  std::vector<bool> freeWithout, freeWith;
  for (const auto& q : qs) freeWithout.push_back(freshIsFree(q));
  world.attach("tool", rod);
  for (const auto& q : qs) freeWith.push_back(freshIsFree(q));
  world.detach("rod", false);
  int differing = 0;
  for (std::size_t i = 0; i < qs.size(); ++i) differing += freeWithout[i] != freeWith[i];
  BOOST_TEST(differing > 10);

  std::atomic<bool> stop{false};
  std::atomic<int> mismatches{0};
  std::thread changer([&] {
    for (int i = 0; i < 100; ++i) {
      world.attach("tool", rod);
      world.detach("rod", false);
    }
    stop = true;
  });
  std::vector<std::thread> readers;
  for (int t = 0; t < kThreads - 1; ++t) {
    readers.emplace_back([&, t] {
      auto context = world.makeContext();
      for (std::size_t i = t; !stop || i < qs.size(); ++i) {
        const std::size_t k = i % qs.size();
        const bool free = world.isFree(qs[k], context);
        if (free != freeWithout[k] && free != freeWith[k]) ++mismatches;
        world.signedDistance(qs[k], context);
      }
    });
  }
  changer.join();
  for (std::thread& th : readers) th.join();
  BOOST_TEST(mismatches == 0);
}

BOOST_AUTO_TEST_SUITE_END()
