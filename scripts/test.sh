#!/usr/bin/env bash
# The README's test command: install what is missing, build, run the whole test suite; then
# the network layer's tests again under AddressSanitizer (issue 5: servers, clients and the
# video pipeline are threaded code). TELEAR_SKIP_ASAN=1 skips that step for local runs; CI
# (.ci/run) always runs it. Each stage's wall time is printed at the end (issue 20: the next
# regression of the loop shows in every CI log).
set -euo pipefail
cd "$(dirname "$0")/.."

stage_names=()
stage_seconds=()
stage_start=0
begin_stage() { stage_start=$(date +%s); echo "test.sh: == $1"; }
end_stage() {
  stage_names+=("$1")
  stage_seconds+=($(($(date +%s) - stage_start)))
}
print_stages() {
  echo "test.sh: stage wall times (s):"
  local total=0
  for i in "${!stage_names[@]}"; do
    printf '  %-16s %5d\n' "${stage_names[$i]}" "${stage_seconds[$i]}"
    total=$((total + stage_seconds[i]))
  done
  printf '  %-16s %5d\n' "total" "$total"
}
trap print_stages EXIT

begin_stage "build"
# The tests' own packages first (Chromium for the page's tests, tests/web); build.sh adds the
# rest.
scripts/install-deps.sh --tests
scripts/build.sh
end_stage "build"
# The reference MCAP reader's npm packages (tests/record/js, pinned by its lock file; ~2 s),
# skipped while node_modules holds what that lock file names.
begin_stage "npm ci"
scripts/npm-ci.sh tests/record/js
end_stage "npm ci"
build_dir=${TELEAR_BUILD_DIR:-build}
asan_dir=${TELEAR_ASAN_BUILD_DIR:-build-asan}
asan=1
if [ "${TELEAR_SKIP_ASAN:-0}" = "1" ]; then
  asan=0
  echo "test.sh: AddressSanitizer step skipped (TELEAR_SKIP_ASAN=1)"
fi

# The fuzz harnesses whose layers this tree has (fuzz/CMakeLists.txt): their corpora and saved
# findings replayed under ASan, so that a fixed leak stays fixed (the GCC replays above catch
# crashes only; docs/fuzzing.md).
asan_fuzz=(robot_file urdf workspace camera_file jpeg_frame robot_rpc vision_messages mesh)
asan_fuzz_targets=()
for h in "${asan_fuzz[@]}"; do asan_fuzz_targets+=(--target "${h}_fuzz_replay"); done

# The AddressSanitizer tree: -O1 -g1, ASan's recommended optimisation with line tables only.
# Unity batches and precompiled headers as in the main tree (the Eigen allocator mismatch with
# Debian's uninstrumented Ceres is settled in CMakeLists.txt). Only the net test executable
# (tests/net/CMakeLists.txt) and the fuzz replays above: the network layer, the simulated
# robot driver and the net tests are compiled instrumented; core, geometry, vision and the
# protoc-generated messages are linked from the main tree's build, uninstrumented
# (TELEAR_PREBUILT_LAYERS; two thirds of this tree's compile time). Their code's own memory
# errors are therefore not looked for here (the fuzz harnesses compile all of it instrumented,
# docs/fuzzing.md); leaks anywhere still are (ASan intercepts every allocation).
asan_build() {
  if [ ! -f "$asan_dir/build.ninja" ]; then
    cmake -S . -B "$asan_dir" -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g1" \
      -DTELEAR_SANITIZE=address -DTELEAR_BUILD_BENCH=OFF \
      -DTELEAR_PREBUILT_DIR="$(cd "$build_dir" && pwd)" -DTELEAR_PREBUILT_LAYERS="core;geometry;vision;proto"
  fi
  cmake --build "$asan_dir" -j "${TELEAR_JOBS:-2}" --target net_test "${asan_fuzz_targets[@]}"
}

# Tests wait on servers, heartbeats and the simulated robot's real-time motion as much as they
# compute, so CTest runs more of them than there are cores (TELEAR_TEST_JOBS overrides). The
# ASan tree builds meanwhile at the lowest priority (nice 19), on the CPU time the tests leave
# idle; whatever is left is built after them, at full priority.
begin_stage "tests"
asan_log="$build_dir/asan-build-during-tests.log"
asan_pid=""
asan_begin=$(date +%s)
if [ "$asan" = "1" ]; then
  (
    renice -n 19 -p "$BASHPID" > /dev/null
    asan_build
    date +%s > "$asan_log.end"
  ) > "$asan_log" 2>&1 &
  asan_pid=$!
fi
tests_status=0
ctest --test-dir "$build_dir" --output-on-failure -j "${TELEAR_TEST_JOBS:-3}" || tests_status=$?
end_stage "tests"
if [ "$tests_status" != "0" ]; then
  [ -n "$asan_pid" ] && kill "$asan_pid" 2> /dev/null
  exit "$tests_status"
fi
[ "$asan" = "1" ] || exit 0

# The rest of the ASan build, if any, now at full priority (a failed build shows its log).
begin_stage "asan build rest"
asan_status=0
wait "$asan_pid" || asan_status=$?
cat "$asan_log"
[ "$asan_status" = "0" ] || exit "$asan_status"
end_stage "asan build rest"
echo "test.sh: the ASan build took $(($(cat "$asan_log.end") - asan_begin)) s from the tests' start"
# Leaks are errors; the suppressions name third-party libraries only, never telear code.
# robot_python_example and server_log_level run the telear binary, which this step does not
# build (they ran above, uninstrumented).
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1"
export LSAN_OPTIONS="suppressions=$(pwd)/scripts/sanitizers/lsan.supp:print_suppressions=0"
begin_stage "asan tests"
ctest --test-dir "$asan_dir" --output-on-failure -j 2 -L '^net$' \
  -E '^(robot_python_example|server_log_level)$'
ctest --test-dir "$asan_dir" --output-on-failure -j 2 \
  -R "^fuzz_replay\.($(IFS='|'; echo "${asan_fuzz[*]}"))\$"
end_stage "asan tests"
