// Body penetration depth benchmark: bodySignedDistance (body_depth.h) against the pairwise
// queries it rests on, for bodies overlapping in 2, 4, 8 and 16 piece pairs.
//
// Family "tiles_N": body B is a grid of N boxes (0.1 x 0.1 footprint, 0.3 thick) touching one
// another, a tiled floor; body A is one box whose footprint covers the grid shrunk or grown by a
// random margin per side (so it overlaps every tile, the edge ones partly), tilted by up to 8
// degrees and pressed 0.05 to 0.25 into the floor. Every tile overlaps A: N overlapping pairs.
// The pairwise answer (the deepest pair) often pushes sideways, into a neighbouring tile.
//
// Per query, `reps` repetitions interleaved between the two methods, median per query:
//   body     one bodySignedDistance call (cold);
//   pairs    the sum over the N pairs of one signedDistance each (cold, certified), which the body
//            query runs first: the pairwise work it needs;
//   ratio    body / pairs (per query, then its median and 90th percentile);
//   pair err |pair depth - body depth| / body depth: how wrong the deepest pair is as the body's
//            answer (median and maximum), and the share of queries where it is off by > 1e-9;
//   search   share of queries that needed the exact search (the deepest pair's point was covered
//            by another pair), mean differences built and faces searched.
//
// Usage: body_pd_bench [--queries N] [--reps N] [--out DIR]
// Writes DIR/body_pd_bench.csv (one row per family) and prints the table as Markdown.

#include "format.h"

#include "deepcheck/geometry/body_depth.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#ifndef DEEPCHECK_BENCH_RESULTS_DIR
#define DEEPCHECK_BENCH_RESULTS_DIR "results"
#endif

using namespace deepcheck::bench;
using namespace deepcheck::geometry;
using Clock = std::chrono::steady_clock;

namespace {

constexpr double kTile = 0.1;

struct Query {
  Eigen::Isometry3d X_WA;
};

struct Family {
  std::string name;
  int rows = 1;
  int cols = 1;
  std::vector<std::shared_ptr<ConvexPolytope>> hulls;  // owns the pieces' polytopes
  Body floor;
  Body pressed;
  std::vector<Query> queries;
};

Family makeFamily(int rows, int cols, int queries, std::mt19937& rng) {
  Family f;
  f.name = "tiles_" + std::to_string(rows * cols);
  f.rows = rows;
  f.cols = cols;
  f.hulls.push_back(std::make_shared<ConvexPolytope>(ConvexPolytope::box(Eigen::Vector3d(kTile, kTile, 0.3))));
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      X.translation() = Eigen::Vector3d((c + 0.5) * kTile, (r + 0.5) * kTile, -0.15);
      f.floor.pieces.push_back({ConvexShape{f.hulls[0].get(), 0.0}, X});
    }
  }
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // One pressed box per family size; its footprint differs from the grid's by margins drawn per
  // query through the pose (shift) and the size (fixed per family, grown by 0.06).
  const Eigen::Vector3d size(cols * kTile + 0.06, rows * kTile + 0.06, 0.4);
  f.hulls.push_back(std::make_shared<ConvexPolytope>(ConvexPolytope::box(size)));
  f.pressed.pieces.push_back({ConvexShape{f.hulls[1].get(), 0.0}, Eigen::Isometry3d::Identity()});
  for (int i = 0; i < queries; ++i) {
    const Eigen::Vector3d axis = Eigen::Vector3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(8.0 * M_PI / 180.0 * u(rng), axis).toRotationMatrix();
    const double depth = 0.05 + 0.2 * u(rng);
    // Shifts up to 0.08 keep the box over every tile (it overhangs the grid by 0.03 per side).
    X.translation() = Eigen::Vector3d(cols * kTile / 2 + 0.16 * (u(rng) - 0.5),
                                      rows * kTile / 2 + 0.16 * (u(rng) - 0.5), 0.2 - depth);
    f.queries.push_back({X});
  }
  return f;
}

double microsSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
}

/// One signedDistance per piece pair, as bodySignedDistance runs them; returns the time.
double pairwiseMicros(const Body& A, const Eigen::Isometry3d& X_WA, const Body& B, const Eigen::Isometry3d& X_WB,
                      double& sink) {
  const auto t0 = Clock::now();
  for (const BodyPiece& a : A.pieces) {
    for (const BodyPiece& b : B.pieces) {
      sink += signedDistance(*a.shape.core, X_WA * a.X_BP, *b.shape.core, X_WB * b.X_BP).distance;
    }
  }
  return microsSince(t0);
}

struct Row {
  std::string family;
  int pairs = 0;
  int queries = 0;
  int overlapping = 0;  ///< queries whose bodies overlap in every pair
  double bodyMedian = 0, pairsMedian = 0, ratioMedian = 0, ratioP90 = 0;
  double pairErrMedian = 0, pairErrMax = 0, pairWrongShare = 0;
  double searchShare = 0, meanDifferences = 0, meanFaces = 0;
};

