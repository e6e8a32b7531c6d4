#!/usr/bin/env bash
# scripts/fuzz.sh [--runs N | --seconds S] [HARNESS...]: the libFuzzer harnesses of fuzz/
# (issue 25, docs/fuzzing.md), built with clang-16 and -fsanitize=fuzzer,address,undefined in
# their own build folder (build-fuzz; TELEAR_FUZZ_BUILD_DIR), each run in turn on its committed
# corpus (fuzz/corpus/<door>/, read-only: new inputs go to build-fuzz/corpus/<door>/) with its
# dictionary. A crash, leak, sanitizer report or input slower than 1 s leaves the input under
# fuzz/crashes/<door>/ and the script exits non-zero. Each harness's libFuzzer output, its
# final "Done N runs" line included, is this script's standard output. Default: --runs 100000,
# every harness. Installs clang-16 and its runtime from Debian's packages when missing
# (Debian 12's clang-14 cannot compile the project's std::views against GCC 12's library).
set -euo pipefail
cd "$(dirname "$0")/.."

runs=100000
seconds=""
harnesses=()
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; seconds=""; shift 2 ;;
    --seconds) seconds="$2"; runs=""; shift 2 ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1 (--runs N | --seconds S)" >&2; exit 2 ;;
    *) harnesses+=("$1"); shift ;;
  esac
done
all=$(sed -n 's/^ *telear_fuzz_harness(\([a-z_]*\) .*/\1/p' fuzz/CMakeLists.txt)
[ ${#harnesses[@]} -gt 0 ] || read -r -a harnesses <<< "$(echo $all)"
for h in "${harnesses[@]}"; do
  if ! grep -qx "$h" <<< "$all"; then
    echo "fuzz.sh: no harness '$h' (fuzz/CMakeLists.txt has: $(echo $all))" >&2
    exit 2
  fi
done

# clang-16 with libFuzzer and the sanitizers' runtime, and the project's own packages.
missing=()
command -v clang++-16 > /dev/null || missing+=(clang-16)
compgen -G "/usr/lib/llvm-16/lib/clang/16*/lib/linux/libclang_rt.fuzzer-x86_64.a" > /dev/null ||
  missing+=(libclang-rt-16-dev)
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" = "0" ] || sudo=sudo
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq "${missing[@]}"
fi
scripts/install-deps.sh

dir=${TELEAR_FUZZ_BUILD_DIR:-build-fuzz}
if [ ! -f "$dir/build.ninja" ]; then
  cmake -S . -B "$dir" -G Ninja -DCMAKE_C_COMPILER=clang-16 -DCMAKE_CXX_COMPILER=clang++-16 \
    -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g -fsanitize=fuzzer-no-link" \
    -DTELEAR_SANITIZE=address,undefined -DTELEAR_FUZZ=ON -DTELEAR_BUILD_TESTS=OFF \
    -DTELEAR_BUILD_BENCH=OFF
fi
targets=()
for h in "${harnesses[@]}"; do targets+=(--target "${h}_fuzz"); done
cmake --build "$dir" -j "${TELEAR_JOBS:-2}" "${targets[@]}"

export TELEAR_DATA_DIR="$(pwd)/data"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$(pwd)/scripts/sanitizers/lsan.supp:print_suppressions=0"
limit=("-runs=$runs")
[ -z "$seconds" ] || limit=("-max_total_time=$seconds")
failed=()
for h in "${harnesses[@]}"; do
  mkdir -p "fuzz/crashes/$h" "$dir/corpus/$h"
  dict=()
  case "$h" in
    urdf) dict=(-dict=fuzz/dicts/urdf.dict) ;;
    spec) dict=(-dict=fuzz/dicts/spec.dict) ;;
    mesh) dict=(-dict=fuzz/dicts/mesh.dict) ;;
    jpeg_frame | robot_rpc | vision_messages | ros_camera_info) ;;  # bytes, not words
    *) dict=(-dict=fuzz/dicts/yaml.dict) ;;
  esac
  # An input slower than 1 s is a finding, except on the robot server's door: a plan's time law
  # (core::time_blended_run) runs ~130x slower under the sanitizers' comparison tracing than
  # in the release build (a 3-waypoint Cartesian plan: 4 s here, 30 ms there), so 10 s there.
  timeout=1
  [ "$h" != "robot_rpc" ] || timeout=10
  echo "fuzz.sh: == $h (${limit[*]})"
  status=0
  "$dir/fuzz/${h}_fuzz" "${limit[@]}" -timeout="$timeout" -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="fuzz/crashes/$h/" "${dict[@]}" "$dir/corpus/$h" "fuzz/corpus/$h" 2>&1 ||
    status=$?
  if [ "$status" != "0" ]; then failed+=("$h"); fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz.sh: findings in: ${failed[*]} (inputs under fuzz/crashes/)" >&2
  exit 1
fi
echo "fuzz.sh: no findings in ${harnesses[*]}"
