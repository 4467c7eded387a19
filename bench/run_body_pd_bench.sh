#!/usr/bin/env bash
# Body penetration-depth benchmark in one command: configure, build, run, plot.
#
#   bench/run_body_pd_bench.sh           200 queries per family, 9 repetitions (seconds), results
#                                        in bench/results/body_pd_bench.csv and body_pd_bench.png
#   bench/run_body_pd_bench.sh --quick   40 queries, 3 repetitions, results in
#                                        <build dir>/body_pd_quick/ (committed results untouched)
# The build folder is build-bench beside bench/, or $BUILD_DIR.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="${BUILD_DIR:-$root/build-bench}"
out="$here/results"
args=()
if [[ "${1:-}" == "--quick" ]]; then
  out="$build/body_pd_quick"
  args=(--queries 40 --reps 3)
  shift
fi
if [[ $# -gt 0 ]]; then
  echo "usage: [BUILD_DIR=DIR] bench/run_body_pd_bench.sh [--quick]" >&2
  exit 2
fi

generator=()
[[ ! -f "$build/CMakeCache.txt" ]] && command -v ninja >/dev/null && generator=(-G Ninja)
cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DDEEPCHECK_BUILD_BENCH=ON >/dev/null
cmake --build "$build" --target body_pd_bench -j 2
mkdir -p "$out"
"$build/bench/body_pd_bench" "${args[@]}" --out "$out"

if command -v gnuplot >/dev/null; then
  gnuplot -e "csv='$out/body_pd_bench.csv'; outdir='$out'" "$here/body_pd_plots.gp"
  echo "plot: $out/body_pd_bench.png"
else
  echo "gnuplot not found: plot skipped (apt-get install gnuplot-nox)"
fi
