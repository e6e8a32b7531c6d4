#!/usr/bin/env bash
# Configures and builds telear (Release, Ninja) into ./build. Extra arguments go to CMake's
# configure step. TELEAR_TARGETS names the targets to build (default: all -- the library, the
# `telear` binary, the tests and the benchmarks); scripts/demo.sh builds `telear` alone.
set -euo pipefail
cd "$(dirname "$0")/.."
"$(pwd)/scripts/install-deps.sh"
# The page's npm packages (web/package-lock.json): three.js, and esbuild, which bundles the
# page into the build folder (`telear web` serves it).
scripts/npm-ci.sh web
build_dir=${TELEAR_BUILD_DIR:-build}
if [ ! -f "$build_dir/build.ninja" ]; then
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
fi
targets=()
for t in ${TELEAR_TARGETS:-}; do targets+=(--target "$t"); done
# Two parallel jobs fit the 2-core, 24 GiB machines this project targets.
cmake --build "$build_dir" -j "${TELEAR_JOBS:-2}" "${targets[@]}"
