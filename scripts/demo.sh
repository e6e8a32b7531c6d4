#!/usr/bin/env bash
# The README's main command: install what is missing, build the `telear` binary (not the tests
# or the benchmarks), and run `telear demo` on the embedded default (the simulated PUMA 560 and
# stereo rig behind real gRPC servers on loopback): calibrate and register (cached after the
# first run), rehearse a pick-and-place on the ghost over the live stereo video, preview it,
# execute it on the robot and monitor it.
# Writes out/demo/: demo_stereo.mp4, key frames (PNG), report.md and report.json.
# Extra arguments go to `telear demo` (e.g. --resolution 1280x720 --delay-ms 600).
set -euo pipefail
cd "$(dirname "$0")/.."
TELEAR_TARGETS=telear scripts/build.sh
build_dir=${TELEAR_BUILD_DIR:-build}
"$build_dir/telear" demo --out "${TELEAR_OUT_DIR:-out}/demo" "$@"
