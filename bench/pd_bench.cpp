// Penetration-depth benchmark: speed against error of DEEP and its peers on the same pairs.
//
// For every family (pd_families.h) and method (pd_methods.h, pd_peers.h) it measures:
//   time per query   each query is run `reps` times, interleaved across methods (so that load
//                    from other processes hits all methods alike); a query's time is the median
//                    of its repetitions, minus the calibrated cost of reading the clock; the
//                    table gives the median and the 90th percentile over the family's queries.
//                    With --sweep each repetition instead runs one method through all queries
//                    (sweepQueries), so that a pair's data is out of cache when it is timed;
//   error            against the exact reference (exactSignedDistance, computed once per query):
//                    relative |sd - sd_exact| / max(|sd_exact|, 1e-3 L), L the larger bounding
//                    radius (as tests/geometry/test_geometry.cpp), and absolute |sd - sd_exact|;
//                    median, 99th percentile and maximum over the scored queries;
//   counts           wrong sign (sd and sd_exact of opposite signs), missing (a penetration-only
//                    method reports no contact while the pair overlaps: scored as sd = 0), NaN,
//                    failed (the method reported failure or threw, or was skipped because the
//                    call would abort the process: not timed), and the share of scored
//                    queries within 1e-12 relative;
//   DEEP walks       local-minimum rate (walks that ended deeper than the final answer / walks
//                    started), mean starts, hub pairs and steps per query, not-converged count;
//                    for the certified method, mean expansions per query (CSV only).
// Penetration-only methods on separated pairs: a "no contact" answer is right and not scored.
// The project's GJK runs on separated pairs only.
//
// Usage: pd_bench [--quick] [--families a,b,...] [--methods a,b,...] [--reps N] [--sweep] [--out DIR]
//                 [--shared DIR]
// Writes DIR/pd_bench.csv, the table as Markdown in DIR/pd_bench.md and, for DEEP answers off by more than 1e-9
// relative (or NaN, failed, thrown), reproducers DIR/repro_pd_<family>_<query>_<method>.txt in the input format of
// `deepcheck pd` (DESIGN.md).

#include "format.h"
#include "pd_families.h"
#include "pd_methods.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#ifndef DEEPCHECK_SHARED_DIR
#define DEEPCHECK_SHARED_DIR ""
#endif
#ifndef DEEPCHECK_BENCH_RESULTS_DIR
#define DEEPCHECK_BENCH_RESULTS_DIR "results"
#endif

using namespace deepcheck::bench;
using Clock = std::chrono::steady_clock;

