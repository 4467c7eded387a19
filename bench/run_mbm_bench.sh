#!/bin/sh
# The MotionBenchMaker benchmark (bench/README.md, "MotionBenchMaker benchmark"): builds mbm_bench
# and runs it single-threaded at low priority, then mbm_summary.py; the results go to bench/results/mbm/.
# Arguments are passed to mbm_bench (e.g. --problems 20); default: 100 problems per scene.
set -e
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
build=${BUILD_DIR:-$root/build}
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target mbm_bench
nice "$build/bench/mbm_bench" --out "$here/results/mbm" "$@"
python3 "$here/mbm_summary.py" "$here/results/mbm/mbm_runs.csv" | tee "$here/results/mbm/mbm_summary.txt"
