#pragma once
// `telear calibrate`: camera calibration from image sets (docs/calibration.md).
//
//   telear calibrate --left 'DIR/left*.png' [--right 'DIR/right*.png']
//                    --pattern chessboard:COLSxROWS:SQUARE_M -o stereo.yaml
//                    [--model plumb_bob|rational_polynomial|equidistant]
//                    [--report report.json] [--camera-info PREFIX]
//
// The globs are expanded by telear (quote them). One progress line per image or pair goes
// to `out` as it is processed, then the summary table; errors are one line on `err`.
// Outputs are checked before the (slow) detection and written all-or-nothing at the end.
// Exit codes: 0 done, 2 bad input (options, files, too few usable views), 1 a file could not
// be written.

#include <iosfwd>
#include <string>

namespace telear::cli {

struct CalibrateOptions {
  std::string left;                   // glob of the left (or only) camera's images
  std::string right;                  // glob of the right camera's images; empty: mono calibration
  std::string pattern;                // e.g. chessboard:9x6:0.025
  std::string output;                 // camera YAML to write
  std::string report;                 // JSON report to write; empty: none
  std::string camera_info;            // ROS camera_info prefix: PREFIX_left.yaml, PREFIX_right.yaml
                                      // (stereo) or PREFIX.yaml (mono); empty: none
  std::string model = "plumb_bob";    // lens model, a ROS name (parse_distortion_model)
  double outlier_factor = 3.0;        // reject views with error > factor x median; 0 keeps all
  bool estimate_k3 = false;           // free k3 (held at 0 by default)
  bool zero_tangential = false;       // hold p1, p2 at 0
  bool keep_mono_intrinsics = false;  // stereo: fix each camera's mono intrinsics
};

int run_calibrate(const CalibrateOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
