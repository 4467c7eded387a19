#!/usr/bin/env bash
# Penetration-depth benchmark in one command: configure, build, run, plot.
#
#   bench/run_pd_bench.sh            full run (~10 min on 2 cores): bench/results/pd_bench.csv and
#                                    its plots pd_bench.png, pd_bench_verts_100.png and
#                                    pd_bench_scaling.png; then a swept run (pd_bench --sweep: pairs
#                                    out of cache) of the main families and methods, whose CSV is
#                                    kept as bench/results/pd_bench_swept.csv
#   bench/run_pd_bench.sh --quick    fewer pairs and repetitions (~2 min), results in
#                                    <build dir>/pd_quick/ (the committed results stay as they are)
# Options: --build-dir DIR (default: build-bench beside bench/), --out DIR, --jobs N (default 2);
# anything after `--` goes to pd_bench (e.g. -- --families verts_100,motion --reps 9).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="$root/build-bench"
jobs=2
quick=0
out=""
extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --quick) quick=1 ;;
    --build-dir) build="$2"; shift ;;
    --out) out="$2"; shift ;;
    --jobs) jobs="$2"; shift ;;
    --) shift; extra=("$@"); break ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) echo "run_pd_bench.sh: unknown option $1 (try --help)" >&2; exit 2 ;;
  esac
  shift
done
if [[ -z "$out" ]]; then
  if [[ $quick -eq 1 ]]; then out="$build/pd_quick"; else out="$here/results"; fi
fi

generator=()
if [[ ! -f "$build/CMakeCache.txt" ]] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DDEEPCHECK_BUILD_BENCH=ON >/dev/null
cmake --build "$build" --target pd_bench -j "$jobs"

mkdir -p "$out"
rm -f "$out"/repro_pd_*.txt

args=()
[[ $quick -eq 1 ]] && args+=(--quick)
"$build/bench/pd_bench" "${args[@]}" --out "$out" "${extra[@]}"

# The same queries timed in sweeps (each pair's data out of the core's caches when it is timed),
# on the families and methods the README's tables compare; only with the full run's pair counts,
# whose hulls exceed the caches.
if [[ $quick -eq 0 && ${#extra[@]} -eq 0 ]]; then
  swept="$build/pd_swept"
  mkdir -p "$swept"
  rm -f "$swept"/repro_pd_*.txt
  "$build/bench/pd_bench" --sweep --families verts_30,verts_100,verts_1000,deep,motion,robots,boxes \
    --methods certified_cold,certified_warm,deep_warm,bullet_signed,fcl_ccd_distance --out "$swept"
  cp "$swept/pd_bench.csv" "$out/pd_bench_swept.csv"
fi

if command -v gnuplot >/dev/null; then
  gnuplot -e "csv='$out/pd_bench.csv'; outdir='$out'" "$here/pd_plots.gp"
  echo "plots: $out/pd_bench.png $out/pd_bench_verts_100.png $out/pd_bench_scaling.png"
else
  echo "gnuplot not found: plots skipped (apt-get install gnuplot-nox)"
fi
