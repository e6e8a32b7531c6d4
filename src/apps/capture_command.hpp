#pragma once
// `telear capture`: record a capture folder for registration through running servers
// (telear/session/registration_capture.hpp, docs/registration.md).
//
//   telear capture --robot HOST:PORT --vision HOST:PORT --token-file F --arm puma560
//                  --poses auto:20 -o captures/
//
// --poses is auto:N (poses chosen around the arm's current pose, where both cameras must see
// the marker) or a YAML file of joint vectors (`poses: [[q1..qn], ...]`, radians). Prints one
// line per pose; exit codes: 0 done, 2 bad input (one line on `err`), 1 the capture failed.
//
// --manual: the operator jogs the arm and confirms each pose, reading commands from `in`
// (telear/session/capture_session.hpp, docs/registration.md "Manual capture"):
//   j N D      jog joint N (from 1) by D degrees (mm for a prismatic joint)
//   x|y|z D    move the tool D mm along the base's axis
//   a, Enter   add the pose the arm is at (at rest)       s   solve with the poses so far
//   q, EOF     finish: the coverage image and how to register          h   the commands
// Exit codes: 0 at least one pose added, 1 none (or the servers failed), 2 bad input.

#include <iosfwd>
#include <string>

#include "telear/geometry/robot_selection.hpp"

namespace telear::cli {

struct CaptureOptions : geometry::RobotSelection {
  std::string robot_server;  // HOST:PORT
  std::string vision_server;
  std::string token_file;
  std::string poses = "auto:20";
  std::string output;
  int frames = 3;
  double speed = 0.3;
  double settle_s = 0.3;
  unsigned seed = 1;
  bool manual = false;  // the operator's poses, commands from stdin
  std::string target;   // --target SPEC (vision/registration_target.hpp); empty: the marker
};

int run_capture(const CaptureOptions& options, std::ostream& out, std::ostream& err);
// --manual with its commands read from `in` (run_capture passes std::cin).
int run_manual_capture(const CaptureOptions& options, std::istream& in, std::ostream& out,
                       std::ostream& err);

}  // namespace telear::cli
