// The static AABB tree against brute force on random boxes.

#include "aabb_tree.h"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <random>
#include <set>

using namespace deepcheck::checker;

namespace {

std::vector<Aabb> randomBoxes(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> position(-3.0, 3.0);
  std::uniform_real_distribution<double> size(0.01, 0.7);
  std::vector<Aabb> boxes;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d c(position(rng), position(rng), position(rng));
    const Eigen::Vector3d h(size(rng), size(rng), size(rng));
    Aabb b;
    b.lo = c - h;
    b.hi = c + h;
    boxes.push_back(b);
  }
  return boxes;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checker_aabb_tree)

BOOST_AUTO_TEST_CASE(overlap_queries_match_brute_force) {
  std::mt19937 rng(41);
  for (int n : {0, 1, 2, 3, 17, 200}) {
    const std::vector<Aabb> boxes = randomBoxes(n, rng);
    const AabbTree tree(boxes);
    BOOST_TEST(tree.size() == n);
    std::uniform_real_distribution<double> position(-3.5, 3.5);
    std::uniform_real_distribution<double> radius(0.0, 1.0);
    for (int k = 0; k < 200; ++k) {
      const Aabb query = Aabb::ofSphere(Eigen::Vector3d(position(rng), position(rng), position(rng)), radius(rng));
      std::set<int> expected, got;
      for (int i = 0; i < n; ++i) {
        if (boxes[i].overlaps(query)) expected.insert(i);
      }
      const bool stopped = tree.visitOverlapping(query, [&](int i) {
        BOOST_TEST(got.insert(i).second);  // each item once
        return false;
      });
      BOOST_TEST(!stopped);
      BOOST_TEST((got == expected));
      if (!expected.empty()) {
        int visits = 0;
        BOOST_TEST(tree.visitOverlapping(query, [&](int) { return ++visits == 1; }));
        BOOST_TEST(visits == 1);
      }
    }
  }
}

// Outside a box the signed distance is the Euclidean one; inside, minus the distance to the
// nearest face; on a face, zero.
BOOST_AUTO_TEST_CASE(signed_distance_of_a_point) {
  Aabb box;
  box.lo = Eigen::Vector3d(-1, -2, -3);
  box.hi = Eigen::Vector3d(1, 2, 3);
  BOOST_TEST(box.signedDistance(Eigen::Vector3d(0, 0, 0)) == -1.0);
  BOOST_TEST(box.signedDistance(Eigen::Vector3d(0.5, 1.9, 0)) == -0.1, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(box.signedDistance(Eigen::Vector3d(1, 0, 0)) == 0.0);
  BOOST_TEST(box.signedDistance(Eigen::Vector3d(4, 6, 3)) == 5.0);
  BOOST_TEST(box.signedDistance(Eigen::Vector3d(0, 0, -3.5)) == 0.5);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> position(-5.0, 5.0);
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Vector3d p(position(rng), position(rng), position(rng));
    const double sd = box.signedDistance(p);
    if (sd > 0) BOOST_TEST(sd == box.distance(p));
    if (box.distance(p) == 0) BOOST_TEST(sd <= 0.0);
  }
}

BOOST_AUTO_TEST_CASE(near_queries_match_brute_force) {
  std::mt19937 rng(42);
  const std::vector<Aabb> boxes = randomBoxes(300, rng);
  const AabbTree tree(boxes);
  std::uniform_real_distribution<double> position(-4.0, 4.0);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d c(position(rng), position(rng), position(rng));
    const double r = 0.2;
    // A fixed bound: exactly the boxes within it, each once, with a correct lower bound.
    const double bound = 0.5;
    std::set<int> expected, got;
    for (int i = 0; i < 300; ++i) {
      if (boxes[i].signedDistance(c) - r < bound) expected.insert(i);
    }
    tree.visitNear(
        c, r, [&] { return bound; },
        [&](int i, double lowerBound) {
          BOOST_TEST(lowerBound == boxes[i].signedDistance(c) - r);
          got.insert(i);
        });
    BOOST_TEST((got == expected));
    // A shrinking bound (nearest-box search): finds the nearest box, or the one c is deepest in.
    double best = std::numeric_limits<double>::infinity();
    tree.visitNear(
        c, 0.0, [&] { return best; }, [&](int i, double) { best = std::min(best, boxes[i].signedDistance(c)); });
    double nearest = std::numeric_limits<double>::infinity();
    for (const Aabb& b : boxes) nearest = std::min(nearest, b.signedDistance(c));
    BOOST_TEST(best == nearest);
  }
}

BOOST_AUTO_TEST_SUITE_END()
