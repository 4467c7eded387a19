#!/usr/bin/env python3
"""Compares two runs of mbm_bench made with the same options by two builds of the checker (the
same --seed, --problems, --planners and --checkers give the planners the same random streams, so
a run that receives the same answers makes the same queries). Per scene: the median planning time
of each run, and the median over the paired runs of the time ratio B / A, counting only the runs
whose number of checks and path length agree. A run stopped by the time limit differs, and runs
after one that differs can differ too (the random streams part from there).

Usage: bench/mbm_compare.py A/mbm_runs.csv B/mbm_runs.csv
"""
import csv
import statistics
import sys


def load(path):
    with open(path, newline="") as f:
        runs = {(r["scene"], r["problem"], r["planner"], r["checker"]): r for r in csv.DictReader(f)}
    if not runs:
        sys.exit(f"mbm_compare: no run in {path}")
    return runs


def same_run(x, y):
    return x["checks"] == y["checks"] and x["length"] == y["length"]


def row(label, keys, a, b):
    ms = lambda runs: 1e3 * statistics.median(float(runs[k]["time_s"]) for k in keys)
    paired = [k for k in keys if same_run(a[k], b[k])]
    ratio = statistics.median(float(b[k]["time_s"]) / float(a[k]["time_s"]) for k in paired) if paired else float("nan")
    print(f"| {label} | {len(keys)} | {len(paired)} | {ms(a):.3g} | {ms(b):.3g} | {ratio:.3f} |")


def main(path_a, path_b):
    a, b = load(path_a), load(path_b)
    keys = [k for k in a if k in b]
    if len(keys) != len(a) or len(keys) != len(b):
        sys.exit(f"mbm_compare: the runs differ ({len(a)} in A, {len(b)} in B, {len(keys)} in both): "
                 "were they made with the same options?")
    print(f"A: {path_a}\nB: {path_b}\n")
    print("| scene, planner, checker | runs | same checks and path | A: median (ms) | B: median (ms) | B / A, paired median |")
    print("|---|--:|--:|--:|--:|--:|")
    groups = {}
    for k in keys:
        groups.setdefault((k[0], k[2], k[3]), []).append(k)
    for (scene, planner, checker), group in groups.items():
        row(f"{scene}, {planner}, {checker}", group, a, b)
    row("all", keys, a, b)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-1])
    main(sys.argv[1], sys.argv[2])
