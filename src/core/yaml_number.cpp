#include "telear/core/yaml_number.hpp"

#include <cmath>

namespace telear::core {

double yaml_number(const YAML::Node& node, const std::string& what, const std::string& separator) {
  const std::string field = what + separator;
  if (!node.IsScalar()) throw YamlParseError{field + "must be a number"};
  double value = 0.0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    throw YamlParseError{field + "must be a number, got '" + node.Scalar() + "'"};
  }
  if (!std::isfinite(value)) throw YamlParseError{field + "must be finite, got " + node.Scalar()};
  return value;
}

}  // namespace telear::core