namespace {

/// Relative error above which a DEEP answer is saved as a reproducer.
constexpr double kReproRelative = 1e-9;
/// Relative error counted as exact in the "exact share" column (the target).
constexpr double kExactRelative = 1e-12;
constexpr int kMaxReprosPerRow = 5;

struct Options {
  bool quick = false;
  std::vector<std::string> families;
  std::vector<std::string> methods;  // empty: all
  int reps = 0;                      // 0: default for the mode
  bool sweep = false;                // each repetition a sweep of the family (sweepQueries) instead of back to back
  std::string out = DEEPCHECK_BENCH_RESULTS_DIR;
  std::string shared = DEEPCHECK_SHARED_DIR;
};

/// Queries per family: full run, quick run. Large hulls get fewer pairs: the exact reference
/// is the hull of nA * nB points (9 million at 3,000 vertices).
std::pair<int, int> pairCounts(const std::string& family) {
  static const std::map<std::string, std::pair<int, int>> counts = {{"verts_300", {300, 60}},
                                                                    {"verts_1000", {50, 10}},
                                                                    {"verts_3000", {10, 3}},
                                                                    {"motion", {2000, 500}},
                                                                    {"robots", {500, 100}}};
  const auto it = counts.find(family);
  return it != counts.end() ? it->second : std::pair<int, int>{1000, 150};
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

double median(std::vector<double> v) { return percentile(std::move(v), 0.5); }

/// Median cost of an empty steady_clock::now() pair, subtracted from every timing.
double clockOverheadMicros() {
  std::vector<double> d;
  for (int i = 0; i < 20000; ++i) {
    const auto t0 = Clock::now();
    const auto t1 = Clock::now();
    d.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
  }
  return median(d);
}

struct Row {
  std::string family, method;
  int queries = 0, overlapping = 0, separated = 0;
  double meanVertices = 0;
  double tMed = NAN, tP90 = NAN;
  double tMedOverlap = NAN, tP90Overlap = NAN;  // over the overlapping pairs only
  int scored = 0;
  double relMed = NAN, relP99 = NAN, relMax = NAN, absMed = NAN, absP99 = NAN, absMax = NAN;
  double exactShare = NAN;
  int wrongSign = 0, missing = 0, nan = 0, failed = 0;
  // DEEP only
  bool walks = false;
  double localMinRate = NAN, startsMean = NAN, hubsMean = NAN, stepsMean = NAN, warmShare = NAN;
  double expansionsMean = NAN;
  int notConverged = 0;
};

/// Per-method accumulation over one family.
struct Tally {
  std::vector<double> times, overlapTimes, rel, abs;
  int ran = 0, wrongSign = 0, missing = 0, nan = 0, failed = 0, withinExact = 0;
  long starts = 0, hubs = 0, steps = 0, localMinima = 0, warm = 0, expansions = 0, walkQueries = 0;
  int notConverged = 0, repros = 0;
};

using deepcheck::bench::fmt;

void writePose(std::ostream& out, const Pose& p) {
  out << p.t.x() << ' ' << p.t.y() << ' ' << p.t.z() << ' ' << p.q.w() << ' ' << p.q.x() << ' ' << p.q.y() << ' '
      << p.q.z();
}

/// Writes a `deepcheck pd` input reproducing query qi of the family for `method`.
void writeRepro(const Options& opt, const Family& f, int qi, const std::string& method, double sd, double exact,
                double rel) {
  const Query& q = f.queries[qi];
  const std::string path = opt.out + "/repro_pd_" + f.name + "_" + std::to_string(qi) + "_" + method + ".txt";
  std::ofstream out(path);
  out.precision(17);
  out << "# deepcheck pd reproducer from bench/pd_bench: family " << f.name << ", query " << qi << ", method " << method
      << "\n# got sd = " << sd << ", exact sd = " << exact << ", relative error " << rel << "\n";
  const bool warm = method.size() > 5 && method.compare(method.size() - 5, 5, "_warm") == 0;
  if (warm) {
    out << (f.sequence
                ? "# warm: the queries before the last are the trajectory's earlier steps (run without --cold)\n"
                : "# warm: the first query primes the cache, the second is the one that fails (run without --cold)\n");
  } else {
    out << "# cold: run with --cold\n";
  }
  const int ids[2] = {q.a, q.b};
  for (int k = 0; k < 2; ++k) {
    const auto& pts = f.points[ids[k]];
    out << "shape " << k << ' ' << pts.size() << '\n';
    for (const auto& p : pts) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  }
  auto query = [&](const Pose& A, const Pose& B) {
    out << "query 0 ";
    writePose(out, A);
    out << " 1 ";
    writePose(out, B);
    out << '\n';
  };
  if (warm && f.sequence) {
    int first = qi;
    while (first > 0 && f.queries[first - 1].a == q.a && f.queries[first - 1].b == q.b) --first;
    for (int i = first; i < qi; ++i) query(f.queries[i].poseA, f.queries[i].poseB);
  } else if (warm && q.primeB) {
    query(q.poseA, *q.primeB);
  }
  query(q.poseA, q.poseB);
  std::cerr << "  wrote reproducer " << path << "\n";
}

Row summarize(const Family& f, const std::string& method, const Tally& t, int overlapping, int separated,
              double meanVertices) {
  Row r;
  r.family = f.name;
  r.method = method;
  r.queries = t.ran;
  r.overlapping = overlapping;
  r.separated = separated;
  r.meanVertices = meanVertices;
  r.tMed = median(t.times);
  r.tP90 = percentile(t.times, 0.9);
  r.tMedOverlap = median(t.overlapTimes);
  r.tP90Overlap = percentile(t.overlapTimes, 0.9);
  r.scored = static_cast<int>(t.rel.size());
  if (!t.rel.empty()) {
    r.relMed = median(t.rel);
    r.relP99 = percentile(t.rel, 0.99);
    r.relMax = *std::max_element(t.rel.begin(), t.rel.end());
    r.absMed = median(t.abs);
    r.absP99 = percentile(t.abs, 0.99);
    r.absMax = *std::max_element(t.abs.begin(), t.abs.end());
    r.exactShare = static_cast<double>(t.withinExact) / static_cast<double>(t.rel.size());
  }
  r.wrongSign = t.wrongSign;
  r.missing = t.missing;
  r.nan = t.nan;
  r.failed = t.failed;
  if (t.walkQueries > 0) {
    r.walks = true;
    r.localMinRate = t.starts > 0 ? static_cast<double>(t.localMinima) / static_cast<double>(t.starts) : 0.0;
    r.startsMean = static_cast<double>(t.starts) / static_cast<double>(t.walkQueries);
    r.hubsMean = static_cast<double>(t.hubs) / static_cast<double>(t.walkQueries);
    r.stepsMean = static_cast<double>(t.steps) / static_cast<double>(t.walkQueries);
    r.warmShare = static_cast<double>(t.warm) / static_cast<double>(t.walkQueries);
    r.expansionsMean = static_cast<double>(t.expansions) / static_cast<double>(t.walkQueries);
    r.notConverged = t.notConverged;
  }
  return r;
}

void printHeader() {
  std::printf("%-12s %-19s %5s %9s %9s %9s %9s %9s %9s %8s %5s %5s %5s %5s %6s %6s\n", "family", "method", "n",
              "t_med_us", "t_p90_us", "rel_med", "rel_p99", "rel_max", "abs_p99", "exact%", "wrong", "miss", "nan",
              "fail", "lmin%", "hubs");
}

void printRow(const Row& r) {
  std::printf("%-12s %-19s %5d %9s %9s %9s %9s %9s %9s %8s %5d %5d %5d %5d %6s %6s\n", r.family.c_str(),
              r.method.c_str(), r.queries, fmt(r.tMed, "%.3g").c_str(), fmt(r.tP90, "%.3g").c_str(),
              fmt(r.relMed, "%.1e").c_str(), fmt(r.relP99, "%.1e").c_str(), fmt(r.relMax, "%.1e").c_str(),
              fmt(r.absP99, "%.1e").c_str(), fmt(100.0 * r.exactShare, "%.2f").c_str(), r.wrongSign, r.missing, r.nan,
              r.failed, fmt(100.0 * r.localMinRate, "%.1f").c_str(), fmt(r.hubsMean, "%.1f").c_str());
  std::fflush(stdout);
}

void writeCsv(const std::string& path, const std::vector<Row>& rows) {
  std::ofstream out(path);
  out << "family,method,queries,overlapping,separated,mean_vertices,t_med_us,t_p90_us,scored,rel_med,rel_p99,"
         "rel_max,abs_med,abs_p99,abs_max,exact_share,wrong_sign,missing,nan,failed,local_min_rate,starts_mean,"
         "hubs_mean,steps_mean,warm_share,not_converged,t_med_overlap_us,t_p90_overlap_us,expansions_mean\n";
  auto num = [](double x) { return std::isnan(x) ? std::string("") : fmt(x, "%.6g"); };
  for (const Row& r : rows) {
    out << r.family << ',' << r.method << ',' << r.queries << ',' << r.overlapping << ',' << r.separated << ','
        << num(r.meanVertices) << ',' << num(r.tMed) << ',' << num(r.tP90) << ',' << r.scored << ',' << num(r.relMed)
        << ',' << num(r.relP99) << ',' << num(r.relMax) << ',' << num(r.absMed) << ',' << num(r.absP99) << ','
        << num(r.absMax) << ',' << num(r.exactShare) << ',' << r.wrongSign << ',' << r.missing << ',' << r.nan << ','
        << r.failed << ',' << (r.walks ? num(r.localMinRate) : "") << ',' << (r.walks ? num(r.startsMean) : "") << ','
        << (r.walks ? num(r.hubsMean) : "") << ',' << (r.walks ? num(r.stepsMean) : "") << ','
        << (r.walks ? num(r.warmShare) : "") << ',' << (r.walks ? std::to_string(r.notConverged) : "") << ','
        << num(r.tMedOverlap) << ',' << num(r.tP90Overlap) << ',' << (r.walks ? num(r.expansionsMean) : "") << '\n';
  }
}

/// The same table in Markdown, one section per family.
void writeMarkdown(const std::string& path, const std::vector<Row>& rows, bool sweep) {
  std::ofstream out(path);
  out << "<!-- generated by bench/pd_bench; see bench/README.md for the columns -->\n";
  if (sweep) out << "\nTimes from sweeps (`--sweep`): one method through all of a family's queries per repetition.\n";
  std::string family;
  for (const Row& r : rows) {
    if (r.family != family) {
      family = r.family;
      out << "\n### " << family << " (" << r.overlapping << " overlapping, " << r.separated << " separated, "
          << fmt(r.meanVertices, "%.0f") << " vertices per hull on average)\n\n"
          << "| method | n | t med (µs) | t p90 (µs) | t med overlapping (µs) | rel med | rel p99 | rel max | abs p99 "
             "| "
             "≤1e-12 | wrong sign | missing | NaN | failed | local min | hubs |\n"
          << "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
    }
    out << "| " << r.method << " | " << r.queries << " | " << fmt(r.tMed, "%.3g") << " | " << fmt(r.tP90, "%.3g")
        << " | " << fmt(r.tMedOverlap, "%.3g") << " | " << fmt(r.relMed, "%.1e") << " | " << fmt(r.relP99, "%.1e")
        << " | " << fmt(r.relMax, "%.1e") << " | " << fmt(r.absP99, "%.1e") << " | "
        << (std::isnan(r.exactShare) ? std::string("-") : fmt(100.0 * r.exactShare, "%.2f") + " %") << " | "
        << r.wrongSign << " | " << r.missing << " | " << r.nan << " | " << r.failed << " | "
        << (r.walks ? fmt(100.0 * r.localMinRate, "%.1f") + " %" : std::string("-")) << " | "
        << (r.walks ? fmt(r.hubsMean, "%.1f") : std::string("-")) << " |\n";
  }
}

/// The comma-separated names of an option value.
std::vector<std::string> splitNames(const std::string& list) {
  std::vector<std::string> names;
  std::stringstream ss(list);
  std::string name;
  while (std::getline(ss, name, ',')) names.push_back(name);
  return names;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument("option " + a + " needs a value");
      return argv[++i];
    };
    if (a == "--quick") {
      o.quick = true;
    } else if (a == "--families") {
      for (const std::string& name : splitNames(value())) o.families.push_back(name);
    } else if (a == "--methods") {
      for (const std::string& name : splitNames(value())) o.methods.push_back(name);
    } else if (a == "--sweep") {
      o.sweep = true;
    } else if (a == "--reps") {
      o.reps = std::stoi(value());
    } else if (a == "--out") {
      o.out = value();
    } else if (a == "--shared") {
      o.shared = value();
    } else if (a == "--help" || a == "-h") {
      std::cout << "usage: pd_bench [--quick] [--families a,b,...] [--methods a,b,...] [--reps N] [--sweep] [--out DIR]"
                   " [--shared DIR]\n"
                   "--sweep: each repetition runs one method through all of a family's queries before the"
                   " next, so that a pair's data\n  has left the core's caches when it is timed (default:"
                   " a query's repetitions back to back)\nfamilies:";
      for (const auto& f : familyNames()) std::cout << ' ' << f;
      std::cout << "\nmethods:";
      for (const auto& m : makeMethods()) std::cout << ' ' << m->name();
      std::cout << "\n";
      std::exit(0);
    } else {
      throw std::invalid_argument("unknown option " + a + " (try --help)");
    }
  }
  if (o.families.empty()) o.families = familyNames();
  const auto all = makeMethods();
  for (const std::string& name : o.methods) {  // a typo would otherwise time no method at all
    bool known = false;
    for (const auto& m : all) known = known || m->name() == name;
    if (!known) throw std::invalid_argument("unknown method '" + name + "' (try --help)");
  }
  if (o.reps <= 0) o.reps = o.quick ? 3 : 7;
  return o;
}

