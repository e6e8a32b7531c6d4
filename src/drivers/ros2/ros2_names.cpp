#include "drivers/ros2/ros2_names.hpp"

#include <cctype>
#include <charconv>

namespace telear::drivers::ros2 {
namespace {

constexpr int kMaxDomainId = 232;

bool token_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

}  // namespace

bool is_absolute_ros_name(const std::string& name) {
  if (name.size() < 2 || name.front() != '/' || name.back() == '/') return false;
  bool token_start = true;
  for (std::size_t i = 1; i < name.size(); ++i) {
    const char c = name[i];
    if (c == '/') {
      if (token_start) return false;  // "//"
      token_start = true;
      continue;
    }
    if (!token_char(c)) return false;
    if (token_start && std::isdigit(static_cast<unsigned char>(c)) != 0) return false;
    token_start = false;
  }
  return true;
}

Result<std::string> dds_topic_name(const std::string& ros_name, const std::string& what) {
  if (!is_absolute_ros_name(ros_name)) {
    return Error{what +
                 " must be an absolute ROS 2 name (/name/name..., letters, digits and _, "
                 "no name starting with a digit), got '" +
                 ros_name + "'"};
  }
  return "rt" + ros_name;
}

Result<std::uint32_t> resolve_domain_id(int option, const char* environment) {
  if (option != -1) {
    if (option < 0 || option > kMaxDomainId) {
      return Error{"the ROS domain id must be 0.." + std::to_string(kMaxDomainId) + ", got " +
                   std::to_string(option)};
    }
    return static_cast<std::uint32_t>(option);
  }
  if (environment == nullptr || *environment == '\0') return std::uint32_t{0};
  const std::string text(environment);
  int value = -1;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < 0 ||
      value > kMaxDomainId) {
    return Error{"$ROS_DOMAIN_ID must be a domain id 0.." + std::to_string(kMaxDomainId) +
                 ", got '" + text + "'"};
  }
  return static_cast<std::uint32_t>(value);
}

}  // namespace telear::drivers::ros2
