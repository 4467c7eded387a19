#!/usr/bin/env bash
# The sanitizer stage of CI (docs/testing.md), run from the repository root after the normal
# build and tests:
#   1. build-asan: AddressSanitizer + UndefinedBehaviorSanitizer (-fno-sanitize-recover=all: the
#      first report fails the run) build of the deep, robots and checker unit tests and of the fuzz
#      harnesses (as corpus replay drivers, or libFuzzer binaries with Clang); runs the tests and
#      replays every committed corpus input.
#   2. build-tsan: ThreadSanitizer build of the checker's concurrency suite alone; runs it.
# The long randomized sweeps of test_deep (see SANITIZE_DEEP_SKIP) run in the normal build only:
# under ASan they alone would take longer than the rest of CI.
#
# Environment: JOBS (parallel build jobs, default: the number of cores).
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

# test_deep suites and cases left to the normal build (minutes of randomized sweeps under ASan).
SANITIZE_DEEP_SKIP='!deep_random:!deep_hard_cases/spheres_with_2000_vertices:!fast_paths/overlaps_unchecked_equals_overlaps'

step() { printf '\n== sanitize: %s\n' "$*"; }

step "ASan+UBSan build"
asan="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
cmake -S . -B build-asan "${common[@]}" -DDEEPCHECK_BUILD_FUZZERS=ON \
  "-DCMAKE_CXX_FLAGS=$asan" "-DCMAKE_EXE_LINKER_FLAGS=$asan" >/dev/null
cmake --build build-asan -j "$jobs" --target test_deep test_robots test_checker \
  fuzz_pd_input fuzz_urdf fuzz_mesh fuzz_config_lines fuzz_moveit_scene

export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# suite <name> <args...>: runs one sanitized suite and prints its output, as one block, when it ends.
suite() {
  local out status=0
  out=$("build-asan/tests/$1" "${@:2}" 2>&1) || status=$?
  printf -- '-- %s (exit status %d)\n%s\n' "$1" "$status" "$out"
  return "$status"
}

step "ASan+UBSan unit tests"
# test_deep (the longest) runs beside test_robots and test_checker: on two cores or more the stage
# takes the time of the longer side; on one, the two sides share it.
failed=0
suite test_deep --report_level=short "--run_test=$SANITIZE_DEEP_SKIP" &
deep_pid=$!
suite test_robots --report_level=short || failed=1
suite test_checker --report_level=short || failed=1
wait "$deep_pid" || failed=1
if (( failed )); then
  echo "sanitize: a sanitized suite failed; its output is above" >&2
  exit 1
fi
step "ASan+UBSan corpus replay"
ctest --test-dir build-asan -R '^fuzz_replay_' --output-on-failure

step "TSan build"
# Without precompiled headers: deep, robots and checker's sources must compile on their own includes.
cmake -S . -B build-tsan "${common[@]}" -DDEEPCHECK_TSAN=ON -DCMAKE_DISABLE_PRECOMPILE_HEADERS=ON >/dev/null
cmake --build build-tsan -j "$jobs" --target test_checker_concurrency
step "TSan concurrency test"
TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1" \
  build-tsan/tests/test_checker_concurrency --report_level=short --run_test=checker_concurrency

step "passed"
