#include "telear/session/plan.hpp"

#include "telear/core/yaml_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <cassert>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#include "telear/core/joint_limits.hpp"
#include "telear/core/number_format.hpp"
#include "telear/session/ghost_arm.hpp"

namespace telear::session {
namespace {

std::string waypoint_name(std::size_t index) {
  return "waypoint[" + std::to_string(index) + "]";
}

void reject_unknown_keys(const YAML::Node& map, const std::set<std::string>& known,
                         const std::string& where) {
  for (const auto& entry : map) {
    const std::string key = entry.first.as<std::string>();
    if (known.count(key) == 0) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw core::YamlFieldError{where + (where.empty() ? "" : ".") + key +
                                 ": unknown key (known: " + list + ")"};
    }
  }
}

// An optional true / false key (false when absent).
bool flag(const YAML::Node& map, const char* key, const std::string& name) {
  const YAML::Node node = map[key];
  if (!node) return false;
  if (!node.IsScalar() || (node.Scalar() != "true" && node.Scalar() != "false")) {
    throw core::YamlFieldError{name + "." + key + ": must be true or false"};
  }
  return node.Scalar() == "true";
}

}  // namespace

Plan::Plan(core::RobotModelPtr model) : model_(std::move(model)) {
  assert(model_ && "Plan: model must not be null");
}

Status Plan::check_waypoint(const PlanWaypoint& w, const std::string& where) const {
  if (w.q.size() != model_->dof()) {
    return Error{where + ": expected " + std::to_string(model_->dof()) + " joint values, got " +
                 std::to_string(w.q.size())};
  }
  for (int j = 0; j < model_->dof(); ++j) {
    if (!std::isfinite(w.q[j])) {
      return Error{where + ": " + core::joint_label(*model_, j) + " is not finite (NaN or inf)"};
    }
  }
  if (const auto violation = core::first_limit_violation(*model_, w.q)) {
    return Error{where + ": " + core::describe_violation(*model_, *violation)};
  }
  if (!std::isfinite(w.min_duration) || w.min_duration < 0.0 ||
      w.min_duration > options_.max_segment_duration) {
    return Error{where + ": min_duration " + core::format_number(w.min_duration) +
                 " s is outside 0.." + core::format_number(options_.max_segment_duration) + " s"};
  }
  if (w.gripper && (!std::isfinite(*w.gripper) || *w.gripper < 0.0 || *w.gripper > 1.0)) {
    return Error{where + ": gripper opening " + core::format_number(*w.gripper) +
                 " is outside 0 (closed) .. 1 (open)"};
  }
  return Status::Ok();
}

Status Plan::check_index(std::size_t index, const char* what) const {
  if (index >= waypoints_.size()) {
    return Error{std::string(what) + ": no " + waypoint_name(index) + " (the plan has " +
                 std::to_string(waypoints_.size()) + " waypoints)"};
  }
  return Status::Ok();
}

Status Plan::add(PlanWaypoint waypoint, std::optional<std::size_t> index) {
  const std::size_t at = index.value_or(waypoints_.size());
  if (at > waypoints_.size()) {
    return Error{"add: cannot insert at " + waypoint_name(at) + " (the plan has " +
                 std::to_string(waypoints_.size()) + " waypoints)"};
  }
  if (Status s = check_waypoint(waypoint, "add: " + waypoint_name(at)); !s) return s;
  if (static_cast<int>(waypoints_.size()) >= options_.max_waypoints) {
    return Error{"add: the plan already has the maximum of " +
                 std::to_string(options_.max_waypoints) + " waypoints"};
  }
  waypoints_.insert(waypoints_.begin() + static_cast<std::ptrdiff_t>(at), std::move(waypoint));
  return Status::Ok();
}

Status Plan::add_from(const GhostArm& ghost, double min_duration, std::string label,
                      bool with_gripper, std::optional<std::size_t> index) {
  assert(ghost.model().dof() == model_->dof() && "Plan::add_from(): ghost of another model");
  PlanWaypoint w;
  w.q = ghost.q();
  if (with_gripper) w.gripper = ghost.gripper();
  w.min_duration = min_duration;
  w.label = std::move(label);
  return add(std::move(w), index);
}

Status Plan::replace(std::size_t index, PlanWaypoint waypoint) {
  return replace_as(index, std::move(waypoint), "replace");
}