/// About the bytes of a family's hull arrays (vertices and their centred copies, face normals,
/// offsets and vertex lists, vertex rings): against the core's cache sizes, whether a swept run
/// (--sweep) finds a pair's hulls out of cache.
double hullMegabytes(const Family& f) {
  // Per vertex: the vertex and its centred copy. Per face: normal, offset, start in the face
  // list, support. Per edge: two ring entries (vertex and face) and two face-list entries.
  constexpr double perVertex = 2 * sizeof(Eigen::Vector3d);
  constexpr double perFace = sizeof(Eigen::Vector3d) + sizeof(double) + 2 * sizeof(int);
  constexpr double perEdge = 6 * sizeof(int);
  double bytes = 0;
  for (const deepcheck::geometry::ConvexPolytope& p : f.shapes)
    bytes += perVertex * p.numVertices() + perFace * p.numFaces() + perEdge * p.numEdges();
  return bytes / (1024.0 * 1024.0);
}

/// The exact answers of a family's queries (they decide where GJK runs and score everything).
struct ExactCounts {
  int overlapping = 0;
  int separated = 0;
  double meanVertices = 0.0;
};

ExactCounts exactAnswers(Family& f) {
  ExactCounts c;
  double vertices = 0;
  for (Query& q : f.queries) {
    const double sd = exactOf(f, q).distance;
    c.overlapping += sd < 0;
    c.separated += sd > 0;
    vertices += 0.5 * (f.shapes[q.a].numVertices() + f.shapes[q.b].numVertices());
  }
  c.meanVertices = vertices / static_cast<double>(f.queries.size());
  return c;
}

