#!/usr/bin/env python3
"""Certified against discrete motion checks (bench/README.md, "MotionBenchMaker benchmark"): reads
the runs bench/run_mbm_motions.sh made, DIR/<round>_<scene>_<motions>/mbm_runs.csv, and per scene
and round takes the median over the solved runs of the planning time (time_s) and of plan +
simplify (time_s + simplify_s) with each motion check, and their ratios certified / discrete.
Also counts the certified runs' returned paths and those FCL's fine check on the meshes accepts
as returned. Writes one CSV row per scene and round, plus a row `all` with the geometric means of
the ratios and the sums of the counts, and prints them as a Markdown table.

Usage: bench/mbm_motions.py DIR OUT.csv
"""
import csv
import glob
import math
import os
import statistics
import sys

COLUMNS = ["scene", "round", "certified_plan_ms", "discrete_plan_ms", "plan_ratio", "certified_total_ms",
           "discrete_total_ms", "total_ratio", "certified_returned", "certified_fcl_ok"]


def medians(path):
    """Median plan and plan + simplify (ms) over the solved runs of one mbm_runs.csv, the solved
    runs and those whose returned path FCL accepts."""
    with open(path, newline="") as f:
        solved = [r for r in csv.DictReader(f) if r["solved"] == "1"]
    if not solved:
        sys.exit(f"mbm_motions: no solved run in {path}")
    plan = statistics.median(float(r["time_s"]) for r in solved)
    total = statistics.median(float(r["time_s"]) + float(r["simplify_s"] or 0.0) for r in solved)
    fcl_ok = sum(r["fcl_fine_ok_as_returned"] == "1" for r in solved)
    return 1e3 * plan, 1e3 * total, len(solved), fcl_ok


def geometric_mean(values):
    return math.exp(sum(math.log(v) for v in values) / len(values))


def main(work, out):
    rows = []
    for path in sorted(glob.glob(os.path.join(work, "*_certified", "mbm_runs.csv"))):
        name = os.path.basename(os.path.dirname(path))[: -len("_certified")]
        other = os.path.join(work, name + "_discrete", "mbm_runs.csv")
        if not os.path.exists(other):
            sys.exit(f"mbm_motions: {path} has no discrete run beside it ({other})")
        round_, scene = name.split("_", 1)
        cp, ct, returned, fcl_ok = medians(path)
        dp, dt, _, _ = medians(other)
        rows.append({"scene": scene, "round": round_, "certified_plan_ms": cp, "discrete_plan_ms": dp,
                     "plan_ratio": cp / dp, "certified_total_ms": ct, "discrete_total_ms": dt, "total_ratio": ct / dt,
                     "certified_returned": returned, "certified_fcl_ok": fcl_ok})
    if not rows:
        sys.exit(f"mbm_motions: no run in {work}")
    rows.append({"scene": "all", "round": "", "plan_ratio": geometric_mean([r["plan_ratio"] for r in rows]),
                 "total_ratio": geometric_mean([r["total_ratio"] for r in rows]),
                 "certified_returned": sum(r["certified_returned"] for r in rows),
                 "certified_fcl_ok": sum(r["certified_fcl_ok"] for r in rows)})
    with open(out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in r.items()})
    print("| scene | round | plan: certified / discrete (ms) | ratio | plan + simplify (ms) | ratio | FCL passes |")
    print("|---|--:|--:|--:|--:|--:|--:|")
    for r in rows[:-1]:
        print(f"| {r['scene']} | {r['round']} | {r['certified_plan_ms']:.3g} / {r['discrete_plan_ms']:.3g} | "
              f"{r['plan_ratio']:.2f} | {r['certified_total_ms']:.3g} / {r['discrete_total_ms']:.3g} | "
              f"{r['total_ratio']:.2f} | {r['certified_fcl_ok']} of {r['certified_returned']} |")
    a = rows[-1]
    print(f"| all (geometric mean of {len(rows) - 1}) | | | {a['plan_ratio']:.2f} | | {a['total_ratio']:.2f} | "
          f"{a['certified_fcl_ok']} of {a['certified_returned']} |")
    print(f"wrote {out}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-1])
    main(sys.argv[1], sys.argv[2])
