#!/bin/sh
# Certified against discrete motion checks on MotionBenchMaker's Panda problems (bench/README.md,
# "MotionBenchMaker benchmark"): builds mbm_bench and runs RRTConnect on our checker, with its
# certified motions (the default) and with OMPL's discrete motion checks (--motions discrete),
# scene by scene, on one core at low priority, twice: certified first, then discrete first, so a
# drift of the machine's speed weighs on both alike. Each run's files stay in
# BUILD_DIR/mbm_motions/<round>_<scene>_<motions>/; mbm_motions.py then writes
# bench/results/mbm_motions.csv and prints the ratios. PROBLEMS problems per scene (default 15);
# about 10 minutes with the default.
set -e
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
build=${BUILD_DIR:-$root/build}
work="$build/mbm_motions"
problems=${PROBLEMS:-15}
scenes="bookshelf_small bookshelf_tall bookshelf_thin cage box kitchen table_pick table_bars"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target mbm_bench
rm -rf "$work"
run() {  # round scene motions
  mkdir -p "$work/$1_$2_$3"
  taskset -c 0 nice "$build/bench/mbm_bench" --planners RRTConnect --checkers deepcheck --motions "$3" \
    --problems "$problems" --scenes "$2" --out "$work/$1_$2_$3" >/dev/null
}
for scene in $scenes; do
  echo "mbm_motions: $scene" >&2
  run 1 "$scene" certified
  run 1 "$scene" discrete
  run 2 "$scene" discrete
  run 2 "$scene" certified
done
python3 "$here/mbm_motions.py" "$work" "$here/results/mbm_motions.csv"
