#!/usr/bin/env bash
# The README's main command: install what is missing, build, and run telear on the embedded
# default, the PUMA 560: its geometric model (FK and all IK solutions at the named
# configurations), then the graphical arm drawn through the shipped stereo camera pair.
# Extra arguments go to `telear kin demo`.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build_dir=${TELEAR_BUILD_DIR:-build}
out_dir=${TELEAR_OUT_DIR:-out}
mkdir -p "$out_dir"
"$build_dir/telear" kin demo --robot puma560 "$@"
"$build_dir/telear" render --robot puma560 --q=-30,-50,-40,0,-90,-30 --deg --gripper 0.05 --camera data/cameras/puma560_stereo.yaml \
  --stereo sbs --floor --cube -o "$out_dir/puma560_stereo.png"
"$build_dir/telear" render --robot puma560 --q=-30,-50,-40,0,-90,-30 --deg --gripper 0.05 --camera data/cameras/puma560_stereo.yaml \
  --stereo sbs --floor --cube --wireframe -o "$out_dir/puma560_stereo_wireframe.png"
echo "telear: wrote $out_dir/puma560_stereo.png and $out_dir/puma560_stereo_wireframe.png"
