// plan_bench's records and report (plan_report.h).

#include "plan_report.h"

#include "deepcheck/planners/tolerances.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace deepcheck::bench {

namespace dp = deepcheck::planners;

Row summarize(const std::vector<Record>& all, const std::string& problem, const std::string& checker,
              const std::string& planner) {
  Row row{problem, checker, planner};
  std::vector<double> t, first, length, clearance, states;
  for (const Record& r : all) {
    if (r.problem != problem || r.checker != checker || r.planner != planner) continue;
    ++row.runs;
    t.push_back(r.time);
    if (!std::isnan(r.graphStates)) states.push_back(r.graphStates);
    if (!r.solved) continue;
    ++row.solved;
    if (r.fclVerified) ++row.verified;
    if (!std::isnan(r.firstSolution)) first.push_back(r.firstSolution);
    length.push_back(r.length);
    clearance.push_back(r.minClearance);
  }
  row.tMed = median(t);
  row.firstMed = median(first);
  row.lengthMed = median(length);
  row.clearanceMed = median(clearance);
  row.statesMed = median(states);
  return row;
}

void writeReport(const ReportSettings& settings, const std::vector<Problem>& selected,
                 const std::vector<Record>& records, const std::vector<std::string>& rejected) {
  std::vector<Row> rows;
  for (const Problem& p : selected) {
    for (const char* c : settings.checkers) {
      std::vector<std::string> names;
      for (const Record& r : records) {
        if (r.problem == p.name && r.checker == c && std::find(names.begin(), names.end(), r.planner) == names.end()) {
          names.push_back(r.planner);
        }
      }
      for (const std::string& n : names) rows.push_back(summarize(records, p.name, c, n));
    }
  }
  {
    std::ofstream csv(settings.out + "/plan_bench.csv");
    csv << "problem,checker,planner,runs,success_pct,median_time_s,median_first_solution_s,median_length,"
           "median_min_clearance_m,fcl_verified_pct,median_graph_states\n";
    for (const Row& r : rows) {
      csv << r.problem << ',' << r.checker << ',' << r.planner << ',' << r.runs << ',' << fmt(r.successPct(), "%.1f")
          << ',' << fmt(r.tMed, "%.4g") << ',' << fmt(r.firstMed, "%.4g") << ',' << fmt(r.lengthMed, "%.4g") << ','
          << fmt(r.clearanceMed, "%.4g") << ',' << fmt(r.verifiedPct(), "%.1f") << ',' << fmt(r.statesMed, "%.0f")
          << '\n';
    }
  }
  std::ostringstream md;
  md << "# Planning benchmark (plan_bench)\n\n";
  md << "Runs per planner, checker and problem: " << settings.runs << ", time limit " << settings.time
     << " s, OMPL seed " << settings.seed << ". Wall time " << fmt(settings.wallSeconds / 60.0, "%.1f") << " min.\n\n";
  md << "success = exact solution within the time limit; medians over all runs (time) or the solved runs (the "
        "rest); first = time to the first exact solution; length = joint-space length of the simplified path "
        "(rad); clearance = minimum of our signed distance along the simplified path every "
     << dp::tol::kFineResolution
     << " rad (m); FCL ok = solved runs whose simplified path FCL finds free at that resolution; states = graph "
        "states.\n\n";
  md << "| problem | checker | planner | runs | success | time (s) | first (s) | length | clearance (m) | FCL ok | "
        "states |\n";
  md << "|---|---|---|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const Row& r : rows) {
    md << "| " << r.problem << " | " << r.checker << " | " << r.planner << " | " << r.runs << " | "
       << fmt(r.successPct(), "%.0f") << " % | " << fmt(r.tMed, "%.3g") << " | " << fmt(r.firstMed, "%.3g") << " | "
       << fmt(r.lengthMed, "%.3g") << " | " << fmt(r.clearanceMed, "%.3f") << " | "
       << (std::isnan(r.verifiedPct()) ? std::string("-") : fmt(r.verifiedPct(), "%.0f") + " %") << " | "
       << fmt(r.statesMed, "%.0f") << " |\n";
  }
  md << "\nStart and goal:\n\n";
  for (const Problem& p : selected) md << "- " << p.name << ": " << p.note << "\n";
  if (!rejected.empty()) {
    md << "\nPaths rejected by the FCL check (" << rejected.size() << "):\n\n";
    for (const std::string& f : rejected) md << "- `" << std::filesystem::path(f).filename().string() << "`\n";
  }
  std::cout << md.str();
  std::ofstream(settings.out + "/plan_bench.md") << md.str();
  std::fprintf(stderr, "wrote %s/plan_bench.csv and plan_bench.md\n", settings.out.c_str());
}

void runGnuplot(const std::string& csv, const std::string& outdir, const std::string& script, const std::string& png,
                const char* who) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    std::fprintf(stderr, "%s: gnuplot not found, no plot\n", who);
    return;
  }
  const std::string cmd = "gnuplot -e \"csv='" + csv + "'; outdir='" + outdir + "'\" '" +
                          std::string(DEEPCHECK_BENCH_DIR) + "/" + script + "'";
  if (std::system(cmd.c_str()) == 0) {
    std::fprintf(stderr, "wrote %s/%s\n", outdir.c_str(), png.c_str());
  } else {
    std::fprintf(stderr, "%s: gnuplot failed (%s)\n", who, cmd.c_str());
  }
}

void plotReport(const std::string& out) {
  runGnuplot(out + "/plan_bench.csv", out, "plan_plots.gp", "plan_bench.png", "plan_bench");
}

}  // namespace deepcheck::bench
