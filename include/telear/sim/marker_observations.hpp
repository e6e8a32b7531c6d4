#pragma once
// Registration observations from the simulated robot and stereo rig (docs/registration.md):
// what `telear sim observations` writes, and a step of the demo's calibration pipeline
// (include/telear/lab/calibration_pipeline.hpp).
//
// Draws seeded random in-limit joint configurations (with collision_free, only those free of
// contact between the arm's links and with the rig's scene, as the robot server would accept
// them: the demo's capture starts at one) and keeps those at which the gripper's ArUco marker
// (include/telear/sim/calibration_targets.hpp) faces both cameras -- its face normal within
// `max_view_angle_deg` of the direction to each optical centre -- and all four corners project,
// with the true cameras, at least `margin_px` inside both images. At each kept configuration the
// "real" images are rendered per eye (include/telear/sim/ scene_renderer.hpp: true distortion,
// sensor noise) and the marker's corners are DETECTED with cv::aruco (DICT_4X4_50), as on a real
// rig, then refined to sub-pixel precision on the black border's outer edges
// (include/telear/vision/marker_detection.hpp). An eye where the marker is not found gets an empty
// pixel list; a configuration seen by neither eye is skipped and counted. point_in_flange are the
// marker's corners in the flange frame, in detection order. Needs OpenGL (the function creates a
// headless context). Single-threaded.

#include <cstdint>
#include <functional>
#include <string>

#include "telear/core/result.hpp"
#include "telear/geometry/robot_geometry.hpp"
#include "telear/vision/observations_file.hpp"

namespace telear::sim {

struct MarkerObservationsOptions {
  std::string rig_file;                // sim::load_stereo_rig's YAML
  std::string robot = "puma560";       // the kinematics of the observations (and of the scene)
  std::string tip;                     // the robot's tip link when its URDF has several leaves
  geometry::GeometryOptions geometry;  // --package-path, --missing-meshes
  int configurations = 20;             // configurations to render, 1..500
  std::uint64_t seed = 1;              // configurations and sensor noise
  double noise_grey = 1.0;             // sensor noise, grey levels (Gaussian sigma), 0..50
  int supersample = 4;                 // anti-aliasing factor per axis, 1..8
  double max_view_angle_deg = 55.0;
  double margin_px = 20.0;
  // Only configurations free of contact (the arm's links with each other, with the rig's
  // scene), checked as the robot server checks them. Off by default: the registration tests'
  // figures and the shipped observations were drawn without it.
  bool collision_free = false;

  // Errors name the field (as the CLI option) and the violated range.
  Status validate() const;
};

struct MarkerObservations {
  vision::RegistrationObservations observations;
  int skipped = 0;  // configurations where neither eye detected the marker
};

// Called after each configuration is rendered: index from 1, count, found per eye.
using ObservationProgress =
    std::function<void(int index, int count, bool left_found, bool right_found)>;

// Errors: invalid options, the rig, robot or body (naming them), no OpenGL context, too few
// configurations facing both cameras (check the rig's pose), or the marker detected nowhere.
Result<MarkerObservations> simulate_marker_observations(const MarkerObservationsOptions& options,
                                                        const ObservationProgress& progress = {});

}  // namespace telear::sim
