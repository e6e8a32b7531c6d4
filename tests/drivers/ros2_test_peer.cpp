// A ROS 2 arm for the ROS 2 driver's tests, as DDS sees one (docs/ros2.md): a Cyclone DDS
// participant that plays ros2_control's joint_state_broadcaster (sensor_msgs/msg/JointState on
// rt/joint_states) and a JointTrajectoryController's topic interface (trajectory_msgs/msg/
// JointTrajectory on rt/<controller>/joint_trajectory), with the types generated from
// data/ros2/idl and the QoS rmw_cyclonedds gives both (system default: reliable, volatile, keep
// last 1). Written here because Debian packages neither ROS 2 nor ros2_control.
//
//   ros2_test_peer --domain N --joints a,b,c [--initial 0,0,0] [--controller NS|none]
//                  [--joint-states TOPIC] [--ghost-topic TOPIC] [--log FILE]
//                  [--silent-file FILE] [--rate HZ] [--stall-after S]
//
// It publishes the joints in an order of its own (reversed) with an extra joint in the middle,
// as a real robot's joint_states often carries the gripper or other joints, stamped with the
// system clock. A trajectory is checked as the controller's validate_trajectory_msg() checks a
// topic message (ros2_controllers, joint_trajectory_controller.cpp, Humble to Rolling): no
// joint names, no points ("Empty trajectory received."), joints other than its own, times not
// strictly increasing, a point without a position per joint: rejected and ignored, the running
// trajectory goes on. An accepted one replaces the running one at once (header stamp 0: "start
// now") and is followed by interpolating linearly in time from where the arm was to the first
// point, then between the points; a one-point trajectory at time 0 is therefore the
// controller's hold. --controller none: no trajectory subscriber at all. With --stall-after the
// arm stops S seconds into each trajectory and stays there (a blocked arm: the controller's
// topic interface reports nothing, the joint states show it).
//
// --log appends one JSON object per line, receipt times on CLOCK_MONOTONIC (the clock telear's
// servers stamp with, so a test compares them with the server's times):
//   {"event":"trajectory","received_ns":..,"stamp_ns":..,"joint_names":[..],"times_ns":[..],
//    "positions":[[..],..],"velocities":N,"q":[..]}   (q: the arm at receipt, --joints order;
//                                                      velocities: points that carry them)
//   {"event":"rejected","received_ns":..,"reason":".."}
//   {"event":"ghost","received_ns":..,"names":[..],"position":[..]}
//   {"event":"endpoint","kind":"publication"|"subscription","topic":..,"type":..,
//    "reliability":"reliable"|"best_effort","durability":"volatile"|"transient_local",
//    "history_depth":N,"data_representation":[..]}   (every endpoint of another participant
//                                                      on the domain, from DDS discovery)
// While --silent-file exists it publishes no joint states. The first line on stdout is
// "peer ready" once its endpoints exist.

#include <dds/dds.h>
#include <sys/stat.h>
#include <time.h>

#include <algorithm>
#include <array>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "sensor_msgs/msg/dds_/JointState_.h"
#include "trajectory_msgs/msg/dds_/JointTrajectory_.h"

namespace {

volatile std::sig_atomic_t g_stop = 0;

std::int64_t clock_ns(clockid_t clock) {
  timespec now{};
  clock_gettime(clock, &now);
  return std::int64_t{now.tv_sec} * 1'000'000'000 + now.tv_nsec;
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, ',')) parts.push_back(part);
  return parts;
}

bool file_exists(const std::string& path) {
  struct stat info {};
  return !path.empty() && stat(path.c_str(), &info) == 0;
}

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

template <typename T>
std::string json_array(const std::vector<T>& values) {
  std::ostringstream out;
  out.precision(17);
  out << "[";
  for (std::size_t i = 0; i < values.size(); ++i) out << (i ? "," : "") << values[i];
  out << "]";
  return out.str();
}

std::string json_rows(const std::vector<std::vector<double>>& rows) {
  std::string out = "[";
  for (std::size_t k = 0; k < rows.size(); ++k) out += (k ? "," : "") + json_array(rows[k]);
  return out + "]";
}

