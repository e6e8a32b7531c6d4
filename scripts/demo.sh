#!/usr/bin/env bash
# The README's main command: install what is missing, build, run telear on the embedded
# default (the PUMA 560). Until `telear demo` exists this shows the arm's geometric model.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build_dir=${TELEAR_BUILD_DIR:-build}
"$build_dir/telear" kin demo --robot puma560 "$@"
