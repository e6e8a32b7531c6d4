#include "telear/vision/observations_file.hpp"

#include "telear/core/number_format.hpp"
#include "telear/core/yaml_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "telear/vision/calibration_file.hpp"

namespace telear::vision {
namespace {

std::vector<Eigen::Vector2d> pixels(const YAML::Node& node, const std::string& what) {
  std::vector<Eigen::Vector2d> result;
  if (!node || node.IsNull()) return result;
  if (!node.IsSequence()) throw core::YamlFieldError{what + ": must be a list of [u, v] pixels"};
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string item = what + "[" + std::to_string(i) + "]";
    const std::vector<double> uv = core::numbers_or_throw(node[i], item);
    if (uv.size() != 2) {
      throw core::YamlFieldError{item + ": a pixel is [u, v], got " + std::to_string(uv.size()) +
                                 " numbers"};
    }
    result.emplace_back(uv[0], uv[1]);
  }
  return result;
}

std::string pixel_list(const std::vector<Eigen::Vector2d>& list) {
  std::string text = "[";
  for (std::size_t i = 0; i < list.size(); ++i) {
    text += (i == 0 ? "[" : ", [") + core::format_number(list[i].x(), "%.17g") + ", " +
            core::format_number(list[i].y(), "%.17g") + "]";
  }
  return text + "]";
}

}  // namespace

Status validate_observations(const RegistrationObservations& observations,
                             const std::string& source) {
  const std::string where = "observations '" + source + "': ";
  const std::size_t points = observations.point_in_flange.size();
  if (points == 0) {
    return Error{where + "point_in_flange: empty; give at least one point fixed to the flange"};
  }
  for (std::size_t i = 0; i < points; ++i) {
    if (!observations.point_in_flange[i].allFinite()) {
      return Error{where + "point_in_flange[" + std::to_string(i) + "]: not finite (NaN or inf)"};
    }
  }
  if (observations.configurations.empty()) {
    return Error{where + "configurations: empty; give at least 3 joint configurations"};
  }
  for (std::size_t c = 0; c < observations.configurations.size(); ++c) {
    const ObservedConfiguration& configuration = observations.configurations[c];
    const std::string at = where + "configurations[" + std::to_string(c) + "]";
    if (configuration.q.size() == 0) return Error{at + ".q: missing or empty"};
    if (!configuration.q.allFinite()) return Error{at + ".q: not finite (NaN or inf)"};
    if (configuration.q.size() != observations.configurations[0].q.size()) {
      return Error{at + ".q: " + std::to_string(configuration.q.size()) +
                   " joint values, but configurations[0] has " +
                   std::to_string(observations.configurations[0].q.size())};
    }
    for (const char* eye : {"left", "right"}) {
      const auto& list =
          std::string(eye) == "left" ? configuration.left_pixels : configuration.right_pixels;
      if (!list.empty() && list.size() != points) {
        return Error{at + "." + eye + ": " + std::to_string(list.size()) +
                     " pixels, but point_in_flange has " + std::to_string(points) +
                     " (list every point in order, or none when the eye did not see them)"};
      }
      for (std::size_t i = 0; i < list.size(); ++i) {
        if (!list[i].allFinite()) {
          return Error{at + "." + eye + "[" + std::to_string(i) + "]: not finite (NaN or inf)"};
        }
      }
    }
  }
  return Status::Ok();
}