Status Plan::replace_as(std::size_t index, PlanWaypoint waypoint, const char* what) {
  if (Status s = check_index(index, what); !s) return s;
  if (Status s = check_waypoint(waypoint, std::string(what) + ": " + waypoint_name(index)); !s) {
    return s;
  }
  waypoints_[index] = std::move(waypoint);
  return Status::Ok();
}

Status Plan::remove(std::size_t index) {
  if (Status s = check_index(index, "remove"); !s) return s;
  waypoints_.erase(waypoints_.begin() + static_cast<std::ptrdiff_t>(index));
  return Status::Ok();
}

Status Plan::move(std::size_t from, std::size_t to) {
  if (Status s = check_index(from, "move"); !s) return s;
  if (Status s = check_index(to, "move"); !s) return s;
  PlanWaypoint w = std::move(waypoints_[from]);
  waypoints_.erase(waypoints_.begin() + static_cast<std::ptrdiff_t>(from));
  waypoints_.insert(waypoints_.begin() + static_cast<std::ptrdiff_t>(to), std::move(w));
  return Status::Ok();
}

Status Plan::set_min_duration(std::size_t index, double seconds) {
  if (Status s = check_index(index, "set duration"); !s) return s;
  PlanWaypoint w = waypoints_[index];
  w.min_duration = seconds;
  return replace_as(index, std::move(w), "set duration");
}

Status Plan::set_gripper(std::size_t index, std::optional<double> opening) {
  if (Status s = check_index(index, "set gripper"); !s) return s;
  PlanWaypoint w = waypoints_[index];
  w.gripper = opening;
  return replace_as(index, std::move(w), "set gripper");
}

Status Plan::set_label(std::size_t index, std::string label) {
  if (Status s = check_index(index, "set label"); !s) return s;
  waypoints_[index].label = std::move(label);
  return Status::Ok();
}

Status Plan::set_scales(double velocity_scale, double acceleration_scale) {
  for (const auto& [name, value] :
       {std::pair{"velocity_scale", velocity_scale}, {"acceleration_scale", acceleration_scale}}) {
    if (!std::isfinite(value) || value <= 0.0 || value > 1.0) {
      return Error{std::string(name) + " " + core::format_number(value) + " is outside (0, 1]"};
    }
  }
  options_.velocity_scale = velocity_scale;
  options_.acceleration_scale = acceleration_scale;
  return Status::Ok();
}

std::vector<core::JointWaypoint> Plan::joint_waypoints() const {
  std::vector<core::JointWaypoint> list;
  list.reserve(waypoints_.size());
  for (const PlanWaypoint& w : waypoints_) {
    list.emplace_back(w.q, w.min_duration, w.gripper, w.via).cartesian = w.cartesian;
  }
  return list;
}

Result<core::Trajectory> Plan::trajectory() const {
  if (waypoints_.empty()) return Error{"the plan is empty; add at least one waypoint"};
  return core::Trajectory::create(*model_, joint_waypoints(), options_);
}

Result<core::TimedWaypoints> Plan::timed_waypoints(double rate_hz) const {
  auto trajectory = this->trajectory();
  if (!trajectory) return trajectory.error();
  return trajectory->sampled(rate_hz);
}

