#include "drivers/ros2/dds_link.hpp"

#include <dds/dds.h>
#include <time.h>

#include <array>
#include <optional>
#include <thread>
#include <utility>

#include "sensor_msgs/msg/dds_/JointState_.h"
#include "trajectory_msgs/msg/dds_/JointTrajectory_.h"

namespace telear::drivers::ros2 {
namespace {

using JointState = sensor_msgs_msg_dds__JointState_;
using JointTrajectory = trajectory_msgs_msg_dds__JointTrajectory_;
using JointTrajectoryPoint = trajectory_msgs_msg_dds__JointTrajectoryPoint_;

// What a waitset trigger was attached with.
enum Attached : dds_attach_t { kJointStates = 1, kJointStatesMatched, kTrajectoryMatched, kStop };

std::string dds_error(const char* call, dds_return_t code) {
  return std::string(call) + ": " + dds_strretcode(code);
}

std::int64_t realtime_ns() {
  timespec now{};
  clock_gettime(CLOCK_REALTIME, &now);
  return std::int64_t{now.tv_sec} * 1'000'000'000 + now.tv_nsec;
}

// A QoS object freed on scope exit.
struct Qos {
  dds_qos_t* qos = dds_create_qos();
  Qos() {
    // XCDR1 only, as rmw_cyclonedds: a writer offering XCDR2 would match no ROS 2 reader.
    const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
    dds_qset_data_representation(qos, 1, &xcdr1);
  }
  ~Qos() { dds_delete_qos(qos); }
  Qos(const Qos&) = delete;
  Qos& operator=(const Qos&) = delete;
};

// Views of telear's vectors as the generated sequences (not owned: _release false, so nothing
// is freed by DDS; valid while the vectors are).
dds_sequence_double double_view(const std::vector<double>& values) {
  return {static_cast<std::uint32_t>(values.size()), static_cast<std::uint32_t>(values.size()),
          const_cast<double*>(values.data()), false};
}

dds_sequence_string string_view(std::vector<char*>& values) {
  return {static_cast<std::uint32_t>(values.size()), static_cast<std::uint32_t>(values.size()),
          values.data(), false};
}

std::vector<char*> c_strings(const std::vector<std::string>& strings) {
  std::vector<char*> pointers;
  pointers.reserve(strings.size());
  for (const std::string& s : strings) pointers.push_back(const_cast<char*>(s.c_str()));
  return pointers;
}

builtin_interfaces_msg_dds__Time_ ros_time(std::int64_t ns) {
  return {static_cast<std::int32_t>(ns / 1'000'000'000),
          static_cast<std::uint32_t>(ns % 1'000'000'000)};
}

JointStateMessage copy_joint_state(const JointState& sample) {
  JointStateMessage message;
  message.stamp_ns = std::int64_t{sample.header_.stamp_.sec_} * 1'000'000'000 +
                     std::int64_t{sample.header_.stamp_.nanosec_};
  for (std::uint32_t i = 0; i < sample.name_._length; ++i) {
    const char* name = sample.name_._buffer[i];
    message.name.emplace_back(name != nullptr ? name : "");
  }
  message.position.assign(sample.position_._buffer,
                          sample.position_._buffer + sample.position_._length);
  message.velocity.assign(sample.velocity_._buffer,
                          sample.velocity_._buffer + sample.velocity_._length);
  return message;
}

}  // namespace

class Link::Participant {
 public:
  Participant(LinkOptions options, JointStatesHandler on_state, LogHandler log)
      : options_(std::move(options)), on_state_(std::move(on_state)), log_(std::move(log)) {}

  ~Participant() {
    if (stop_ > 0) dds_set_guardcondition(stop_, true);
    if (thread_.joinable()) thread_.join();
    if (participant_ > 0) dds_delete(participant_);  // and everything created in it
  }

  bool create(std::string* error) {
    participant_ = dds_create_participant(options_.domain_id, nullptr, nullptr);
    if (participant_ < 0) {
      *error = "cannot join DDS domain " + std::to_string(options_.domain_id) + " (" +
               dds_error("dds_create_participant", participant_) + "; check $CYCLONEDDS_URI)";
      return false;
    }
    const dds_entity_t states_topic =
        dds_create_topic(participant_, &sensor_msgs_msg_dds__JointState__desc,
                         options_.joint_states_topic.c_str(), nullptr, nullptr);
    const dds_entity_t trajectory_topic =
        dds_create_topic(participant_, &trajectory_msgs_msg_dds__JointTrajectory__desc,
                         options_.trajectory_topic.c_str(), nullptr, nullptr);
    const dds_entity_t ghost_topic =
        dds_create_topic(participant_, &sensor_msgs_msg_dds__JointState__desc,
                         options_.ghost_topic.c_str(), nullptr, nullptr);
    for (const dds_entity_t topic : {states_topic, trajectory_topic, ghost_topic}) {
      if (topic < 0) return fail("dds_create_topic", topic, error);
    }
    {
      Qos qos;
      dds_qset_reliability(qos.qos, DDS_RELIABILITY_BEST_EFFORT, 0);
      dds_qset_durability(qos.qos, DDS_DURABILITY_VOLATILE);
      dds_qset_history(qos.qos, DDS_HISTORY_KEEP_LAST, 1);
      states_reader_ = dds_create_reader(participant_, states_topic, qos.qos, nullptr);
      if (states_reader_ < 0) return fail("dds_create_reader", states_reader_, error);
    }
    {
      Qos qos;
      dds_qset_reliability(qos.qos, DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
      dds_qset_durability(qos.qos, DDS_DURABILITY_VOLATILE);
      dds_qset_history(qos.qos, DDS_HISTORY_KEEP_LAST, 10);
      trajectory_writer_ = dds_create_writer(participant_, trajectory_topic, qos.qos, nullptr);
      if (trajectory_writer_ < 0) return fail("dds_create_writer", trajectory_writer_, error);
    }
    {
      Qos qos;
      dds_qset_reliability(qos.qos, DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
      dds_qset_durability(qos.qos, DDS_DURABILITY_TRANSIENT_LOCAL);
      dds_qset_history(qos.qos, DDS_HISTORY_KEEP_LAST, 1);
      ghost_writer_ = dds_create_writer(participant_, ghost_topic, qos.qos, nullptr);
      if (ghost_writer_ < 0) return fail("dds_create_writer", ghost_writer_, error);
    }
    // The waitset: new joint states, the two topics' matches, and the stop.
    waitset_ = dds_create_waitset(participant_);
    stop_ = dds_create_guardcondition(participant_);
    const dds_entity_t data = dds_create_readcondition(states_reader_, DDS_ANY_STATE);
    if (waitset_ < 0) return fail("dds_create_waitset", waitset_, error);
    if (stop_ < 0) return fail("dds_create_guardcondition", stop_, error);
    if (data < 0) return fail("dds_create_readcondition", data, error);
    dds_set_status_mask(states_reader_, DDS_SUBSCRIPTION_MATCHED_STATUS);
    dds_set_status_mask(trajectory_writer_, DDS_PUBLICATION_MATCHED_STATUS);
    const std::array<std::pair<dds_entity_t, dds_attach_t>, 4> attachments{{
        {data, kJointStates},
        {states_reader_, kJointStatesMatched},
        {trajectory_writer_, kTrajectoryMatched},
        {stop_, kStop},
    }};
    for (const auto& [entity, what] : attachments) {
      if (dds_return_t r = dds_waitset_attach(waitset_, entity, what); r < 0) {
        return fail("dds_waitset_attach", r, error);
      }
    }
    log_("joined DDS domain " + std::to_string(options_.domain_id) + ": reading " +
         options_.joint_states_topic + ", writing " + options_.trajectory_topic + " and " +
         options_.ghost_topic);
    thread_ = std::thread([this] { run(); });
    return true;
  }

  int trajectory_subscribers() const {
    const dds_return_t n = dds_get_matched_subscriptions(trajectory_writer_, nullptr, 0);
    return n < 0 ? 0 : static_cast<int>(n);
  }

  bool publish_trajectory(const TrajectoryMessage& message) {
    std::vector<char*> names = c_strings(message.joint_names);
    std::vector<JointTrajectoryPoint> points(message.times_ns.size());
    for (std::size_t k = 0; k < points.size(); ++k) {
      const std::int64_t t = message.times_ns[k];
      points[k] = JointTrajectoryPoint{};
      points[k].positions_ = double_view(message.positions[k]);
      points[k].time_from_start_ = {static_cast<std::int32_t>(t / 1'000'000'000),
                                    static_cast<std::uint32_t>(t % 1'000'000'000)};
    }
    JointTrajectory sample{};
    sample.header_.frame_id_ = const_cast<char*>("");
    sample.joint_names_ = string_view(names);
    sample.points_ = {static_cast<std::uint32_t>(points.size()),
                      static_cast<std::uint32_t>(points.size()), points.data(), false};
    if (const dds_return_t r = dds_write(trajectory_writer_, &sample); r < 0) {
      log_("could not write " + options_.trajectory_topic + " (" + dds_error("dds_write", r) + ")");
      return false;
    }
    return true;
  }

  void publish_ghost(const std::vector<std::string>& names, const std::vector<double>& position) {
    std::vector<char*> pointers = c_strings(names);
    JointState sample{};
    sample.header_.stamp_ = ros_time(realtime_ns());
    sample.header_.frame_id_ = const_cast<char*>("");
    sample.name_ = string_view(pointers);
    sample.position_ = double_view(position);
    if (const dds_return_t r = dds_write(ghost_writer_, &sample); r < 0) {
      log_("could not write " + options_.ghost_topic + " (" + dds_error("dds_write", r) + ")");
    }
  }

 private:
  bool fail(const char* call, dds_return_t code, std::string* error) {
    *error = "Cyclone DDS refused the driver's entities (" + dds_error(call, code) + ")";
    return false;
  }

  void run() {
    std::array<dds_attach_t, 8> triggered{};
    for (;;) {
      const dds_return_t n =
          dds_waitset_wait(waitset_, triggered.data(), triggered.size(), DDS_INFINITY);
      if (n < 0) {
        log_("the waitset failed (" + dds_error("dds_waitset_wait", n) + "); no more joint states");
        return;
      }
      for (dds_return_t i = 0; i < n; ++i) {
        switch (triggered[static_cast<std::size_t>(i)]) {
          case kStop:
            return;
          case kJointStates:
            take_joint_states();
            break;
          case kJointStatesMatched: {
            dds_subscription_matched_status_t status{};
            dds_get_subscription_matched_status(states_reader_, &status);
            log_(options_.joint_states_topic + " has " + std::to_string(status.current_count) +
                 " publisher(s)");
            break;
          }
          case kTrajectoryMatched: {
            dds_publication_matched_status_t status{};
            dds_get_publication_matched_status(trajectory_writer_, &status);
            log_(options_.trajectory_topic + " has " + std::to_string(status.current_count) +
                 " subscriber(s)");
            break;
          }
          default:
            break;
        }
      }
    }
  }

  // The newest valid sample, copied out before the handler runs (no loan held across it).
  void take_joint_states() {
    constexpr std::size_t kMax = 8;
    std::array<void*, kMax> samples{};
    std::array<dds_sample_info_t, kMax> infos{};
    const dds_return_t n =
        dds_take(states_reader_, samples.data(), infos.data(), kMax, static_cast<uint32_t>(kMax));
    if (n <= 0) return;
    std::optional<JointStateMessage> newest;
    for (dds_return_t i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (infos[k].valid_data) newest = copy_joint_state(*static_cast<JointState*>(samples[k]));
    }
    dds_return_loan(states_reader_, samples.data(), n);
    if (newest) on_state_(*newest);
  }

  LinkOptions options_;
  JointStatesHandler on_state_;
  LogHandler log_;
  dds_entity_t participant_ = 0, states_reader_ = 0, trajectory_writer_ = 0, ghost_writer_ = 0;
  dds_entity_t waitset_ = 0, stop_ = 0;
  std::thread thread_;
};

std::unique_ptr<Link> Link::start(const LinkOptions& options, JointStatesHandler on_state,
                                  LogHandler log, std::string* error) {
  auto participant = std::make_unique<Participant>(options, std::move(on_state), std::move(log));
  if (!participant->create(error)) return nullptr;
  return std::unique_ptr<Link>(new Link(std::move(participant)));
}

Link::Link(std::unique_ptr<Participant> participant) : participant_(std::move(participant)) {}

Link::~Link() = default;

int Link::trajectory_subscribers() const {
  return participant_->trajectory_subscribers();
}

bool Link::publish_trajectory(const TrajectoryMessage& message) {
  return participant_->publish_trajectory(message);
}

void Link::publish_ghost(const std::vector<std::string>& names,
                         const std::vector<double>& position) {
  participant_->publish_ghost(names, position);
}

}  // namespace telear::drivers::ros2
