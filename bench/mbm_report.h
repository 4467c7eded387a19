#pragma once
// mbm_bench's records and report: one record per planning run, rows per scene, checker and planner,
// written as mbm_runs.csv (every run), mbm_bench.csv and mbm_bench.md (the table, also printed)
// and plotted by bench/mbm_plots.gp.

#include "format.h"

#include <cmath>
#include <string>
#include <vector>

namespace deepcheck::bench {

struct MbmRecord {
  std::string scene, checker, planner;
  int problem = 0;
  bool solved = false;                 ///< exact solution within the time limit
  double time = 0.0;                   ///< planning time, seconds (OMPL's "time REAL")
  double checks = 0.0;                 ///< state validity queries while planning (motion checks included)
  double length = std::nan("");        ///< joint-space length of the simplified path, rad
  bool certifiedAsPlanned = false;     ///< certifyPath accepted the simplified path without repair
  bool certified = false;              ///< ... after repair
  bool certifiedExact = false;         ///< ... with every motion certified by clearance (no fallback
                                       ///< step near contact: PathCertificate::exact())
  bool fclFine = false;                ///< the certified path passes the fine FCL check
  bool fclReturned = false;            ///< the simplified path, as returned, passes the fine FCL check
  double simplifyTime = std::nan("");  ///< simplifySolutionChecked, seconds
  double certifyTime = std::nan("");   ///< certifyPath on the simplified path, seconds
};

/// A scene that could not be benchmarked, and why.
struct SceneFailure {
  std::string scene, reason;
};

struct MbmSettings {
  std::string out;
  int problems = 0;
  int runs = 1;  ///< per problem, planner and checker
  double time = 0.0;
  unsigned seed = 0;
  double wallSeconds = 0.0;
  std::vector<std::string> scenes, checkers, planners;
};

/// Writes OUT/mbm_runs.csv, OUT/mbm_bench.csv and OUT/mbm_bench.md; printed unless `partial` (more
/// scenes to come).
void writeMbmReport(const MbmSettings& settings, const std::vector<MbmRecord>& records,
                    const std::vector<SceneFailure>& failures, bool partial = false);

/// Plots OUT/mbm_bench.csv into OUT/mbm_bench.png with gnuplot (skipped when missing).
void plotMbmReport(const std::string& out);

}  // namespace deepcheck::bench
