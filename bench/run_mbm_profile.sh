#!/bin/sh
# Where RRTConnect's time goes with our checker on MotionBenchMaker problems (bench/README.md,
# "MotionBenchMaker benchmark"): perf samples (user space, call graphs by DWARF unwinding) of
# mbm_bench with RRTConnect on our checker only, 20 runs on each of 3 problems of 4 scenes, split by
# bench/mbm_profile.py. Needs perf (linux-perf) and kernel.perf_event_paranoid <= 2.
# Prints the profile and writes it to BUILD_DIR/mbm_profile_rrtconnect.txt (not a kept result);
# perf's data stays in a temporary folder.
set -e
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
build=${BUILD_DIR:-$root/build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --build "$build" --target mbm_bench
nice perf record -q -e cpu-clock:u -F 499 --call-graph dwarf,16384 -o "$tmp/perf.data" \
  "$build/bench/mbm_bench" --problems 3 --runs 20 --scenes bookshelf_small,bookshelf_tall,box,table_pick \
  --planners RRTConnect --checkers deepcheck --out "$tmp/out" >/dev/null
perf script -i "$tmp/perf.data" -F ip,sym 2>/dev/null >"$tmp/stacks.txt"
{
  echo "mbm_bench --problems 3 --runs 20 --scenes bookshelf_small,bookshelf_tall,box,table_pick --planners RRTConnect --checkers deepcheck"
  echo
  python3 "$here/mbm_profile.py" "$tmp/stacks.txt"
  echo
  cat "$tmp/out/mbm_bench.md"
} >"$build/mbm_profile_rrtconnect.txt"
cat "$build/mbm_profile_rrtconnect.txt"
