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

#include <iosfwd>
#include <string>

#include "apps/robot_arguments.hpp"

namespace telear::cli {

struct CaptureOptions : RobotArguments {
  std::string robot_server;  // HOST:PORT
  std::string vision_server;
  std::string token_file;
  std::string poses = "auto:20";
  std::string output;
  int frames = 3;
  double speed = 0.3;
  double settle_s = 0.3;
  unsigned seed = 1;
};

int run_capture(const CaptureOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
