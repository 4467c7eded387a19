#!/usr/bin/env bash
# The sanitizer stage of CI (docs/testing.md), run from the repository root after the normal
# build and tests:
#   1. build-asan: Clang build with AddressSanitizer + UndefinedBehaviorSanitizer
#      (-fno-sanitize-recover=all: the first report fails the run) and libFuzzer's coverage
#      instrumentation (-fsanitize=fuzzer-no-link) of the libraries that the geometry,
#      decomposition, robots and checker unit tests and the fuzz harnesses (libFuzzer binaries)
#      link; runs the tests, then fuzzes each harness for FUZZ_SECONDS from its committed corpus
#      (every committed input runs first), two at a time (fuzz/run_fuzzer.sh): any finding fails
#      the stage. With FUZZ_SECONDS=0 it replays the committed corpora instead.
#   2. build-tsan: ThreadSanitizer build of the checker's concurrency suite alone; runs it.
# The long randomized sweeps of test_geometry (see SANITIZE_DEEP_SKIP) run in the normal build only:
# under ASan they alone would take longer than the rest of CI.
#
# Environment: JOBS (parallel build jobs, default: the number of cores); FUZZ_SECONDS (per
# harness, default 10; 0 skips the fuzzing).
set -euo pipefail
cd "$(dirname "$0")/../.."

jobs="${JOBS:-$(nproc)}"
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# -O1 keeps the sanitized tests fast and the builds short; assertions stay on (no -DNDEBUG).
common=("${generator[@]}" "${launcher[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo
        "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" -DDEEPCHECK_BUILD_BENCH=OFF)

# test_geometry suites and cases left to the normal build (minutes of randomized sweeps under ASan).
SANITIZE_DEEP_SKIP='!deep_random:!deep_hard_cases/spheres_with_2000_vertices:!fast_paths/overlaps_unchecked_equals_overlaps'
# ... and the body depth's sweeps against its brute-force reference (the reference enumerates
# every plane triple of every Minkowski difference: seconds in Release, many minutes here).
SANITIZE_DEEP_SKIP+=':!body_depth/random_unions_agree_with_the_reference:!body_depth/identical_bodies_at_one_pose'
SANITIZE_DEEP_SKIP+=':!body_depth/large_pieces_agree_with_the_reference'
# test_geometry cases that fail in this Clang build only, left to the normal (GCC) build, where they
# pass (docs/testing.md, "Sanitizers"): they draw random values inside one argument list, whose
# order of evaluation differs between the compilers, so Clang's run tests other random pairs, on
# which two expect at least one cold query to need an expansion (none does) and one expects fewer
# than 45 of 50 tetrahedra pairs to overlap (45 do).
SANITIZE_DEEP_SKIP+=':!certified/exact_and_certified_on_random_pairs:!certified/warm_equals_cold_along_motions'
SANITIZE_DEEP_SKIP+=':!exact/tetrahedra_are_optimal'

# test_checker's 10,000-configuration brute-force sweep, left to the normal build likewise (its
# 2,000 configurations on the other broad phases run here).
SANITIZE_CHECKER_SKIP='!distance_bounds/world_equals_brute_force_with_swallowing_obstacles'

# test_decomposition's two largest meshes (34 cubes; a torus of 6,144 triangles), left to the normal
# build likewise: 200 of the suite's 280 s here. The smaller meshes of the other cases run the same
# code, but for the budget's growth past 32 pieces.
SANITIZE_DECOMPOSITION_SKIP='!convex_decomposition/the_budget_grows_past_32_while_the_target_is_missed'
SANITIZE_DECOMPOSITION_SKIP+=':!convex_decomposition/a_finely_tessellated_torus_is_covered_and_meets_the_target'

# step <what>: a stage's heading, with the seconds since the stage began.
step() { printf '\n== sanitize (%d s): %s\n' "$SECONDS" "$*"; }

step "ASan+UBSan build (Clang, libFuzzer instrumentation)"
# -fno-sanitize=float-cast-overflow: the checks of GCC's -fsanitize=undefined, which the stage ran
# before it was built with Clang. The two casts Clang's check reported (a NaN and a value beyond
# int cast to int, in the direction index and a cross-section's buckets) are clamped now.
asan="-fsanitize=address,undefined -fno-sanitize=float-cast-overflow -fno-sanitize-recover=all -fno-omit-frame-pointer"
# A tree configured with another compiler (an older GCC build-asan) is configured afresh.
if [[ -f build-asan/CMakeCache.txt ]] && ! grep -q '^CMAKE_CXX_COMPILER:[A-Z]*=.*clang++' build-asan/CMakeCache.txt; then
  rm -rf build-asan
fi
# The suites' own sources compile without instrumentation (DEEPCHECK_SUITE_COMPILE_OPTIONS): what
# they test, the libraries, carries it; the suites link the sanitizers' runtime all the same.
cmake -S . -B build-asan "${common[@]}" -DCMAKE_CXX_COMPILER=clang++ -DDEEPCHECK_BUILD_FUZZERS=ON \
  "-DCMAKE_CXX_FLAGS=-fsanitize=fuzzer-no-link $asan" "-DCMAKE_EXE_LINKER_FLAGS=$asan" \
  -DDEEPCHECK_SUITE_COMPILE_OPTIONS=-fno-sanitize=all >/dev/null
