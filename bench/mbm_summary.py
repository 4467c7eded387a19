#!/usr/bin/env python3
"""MotionBenchMaker's one result file (bench/README.md, "MotionBenchMaker benchmark"): reads the
per-run files of mbm_bench's runs, one per motion validator of our checker (certified, discrete),
and writes one CSV row per motion check, checker and scene, plus a row `all` over every scene. The
FCL checker always checks motions discretely (OMPL's DiscreteMotionValidator): its rows say so. Prints the `all` rows
as the Markdown table bench/README.md shows.

Columns: runs; solved_pct; median and 90th percentile of the planning time over all runs (a
failed run counts with its time); median plan + simplify and median certifyPath time over the
solved runs; returned paths and those FCL's fine check on the meshes accepts as returned.
Times and quantiles are computed as mbm_bench computes them (linear between order statistics).

Usage: bench/mbm_summary.py OUT.csv MOTIONS=RUNS.csv [MOTIONS=RUNS.csv ...]
  e.g. bench/mbm_summary.py bench/results/mbm_bench.csv certified=a/mbm_runs.csv discrete=b/mbm_runs.csv
"""
import csv
import math
import sys

COLUMNS = ["motions", "checker", "scene", "runs", "solved_pct", "median_plan_ms", "p90_plan_ms",
           "median_plan_simplify_ms", "median_certify_ms", "returned", "fcl_ok_as_returned", "fcl_ok_as_returned_pct"]


def quantile(values, q):
    if not values:
        return math.nan
    v = sorted(values)
    at = q * (len(v) - 1)
    lo = math.floor(at)
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (at - lo) * (v[hi] - v[lo])


def row(motions, checker, scene, runs):
    solved = [r for r in runs if r["solved"] == "1"]
    ok = sum(r["fcl_fine_ok_as_returned"] == "1" for r in solved)
    ms = lambda values, q: f"{1e3 * quantile(values, q):.3g}"
    return {
        "motions": motions, "checker": checker, "scene": scene, "runs": len(runs),
        "solved_pct": f"{100.0 * len(solved) / len(runs):.1f}",
        "median_plan_ms": ms([float(r["time_s"]) for r in runs], 0.5),
        "p90_plan_ms": ms([float(r["time_s"]) for r in runs], 0.9),
        "median_plan_simplify_ms": ms([float(r["time_s"]) + float(r["simplify_s"]) for r in solved], 0.5),
        "median_certify_ms": ms([float(r["certify_s"]) for r in solved], 0.5),
        "returned": len(solved), "fcl_ok_as_returned": ok,
        "fcl_ok_as_returned_pct": f"{100.0 * ok / len(solved):.1f}" if solved else "",
    }


def rows_of(motions, path):
    with open(path, newline="") as f:
        runs = list(csv.DictReader(f))
    if not runs:
        sys.exit(f"mbm_summary: no run in {path}")
    out = []
    for checker in dict.fromkeys(r["checker"] for r in runs):
        mine = [r for r in runs if r["checker"] == checker]
        label = motions if checker == "deepcheck" else "discrete"
        for scene in dict.fromkeys(r["scene"] for r in mine):
            out.append(row(label, checker, scene, [r for r in mine if r["scene"] == scene]))
        out.append(row(label, checker, "all", mine))
    return out


def main(out_path, inputs):
    rows = []
    for spec in inputs:
        motions, sep, path = spec.partition("=")
        if not sep:
            sys.exit(__doc__.strip().splitlines()[-2])
        rows += rows_of(motions, path)
    with open(out_path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS, lineterminator="\n")
        writer.writeheader()
        writer.writerows(rows)
    print("| all scenes | runs | solved | plan: median, p90 (ms) | plan + simplify (ms) | certifyPath (ms) "
          "| returned paths FCL passes |")
    print("|---|--:|--:|--:|--:|--:|--:|")
    for r in rows:
        if r["scene"] == "all":
            print(f"| {r['checker']}, {r['motions']} motions | {r['runs']} | {r['solved_pct']} % | "
                  f"{r['median_plan_ms']}, {r['p90_plan_ms']} | {r['median_plan_simplify_ms']} | "
                  f"{r['median_certify_ms']} | {r['fcl_ok_as_returned_pct']} % ({r['fcl_ok_as_returned']} of {r['returned']}) |")
    print(f"wrote {out_path}", file=sys.stderr)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__.strip().splitlines()[-2])
    main(sys.argv[1], sys.argv[2:])