/// One method's first answer to a query, and the median of its repetitions' times.
struct Run {
  Answer answer;
  WalkStats walk;
  bool threw = false;
  double micros = NAN;
};

/// One timed call of method m on query qi: its time in µs, the clock's overhead subtracted. The
/// answer and walk statistics are kept in `run` when `keep` (the first repetition).
double timeOnce(Method& m, Family& f, int qi, double overhead, bool keep, Run& run) {
  m.beforeRun(f, qi);
  Answer a;
  bool failed = false;
  const auto s0 = Clock::now();
  try {
    a = m.run(f, qi);
  } catch (const std::exception& e) {
    failed = true;
    if (keep) std::cerr << "  " << m.name() << " threw on query " << qi << ": " << e.what() << "\n";
  }
  const auto s1 = Clock::now();
  if (keep) run = {a, m.lastWalk(), failed, NAN};
  m.afterRun(f, qi);
  return std::chrono::duration<double, std::micro>(s1 - s0).count() - overhead;
}

/// Runs query qi `reps` times with every method, the order rotated between repetitions (so that
/// load from other processes hits all methods alike). Methods that do not run on the query are
/// left with NaN time and a default answer. The pair's data stays in the core's caches between
/// repetitions: the median is a cache-warm time.
std::vector<Run> runQuery(const Options& opt, const std::vector<std::unique_ptr<Method>>& methods, Family& f, int qi,
                          double overhead) {
  const double exact = f.queries[qi].exact->distance;
  const int nm = static_cast<int>(methods.size());
  std::vector<Run> runs(nm);
  std::vector<std::vector<double>> perRep(nm);
  for (int rep = 0; rep < opt.reps; ++rep) {
    for (int k = 0; k < nm; ++k) {
      const int mi = (k + rep) % nm;  // rotate the order between repetitions
      Method& m = *methods[mi];
      if (m.separatedOnly() && !(exact > 0)) continue;
      perRep[mi].push_back(timeOnce(m, f, qi, overhead, rep == 0, runs[mi]));
    }
  }
  for (int mi = 0; mi < nm; ++mi) runs[mi].micros = median(perRep[mi]);
  return runs;
}

