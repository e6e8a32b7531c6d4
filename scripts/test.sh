#!/usr/bin/env bash
# The README's test command: install what is missing, build, run the whole test suite; then
# the network layer's tests again under AddressSanitizer (issue 5: servers, clients and the
# video pipeline are threaded code). TELEAR_SKIP_ASAN=1 skips that step for local runs; CI
# (.ci/run) always runs it.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build_dir=${TELEAR_BUILD_DIR:-build}
ctest --test-dir "$build_dir" --output-on-failure -j 2

if [ "${TELEAR_SKIP_ASAN:-0}" = "1" ]; then
  echo "test.sh: AddressSanitizer step skipped (TELEAR_SKIP_ASAN=1)"
  exit 0
fi
asan_dir=${TELEAR_ASAN_BUILD_DIR:-build-asan}
if [ ! -f "$asan_dir/build.ninja" ]; then
  # -O1 -g1: ASan's recommended optimisation with line tables only, to keep the 2-core
  # CI build short.
  cmake -S . -B "$asan_dir" -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g1" \
    -DTELEAR_SANITIZE=address -DTELEAR_BUILD_BENCH=OFF
fi
# Only the net test executables (tests/net/CMakeLists.txt), not the whole tree.
cmake --build "$asan_dir" -j "${TELEAR_JOBS:-2}" --target robot_server_test vision_server_test \
  net_client_test
# Leaks are errors; the suppressions name third-party libraries only (Mesa's EGL/llvmpipe,
# LLVM), never telear code. robot_python_example and server_log_level run the telear binary,
# which this step does not build (they ran above, uninstrumented).
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1"
export LSAN_OPTIONS="suppressions=$(pwd)/scripts/sanitizers/lsan.supp:print_suppressions=0"
ctest --test-dir "$asan_dir" --output-on-failure -j 2 -L net -E '^(robot_python_example|server_log_level)$'