if ! grep -q '^DEEPCHECK_HAVE_LIBFUZZER:INTERNAL=1' build-asan/CMakeCache.txt; then
  echo "sanitize: clang++ cannot link libFuzzer (-fsanitize=fuzzer): install clang and libclang-rt-14-dev (packages.txt)" >&2
  exit 1
fi
harnesses=(pd_input urdf mesh config_lines moveit_scene scene_text srdf problems decomposition_cache ompl_state goal_pose)
cmake --build build-asan -j "$jobs" --target test_geometry test_decomposition test_robots test_checker "${harnesses[@]/#/fuzz_}"

export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# suite <name> <args...>: runs one sanitized suite and prints its output, as one block, when it ends.
suite() {
  local out status=0 start=$SECONDS
  out=$("build-asan/tests/$1" "${@:2}" 2>&1) || status=$?
  printf -- '-- %s (exit status %d, %d s)\n%s\n' "$1" "$status" "$((SECONDS - start))" "$out"
  return "$status"
}

step "ASan+UBSan unit tests"
# test_checker keeps the convex pieces and self-pair grids of its robots in a cache folder of its
# build. The normal build's tests have just filled theirs: its entries are copied (never over an
# entry already here), so that the sanitized run does not decompose and grid every robot again
# (several minutes under ASan). An entry is still checked when read, and the decomposition and
# the grids are computed under the sanitizers by their own suites (test_decomposition, the grid
# cache cases), in folders of their own.
if [[ -d build/checker_test_cache ]]; then
  mkdir -p build-asan/checker_test_cache
  cp -rn build/checker_test_cache/. build-asan/checker_test_cache/
fi
# test_checker (the longest, about 4 minutes alone) runs beside test_geometry, test_decomposition and
# test_robots (together about as long): on two cores or more the stage takes the time of the longer
# side; on one, the two sides share it.
failed=0
suite test_checker --report_level=short "--run_test=$SANITIZE_CHECKER_SKIP" &
checker_pid=$!
suite test_geometry --report_level=short "--run_test=$SANITIZE_DEEP_SKIP" || failed=1
suite test_decomposition --report_level=short "--run_test=$SANITIZE_DECOMPOSITION_SKIP" || failed=1
suite test_robots --report_level=short || failed=1
wait "$checker_pid" || failed=1
if (( failed )); then
  echo "sanitize: a sanitized suite failed; its output is above" >&2
  exit 1
fi
# A fuzzing run first executes every input of its committed corpus, whatever its time limit, so the
# corpus replay (ctest's fuzz_replay_* tests) runs only when the fuzzing is skipped.
fuzz_seconds="${FUZZ_SECONDS:-10}"
if (( fuzz_seconds == 0 )); then
  step "ASan+UBSan corpus replay"
  ctest --test-dir build-asan -R '^fuzz_replay_' --output-on-failure
else
  step "fuzzing: each harness ${fuzz_seconds} s from its committed corpus (every input run first), two at a time"
  # fuzz_one <harness>: one bounded run, its summary printed when it ends; non-zero on a finding.
  fuzz_one() {
    local work="build-asan/fuzz-ci/$1" status=0
    rm -rf "$work"
    fuzz/run_fuzzer.sh build-asan "$1" "$work" -max_total_time="$fuzz_seconds" || status=$?
    printf -- '-- fuzz_%s (exit status %d): %s\n' "$1" "$status" \
      "$(grep -E '^#[0-9]+[[:space:]]+DONE' "$work/log" | tr -s '[:space:]' ' ')"
    if (( status != 0 )); then
      tail -n 60 "$work/log"
      echo "the input is in $work (crash-, leak-, timeout- or oom-<hash>); replay: build-asan/fuzz/fuzz_$1 <input>"
    fi
    return "$status"
  }
  failed=0
  for (( i = 0; i < ${#harnesses[@]}; i += 2 )); do
    fuzz_one "${harnesses[i]}" &
    pid=$!
    if (( i + 1 < ${#harnesses[@]} )); then fuzz_one "${harnesses[i + 1]}" || failed=1; fi
    wait "$pid" || failed=1
  done
  if (( failed )); then
    echo "sanitize: fuzzing found an input that fails a harness; see above" >&2
    exit 1
  fi
fi

step "TSan build"
# A unity build like the others: consumer_add_subdirectory (ctest) is the build that compiles every
# library source on its own includes.
cmake -S . -B build-tsan "${common[@]}" -DDEEPCHECK_TSAN=ON -DDEEPCHECK_UNITY_BUILD=ON \
  -DCMAKE_DISABLE_PRECOMPILE_HEADERS=OFF >/dev/null
cmake --build build-tsan -j "$jobs" --target test_checker_concurrency
step "TSan concurrency test"
TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1" \
  build-tsan/tests/test_checker_concurrency --report_level=short --run_test=checker_concurrency

step "passed"
