// VectorNearest against a brute-force search with the space's distance, on both sides of its switch
// to GNAT; and makePlanner's RRTConnect, which uses it, planning the very path OMPL's RRTConnect
// with GNAT plans from the same samples.

#include "bundled.h"

#include "deepcheck/planners/planner_factory.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/planners/vector_nearest.h"

#include <boost/test/unit_test.hpp>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Exception.h>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <typeinfo>
#include <vector>

namespace dp = deepcheck::planners;
namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

constexpr unsigned kDimension = 7;
/// A scan limit that a test passes in a few hundred elements.
constexpr std::size_t kTestScanLimit = 300;

/// A tree node as OMPL's tree planners keep it.
struct Node {
  ob::State* state = nullptr;
};
using Nearest = dp::VectorNearest<Node*>;

/// Nodes in a space of kDimension values, with the space's distance; half in a few tight clusters
/// (a tree's nodes bunch where it grew), half spread over [-3, 3], and some duplicates.
class Nodes {
 public:
  explicit Nodes(std::size_t count, std::uint64_t seed) : space_(kDimension), nodes_(count) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> wide(-3.0, 3.0);
    std::normal_distribution<double> tight(0.0, 0.01);
    for (std::size_t i = 0; i < count; ++i) {
      nodes_[i].state = space_.allocState();
      double* x = values(i);
      for (unsigned d = 0; d < kDimension; ++d)
        x[d] = i % 2 == 0 ? wide(rng) : 0.5 * static_cast<double>(i % 7) + tight(rng);
      if (i % 50 == 49) std::copy(values(i - 1), values(i - 1) + kDimension, x);  // a duplicate of the one before
    }
  }
  Nodes(const Nodes&) = delete;
  Nodes& operator=(const Nodes&) = delete;
  ~Nodes() {
    for (Node& n : nodes_) space_.freeState(n.state);
  }

  Node* at(std::size_t i) { return &nodes_[i]; }
  std::size_t size() const { return nodes_.size(); }
  double* values(std::size_t i) { return nodes_[i].state->as<ob::RealVectorStateSpace::StateType>()->values; }
  double distance(const Node* a, const Node* b) const { return space_.distance(a->state, b->state); }
  Nearest::DistanceFunction distanceFunction() const {
    return [this](const Node* a, const Node* b) { return distance(a, b); };
  }

 private:
  ob::RealVectorStateSpace space_;
  std::vector<Node> nodes_;
};

