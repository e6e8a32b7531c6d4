#pragma once
// ROS 2 names as DDS sees them (docs/ros2.md): a ROS topic /x/y is the DDS topic rt/x/y (the
// "rt" prefix rmw_cyclonedds gives every ROS topic; services are rq/ and rr/), and the ROS domain
// is the DDS domain, $ROS_DOMAIN_ID by default. Only absolute names are taken: telear is no ROS
// node, so it has no namespace to resolve a relative name or ~ in.

#include <cstdint>
#include <string>

#include "telear/core/result.hpp"

namespace telear::drivers::ros2 {

// Whether `name` is an absolute ROS 2 name: /token[/token...], each token letters, digits and
// underscores, not starting with a digit.
bool is_absolute_ros_name(const std::string& name);

// "rt" + name for an absolute ROS 2 topic name; an error naming `what` otherwise.
Result<std::string> dds_topic_name(const std::string& ros_name, const std::string& what);

// The DDS domain: `option` when it is not -1, else $ROS_DOMAIN_ID (`environment`, null when
// unset), else 0. ROS 2 allows 0..232 (DDS's port mapping ends there).
Result<std::uint32_t> resolve_domain_id(int option, const char* environment);

}  // namespace telear::drivers::ros2
