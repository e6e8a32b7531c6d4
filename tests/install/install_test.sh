#!/usr/bin/env bash
# The installed package end to end (tests/install/CMakeLists.txt, docs/install.md):
#   1. cmake --install BUILD into a temporary prefix, then move the prefix (it must be
#      relocatable), and check the layout: bin/telear, share/telear/data, the headers (with
#      version.hpp and the generated telear/v1/*.pb.h), the libraries, lib*/cmake/telear;
#   2. configure, build and run examples/consumer against it (CMAKE_PREFIX_PATH only);
#   3. run the INSTALLED telear from another working directory, TELEAR_DATA_DIR unset:
#      --version (same as the build tree's), kin fk on the shipped robot and on a robot that
#      exists only in the installed data directory, sim frame writing both PNGs.
# Everything happens in a temporary directory under WORK_PARENT (in the build tree), removed
# on exit. Any failed step prints what failed and exits non-zero.
#
# usage: install_test.sh BUILD_DIR CONSUMER_SOURCE_DIR TELEAR_FILE WORK_PARENT GENERATOR CXX
#                        [CXX_LAUNCHER]
set -euo pipefail

if [[ $# -lt 6 ]]; then
  echo "usage: $0 BUILD_DIR CONSUMER_SOURCE_DIR TELEAR_FILE WORK_PARENT GENERATOR CXX [LAUNCHER]" >&2
  exit 2
fi
build_dir=$1 consumer_source=$2 telear_file=$3 work_parent=$4 generator=$5 cxx=$6
launcher=${7:-}

fail() {
  echo "install_test: FAILED: $*" >&2
  exit 1
}
step() { echo "install_test: $*"; }
# Runs a command with its output in LOG; on failure prints the log and fails with MESSAGE.
run_logged() {
  local log=$1 message=$2
  shift 2
  if ! "$@" >"$log" 2>&1; then
    cat "$log" >&2
    fail "$message (command: $*)"
  fi
}

[[ -x $telear_file ]] || fail "the telear binary '$telear_file' is not built (ninja -C $build_dir telear)"
unset TELEAR_DATA_DIR

mkdir -p "$work_parent"
work=$(mktemp -d "$work_parent/install_test.XXXXXX")
trap 'rm -rf "$work"' EXIT

# 1. Install, relocate, check the layout.
step "installing $build_dir into $work/staged"
run_logged "$work/install.log" "cmake --install failed" \
  cmake --install "$build_dir" --prefix "$work/staged"
mv "$work/staged" "$work/prefix"
prefix=$work/prefix
telear=$prefix/bin/$(basename "$telear_file")
for f in "$telear" \
         "$prefix/share/telear/data/robots/puma560.yaml" \
         "$prefix/share/telear/data/rigs/puma560_rig.yaml" \
         "$prefix/share/telear/data/cameras/puma560_stereo.yaml" \
         "$prefix/share/telear/web/index.html" \
         "$prefix/share/telear/web/app.js" \
         "$prefix/include/telear/core/robot_loader.hpp" \
         "$prefix/include/telear/core/version.hpp" \
         "$prefix/include/telear/net/robot_service.hpp" \
         "$prefix/include/telear/v1/robot.pb.h" \
         "$prefix/include/telear/v1/robot.grpc.pb.h" \
         "$prefix/include/telear/v1/vision.grpc.pb.h"; do
  [[ -f $f ]] || fail "not installed: ${f#"$prefix"/}"
done
config=$(find "$prefix" -path '*/cmake/telear/telearConfig.cmake' | head -n 1)
[[ -n $config ]] || fail "not installed: lib/cmake/telear/telearConfig.cmake"
libdir=$(dirname "$(dirname "$(dirname "$config")")")
for f in telearConfigVersion.cmake telearTargets.cmake; do
  [[ -f $libdir/cmake/telear/$f ]] || fail "not installed: ${libdir#"$prefix"/}/cmake/telear/$f"
done
for lib in core geometry vision render sim_robot sim_rig proto net session lab console; do
  [[ -f $libdir/libtelear_$lib.a ]] || fail "not installed: ${libdir#"$prefix"/}/libtelear_$lib.a"
done

# 2. The out-of-tree consumer, against the installed package only.
step "building examples/consumer against $prefix"
consumer_args=(-S "$consumer_source" -B "$work/consumer" -G "$generator"
               -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix"
               -DCMAKE_CXX_COMPILER="$cxx")
[[ -n $launcher ]] && consumer_args+=(-DCMAKE_CXX_COMPILER_LAUNCHER="$launcher")
run_logged "$work/consumer-configure.log" "configuring examples/consumer against the package failed" \
  cmake "${consumer_args[@]}"
run_logged "$work/consumer-build.log" "building examples/consumer against the package failed" \
  cmake --build "$work/consumer"
step "running the consumer"
run_logged "$work/consumer-run.log" "the consumer failed" "$work/consumer/telear_consumer"
cat "$work/consumer-run.log"
grep -q "puma560 (6 joints) at qr" "$work/consumer-run.log" ||
  fail "the consumer did not print the PUMA's forward kinematics"

# 3. The installed telear from another directory, no TELEAR_DATA_DIR.
mkdir "$work/elsewhere"
cd "$work/elsewhere"
step "running $telear from $PWD"

run_logged "$work/version.log" "telear --version failed" "$telear" --version
version=$(cat "$work/version.log")
[[ $version =~ ^telear\ [0-9]+\.[0-9]+\.[0-9]+ ]] ||
  fail "telear --version printed '$version', expected 'telear MAJOR.MINOR.PATCH ...'"
build_version=$("$telear_file" --version)
[[ $version == "$build_version" ]] ||
  fail "installed telear --version '$version' differs from the build's '$build_version'"
echo "$version"

run_logged "$work/fk.log" "telear kin fk --robot puma560 --q qr --json failed" \
  "$telear" kin fk --robot puma560 --q qr --json
grep -q '"T_base_tool"' "$work/fk.log" ||
  fail "telear kin fk --json printed no T_base_tool: $(cat "$work/fk.log")"

# A robot only the installed data directory has: found through <bin>/../share/telear/data,
# not through the source tree the build recorded.
sed 's/^name: puma560$/name: install_test_arm/' "$prefix/share/telear/data/robots/puma560.yaml" \
  >"$prefix/share/telear/data/robots/install_test_arm.yaml"
run_logged "$work/fk_installed.log" \
  "telear did not find a robot in its installed data directory $prefix/share/telear/data" \
  "$telear" kin fk --robot install_test_arm --q qr --json
cmp -s "$work/fk.log" "$work/fk_installed.log" ||
  fail "the same robot under another name gave other FK: $(cat "$work/fk.log") vs $(cat "$work/fk_installed.log")"

run_logged "$work/frame.log" "telear sim frame --q qr -o frame failed" \
  "$telear" sim frame --q qr -o frame
for eye in left right; do
  [[ -s frame_$eye.png ]] || fail "telear sim frame did not write frame_$eye.png in $PWD"
done

# The browser operator's page, found beside the installed program (not in the build tree).
timeout 8 "$telear" web --listen 127.0.0.1:0 > "$work/web.out" 2> "$work/web.err" || true
grep -q "^listening on http://127.0.0.1:" "$work/web.out" ||
  fail "the installed telear web did not start: $(cat "$work/web.out" "$work/web.err")"
grep -q "the page from $prefix/share/telear/web" "$work/web.err" ||
  fail "the installed telear web did not serve its installed page: $(cat "$work/web.err")"

step "passed"