/// Every query of the family, timed in sweeps: each repetition runs one method through all
/// queries before the next method starts (the methods' order rotated between repetitions). When
/// a query is timed, the rest of the family has run since its pair's hulls and warm start were
/// last touched, so on a family whose data exceeds the core's caches the median is a cache-cold
/// time, as in a checker that visits many pairs between two queries of one. runs[qi][mi].
std::vector<std::vector<Run>> sweepQueries(const Options& opt, const std::vector<std::unique_ptr<Method>>& methods,
                                           Family& f, double overhead) {
  const int nq = static_cast<int>(f.queries.size());
  const int nm = static_cast<int>(methods.size());
  std::vector<std::vector<Run>> runs(nq, std::vector<Run>(nm));
  std::vector<std::vector<std::vector<double>>> perRep(nq, std::vector<std::vector<double>>(nm));
  for (int rep = 0; rep < opt.reps; ++rep) {
    for (int k = 0; k < nm; ++k) {
      const int mi = (k + rep) % nm;
      Method& m = *methods[mi];
      for (int qi = 0; qi < nq; ++qi) {
        if (m.separatedOnly() && !(f.queries[qi].exact->distance > 0)) continue;
        perRep[qi][mi].push_back(timeOnce(m, f, qi, overhead, rep == 0, runs[qi][mi]));
      }
    }
  }
  for (int qi = 0; qi < nq; ++qi)
    for (int mi = 0; mi < nm; ++mi) runs[qi][mi].micros = median(perRep[qi][mi]);
  return runs;
}

