#include "apps/sim_command.hpp"

#include <ostream>

#include "telear/sim/calibration_capture.hpp"

namespace telear::cli {

int run_sim_capture(const SimCaptureOptions& options, std::ostream& out, std::ostream& err) {
  sim::CalibrationCaptureOptions capture;
  capture.rig_file = options.rig;
  capture.pattern = options.pattern;
  capture.views = options.views;
  capture.output_dir = options.output;
  capture.seed = options.seed;
  capture.noise_grey = options.noise;
  capture.supersample = options.supersample;
  capture.show_scene = !options.no_scene;
  if (Status s = capture.validate(); !s) {
    err << "error: " << s.error().message << "\n";
    return 2;
  }
  auto result = sim::capture_calibration_views(
      capture, [&out](int view, int views, const std::string& left, const std::string& right) {
        out << "view " << view << "/" << views << ": " << left << ", " << right << "\n"
            << std::flush;
      });
  if (!result) {
    err << "error: " << result.error().message << "\n";
    return 1;
  }
  out << "wrote " << options.views << " stereo pairs and " << result->truth_file << "\n";
  return 0;
}

}  // namespace telear::cli
