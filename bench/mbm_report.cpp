// mbm_bench's records and report (mbm_report.h).

#include "mbm_report.h"

#include "plan_report.h"

#include "deepcheck/planners/tolerances.h"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

namespace deepcheck::bench {

namespace dp = deepcheck::planners;

namespace {

/// Scene, checker and planner summarized over their runs.
struct MbmRow {
  std::string scene, checker, planner;
  int runs = 0, solved = 0, certifiedAsPlanned = 0, certified = 0, certifiedExact = 0, fclFine = 0, fclReturned = 0;
  double tMed = std::nan(""), tP90 = std::nan(""), checksPerSecond = std::nan(""), lengthMed = std::nan("");
  double planSimplifyMed = std::nan(""), certifyMed = std::nan("");  ///< over the solved runs, seconds
  double successPct() const { return runs > 0 ? 100.0 * solved / runs : std::nan(""); }
  double pctOfSolved(int n) const { return solved > 0 ? 100.0 * n / solved : std::nan(""); }
};

/// The row of the runs accepted by `keep`: times over all runs (a failed run counts with its
/// time, about the limit), lengths and checks over the solved ones.
template <class Keep>
MbmRow summarize(const std::vector<MbmRecord>& records, Keep keep) {
  MbmRow row;
  std::vector<double> t, length, planSimplify, certify;
  double checks = 0.0, seconds = 0.0;
  for (const MbmRecord& r : records) {
    if (!keep(r)) continue;
    ++row.runs;
    t.push_back(r.time);
    checks += r.checks;
    seconds += r.time;
    if (!r.solved) continue;
    ++row.solved;
    row.certifiedAsPlanned += r.certifiedAsPlanned;
    row.certified += r.certified;
    row.certifiedExact += r.certifiedExact;
    row.fclFine += r.fclFine;
    row.fclReturned += r.fclReturned;
    length.push_back(r.length);
    planSimplify.push_back(r.time + r.simplifyTime);
    certify.push_back(r.certifyTime);
  }
  row.tMed = median(t);
  row.tP90 = quantile(t, 0.9);
  row.checksPerSecond = seconds > 0.0 ? checks / seconds : std::nan("");
  row.lengthMed = median(length);
  row.planSimplifyMed = median(planSimplify);
  row.certifyMed = median(certify);
  return row;
}

std::vector<MbmRow> rowsOf(const MbmSettings& s, const std::vector<MbmRecord>& records) {
  std::vector<MbmRow> rows;
  for (const std::string& scene : s.scenes) {
    for (const std::string& planner : s.planners) {
      for (const std::string& checker : s.checkers) {
        MbmRow row = summarize(records, [&](const MbmRecord& r) {
          return r.scene == scene && r.checker == checker && r.planner == planner;
        });
        if (row.runs == 0) continue;
        row.scene = scene;
        row.checker = checker;
        row.planner = planner;
        rows.push_back(row);
      }
    }
  }
  return rows;
}

std::string pct(double v) { return std::isnan(v) ? "-" : fmt(v, "%.0f") + " %"; }
std::string ms(double seconds) { return fmt(1e3 * seconds, "%.3g"); }

void writeCsv(const MbmSettings& s, const std::vector<MbmRecord>& records, const std::vector<MbmRow>& rows) {
  std::ofstream runs(s.out + "/mbm_runs.csv");
  runs << "scene,problem,checker,planner,solved,time_s,checks,length,certified_as_planned,certified,certified_exact,"
          "fcl_fine_ok,fcl_fine_ok_as_returned,simplify_s,certify_s\n";
  for (const MbmRecord& r : records) {
    runs << r.scene << ',' << r.problem << ',' << r.checker << ',' << r.planner << ',' << r.solved << ','
         << fmt(r.time, "%.6g") << ',' << fmt(r.checks, "%.0f") << ',' << fmt(r.length, "%.6g") << ','
         << r.certifiedAsPlanned << ',' << r.certified << ',' << r.certifiedExact << ',' << r.fclFine << ','
         << r.fclReturned << ',' << fmt(r.simplifyTime, "%.6g") << ',' << fmt(r.certifyTime, "%.6g") << '\n';
  }
  std::ofstream csv(s.out + "/mbm_bench.csv");
  csv << "scene,checker,planner,runs,success_pct,median_time_s,p90_time_s,checks_per_s,median_length,"
         "certified_as_planned_pct,certified_pct,certified_exact_pct,fcl_fine_ok_pct,fcl_fine_ok_as_returned_pct,"
         "median_plan_simplify_s,median_certify_s\n";
  for (const MbmRow& r : rows) {
    csv << r.scene << ',' << r.checker << ',' << r.planner << ',' << r.runs << ',' << fmt(r.successPct(), "%.1f") << ','
        << fmt(r.tMed, "%.6g") << ',' << fmt(r.tP90, "%.6g") << ',' << fmt(r.checksPerSecond, "%.0f") << ','
        << fmt(r.lengthMed, "%.4g") << ',' << fmt(r.pctOfSolved(r.certifiedAsPlanned), "%.1f") << ','
        << fmt(r.pctOfSolved(r.certified), "%.1f") << ',' << fmt(r.pctOfSolved(r.certifiedExact), "%.1f") << ','
        << fmt(r.pctOfSolved(r.fclFine), "%.1f") << ',' << fmt(r.pctOfSolved(r.fclReturned), "%.1f") << ','
        << fmt(r.planSimplifyMed, "%.6g") << ',' << fmt(r.certifyMed, "%.6g") << '\n';
  }
}

/// Per planner, over every scene: ours against FCL.
void writeHeadline(std::ostringstream& md, const MbmSettings& s, const std::vector<MbmRecord>& records) {
  md << "| planner (all scenes) | checker | runs | success | median (ms) | p90 (ms) | checks/s | plan + simplify (ms) "
        "| certify (ms) | FCL ok as returned |\n";
  md << "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const std::string& planner : s.planners) {
    double medians[2] = {std::nan(""), std::nan("")};
    for (std::size_t c = 0; c < s.checkers.size(); ++c) {
      const MbmRow r =
          summarize(records, [&](const MbmRecord& x) { return x.planner == planner && x.checker == s.checkers[c]; });
      if (r.runs == 0) continue;
      if (c < 2) medians[c] = r.tMed;
      md << "| " << planner << " | " << s.checkers[c] << " | " << r.runs << " | " << pct(r.successPct()) << " | "
         << ms(r.tMed) << " | " << ms(r.tP90) << " | " << fmt(r.checksPerSecond, "%.3g") << " | "
         << ms(r.planSimplifyMed) << " | " << ms(r.certifyMed) << " | " << pct(r.pctOfSolved(r.fclReturned)) << " |\n";
    }
    if (!std::isnan(medians[0]) && !std::isnan(medians[1])) {
      md << "| " << planner << " | FCL median / ours | | | " << fmt(medians[1] / medians[0], "%.2g")
         << "x | | | | | |\n";
    }
  }
  md << "\n";
}

}  // namespace

