#pragma once
// Reading untrusted YAML files (robot tables, body files, camera files, observations, plans,
// stereo rigs): one way to load them and one way to say what is wrong, so that every file
// reports a syntax error and a bad number the same way. No exception leaves these functions:
// they answer with a Result whose message names the file (the caller's `where`, e.g.
// "camera file 'cam.yaml': "), the line and the key.
//
// A loader may parse by throwing its own error type deep inside its translation unit and
// turning it into a Result at its entry point; what it gets from core is Results.

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "telear/core/result.hpp"

namespace telear::core {

// "not valid YAML at line 6: end of sequence flow not found" (no line when yaml-cpp has none).
std::string describe_yaml_error(const YAML::Exception& error);

// The document in `text`; error: where + describe_yaml_error(...).
Result<YAML::Node> load_yaml(const std::string& text, const std::string& where);

// The document in the file `path`; errors: "<where>cannot be read" or as load_yaml.
Result<YAML::Node> load_yaml_file(const std::string& path, const std::string& where);

// The finite number in `node`: "<what><separator>must be a number[, got '<text>']" or
// "<what><separator>must be finite, got <text>".
Result<double> yaml_number(const YAML::Node& node, const std::string& what,
                           const std::string& separator = ": ");

// A list of finite numbers: "<what>: must be a list of numbers"; items are named what[i].
Result<std::vector<double>> yaml_numbers(const YAML::Node& node, const std::string& what);

// Exactly three finite numbers: "<what> must be a list of 3 numbers" or yaml_number's message
// for the item what[i].
Result<Eigen::Vector3d> yaml_vector3(const YAML::Node& node, const std::string& what);

// A placement written {xyz: [x, y, z], rpy: [roll, pitch, yaw]} (metres, radians; rpy optional,
// fixed axes x then y then z as in URDF; no other key): "<what> must be a map {xyz: ...}",
// "<what>.xyz: missing", "<what>: unknown key 'k' (expected xyz, rpy)" or the items' messages.
Result<Eigen::Isometry3d> yaml_pose(const YAML::Node& node, const std::string& what);

}  // namespace telear::core