/// Checks nearest, nearestK and nearestR of `nn` (holding `held`) against brute force, for queries
/// `queries` of `nodes`.
void checkAgainstBruteForce(const Nearest& nn, const std::vector<Node*>& held, Nodes& nodes,
                            const std::vector<Node*>& queries) {
  for (Node* q : queries) {
    std::vector<double> d;
    for (Node* e : held) d.push_back(nodes.distance(e, q));
    std::vector<double> sorted = d;
    std::sort(sorted.begin(), sorted.end());
    BOOST_TEST(nodes.distance(nn.nearest(q), q) == sorted.front(), boost::test_tools::tolerance(1e-12));

    std::vector<Node*> k;
    nn.nearestK(q, 10, k);
    BOOST_TEST_REQUIRE(k.size() == std::min<std::size_t>(10, held.size()));
    for (std::size_t j = 0; j < k.size(); ++j) {
      BOOST_TEST(nodes.distance(k[j], q) == sorted[j], boost::test_tools::tolerance(1e-12));
    }

    // A radius between two distinct neighbour distances, so that rounding cannot decide membership.
    std::size_t j5 = 5;
    while (j5 < sorted.size() && sorted[j5] == sorted[j5 - 1]) ++j5;
    BOOST_TEST_REQUIRE(j5 < sorted.size());
    const double radius = 0.5 * (sorted[j5 - 1] + sorted[j5]);
    std::vector<Node*> r;
    nn.nearestR(q, radius, r);
    BOOST_TEST(r.size() ==
               static_cast<std::size_t>(std::count_if(d.begin(), d.end(), [&](double x) { return x <= radius; })));
    for (std::size_t j = 0; j + 1 < r.size(); ++j) BOOST_TEST(nodes.distance(r[j], q) <= nodes.distance(r[j + 1], q));
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(planners_vector_nearest)

BOOST_AUTO_TEST_CASE(answers_are_the_nearest_by_the_space_distance_while_scanning_and_past_the_switch) {
  const std::size_t total = kTestScanLimit + 300;
  Nodes nodes(total + 40, 7);
  std::vector<Node*> queries;
  for (std::size_t i = total; i < nodes.size(); ++i) queries.push_back(nodes.at(i));
  // Queries that are elements themselves (distance 0), one of them duplicated.
  queries.push_back(nodes.at(48));
  queries.push_back(nodes.at(10));

  Nearest nn(kDimension, kTestScanLimit);
  nn.setDistanceFunction(nodes.distanceFunction());
  std::vector<Node*> held;
  for (std::size_t i = 0; i < total; ++i) {
    nn.add(nodes.at(i));
    held.push_back(nodes.at(i));
    if (i == 60 || i + 2 == kTestScanLimit || i == kTestScanLimit || i + 1 == total) {
      BOOST_TEST(nn.size() == held.size());
      checkAgainstBruteForce(nn, held, nodes, queries);
    }
  }
  std::vector<Node*> listed;
  nn.list(listed);
  std::sort(listed.begin(), listed.end());
  std::sort(held.begin(), held.end());
  BOOST_TEST((listed == held));
}

BOOST_AUTO_TEST_CASE(of_equally_near_elements_the_first_added_is_the_nearest) {
  Nodes nodes(100, 11);
  Nearest nn(kDimension);
  nn.setDistanceFunction(nodes.distanceFunction());
  for (std::size_t i = 0; i < 60; ++i) nn.add(nodes.at(i));
  // Node 49 duplicates node 48.
  BOOST_TEST(nn.nearest(nodes.at(49)) == nodes.at(48));
  std::vector<Node*> k;
  nn.nearestK(nodes.at(49), 2, k);
  BOOST_TEST_REQUIRE(k.size() == 2u);
  BOOST_TEST(k[0] == nodes.at(48));
  BOOST_TEST(k[1] == nodes.at(49));
}

BOOST_AUTO_TEST_CASE(removed_elements_are_never_answered_and_clear_empties_it) {
  for (std::size_t count : {std::size_t{200}, kTestScanLimit + 100}) {
    Nodes nodes(count + 20, 13);
    Nearest nn(kDimension, kTestScanLimit);
    nn.setDistanceFunction(nodes.distanceFunction());
    std::vector<Node*> held;
    for (std::size_t i = 0; i < count; ++i) nn.add(nodes.at(i));
    for (std::size_t i = 0; i < count; ++i) {
      if (i % 3 == 0) {
        BOOST_TEST(nn.remove(nodes.at(i)));
      } else {
        held.push_back(nodes.at(i));
      }
    }
    BOOST_TEST(!nn.remove(nodes.at(0)));      // already removed
    BOOST_TEST(!nn.remove(nodes.at(count)));  // never added
    BOOST_TEST(nn.size() == held.size());
    std::vector<Node*> queries;
    for (std::size_t i = 0; i < count; i += 3) queries.push_back(nodes.at(i));
    checkAgainstBruteForce(nn, held, nodes, queries);

    nn.clear();
    BOOST_TEST(nn.size() == 0u);
    BOOST_CHECK_THROW(nn.nearest(nodes.at(0)), ompl::Exception);
    nn.add(nodes.at(5));
    BOOST_TEST(nn.nearest(nodes.at(0)) == nodes.at(5));
  }
}

// nearest() asked again for the same values scans only what was added since: interleaved with
// adds, removals, other queries and a query changed in place, every answer is a full scan's.
BOOST_AUTO_TEST_CASE(a_query_asked_again_as_elements_come_and_go_gets_a_full_scans_answer) {
  Nodes nodes(420, 19);
  Nearest nn(kDimension);
  nn.setDistanceFunction(nodes.distanceFunction());
  Node* query = nodes.at(410);
  std::mt19937_64 rng(5);
  std::vector<Node*> held;
  for (std::size_t i = 0; i < 400; ++i) {
    nn.add(nodes.at(i));
    held.push_back(nodes.at(i));
    if (i % 37 == 36) {  // the same node, new values
      std::copy(nodes.values(400 + i % 9), nodes.values(400 + i % 9) + kDimension, nodes.values(410));
    }
    if (i % 53 == 52) {
      const std::size_t j = std::uniform_int_distribution<std::size_t>(0, held.size() - 1)(rng);
      BOOST_TEST(nn.remove(held[j]));
      held.erase(held.begin() + static_cast<std::ptrdiff_t>(j));
    }
    if (i % 41 == 40) {
      std::vector<Node*> k;
      nn.nearestK(nodes.at(415), 3, k);
      BOOST_TEST(nodes.distance(nn.nearest(nodes.at(415)), nodes.at(415)) == nodes.distance(k.front(), nodes.at(415)));
    }
    for (int again = 0; again < 2; ++again) {
      double nearest = std::numeric_limits<double>::infinity();
      for (Node* e : held) nearest = std::min(nearest, nodes.distance(e, query));
      BOOST_TEST(nodes.distance(nn.nearest(query), query) == nearest, boost::test_tools::tolerance(1e-12));
    }
  }
}

BOOST_AUTO_TEST_CASE(bad_use_is_reported) {
  BOOST_CHECK_THROW(Nearest(0), std::invalid_argument);
  BOOST_CHECK_THROW(Nearest(kDimension, 0), std::invalid_argument);
  Nodes nodes(2, 17);
  Nearest nn(kDimension);
  nn.setDistanceFunction(nodes.distanceFunction());
  BOOST_CHECK_THROW(nn.nearest(nodes.at(0)), ompl::Exception);
  std::vector<Node*> found{nodes.at(1)};
  nn.nearestK(nodes.at(0), 3, found);
  BOOST_TEST(found.empty());
  nn.nearestR(nodes.at(0), 1.0, found);
  BOOST_TEST(found.empty());
}

BOOST_AUTO_TEST_CASE(make_planner_rrt_connect_plans_the_path_gnat_plans_from_the_same_samples) {
  // Both planners draw from samplers pinned to the same seed: the paths agree state for state only
  // when every nearest neighbour agrees.
  const auto world = dp::test::bundledWorld("shelf");
  for (std::uint_fast32_t seed = 1; seed <= 3; ++seed) {
    std::vector<std::vector<double>> paths[2];
    double range = 0.0;
    for (int which = 0; which < 2; ++which) {
      auto ss = dp::makeSimpleSetup(world, dp::test::bundledOptions());
      ss->getStateSpace()->setStateSamplerAllocator(
          [seed](const ob::StateSpace* s) { return std::make_shared<dp::test::SeededSampler>(s, seed); });
      dp::setStartAndGoal(*ss, dp::test::suggestedStart(), dp::test::suggestedGoal("shelf"));
      ob::PlannerPtr planner;
      if (which == 0) {
        planner = dp::makePlanner("RRTConnect", ss->getSpaceInformation());
        BOOST_TEST((typeid(*planner) != typeid(og::RRTConnect)));  // its own nearest neighbours
        range = planner->as<og::RRTConnect>()->getRange();
      } else {
        auto gnat = std::make_shared<og::RRTConnect>(ss->getSpaceInformation());
        gnat->setRange(range);
        planner = gnat;
      }
      ss->setPlanner(planner);
      BOOST_TEST_REQUIRE(ss->solve(30.0) == ob::PlannerStatus::EXACT_SOLUTION);
      const og::PathGeometric& path = ss->getSolutionPath();
      for (std::size_t i = 0; i < path.getStateCount(); ++i) {
        const double* x = path.getState(i)->as<ob::RealVectorStateSpace::StateType>()->values;
        paths[which].emplace_back(x, x + kDimension);
      }
    }
    BOOST_TEST(paths[0].size() > 2u);
    BOOST_TEST((paths[0] == paths[1]), "seed " << seed);
  }
}

BOOST_AUTO_TEST_SUITE_END()