void writeMbmReport(const MbmSettings& s, const std::vector<MbmRecord>& records,
                    const std::vector<SceneFailure>& failures, bool partial) {
  const std::vector<MbmRow> rows = rowsOf(s, records);
  writeCsv(s, records, rows);
  std::ostringstream md;
  md << "# MotionBenchMaker benchmark (mbm_bench)\n\n";
  md << "The Panda, " << s.problems << " generated problems per scene (seed " << s.seed << "), time limit " << s.time
     << " s per run, " << s.runs << " run(s) per problem, planner and checker. Wall time "
     << fmt(s.wallSeconds / 60.0, "%.1f") << " min.\n\n";
  md << "success = exact solution within the limit; time = planning time (OMPL's, without simplification), median "
        "and 90th percentile over all runs (a failed run counts with its time); checks/s = state validity queries "
        "(motion checks included) per second of planning; length = joint-space length of the simplified path (rad, "
        "median of the solved runs); certified = simplified paths that certifyPath accepts as planned / after its "
        "repair / after its repair with every motion certified (no fallback step near contact); plan + simplify and "
        "certify = "
        "medians over the solved runs; FCL ok = paths free for FCL on the original meshes at every "
     << dp::tol::kFineResolution << " rad, as returned (simplified) and after certification.\n\n";
  writeHeadline(md, s, records);
  md << "| scene | planner | checker | runs | success | median (ms) | p90 (ms) | checks/s | length | certified | "
        "FCL ok |\n";
  md << "|---|---|---|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const MbmRow& r : rows) {
    md << "| " << r.scene << " | " << r.planner << " | " << r.checker << " | " << r.runs << " | " << pct(r.successPct())
       << " | " << ms(r.tMed) << " | " << ms(r.tP90) << " | " << fmt(r.checksPerSecond, "%.3g") << " | "
       << fmt(r.lengthMed, "%.3g") << " | " << pct(r.pctOfSolved(r.certifiedAsPlanned)) << " / "
       << pct(r.pctOfSolved(r.certified)) << " / " << pct(r.pctOfSolved(r.certifiedExact)) << " | "
       << pct(r.pctOfSolved(r.fclFine)) << " |\n";
  }
  for (const SceneFailure& f : failures) {
    md << "| " << f.scene << " | - | - | 0 | not run: " << f.reason << " | | | | | | |\n";
  }
  if (!partial) std::cout << md.str();
  std::ofstream(s.out + "/mbm_bench.md") << md.str();
  std::fprintf(stderr, "wrote %s/mbm_bench.md, mbm_bench.csv and mbm_runs.csv\n", s.out.c_str());
}

void plotMbmReport(const std::string& out) {
  runGnuplot(out + "/mbm_bench.csv", out, "mbm_plots.gp", "mbm_bench.png", "mbm_bench");
}

}  // namespace deepcheck::bench
