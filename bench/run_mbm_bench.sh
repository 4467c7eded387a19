#!/bin/sh
# The MotionBenchMaker benchmark (bench/README.md, "MotionBenchMaker benchmark"): builds mbm_bench
# and runs RRTConnect on 100 problems per scene, on one core at low priority, twice:
#   certified  our checker with its certified motions (the default) and the FCL mesh checker;
#   discrete   our checker with OMPL's discrete motion checks.
# Each run's own files (OMPL logs, per-run CSV, tables) stay in BUILD_DIR/mbm_bench/<run>/; then
# mbm_summary.py writes the one kept result, bench/results/mbm_bench.csv (both runs, per scene and
# over all scenes), and the certified run's plot is copied to bench/results/mbm_bench.png.
# Arguments are passed to both runs (e.g. --problems 20); about 15 minutes in all.
set -e
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
build=${BUILD_DIR:-$root/build}
work="$build/mbm_bench"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target mbm_bench
mkdir -p "$work/certified" "$work/discrete"
taskset -c 0 nice "$build/bench/mbm_bench" --planners RRTConnect --out "$work/certified" "$@"
taskset -c 0 nice "$build/bench/mbm_bench" --planners RRTConnect --checkers deepcheck --motions discrete \
  --out "$work/discrete" "$@"
python3 "$here/mbm_summary.py" "$here/results/mbm_bench.csv" \
  certified="$work/certified/mbm_runs.csv" discrete="$work/discrete/mbm_runs.csv"
if [ -f "$work/certified/mbm_bench.png" ]; then
  cp "$work/certified/mbm_bench.png" "$here/results/mbm_bench.png"
fi