/// Adds one method's run of query qi to its tally (and writes a reproducer for a bad DEEP answer).
void score(const Options& opt, const Family& f, int qi, const std::string& method, const Run& run, Tally& t) {
  const double exact = f.queries[qi].exact->distance;
  const double L = f.pairScale(f.queries[qi]);
  ++t.ran;
  const Answer& a = run.answer;
  if (a.kind != Answer::Kind::Skipped) {
    t.times.push_back(std::max(0.0, run.micros));
    if (exact < 0) t.overlapTimes.push_back(t.times.back());
  }
  double sd = NAN;
  bool scored = false;
  if (run.threw || a.kind == Answer::Kind::Failed || a.kind == Answer::Kind::Skipped) {
    ++t.failed;
  } else if (a.kind == Answer::Kind::NoContact) {
    if (exact < 0) {
      ++t.missing;
      sd = 0.0;
      scored = true;
    }
  } else if (!std::isfinite(a.sd)) {
    ++t.nan;
  } else {
    sd = a.sd;
    scored = true;
    if ((exact < 0 && sd > 0) || (exact > 0 && sd < 0)) ++t.wrongSign;
  }
  double rel = NAN;
  if (scored) {
    rel = std::abs(sd - exact) / std::max(std::abs(exact), 1e-3 * L);
    t.rel.push_back(rel);
    t.abs.push_back(std::abs(sd - exact));
    t.withinExact += rel <= kExactRelative;
  }
  if (!run.walk.valid) return;  // not DEEP
  const WalkStats& w = run.walk;
  ++t.walkQueries;
  t.starts += w.starts;
  t.hubs += w.hubs;
  t.steps += w.steps;
  t.expansions += w.expansions;
  t.localMinima += w.localMinima;
  t.warm += w.warm;
  t.notConverged += w.notConverged;
  const bool bad = !scored || !(rel <= kReproRelative);
  if (bad && t.repros < kMaxReprosPerRow) {
    ++t.repros;
    writeRepro(opt, f, qi, method, run.threw ? NAN : a.sd, exact, rel);
  }
}

/// The exact reference's own row: its time per query.
Row exactRow(const Family& f, const ExactCounts& counts) {
  Tally exactTally;
  for (const Query& q : f.queries) {
    exactTally.times.push_back(q.exactMicros);
    if (q.exact->distance < 0) exactTally.overlapTimes.push_back(q.exactMicros);
  }
  exactTally.ran = static_cast<int>(exactTally.times.size());
  return summarize(f, "exact", exactTally, counts.overlapping, counts.separated, counts.meanVertices);
}

