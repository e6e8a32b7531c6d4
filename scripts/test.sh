#!/usr/bin/env bash
# The README's test command: install what is missing, build, run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build_dir=${TELEAR_BUILD_DIR:-build}
ctest --test-dir "$build_dir" --output-on-failure -j 2
