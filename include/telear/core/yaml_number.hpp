#pragma once
// Reading numbers from untrusted YAML files (robot tables, camera files, observations,
// plans): one reader so every file says the same thing about a bad number.
//
// The loaders parse by throwing YamlParseError deep inside and turning it into a Result at
// their entry point; the message names the field (`what`) and says why.

#include <yaml-cpp/yaml.h>

#include <string>

namespace telear::core {

struct YamlParseError {
  std::string message;
};

// The finite number in `node`; throws YamlParseError "<what><separator>must be a number
// [, got '<text>']" or "...must be finite, got <text>".
double yaml_number(const YAML::Node& node, const std::string& what,
                   const std::string& separator = ": ");

}  // namespace telear::core
