#include "apps/sim_observations_command.hpp"

#include <ostream>

#include "apps/command_failure.hpp"
#include "telear/sim/marker_observations.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/observations_file.hpp"

namespace telear::cli {
int run_sim_observations(const SimObservationsOptions& options, std::ostream& out,
                         std::ostream& err) {
  const CommandFailure fail{err, "telear sim observations"};
  sim::MarkerObservationsOptions simulation;
  simulation.rig_file = options.rig;
  simulation.robot = options.robot;
  simulation.tip = options.tip;
  auto geometry = options.geometry_options();
  if (!geometry) return fail(geometry.error().message);
  simulation.geometry = *geometry;
  simulation.configurations = options.configs;
  simulation.seed = options.seed;
  simulation.noise_grey = options.noise;
  simulation.supersample = options.supersample;
  simulation.collision_free = options.collision_free;
  simulation.max_view_angle_deg = options.max_view_angle_deg;
  simulation.margin_px = options.margin_px;
  if (Status s = simulation.validate(); !s) return fail(s.error().message);
  if (options.output.empty())
    return fail("-o: give the observations file to write, e.g. -o obs.yaml");
  if (Status s = vision::check_output_path(options.output, "-o"); !s)
    return fail(s.error().message);

  auto result = sim::simulate_marker_observations(
      simulation, [&out](int index, int count, bool left_found, bool right_found) {
        out << "configuration " << index << "/" << count << ": left "
            << (left_found ? "found" : "not found") << ", right "
            << (right_found ? "found" : "not found")
            << (left_found || right_found
                    ? ""
                    : " (skipped: the marker was not detected in either image)")
            << "\n"
            << std::flush;
      });
  if (!result) return fail(result.error().message, 1);
  if (Status s = vision::write_observations_file(result->observations, options.output); !s) {
    return fail(s.error().message, 1);
  }
  out << "wrote " << result->observations.configurations.size() << " configurations to "
      << options.output;
  if (result->skipped > 0) out << " (" << result->skipped << " skipped: marker not detected)";
  out << "\n";
  return 0;
}

}  // namespace telear::cli
