#!/usr/bin/env bash
# Runs one fuzz harness of a libFuzzer build with the options it is fuzzed with, from its committed
# corpus fuzz/corpus/<harness>/ (read, never written):
#   fuzz/run_fuzzer.sh BUILD_DIR HARNESS WORK_DIR [libFuzzer options...]
# New inputs go to WORK_DIR/corpus, findings (crash-, leak-, timeout-, oom-<hash>) to WORK_DIR, and
# libFuzzer's output to WORK_DIR/log. Options given after WORK_DIR come last and win, e.g.
# -max_total_time=20 (CI), -runs=1000000. Exit status: libFuzzer's (0: no finding).
#
# Per harness: the longest input (-max_len; the text formats are allowed the sizes that nesting and
# long element lists need), the dictionary fuzz/dict/<harness>.dict when there is one, and
# fuzz/lsan.supp (leaks inside libassimp are not ours: see the file).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="$1" harness="$2" work="$3"
shift 3

case "$harness" in
  urdf|srdf|moveit_scene|scene_text|problems) max_len=131072 ;;
  mesh|decomposition_cache|pd_input|config_lines) max_len=262144 ;;
  goal_pose) max_len=65536 ;;
  ompl_state) max_len=512 ;;
  *) echo "run_fuzzer.sh: unknown harness '$harness'" >&2; exit 2 ;;
esac
# Every committed input fits: a run executes each whole before it mutates (CI's stage replays the
# corpora that way), where a longer one would be cut to -max_len.
too_long=$(find "$here/corpus/$harness" -type f -size +"$max_len"c)
if [[ -n "$too_long" ]]; then
  echo "run_fuzzer.sh: committed inputs longer than -max_len=$max_len bytes: $too_long" >&2
  exit 2
fi
options=(-max_len="$max_len" -timeout=25 -rss_limit_mb=2560 -print_final_stats=1)
[[ -f "$here/dict/$harness.dict" ]] && options+=(-dict="$here/dict/$harness.dict")

mkdir -p "$work/corpus"
binary="$(cd "$build" && pwd)/fuzz/fuzz_$harness"
export LSAN_OPTIONS="suppressions=$here/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
export ASAN_OPTIONS="${ASAN_OPTIONS:-malloc_context_size=10}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
"$binary" "${options[@]}" -artifact_prefix="$work/" "$@" "$work/corpus" "$here/corpus/$harness" >"$work/log" 2>&1
