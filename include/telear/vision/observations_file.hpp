#pragma once
// Registration observations: what the cameras saw of points fixed to the robot's flange, at a
// number of joint configurations (docs/registration.md). `telear register` reads them; the
// simulator (`telear sim observations`) and, later, the console's operator clicks write them.
//
// A point fixed to the flange has known coordinates p_flange in the flange frame -- the frame
// of the last link, T_base_link[n], *before* the tool transform T_flange_tool -- so at joint
// configuration q it lies at p_base = T_base_link[n](q) * p_flange, and the camera sees it at
// pixel project(T_cam_base * p_base). Pixels are raw (distorted) image pixels in OpenCV's
// convention (centre of the top-left pixel = (0, 0)).
//
// File format (YAML, plain lists; `#` comments allowed):
//
//   telear_observations: 1          # format version (required, = 1)
//   robot: puma560                  # optional, informational (checked against --robot's dof)
//   point_in_flange:                # P >= 1 points, metres, flange frame
//     - [-0.025, -0.025, 0.10]      #   e.g. the 4 corners of an ArUco marker, in the order of
//     - [ 0.025, -0.025, 0.10]      #   cv::aruco (top-left, top-right, bottom-right,
//     - [ 0.025,  0.025, 0.10]      #   bottom-left), or one point: the tool tip
//     - [-0.025,  0.025, 0.10]
//   configurations:                 # N entries
//     - q: [0.1, -0.7, 0.2, 0.0, 0.5, 0.3]   # rad, one value per joint
//       left:  [[u, v], [u, v], [u, v], [u, v]]   # P pixels, same order as point_in_flange
//       right: [[u, v], [u, v], [u, v], [u, v]]
//     - q: [...]
//       left: [[u, v], ...]
//       right: []                   # not seen by this eye: an empty list (or the key omitted)
//
// An eye's list is either empty (the marker was not found in that image) or has exactly P
// pixels; partial detections are not stored. The operator-assisted path is the same file with
// one point_in_flange (the tool tip) and one clicked pixel per eye and configuration.
//
// Every malformed input is a Result error "observations '<source>': <where>: <why>", e.g.
// "observations 'obs.yaml': configurations[3].left: 3 pixels, but point_in_flange has 4".

#include <Eigen/Core>
#include <string>
#include <vector>

#include "telear/core/result.hpp"

namespace telear::vision {

// One joint configuration and what each eye saw there. An empty eye vector: not seen.
struct ObservedConfiguration {
  Eigen::VectorXd q;                         // rad
  std::vector<Eigen::Vector2d> left_pixels;  // empty or point_in_flange.size()
  std::vector<Eigen::Vector2d> right_pixels;
};

struct RegistrationObservations {
  std::string robot;                             // optional, informational
  std::vector<Eigen::Vector3d> point_in_flange;  // metres, flange frame
  std::vector<ObservedConfiguration> configurations;
};

// Checks counts and finiteness (the rules above; q sizes are checked against the robot by
// the registration). Used by the parser and by callers that build observations in memory.
Status validate_observations(const RegistrationObservations& observations,
                             const std::string& source);

Result<RegistrationObservations> parse_observations_yaml(const std::string& text,
                                                         const std::string& source);
Result<RegistrationObservations> load_observations_file(const std::string& path);

// YAML text in the format above (full double precision), which parse_observations_yaml
// reads back to the same values.
std::string observations_yaml(const RegistrationObservations& observations);
// Writes it atomically (temporary file + rename); errors name the path.
Status write_observations_file(const RegistrationObservations& observations,
                               const std::string& path);

}  // namespace telear::vision
