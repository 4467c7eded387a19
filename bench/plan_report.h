#pragma once
// plan_bench's records and report: one record per run, medians per problem, checker and planner,
// written as plan_bench.csv and plan_bench.md (also printed) and plotted by bench/plan_plots.gp.

#include "format.h"
#include "plan_problems.h"

#include <cmath>
#include <string>
#include <vector>

namespace deepcheck::bench {

struct Record {
  std::string problem, checker, planner;
  bool solved = false;  // exact
  double time = 0.0, firstSolution = std::nan(""), length = std::nan(""), minClearance = std::nan("");
  bool fclVerified = false;
  double graphStates = std::nan("");
};

struct Row {
  std::string problem, checker, planner;
  int runs = 0, solved = 0, verified = 0;
  double tMed = 0, firstMed = 0, lengthMed = 0, clearanceMed = 0, statesMed = 0;
  double successPct() const { return runs > 0 ? 100.0 * solved / runs : 0.0; }
  double verifiedPct() const { return solved > 0 ? 100.0 * verified / solved : std::nan(""); }
};

/// The row of one problem, checker and planner: medians over its records.
Row summarize(const std::vector<Record>& all, const std::string& problem, const std::string& checker,
              const std::string& planner);

/// What the report says about the run besides its records.
struct ReportSettings {
  std::string out;  ///< output folder
  int runs = 0;
  double time = 0.0;
  unsigned seed = 0;
  double wallSeconds = 0.0;
  std::vector<const char*> checkers;
};

/// Writes OUT/plan_bench.csv and OUT/plan_bench.md (also printed) for the `selected` problems.
void writeReport(const ReportSettings& settings, const std::vector<Problem>& selected,
                 const std::vector<Record>& records, const std::vector<std::string>& rejected);

/// Runs gnuplot on bench/SCRIPT with the variables csv and outdir set; says on stderr that it
/// wrote OUTDIR/PNG, or why not (gnuplot missing or failing; `who` names the benchmark).
void runGnuplot(const std::string& csv, const std::string& outdir, const std::string& script, const std::string& png,
                const char* who);

/// Plots OUT/plan_bench.csv into OUT/plan_bench.png with gnuplot (skipped when missing).
void plotReport(const std::string& out);

}  // namespace deepcheck::bench
