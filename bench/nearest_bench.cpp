// nearest_bench: the nearest-neighbour query a tree planner makes once per extension, on the Panda's
// 7 joints: OMPL's GNAT (its default for tree planners), OMPL's linear search, and VectorNearest
// (planners/vector_nearest.h, what makePlanner gives RRTConnect), at tree sizes from 16 to 16384.
//
// The elements and the queries are uniform samples of the Panda arm's joint space (OMPL's sampler
// of the space makeStateSpace makes; a planner's queries are such samples). Per size and method:
// the mean time of a query, and how many answers are as near as the exact nearest (found by
// comparing every element with the space's distance), with the largest difference in distance.
//
// Output: the table on stdout, bench/results/nearest_bench.csv and nearest_bench.png (gnuplot,
// bench/nearest_plots.gp).
//
// Usage: nearest_bench [--queries N] [--seed S] [--csv FILE]

#include "csv_out.h"
#include "mbm_problems.h"
#include "options.h"
#include "plan_problems.h"
#include "plan_report.h"

#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/state_space.h"
#include "deepcheck/planners/vector_nearest.h"

#include <ompl/datastructures/NearestNeighborsGNATNoThreadSafety.h>
#include <ompl/datastructures/NearestNeighborsLinear.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace {

namespace dp = deepcheck::planners;
namespace ob = ompl::base;
using namespace deepcheck::bench;

/// What a tree planner keeps per node: the state (the nearest-neighbour structures read `state`).
struct Node {
  ob::State* state = nullptr;
};
using NodeNearest = ompl::NearestNeighbors<Node*>;

struct Options {
  int queries = 2000;
  int seed = 1;
  std::string csv = std::string(DEEPCHECK_BENCH_RESULTS_DIR) + "/nearest_bench.csv";
};

[[noreturn]] void usage(const std::string& error) {
  if (!error.empty()) std::fprintf(stderr, "nearest_bench: %s\n", error.c_str());
  std::fprintf(stderr, "usage: nearest_bench [--queries N] [--seed S] [--csv FILE]\n");
  std::exit(2);
}

Options parseOptions(int argc, char** argv) {
  Options opt;
  readOptions(argc, argv, usage, [&](const std::string& arg, auto value) {
    if (arg == "--queries") {
      opt.queries = positiveCount(value(), arg, usage);
    } else if (arg == "--seed") {
      opt.seed = std::stoi(value());
    } else if (arg == "--csv") {
      opt.csv = value();
    } else {
      return false;
    }
    return true;
  });
  return opt;
}

/// `count` uniform samples of the space, each in a Node.
std::vector<Node> sampleNodes(const ob::SpaceInformationPtr& si, std::size_t count) {
  std::vector<Node> nodes(count);
  ob::StateSamplerPtr sampler = si->allocStateSampler();
  for (Node& n : nodes) {
    n.state = si->allocState();
    sampler->sampleUniform(n.state);
  }
  return nodes;
}

struct Result {
  double nsPerQuery = 0.0;
  int exact = 0;             ///< answers as near as the exact nearest
  double worstExcess = 0.0;  ///< the largest distance beyond the exact nearest's (rad)
};

Result measure(NodeNearest& nn, std::vector<Node>& elements, std::vector<Node>& queries,
               const NodeNearest::DistanceFunction& distance) {
  nn.setDistanceFunction(distance);
  for (Node& e : elements) nn.add(&e);
  std::vector<Node*> answers(queries.size());
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < queries.size(); ++i) answers[i] = nn.nearest(&queries[i]);
  const std::chrono::duration<double, std::nano> took = std::chrono::steady_clock::now() - start;
  Result r;
  r.nsPerQuery = took.count() / static_cast<double>(queries.size());
  for (std::size_t i = 0; i < queries.size(); ++i) {
    double best = INFINITY;
    for (Node& e : elements) best = std::min(best, distance(&e, &queries[i]));
    const double excess = distance(answers[i], &queries[i]) - best;
    r.exact += excess <= 0.0 ? 1 : 0;
    r.worstExcess = std::max(r.worstExcess, excess);
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const Options opt = parseOptions(argc, argv);
  if (!haveShared()) {
    std::fprintf(stderr, "nearest_bench: ../shared is absent (%s): no Panda\n", sharedDir().c_str());
    return 1;
  }
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(opt.seed));
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  const auto world = dp::loadWorld(pandaUrdf(), {}, pandaArmOptions());
  auto si = std::make_shared<ob::SpaceInformation>(dp::makeStateSpace(world->robot()));
  const unsigned dimension = si->getStateDimension();
  const NodeNearest::DistanceFunction distance = [&](const Node* a, const Node* b) {
    return si->distance(a->state, b->state);
  };
  std::vector<Node> queries = sampleNodes(si, static_cast<std::size_t>(opt.queries));

  std::FILE* csv = openCsv("nearest_bench", opt.csv, "elements,method,ns_per_query,exact_pct,worst_excess_rad");
  std::printf("Nearest neighbour of a uniform sample among n uniform samples, Panda arm (%u joints), %d queries\n\n",
              dimension, opt.queries);
  std::printf("| n | GNAT (ns) | linear (ns) | VectorNearest (ns) | exact answers (GNAT / linear / VectorNearest) |\n");
  std::printf("|--:|--:|--:|--:|--:|\n");
  for (std::size_t n = 16; n <= 16384; n *= 4) {
    std::vector<Node> elements = sampleNodes(si, n);
    ompl::NearestNeighborsGNATNoThreadSafety<Node*> gnat;
    ompl::NearestNeighborsLinear<Node*> linear;
    dp::VectorNearest<Node*> vector(dimension);
    const struct {
      const char* name;
      NodeNearest* nn;
    } methods[] = {{"GNAT", &gnat}, {"linear", &linear}, {"VectorNearest", &vector}};
    Result r[3];
    for (int m = 0; m < 3; ++m) {
      r[m] = measure(*methods[m].nn, elements, queries, distance);
      std::fprintf(csv, "%zu,%s,%.1f,%.2f,%.3g\n", n, methods[m].name, r[m].nsPerQuery,
                   100.0 * r[m].exact / opt.queries, r[m].worstExcess);
    }
    std::printf("| %zu | %.0f | %.0f | %.0f | %.1f / %.1f / %.1f %% |\n", n, r[0].nsPerQuery, r[1].nsPerQuery,
                r[2].nsPerQuery, 100.0 * r[0].exact / opt.queries, 100.0 * r[1].exact / opt.queries,
                100.0 * r[2].exact / opt.queries);
    for (Node& e : elements) si->freeState(e.state);
  }
  for (Node& q : queries) si->freeState(q.state);
  std::fclose(csv);
  std::fprintf(stderr, "wrote %s\n", opt.csv.c_str());
  const std::string dir = opt.csv.substr(0, opt.csv.find_last_of('/'));
  runGnuplot(opt.csv, dir, "nearest_plots.gp", "nearest_bench.png", "nearest_bench");
  return 0;
}