std::string json_strings(const std::vector<std::string>& values) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) out += (i ? "," : "") + json_string(values[i]);
  return out + "]";
}

struct Options {
  std::uint32_t domain = 0;
  std::vector<std::string> joints;
  std::vector<double> initial;
  std::string controller = "/joint_trajectory_controller";
  std::string joint_states = "/joint_states";
  std::string ghost_topic;
  std::string log;
  std::string silent_file;
  double rate_hz = 100.0;
  double stall_after_s = -1.0;
};

// A trajectory being followed: its points in this arm's joint order.
struct Following {
  std::int64_t start_ns = 0;
  std::vector<double> from;  // the arm when it arrived
  std::vector<std::int64_t> times_ns;
  std::vector<std::vector<double>> points;
};

class Peer {
 public:
  explicit Peer(Options options) : options_(std::move(options)), q_(options_.initial) {}

  ~Peer() {
    if (participant_ > 0) dds_delete(participant_);
  }

  bool create() {
    participant_ = dds_create_participant(options_.domain, nullptr, nullptr);
    if (participant_ < 0) return fail("dds_create_participant", participant_);
    dds_get_guid(participant_, &guid_);
    dds_qos_t* qos = dds_create_qos();
    const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
    dds_qset_data_representation(qos, 1, &xcdr1);
    // rmw_cyclonedds' "system default": reliable, volatile, keep last 1 (its
    // create_readwrite_qos), what joint_state_broadcaster and the controller's subscription use.
    dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_INFINITY);
    dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
    dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 1);
    const dds_entity_t states_topic =
        dds_create_topic(participant_, &sensor_msgs_msg_dds__JointState__desc,
                         ("rt" + options_.joint_states).c_str(), nullptr, nullptr);
    if (states_topic < 0) return fail("dds_create_topic", states_topic);
    states_writer_ = dds_create_writer(participant_, states_topic, qos, nullptr);
    if (states_writer_ < 0) return fail("dds_create_writer", states_writer_);
    waitset_ = dds_create_waitset(participant_);
    if (options_.controller != "none") {
      const dds_entity_t topic = dds_create_topic(
          participant_, &trajectory_msgs_msg_dds__JointTrajectory__desc,
          ("rt" + options_.controller + "/joint_trajectory").c_str(), nullptr, nullptr);
      if (topic < 0) return fail("dds_create_topic", topic);
      trajectory_reader_ = dds_create_reader(participant_, topic, qos, nullptr);
      if (trajectory_reader_ < 0) return fail("dds_create_reader", trajectory_reader_);
      dds_waitset_attach(waitset_, dds_create_readcondition(trajectory_reader_, DDS_ANY_STATE), 0);
    }
    if (!options_.ghost_topic.empty()) {
      // ROS 2's latched: a late subscriber gets the last sample.
      dds_qset_durability(qos, DDS_DURABILITY_TRANSIENT_LOCAL);
      const dds_entity_t topic =
          dds_create_topic(participant_, &sensor_msgs_msg_dds__JointState__desc,
                           ("rt" + options_.ghost_topic).c_str(), nullptr, nullptr);
      if (topic < 0) return fail("dds_create_topic", topic);
      ghost_reader_ = dds_create_reader(participant_, topic, qos, nullptr);
      if (ghost_reader_ < 0) return fail("dds_create_reader", ghost_reader_);
      dds_waitset_attach(waitset_, dds_create_readcondition(ghost_reader_, DDS_ANY_STATE), 0);
    }
    dds_delete_qos(qos);
    publications_ =
        dds_create_reader(participant_, DDS_BUILTIN_TOPIC_DCPSPUBLICATION, nullptr, nullptr);
    subscriptions_ =
        dds_create_reader(participant_, DDS_BUILTIN_TOPIC_DCPSSUBSCRIPTION, nullptr, nullptr);
    if (publications_ < 0 || subscriptions_ < 0) return fail("dds_create_reader (builtin)", -1);
    return true;
  }

  // Follows, publishes and logs at --rate until SIGINT or SIGTERM; between ticks it waits on
  // the trajectory reader, so a trajectory's receipt time is when it arrived.
  void run() {
    const std::int64_t period_ns = static_cast<std::int64_t>(1e9 / options_.rate_hz);
    std::int64_t next_tick = clock_ns(CLOCK_MONOTONIC);
    while (g_stop == 0) {
      if (trajectory_reader_ > 0) take_trajectories();
      if (ghost_reader_ > 0) take_ghost();
      const std::int64_t now = clock_ns(CLOCK_MONOTONIC);
      if (now >= next_tick) {
        follow(now);
        discover(publications_, "publication");
        discover(subscriptions_, "subscription");
        if (!file_exists(options_.silent_file)) publish_state();
        next_tick += period_ns;
        if (next_tick < now) next_tick = now + period_ns;
      }
      // CLOCK_MONOTONIC is Cyclone's dds_time_t base for relative waits: wait the remainder.
      const std::int64_t remaining =
          std::max<std::int64_t>(next_tick - clock_ns(CLOCK_MONOTONIC), 0);
      dds_waitset_wait(waitset_, nullptr, 0, remaining);
    }
  }

 private:
  bool fail(const char* call, dds_return_t code) {
    std::cerr << "ros2_test_peer: " << call << ": " << dds_strretcode(code) << "\n";
    return false;
  }

  void log(const std::string& line) {
    if (options_.log.empty()) return;
    std::ofstream out(options_.log, std::ios::app);
    out << line << "\n";
  }

  void take_trajectories() {
    void* samples[1] = {nullptr};
    dds_sample_info_t info{};
    while (dds_take(trajectory_reader_, samples, &info, 1, 1) > 0) {
      const std::int64_t received = clock_ns(CLOCK_MONOTONIC);
      if (info.valid_data) {
        on_trajectory(*static_cast<trajectory_msgs_msg_dds__JointTrajectory_*>(samples[0]),
                      received);
      }
      dds_return_loan(trajectory_reader_, samples, 1);
    }
  }

  void on_trajectory(const trajectory_msgs_msg_dds__JointTrajectory_& message,
                     std::int64_t received) {
    std::vector<std::string> names;
    for (std::uint32_t i = 0; i < message.joint_names_._length; ++i) {
      names.emplace_back(message.joint_names_._buffer[i]);
    }
    std::vector<std::int64_t> times;
    std::vector<std::vector<double>> positions;
    std::size_t with_velocities = 0;
    for (std::uint32_t k = 0; k < message.points_._length; ++k) {
      const auto& point = message.points_._buffer[k];
      times.push_back(std::int64_t{point.time_from_start_.sec_} * 1'000'000'000 +
                      point.time_from_start_.nanosec_);
      positions.emplace_back(point.positions_._buffer,
                             point.positions_._buffer + point.positions_._length);
      if (point.velocities_._length > 0) ++with_velocities;
    }
    const std::int64_t stamp =
        std::int64_t{message.header_.stamp_.sec_} * 1'000'000'000 + message.header_.stamp_.nanosec_;
    log(R"({"event":"trajectory","received_ns":)" + std::to_string(received) + R"(,"stamp_ns":)" +
        std::to_string(stamp) + R"(,"joint_names":)" + json_strings(names) + R"(,"times_ns":)" +
        json_array(times) + R"(,"positions":)" + json_rows(positions) + R"(,"velocities":)" +
        std::to_string(with_velocities) + R"(,"q":)" + json_array(q_) + "}");
    if (const std::string reason = validate(names, times, positions); !reason.empty()) {
      log(R"({"event":"rejected","received_ns":)" + std::to_string(received) + R"(,"reason":)" +
          json_string(reason) + "}");
      return;
    }
    Following next;
    next.start_ns = received;
    next.from = q_;
    next.times_ns = times;
    for (const auto& point : positions) {
      std::vector<double> ordered(options_.joints.size());
      for (std::size_t j = 0; j < options_.joints.size(); ++j) {
        const auto at = std::find(names.begin(), names.end(), options_.joints[j]);
        ordered[j] = point[static_cast<std::size_t>(at - names.begin())];
      }
      next.points.push_back(ordered);
    }
    following_ = next;
    follow(received);  // a hold at time 0 takes effect now, as in the controller's update
  }

  // The controller's checks of a topic message, in its order; "" when it takes it.
  std::string validate(const std::vector<std::string>& names,
                       const std::vector<std::int64_t>& times,
                       const std::vector<std::vector<double>>& positions) const {
    if (names.size() != options_.joints.size()) {
      return "Joints on incoming trajectory don't match the controller joints.";
    }
    if (names.empty()) return "Empty joint names on incoming trajectory.";
    if (times.empty()) return "Empty trajectory received.";
    for (const std::string& name : names) {
      if (std::find(options_.joints.begin(), options_.joints.end(), name) ==
          options_.joints.end()) {
        return "Incoming joint " + name + " doesn't match the controller's joints.";
      }
    }
    for (std::size_t k = 0; k < times.size(); ++k) {
      if (k > 0 && times[k] <= times[k - 1]) {
        return "Time between points " + std::to_string(k - 1) + " and " + std::to_string(k) +
               " is not strictly increasing";
      }
      if (positions[k].size() != names.size()) {
        return "Mismatch between joint_names size and positions at point " + std::to_string(k);
      }
    }
    return "";
  }

  // Moves q_ along the trajectory being followed: from where the arm was to the first point,
  // then point to point, linearly in time; the last point is held.
  void follow(std::int64_t now) {
    if (!following_) return;
    const Following& f = *following_;
    const std::int64_t t = now - f.start_ns;
    if (options_.stall_after_s >= 0.0 &&
        t >= static_cast<std::int64_t>(options_.stall_after_s * 1e9)) {
      following_.reset();  // stays where it got to
      return;
    }
    std::size_t k = 0;
    while (k < f.times_ns.size() && f.times_ns[k] <= t) ++k;
    if (k == f.times_ns.size()) {
      q_ = f.points.back();
      following_.reset();
      return;
    }
    const std::vector<double>& a = k == 0 ? f.from : f.points[k - 1];
    const std::int64_t t0 = k == 0 ? 0 : f.times_ns[k - 1];
    const double s = static_cast<double>(t - t0) / static_cast<double>(f.times_ns[k] - t0);
    for (std::size_t j = 0; j < q_.size(); ++j) q_[j] = a[j] + (f.points[k][j] - a[j]) * s;
  }

  void publish_state() {
    // Reversed, with a joint the robot description does not have in the middle.
    std::vector<std::string> names;
    std::vector<double> position;
    for (std::size_t j = q_.size(); j-- > 0;) {
      names.push_back(options_.joints[j]);
      position.push_back(q_[j]);
      if (j == q_.size() / 2) {
        names.push_back("extra_conveyor_joint");
        position.push_back(42.0);
      }
    }
    std::vector<double> velocity(position.size(), 0.0);
    std::vector<char*> name_pointers;
    for (std::string& name : names) name_pointers.push_back(name.data());
    const auto length = static_cast<std::uint32_t>(names.size());
    sensor_msgs_msg_dds__JointState_ sample{};
    const std::int64_t stamp = clock_ns(CLOCK_REALTIME);
    sample.header_.stamp_.sec_ = static_cast<std::int32_t>(stamp / 1'000'000'000);
    sample.header_.stamp_.nanosec_ = static_cast<std::uint32_t>(stamp % 1'000'000'000);
    sample.header_.frame_id_ = const_cast<char*>("");
    sample.name_ = {length, length, name_pointers.data(), false};
    sample.position_ = {length, length, position.data(), false};
    sample.velocity_ = {length, length, velocity.data(), false};
    dds_write(states_writer_, &sample);
  }

  void take_ghost() {
    void* samples[1] = {nullptr};
    dds_sample_info_t info{};
    while (dds_take(ghost_reader_, samples, &info, 1, 1) > 0) {
      if (info.valid_data) {
        const auto& sample = *static_cast<sensor_msgs_msg_dds__JointState_*>(samples[0]);
        std::vector<std::string> names;
        for (std::uint32_t i = 0; i < sample.name_._length; ++i) {
          names.emplace_back(sample.name_._buffer[i]);
        }
        const std::vector<double> position(sample.position_._buffer,
                                           sample.position_._buffer + sample.position_._length);
        log(R"({"event":"ghost","received_ns":)" + std::to_string(clock_ns(CLOCK_MONOTONIC)) +
            R"(,"names":)" + json_strings(names) + R"(,"position":)" + json_array(position) + "}");
      }
      dds_return_loan(ghost_reader_, samples, 1);
    }
  }

  // Logs the endpoints DDS discovery reports for other participants, with the type name and
  // the QoS that decide whether a ROS 2 node matches them.
  void discover(dds_entity_t reader, const char* kind) {
    void* samples[1] = {nullptr};
    dds_sample_info_t info{};
    while (dds_take(reader, samples, &info, 1, 1) > 0) {
      const auto& endpoint = *static_cast<dds_builtintopic_endpoint_t*>(samples[0]);
      if (info.valid_data && info.instance_state == DDS_IST_ALIVE &&
          std::memcmp(&endpoint.participant_key, &guid_, sizeof guid_) != 0) {
        dds_reliability_kind_t reliability{};
        dds_duration_t blocking = 0;
        dds_durability_kind_t durability{};
        dds_history_kind_t history{};
        std::int32_t depth = 0;
        uint32_t n = 0;
        dds_data_representation_id_t* representations = nullptr;
        dds_qget_reliability(endpoint.qos, &reliability, &blocking);
        dds_qget_durability(endpoint.qos, &durability);
        dds_qget_history(endpoint.qos, &history, &depth);
        std::vector<int> ids;
        if (dds_qget_data_representation(endpoint.qos, &n, &representations)) {
          for (uint32_t i = 0; i < n; ++i) ids.push_back(representations[i]);
          dds_free(representations);
        }
        log(std::string(R"({"event":"endpoint","kind":")") + kind + R"(","topic":)" +
            json_string(endpoint.topic_name) + R"(,"type":)" + json_string(endpoint.type_name) +
            R"(,"reliability":)" +
            (reliability == DDS_RELIABILITY_RELIABLE ? "\"reliable\"" : "\"best_effort\"") +
            R"(,"durability":)" +
            (durability == DDS_DURABILITY_VOLATILE          ? "\"volatile\""
             : durability == DDS_DURABILITY_TRANSIENT_LOCAL ? "\"transient_local\""
                                                            : "\"other\"") +
            R"(,"history_depth":)" + std::to_string(history == DDS_HISTORY_KEEP_ALL ? -1 : depth) +
            R"(,"data_representation":)" + json_array(ids) + "}");
      }
      dds_return_loan(reader, samples, 1);
    }
  }

  Options options_;
  std::vector<double> q_;
  std::optional<Following> following_;
  dds_entity_t participant_ = 0, states_writer_ = 0, trajectory_reader_ = 0, ghost_reader_ = 0;
  dds_entity_t publications_ = 0, subscriptions_ = 0, waitset_ = 0;
  dds_guid_t guid_{};
};

}  // namespace

int main(int argc, char** argv) {
  Options options;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--domain") {
      options.domain = static_cast<std::uint32_t>(std::stoul(value));
    } else if (flag == "--joints") {
      options.joints = split(value);
    } else if (flag == "--initial") {
      for (const std::string& v : split(value)) options.initial.push_back(std::stod(v));
    } else if (flag == "--controller") {
      options.controller = value;
    } else if (flag == "--joint-states") {
      options.joint_states = value;
    } else if (flag == "--ghost-topic") {
      options.ghost_topic = value;
    } else if (flag == "--log") {
      options.log = value;
    } else if (flag == "--silent-file") {
      options.silent_file = value;
    } else if (flag == "--rate") {
      options.rate_hz = std::stod(value);
    } else if (flag == "--stall-after") {
      options.stall_after_s = std::stod(value);
    } else {
      std::cerr << "ros2_test_peer: unknown option " << flag << "\n";
      return 2;
    }
  }
  if (options.joints.empty()) {
    std::cerr << "ros2_test_peer: --joints is required\n";
    return 2;
  }
  options.initial.resize(options.joints.size(), 0.0);
  std::signal(SIGINT, [](int) { g_stop = 1; });
  std::signal(SIGTERM, [](int) { g_stop = 1; });
  Peer peer(options);
  if (!peer.create()) return 1;
  std::cout << "peer ready" << std::endl;
  peer.run();
  return 0;
}