std::string Plan::to_yaml() const {
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::BeginMap;
  out << YAML::Key << "robot" << YAML::Value << model_->name();
  out << YAML::Key << "velocity_scale" << YAML::Value << options_.velocity_scale;
  out << YAML::Key << "acceleration_scale" << YAML::Value << options_.acceleration_scale;
  out << YAML::Key << "waypoints" << YAML::Value << YAML::BeginSeq;
  for (const PlanWaypoint& w : waypoints_) {
    out << YAML::Flow << YAML::BeginMap;
    if (!w.label.empty()) out << YAML::Key << "label" << YAML::Value << w.label;
    out << YAML::Key << "q_rad" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (int j = 0; j < w.q.size(); ++j) out << w.q[j];
    out << YAML::EndSeq;
    if (w.gripper) out << YAML::Key << "gripper" << YAML::Value << *w.gripper;
    if (w.min_duration != 0.0)
      out << YAML::Key << "min_duration_s" << YAML::Value << w.min_duration;
    if (w.via) out << YAML::Key << "via" << YAML::Value << true;
    if (w.cartesian) out << YAML::Key << "cartesian" << YAML::Value << true;
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

Result<Plan> Plan::from_yaml(core::RobotModelPtr model, const std::string& text,
                             const std::string& source) {
  const std::string where = "plan '" + source + "': ";
  const auto loaded = core::load_yaml(text, where);
  if (!loaded) return loaded.error();
  const YAML::Node& root = *loaded;
  return core::catch_yaml_errors<Plan>(where, [&]() -> Result<Plan> {
    Plan plan(std::move(model));
    if (!root.IsMap()) throw core::YamlFieldError{"expected a map with robot and waypoints"};
    reject_unknown_keys(root, {"robot", "velocity_scale", "acceleration_scale", "waypoints"}, "");
    if (!root["robot"] || !root["robot"].IsScalar()) {
      throw core::YamlFieldError{
          "robot: missing (the model's name, e.g. robot: " + plan.model().name() + ")"};
    }
    const std::string robot = root["robot"].Scalar();
    if (robot != plan.model().name()) {
      throw core::YamlFieldError{"robot: the plan is for '" + robot +
                                 "', not for the loaded model '" + plan.model().name() + "'"};
    }
    const double velocity_scale =
        root["velocity_scale"] ? core::number_or_throw(root["velocity_scale"], "velocity_scale")
                               : 1.0;
    const double acceleration_scale =
        root["acceleration_scale"]
            ? core::number_or_throw(root["acceleration_scale"], "acceleration_scale")
            : 1.0;
    if (Status s = plan.set_scales(velocity_scale, acceleration_scale); !s) {
      throw core::YamlFieldError{s.error().message};
    }
    const YAML::Node list = root["waypoints"];
    if (!list) throw core::YamlFieldError{"waypoints: missing"};
    if (list.IsNull()) return plan;  // an empty plan is a valid file
    if (!list.IsSequence()) throw core::YamlFieldError{"waypoints: must be a list"};
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string name = waypoint_name(i);
      const YAML::Node node = list[i];
      if (!node.IsMap()) throw core::YamlFieldError{name + ": must be a map with q_rad"};
      reject_unknown_keys(node, {"label", "q_rad", "gripper", "min_duration_s", "via", "cartesian"},
                          name);
      PlanWaypoint w;
      const YAML::Node q = node["q_rad"];
      if (!q) throw core::YamlFieldError{name + ".q_rad: missing"};
      if (!q.IsSequence()) throw core::YamlFieldError{name + ".q_rad: must be a list of numbers"};
      if (static_cast<int>(q.size()) != plan.model().dof()) {
        throw core::YamlFieldError{name + ".q_rad: expected " + std::to_string(plan.model().dof()) +
                                   " numbers, got " + std::to_string(q.size())};
      }
      w.q.resize(plan.model().dof());
      for (int j = 0; j < plan.model().dof(); ++j) {
        w.q[j] = core::number_or_throw(q[static_cast<std::size_t>(j)],
                                       name + ".q_rad[" + std::to_string(j) + "]");
      }
      if (node["gripper"]) w.gripper = core::number_or_throw(node["gripper"], name + ".gripper");
      if (node["min_duration_s"]) {
        w.min_duration = core::number_or_throw(node["min_duration_s"], name + ".min_duration_s");
      }
      w.via = flag(node, "via", name);
      w.cartesian = flag(node, "cartesian", name);
      if (node["label"]) {
        if (!node["label"].IsScalar()) throw core::YamlFieldError{name + ".label: must be text"};
        w.label = node["label"].Scalar();
      }
      if (Status s = plan.check_waypoint(w, name); !s)
        throw core::YamlFieldError{s.error().message};
      if (Status s = plan.add(std::move(w)); !s) throw core::YamlFieldError{s.error().message};
    }
    return plan;
  });
}

Status Plan::save(const std::string& path) const {
  std::ofstream file(path);
  if (!file) return Error{"plan '" + path + "': cannot be written"};
  file << "# telear plan (docs/session.md): joint waypoints in radians, durations in seconds\n"
       << to_yaml();
  file.flush();
  if (!file) return Error{"plan '" + path + "': write failed"};
  return Status::Ok();
}

Result<Plan> Plan::load(core::RobotModelPtr model, const std::string& path) {
  std::ifstream file(path);
  if (!file) return Error{"plan '" + path + "': cannot be opened"};
  std::ostringstream text;
  text << file.rdbuf();
  return from_yaml(std::move(model), text.str(), path);
}

}  // namespace telear::session
