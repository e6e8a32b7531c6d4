#pragma once
// `telear eval`: accuracy of a calibration + registration against ground truth
// (docs/registration.md, "Accuracy against ground truth"; issue 4 items 6 and 7).
//
//   telear eval --truth truth.yaml --estimate stereo.yaml --robot puma560 [--json report.json]
//
// Both files are stereo camera files with T_cam_base for both eyes (the truth: the
// simulator's truth.yaml; the estimate: `telear register`'s output). Prints the table:
// per eye fx, fy, cx, cy, k1, k2, k3, p1, p2 truth / estimate / error (% for focal lengths,
// px for the principal point), the stereo baseline (mm), the registration error per eye
// (mm, deg), the overlay error RMS / max per eye (px, telear/vision/overlay_accuracy.hpp), and PASS
// or FAIL against the targets of include/telear/vision/accuracy_check.hpp (whose JSON
// --json writes). Exit codes: 0 evaluated (whatever the verdict), 2 bad
// input (one line on `err`), 1 the JSON could not be written.

#include <iosfwd>
#include <string>

#include "telear/geometry/robot_selection.hpp"

namespace telear::cli {

struct EvalOptions : geometry::RobotSelection {
  std::string truth;
  std::string estimate;
  std::string json;         // report to write; empty: none
  int configurations = 60;  // random arm configurations of the overlay (plus the named ones)
  double spacing_m = 0.01;  // sample spacing along the body's edges
};

int run_eval(const EvalOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
