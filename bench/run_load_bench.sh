#!/usr/bin/env bash
# Load-time benchmark in one command: configure, build, run load_bench, plot.
#
#   bench/run_load_bench.sh          sizes 250 to 8,000 for every kind, then the non-convex
#                                    `hand` and `comb` meshes up to 100,000 triangles (about 5
#                                    minutes on 2 cores); results in bench/results/load_bench.csv,
#                                    load_bench.png and load_bench_hand.png (pieces and excess)
# Options: --build-dir DIR (default: build-bench beside bench/), --out DIR, --jobs N (default 2);
# anything after `--` goes to load_bench (e.g. -- --kinds mesh --sizes 1000,10000).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="$root/build-bench"
jobs=2
out="$here/results"
extra=(--kinds scene_yaml,obstacles,obstacles_batch,scene_urdf,robot_star,robot_hub,mesh --sizes 250,500,1000,2000,4000,8000)
hand=(--kinds hand,comb --sizes 1000,4000,16000,45000,100000)
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir) build="$2"; shift ;;
    --out) out="$2"; shift ;;
    --jobs) jobs="$2"; shift ;;
    --) shift; extra=("$@"); hand=(); break ;;
    -h|--help) sed -n '2,7p' "$0"; exit 0 ;;
    *) echo "run_load_bench.sh: unknown option $1 (try --help)" >&2; exit 2 ;;
  esac
  shift
done

generator=()
if [[ ! -f "$build/CMakeCache.txt" ]] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DDEEPCHECK_BUILD_BENCH=ON >/dev/null
cmake --build "$build" --target load_bench -j "$jobs"
mkdir -p "$out"
"$build/bench/load_bench" --out "$out" "${extra[@]}"
if [[ ${#hand[@]} -gt 0 ]]; then
  # The hand at its own sizes, its rows appended (without the header) to the same CSV.
  cp "$out/load_bench.csv" "$out/load_bench_kinds.csv"
  "$build/bench/load_bench" --out "$out" "${hand[@]}"
  { cat "$out/load_bench_kinds.csv"; tail -n +2 "$out/load_bench.csv"; } > "$out/load_bench_all.csv"
  mv "$out/load_bench_all.csv" "$out/load_bench.csv"
  rm "$out/load_bench_kinds.csv"
fi
gnuplot -e "csv='$out/load_bench.csv'; outdir='$out'" "$here/load_plots.gp"
echo "wrote $out/load_bench.csv, $out/load_bench.png and $out/load_bench_hand.png"