Result<RegistrationObservations> parse_observations_yaml(const std::string& text,
                                                         const std::string& source) {
  const std::string where = "observations '" + source + "': ";
  const auto loaded = core::load_yaml(text, where);
  if (!loaded) return loaded.error();
  auto parsed = core::catch_yaml_errors<RegistrationObservations>(where, [&] {
    RegistrationObservations observations;
    const YAML::Node& root = *loaded;
    if (!root.IsMap())
      throw core::YamlFieldError{"the file must be a YAML map (docs/registration.md)"};
    const YAML::Node version = root["telear_observations"];
    if (!version) {
      throw core::YamlFieldError{
          "telear_observations: missing (the format version, 1); is this an "
          "observations file?"};
    }
    if (core::number_or_throw(version, "telear_observations") != 1.0) {
      throw core::YamlFieldError{"telear_observations: unsupported version " + version.Scalar() +
                                 " (this telear reads 1)"};
    }
    if (const YAML::Node robot = root["robot"]) {
      if (!robot.IsScalar()) throw core::YamlFieldError{"robot: must be a name"};
      observations.robot = robot.Scalar();
    }
    const YAML::Node points = root["point_in_flange"];
    if (!points)
      throw core::YamlFieldError{"point_in_flange: missing (the points' flange coordinates, m)"};
    if (!points.IsSequence())
      throw core::YamlFieldError{"point_in_flange: must be a list of [x, y, z]"};
    for (std::size_t i = 0; i < points.size(); ++i) {
      const std::string item = "point_in_flange[" + std::to_string(i) + "]";
      const std::vector<double> xyz = core::numbers_or_throw(points[i], item);
      if (xyz.size() != 3) {
        throw core::YamlFieldError{item + ": a point is [x, y, z], got " +
                                   std::to_string(xyz.size()) + " numbers"};
      }
      observations.point_in_flange.emplace_back(xyz[0], xyz[1], xyz[2]);
    }
    const YAML::Node configurations = root["configurations"];
    if (!configurations) throw core::YamlFieldError{"configurations: missing"};
    if (!configurations.IsSequence()) throw core::YamlFieldError{"configurations: must be a list"};
    for (std::size_t c = 0; c < configurations.size(); ++c) {
      const std::string at = "configurations[" + std::to_string(c) + "]";
      const YAML::Node entry = configurations[c];
      if (!entry.IsMap()) throw core::YamlFieldError{at + ": must be a map with q, left, right"};
      if (!entry["q"]) throw core::YamlFieldError{at + ".q: missing (joint values, rad)"};
      const std::vector<double> q = core::numbers_or_throw(entry["q"], at + ".q");
      ObservedConfiguration configuration;
      configuration.q =
          Eigen::Map<const Eigen::VectorXd>(q.data(), static_cast<Eigen::Index>(q.size()));
      configuration.left_pixels = pixels(entry["left"], at + ".left");
      configuration.right_pixels = pixels(entry["right"], at + ".right");
      observations.configurations.push_back(std::move(configuration));
    }
    return observations;
  });
  if (!parsed) return parsed;
  if (Status status = validate_observations(*parsed, source); !status) return status.error();
  return parsed;
}

Result<RegistrationObservations> load_observations_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{"cannot open observations file '" + path + "'"};
  std::ostringstream text;
  text << in.rdbuf();
  return parse_observations_yaml(text.str(), path);
}

std::string observations_yaml(const RegistrationObservations& observations) {
  std::string text =
      "# telear registration observations (docs/registration.md): pixels of points fixed to "
      "the\n# flange, per joint configuration (rad) and eye.\ntelear_observations: 1\n";
  if (!observations.robot.empty()) text += "robot: " + observations.robot + "\n";
  text += "point_in_flange:\n";
  for (const Eigen::Vector3d& p : observations.point_in_flange) {
    text += "  - [" + core::format_number(p.x(), "%.17g") + ", " +
            core::format_number(p.y(), "%.17g") + ", " + core::format_number(p.z(), "%.17g") +
            "]\n";
  }
  text += "configurations:\n";
  for (const ObservedConfiguration& configuration : observations.configurations) {
    text += "  - q: [";
    for (Eigen::Index j = 0; j < configuration.q.size(); ++j) {
      text += (j == 0 ? "" : ", ") + core::format_number(configuration.q[j], "%.17g");
    }
    text += "]\n    left: " + pixel_list(configuration.left_pixels) + "\n";
    text += "    right: " + pixel_list(configuration.right_pixels) + "\n";
  }
  return text;
}

Status write_observations_file(const RegistrationObservations& observations,
                               const std::string& path) {
  return write_files_atomically({{path, observations_yaml(observations)}});
}

}  // namespace telear::vision
