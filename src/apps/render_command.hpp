#pragma once
// `telear render`: the arm at one configuration, drawn headless (EGL) through a calibrated
// camera -- or a default view of the whole arm -- optionally on a video frame, mono or
// stereo, written as PNG (docs/cameras.md, docs/cli.md).
//
//   telear render --robot puma560 --q qn --camera data/cameras/puma560_stereo.yaml
//                 --stereo sbs --background left.png,right.png -o out.png
//
// Every bad input (missing or malformed file, wrong joint count, unreadable image, a size
// mismatch, an option out of range) is one line on `err` and exit code 2; a GL failure is
// exit code 1.

#include <iosfwd>
#include <optional>
#include <string>

#include "telear/geometry/robot_selection.hpp"

namespace telear::cli {

struct RenderOptions : geometry::RobotSelection {
  std::string q;  // joint values q1,...,qn (rad, or deg with degrees) or a name
  bool degrees = false;
  std::string camera;  // camera file (mono or stereo), or left.yaml,right.yaml; empty: default
  std::string eye;     // left | right | both; empty: both for a stereo camera, else left
  std::string stereo = "sbs";  // sbs | tb | anaglyph | separate, when both eyes are drawn
  std::string background;      // image for every eye, or left.png,right.png
  bool wireframe = false;
  int segments = 0;               // > 0: every cylinder gets this many segments
  std::optional<double> gripper;  // opening, m
  double alpha = 1.0;             // < 1: ghost
  bool undistort = false;         // undistorted overlay mode (default: raw)
  bool floor = false;             // a checkered floor at z = 0
  bool cube = false;              // the seed's cube on the floor in front of the arm
  bool no_arm = false;            // the scene without the arm (e.g. to make a background)
  int width = 640;                // image size of the default view (no camera, no background)
  int height = 480;
  std::string output;  // PNG; with --stereo separate, NAME_left.png / NAME_right.png
};

int run_render(const RenderOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