Row run(const Family& f, int reps) {
  Row row;
  row.family = f.name;
  row.pairs = static_cast<int>(f.floor.pieces.size());
  row.queries = static_cast<int>(f.queries.size());
  std::vector<double> body, pairs, ratio, pairErr;
  int wrong = 0, searched = 0;
  double differences = 0, faces = 0, sink = 0;
  for (const Query& q : f.queries) {
    std::vector<double> tb, tp;
    BodySignedDistanceResult r;
    for (int k = 0; k < reps; ++k) {
      const auto t0 = Clock::now();
      r = bodySignedDistance(f.pressed, q.X_WA, f.floor, Eigen::Isometry3d::Identity());
      tb.push_back(microsSince(t0));
      tp.push_back(pairwiseMicros(f.pressed, q.X_WA, f.floor, Eigen::Isometry3d::Identity(), sink));
    }
    if (r.overlappingPairs == row.pairs) ++row.overlapping;
    body.push_back(median(tb));
    pairs.push_back(median(tp));
    ratio.push_back(body.back() / pairs.back());
    const double depth = -r.distance;
    const double err = std::abs(r.pairDepth - depth) / depth;
    pairErr.push_back(err);
    wrong += err > 1e-9 ? 1 : 0;
    searched += r.differences > 0 ? 1 : 0;
    differences += r.differences;
    faces += r.facesSearched;
  }
  if (sink == 42.0) std::puts("");  // keeps the pairwise calls from being optimized away
  row.bodyMedian = median(body);
  row.pairsMedian = median(pairs);
  row.ratioMedian = median(ratio);
  row.ratioP90 = quantile(ratio, 0.9);
  row.pairErrMedian = median(pairErr);
  row.pairErrMax = *std::max_element(pairErr.begin(), pairErr.end());
  const double n = static_cast<double>(f.queries.size());
  row.pairWrongShare = wrong / n;
  row.searchShare = searched / n;
  row.meanDifferences = differences / n;
  row.meanFaces = faces / n;
  return row;
}

int intOption(char** argv, int& i, int argc, const char* name) {
  if (i + 1 >= argc) throw std::invalid_argument(std::string(name) + " needs a value");
  const int v = std::atoi(argv[++i]);
  if (v < 1) throw std::invalid_argument(std::string(name) + " must be a positive integer");
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  int queries = 200;
  int reps = 9;
  std::string out = DEEPCHECK_BENCH_RESULTS_DIR;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--queries") queries = intOption(argv, i, argc, "--queries");
      else if (a == "--reps") reps = intOption(argv, i, argc, "--reps");
      else if (a == "--out" && i + 1 < argc) out = argv[++i];
      else
        throw std::invalid_argument("unknown argument '" + a +
                                    "' (usage: body_pd_bench [--queries N] [--reps N] [--out DIR])");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "body_pd_bench: %s\n", e.what());
    return 2;
  }
  std::mt19937 rng(38);
  std::vector<Row> rows;
  for (const auto& [r, c] : {std::pair{1, 2}, std::pair{2, 2}, std::pair{2, 4}, std::pair{4, 4}}) {
    rows.push_back(run(makeFamily(r, c, queries, rng), reps));
  }
  std::filesystem::create_directories(out);
  std::ofstream csv(out + "/body_pd_bench.csv");
  csv << "family,pairs,queries,all_overlapping,body_us,pairs_us,ratio_median,ratio_p90,pair_err_median,"
         "pair_err_max,pair_wrong_share,search_share,mean_differences,mean_faces\n";
  std::printf(
      "| family | pairs | body µs | pairs µs | ratio (median, p90) | pair error (median, max) | pair wrong | searched "
      "| differences | faces |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Row& r : rows) {
    csv << r.family << ',' << r.pairs << ',' << r.queries << ',' << r.overlapping << ',' << r.bodyMedian << ','
        << r.pairsMedian << ',' << r.ratioMedian << ',' << r.ratioP90 << ',' << r.pairErrMedian << ',' << r.pairErrMax
        << ',' << r.pairWrongShare << ',' << r.searchShare << ',' << r.meanDifferences << ',' << r.meanFaces << '\n';
    std::printf("| %s | %d | %s | %s | %s, %s | %s, %s | %s %% | %s %% | %s | %s |\n", r.family.c_str(), r.pairs,
                fmt(r.bodyMedian).c_str(), fmt(r.pairsMedian).c_str(), fmt(r.ratioMedian).c_str(),
                fmt(r.ratioP90).c_str(), fmt(r.pairErrMedian).c_str(), fmt(r.pairErrMax).c_str(),
                fmt(100 * r.pairWrongShare, "%.0f").c_str(), fmt(100 * r.searchShare, "%.0f").c_str(),
                fmt(r.meanDifferences, "%.1f").c_str(), fmt(r.meanFaces, "%.1f").c_str());
    if (r.overlapping != r.queries) {
      std::printf("  (%s: %d of %d queries overlap in every pair)\n", r.family.c_str(), r.overlapping, r.queries);
    }
  }
  std::printf("csv: %s/body_pd_bench.csv\n", out.c_str());
  return 0;
}
