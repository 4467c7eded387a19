#!/usr/bin/env bash
# Body penetration-depth benchmark in one command: configure, build, run, plot.
#
#   bench/run_body_pd_bench.sh           200 queries per family, 9 repetitions (seconds), results
#                                        in bench/results/body_pd_bench.csv and body_pd_bench.png
#   bench/run_body_pd_bench.sh --quick   40 queries, 3 repetitions, results in
#                                        <build dir>/body_pd_quick/ (committed results untouched)
# Options: --build-dir DIR (default: build-bench beside bench/), --out DIR, --jobs N (default 2).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="$root/build-bench"
jobs=2
quick=0
out=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --quick) quick=1 ;;
    --build-dir) build="$2"; shift ;;
    --out) out="$2"; shift ;;
    --jobs) jobs="$2"; shift ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    *) echo "run_body_pd_bench.sh: unknown option $1 (try --help)" >&2; exit 2 ;;
  esac
  shift
done
if [[ -z "$out" ]]; then
  if [[ $quick -eq 1 ]]; then out="$build/body_pd_quick"; else out="$here/results"; fi
fi

generator=()
if [[ ! -f "$build/CMakeCache.txt" ]] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DDEEPCHECK_BUILD_BENCH=ON >/dev/null
cmake --build "$build" --target body_pd_bench -j "$jobs"

mkdir -p "$out"
args=()
[[ $quick -eq 1 ]] && args+=(--queries 40 --reps 3)
"$build/bench/body_pd_bench" "${args[@]}" --out "$out"

if command -v gnuplot >/dev/null; then
  gnuplot -e "csv='$out/body_pd_bench.csv'; outdir='$out'" "$here/body_pd_plots.gp"
  echo "plot: $out/body_pd_bench.png"
else
  echo "gnuplot not found: plot skipped (apt-get install gnuplot-nox)"
fi
