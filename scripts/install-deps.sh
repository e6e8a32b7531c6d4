#!/usr/bin/env bash
# Installs the Debian 12 packages telear builds against, skipping those already present; with
# --tests, also what only the tests need (Chromium, which drives the browser operator's page).
# Idempotent: a second run with everything installed returns at once without apt-get.
set -euo pipefail

packages=(
  # toolchain
  cmake ninja-build g++ pkg-config clang-format
  # the linker: mold links telear and the test executables much faster than ld.bfd
  mold
  # core: math, robot descriptions, file formats
  libeigen3-dev liburdfdom-dev libtinyxml-dev libyaml-cpp-dev nlohmann-json3-dev
  # core: SHA-256 of plans (libcrypto)
  libssl-dev
  # geometry: mesh files (STL, COLLADA, OBJ); collision checking and distances (FCL 0.7)
  libassimp-dev libfcl-dev
  # geometry: a level of detail for fine visual meshes (edge-collapse simplification)
  libmeshoptimizer-dev
  # apps
  libcli11-dev libspdlog-dev
  # vision: camera models, distortion maps, calibration; hand-eye bundle adjustment (Ceres)
  libopencv-dev libceres-dev
  # render: GL headers and loader, headless EGL with Mesa's llvmpipe, GLFW windows, stb images
  libgl-dev libegl-dev libepoxy-dev libegl-mesa0 libgl1-mesa-dri libglfw3-dev libstb-dev libpng-dev
  # net: gRPC services and clients, TurboJPEG for the video stream; the Python example client
  libgrpc++-dev libprotobuf-dev protobuf-compiler protobuf-compiler-grpc libturbojpeg0-dev
  libjpeg62-turbo-dev python3-grpcio python3-grpc-tools python3-protobuf
  # console: Dear ImGui (GLFW + OpenGL3 backends); Xvfb for window tests without a display
  libimgui-dev xvfb xauth
  # tests and benchmarks (Orocos KDL is the benchmark baseline; kdl_parser the URDF FK reference)
  libgtest-dev libgmock-dev libbenchmark-dev liborocos-kdl-dev libkdl-parser-dev
  # drivers: ROS 1 (docs/ros.md): roscpp, actionlib, the message headers and definitions, the
  # generators for control_msgs (genmsg, gencpp); the tests' rosmaster, rostopic and
  # image_publisher, the Python message modules rostopic prints with
  libroscpp-dev libactionlib-dev libactionlib-msgs-dev libsensor-msgs-dev libtrajectory-msgs-dev
  libgeometry-msgs-dev libstd-msgs-dev libvisualization-msgs-dev
  ros-std-msgs ros-trajectory-msgs ros-actionlib-msgs ros-geometry-msgs ros-sensor-msgs
  ros-visualization-msgs python3-genmsg python3-gencpp ros-message-generation
  python3-rosmaster python3-rostopic python3-rospy python3-sensor-msgs python3-std-msgs
  python3-visualization-msgs python3-geometry-msgs python3-tf2-msgs ros-robot-state-publisher
  ros-image-publisher
  # the camera tests (tests/drivers/ros1_camera_test.py): image_publisher is a nodelet, which
  # pluginlib finds only through its own and nodelet's package.xml (in these two); PIL writes
  # the test images and decodes the served JPEGs
  libimage-publisher-dev libnodeletlib-tools python3-pil
  # drivers: ROS 2 over DDS (docs/ros2.md): Cyclone DDS's C library and its IDL compiler (idlc)
  cyclonedds-dev cyclonedds-tools
  # tests: the shipped arms' check (tests/data/check_arms.py) reads the robot files
  python3-yaml
  # tests: OpenCV's real stereo chessboard images (examples/data), ~95 MB, not needed to build
  opencv-doc
  # record: libzstd compresses MCAP chunks; node runs the reference MCAP reader (tests/record/js)
  libzstd-dev nodejs
  # report: gnuplot draws a recording's plots (its pngcairo terminal), fed through
  # gnuplot-iostream (header-only, over Boost.Iostreams, which it brings in)
  gnuplot-nox libgnuplot-iostream-dev
)
# web: Boost.Beast (HTTP and WebSocket, header-only) for `telear web`; HTTPS through libssl
packages+=(libboost-dev)
if [ "${1:-}" = "--tests" ]; then
  # tests/web: the page in a real browser (driven by npm's playwright-core)
  packages+=(chromium)
fi
# npm: Debian's package, unless the installed nodejs already brings it (NodeSource's does, and
# conflicts with Debian's npm).
command -v npm > /dev/null 2>&1 || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "telear: all ${#packages[@]} Debian packages already installed"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then
    sudo_cmd=(sudo)
  else
    echo "telear: need root or sudo to install: ${missing[*]}" >&2
    exit 1
  fi
fi

echo "telear: installing ${#missing[@]} missing Debian packages: ${missing[*]}"
"${sudo_cmd[@]}" apt-get update -q
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
