#!/usr/bin/env python3
"""Totals over mbm_bench's runs that its tables do not give (bench/README.md, "MotionBenchMaker
benchmark"): per planner, the FCL / ours ratio of planning times problem by problem (median over the
problems both checkers solved); and the certification of the returned paths, in all and by checker.

Usage: bench/mbm_summary.py [results/mbm/mbm_runs.csv]
"""
import collections
import csv
import os
import statistics
import sys


def main(path):
    with open(path, newline="") as f:
        runs = list(csv.DictReader(f))
    if not runs:
        sys.exit(f"mbm_summary: no run in {path}")
    solved = lambda r: r["solved"] == "1"
    by_planner = collections.defaultdict(dict)
    for r in runs:
        by_planner[r["planner"]][(r["scene"], r["problem"], r["checker"])] = r
    print(f"{os.path.basename(path)}: {len(runs)} runs")
    for planner, table in by_planner.items():
        ratios = [float(table[(s, p, "fcl")]["time_s"]) / float(r["time_s"])
                  for (s, p, c), r in table.items()
                  if c == "deepcheck" and solved(r) and (s, p, "fcl") in table and solved(table[(s, p, "fcl")])]
        if ratios:
            print(f"{planner}: FCL / ours per problem, median {statistics.median(ratios):.3g}x over {len(ratios)} problems both solved")
    done = [r for r in runs if solved(r)]
    certified = [r for r in done if r["certified"] == "1"]
    refused = [r for r in done if r["certified"] != "1"]
    print(f"paths returned {len(done)}; certified as planned {sum(r['certified_as_planned'] == '1' for r in done)}, "
          f"after repair {len(certified)}; FCL fine check accepts {sum(r['fcl_fine_ok'] == '1' for r in certified)} of the certified")
    if certified and "certified_exact" in certified[0]:
        print(f"certified with every motion certified by clearance (no fallback step): "
              f"{sum(r['certified_exact'] == '1' for r in certified)} of {len(certified)}")
    for checker in ("deepcheck", "fcl"):
        mine = [r for r in done if r["checker"] == checker]
        if mine:
            share = 100.0 * sum(r["certified_as_planned"] == "1" for r in mine) / len(mine)
            print(f"  planned with {checker}: {len(mine)} paths, {share:.0f} % certified as planned, "
                  f"{sum(r['certified'] != '1' for r in mine)} not certified after repair")
    scenes = collections.Counter(r["scene"] for r in refused)
    print(f"not certified after repair {len(refused)} (by scene: {dict(scenes)}); "
          f"FCL fine check accepts {sum(r['fcl_fine_ok'] == '1' for r in refused)} of them")
    for r in certified:
        if r["fcl_fine_ok"] != "1":
            print(f"  certified but rejected by FCL: {r['scene']} problem {r['problem']}, {r['planner']} with {r['checker']}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "bench/results/mbm/mbm_runs.csv")
