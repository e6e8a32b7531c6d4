#pragma once
// Reading untrusted YAML files (robot tables, body files, camera files, observations, plans,
// stereo rigs): one way to load them and one way to say what is wrong, so that every file
// reports a syntax error and a bad number the same way. The functions that answer with a Result
// throw nothing; the message names the file (the caller's `where`, e.g.
// "camera file 'cam.yaml': "), the line and the key.
//
// A reader that parses by throwing deep inside its translation unit throws YamlFieldError
// (the *_or_throw helpers below) and turns it into a Result once, at its entry point, with
// catch_yaml_errors: one error type and one catch for every reader.

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <set>
#include <string>
#include <utility>
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

// Every key of the map `node` is one of `allowed`: "<what>: unknown key 'k' (expected a, b)"
// (the allowed keys in sorted order; no "<what>: " when `what` is empty).
Status check_yaml_keys(const YAML::Node& node, const std::set<std::string>& allowed,
                       const std::string& what);

// [SECTION] Parsing by throwing

// What a reader throws for a bad field; catch_yaml_errors turns it into a Result. The message
// names the field, not the file (catch_yaml_errors prefixes the file).
struct YamlFieldError {
  std::string message;
};

// The value of `result`, or throws YamlFieldError with its message.
template <typename T>
T value_or_throw(Result<T> result) {
  if (!result) throw YamlFieldError{result.error().message};
  return std::move(*result);
}

// Throws YamlFieldError with the message of a failed `status`.
void ok_or_throw(const Status& status);

// yaml_number and yaml_numbers, throwing YamlFieldError with their messages.
double number_or_throw(const YAML::Node& node, const std::string& what,
                       const std::string& separator = ": ");
std::vector<double> numbers_or_throw(const YAML::Node& node, const std::string& what);

// Runs `parse` (returning T or Result<T>) and answers with its result; a YamlFieldError or a
// yaml-cpp exception (a bad conversion deep in the reader) becomes Error{where + message}, the
// latter worded by describe_yaml_error. Nothing is thrown past it.
template <typename T, typename Parse>
Result<T> catch_yaml_errors(const std::string& where, Parse&& parse) {
  try {
    return std::forward<Parse>(parse)();
  } catch (const YamlFieldError& e) {
    return Error{where + e.message};
  } catch (const YAML::Exception& e) {
    return Error{where + describe_yaml_error(e)};
  }
}

}  // namespace telear::core