/// Builds, answers exactly, times and scores one family; appends its rows. False when the family
/// cannot be built here.
bool runFamily(const Options& opt, const std::string& name, const std::vector<std::unique_ptr<Method>>& methods,
               double overhead, std::vector<Row>* rows) {
  const auto [full, quick] = pairCounts(name);
  const auto t0 = Clock::now();
  std::optional<Family> fam;
  try {
    fam = makeFamily(name, opt.quick ? quick : full, opt.shared);
  } catch (const std::exception& e) {
    std::cerr << name << ": cannot build the family: " << e.what() << "\n";
    return false;
  }
  if (!fam) return false;
  Family& f = *fam;
  const auto t1 = Clock::now();
  const ExactCounts counts = exactAnswers(f);
  const auto t2 = Clock::now();
  std::cerr << f.name << ": " << f.queries.size() << " queries (" << counts.overlapping << " overlapping, "
            << counts.separated << " separated), " << f.description << ", " << f.shapes.size() << " hulls of about "
            << fmt(hullMegabytes(f), "%.2g") << " MB; built in "
            << fmt(std::chrono::duration<double>(t1 - t0).count(), "%.1f") << " s, exact answers in "
            << fmt(std::chrono::duration<double>(t2 - t1).count(), "%.1f") << " s\n";

  for (auto& m : methods) m->beginFamily(f);
  const int nm = static_cast<int>(methods.size());
  std::vector<Tally> tally(nm);
  const std::vector<std::vector<Run>> swept =
      opt.sweep ? sweepQueries(opt, methods, f, overhead) : std::vector<std::vector<Run>>{};
  for (int qi = 0; qi < static_cast<int>(f.queries.size()); ++qi) {
    const std::vector<Run> runs = opt.sweep ? swept[qi] : runQuery(opt, methods, f, qi, overhead);
    const double exact = f.queries[qi].exact->distance;
    for (int mi = 0; mi < nm; ++mi) {
      if (methods[mi]->separatedOnly() && !(exact > 0)) continue;
      score(opt, f, qi, methods[mi]->name(), runs[mi], tally[mi]);
    }
  }
  for (int mi = 0; mi < nm; ++mi) {
    rows->push_back(
        summarize(f, methods[mi]->name(), tally[mi], counts.overlapping, counts.separated, counts.meanVertices));
    printRow(rows->back());
  }
  rows->push_back(exactRow(f, counts));
  printRow(rows->back());
  for (auto& m : methods) m->endFamily();
  std::cerr << f.name << ": timed in " << fmt(std::chrono::duration<double>(Clock::now() - t2).count(), "%.1f")
            << " s\n";
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  try {
    opt = parse(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "pd_bench: " << e.what() << "\n";
    return 2;
  }
  std::filesystem::create_directories(opt.out);
  const double overhead = clockOverheadMicros();
  std::cerr << "pd_bench: " << (opt.quick ? "quick" : "full") << " run, " << opt.reps << " repetitions per query"
            << (opt.sweep ? ", each a sweep of the family" : "") << ", clock overhead " << fmt(overhead * 1e3, "%.1f")
            << " ns (subtracted)\n";

  std::vector<std::unique_ptr<Method>> methods;
  for (auto& m : makeMethods()) {
    if (opt.methods.empty() || std::find(opt.methods.begin(), opt.methods.end(), m->name()) != opt.methods.end())
      methods.push_back(std::move(m));
  }
  std::vector<Row> rows;
  printHeader();
  const auto runStart = Clock::now();
  for (const std::string& name : opt.families) {
    if (!runFamily(opt, name, methods, overhead, &rows)) continue;
    // After every family, so that a partial run leaves data.
    writeCsv(opt.out + "/pd_bench.csv", rows);
    writeMarkdown(opt.out + "/pd_bench.md", rows, opt.sweep);
  }
  std::cerr << "pd_bench: done in " << fmt(std::chrono::duration<double>(Clock::now() - runStart).count(), "%.0f")
            << " s; wrote " << opt.out << "/pd_bench.csv\n";
  return 0;
}
