#include "telear/record/session_recorder.hpp"

#include <google/protobuf/timestamp.pb.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "foxglove/CameraCalibration.pb.h"
#include "foxglove/CompressedImage.pb.h"
#include "foxglove/FrameTransforms.pb.h"
#include "foxglove/JointStates.pb.h"
#include "foxglove/Log.pb.h"
#include "foxglove/SceneUpdate.pb.h"
#include "telear/core/clock.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/workspace.hpp"
#include "telear/record/recording_topics.hpp"
#include "telear/record/schema_descriptors.hpp"
#include "telear/record/v1/latency_stages.pb.h"
#include "telear/record/v1/plan_event.pb.h"
#include "telear/vision/camera_file.hpp"

namespace telear::record {
namespace {

constexpr std::int64_t kSecondNs = 1'000'000'000;

void set_time(google::protobuf::Timestamp* t, std::int64_t wall_ns) {
  t->set_seconds(wall_ns / kSecondNs);
  t->set_nanos(static_cast<std::int32_t>(wall_ns % kSecondNs));
}

void set_pose(const Eigen::Isometry3d& T, foxglove::Vector3* position,
              foxglove::Quaternion* orientation) {
  const Eigen::Quaterniond r(T.rotation());
  position->set_x(T.translation().x());
  position->set_y(T.translation().y());
  position->set_z(T.translation().z());
  orientation->set_x(r.x());
  orientation->set_y(r.y());
  orientation->set_z(r.z());
  orientation->set_w(r.w());
}

// foxglove.CameraCalibration of a plumb-bob (or equidistant) camera: K, D, identity R, P = K
// with a zero fourth column (each eye its own frame; the baseline is in /tf).
foxglove::CameraCalibration calibration_message(const vision::CameraModel& camera,
                                                std::string_view frame_id) {
  foxglove::CameraCalibration c;
  c.set_frame_id(std::string(frame_id));
  c.set_width(static_cast<std::uint32_t>(camera.width));
  c.set_height(static_cast<std::uint32_t>(camera.height));
  // ROS's names (what Foxglove reads): plumb_bob, rational_polynomial; an equidistant lens is
  // ROS's "equidistant" too.
  c.set_distortion_model(vision::distortion_model_name(camera.kc.model));
  for (double k : camera.kc.coefficients()) c.add_d(k);
  const double K[9] = {
      camera.fx, camera.alpha_c * camera.fx, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1};
  for (double k : K) c.add_k(k);
  for (double r : {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0}) c.add_r(r);
  for (int i = 0; i < 12; ++i) c.add_p(i % 4 == 3 ? 0.0 : K[(i / 4) * 3 + i % 4]);
  return c;
}

}  // namespace

struct SessionRecorder::Impl {
  struct Item {
    std::string topic;  // for the drop counts
    std::size_t bytes = 0;
    std::function<void()> write;
  };

  SessionRecorderOptions options;
  RecordedSetup setup;
  core::RobotDescription description;
  std::vector<std::string> joint_names;
  std::unique_ptr<core::KinematicsData> kinematics;
  std::int64_t wall_minus_monotonic_ns = 0;
  McapWriter writer;
  std::map<std::string, std::uint16_t, std::less<>> channels;

  mutable std::mutex mutex;
  std::condition_variable cv;
  std::deque<Item> queue;
  std::size_t queued_bytes = 0;
  bool stopping = false;
  std::thread thread;
  RecordingCounts counts;
  std::optional<Status> write_error;
  bool closed = false;

  // Writer-thread state: what changes between states (for /events), when the calibration and
  // the cameras' transforms were last written.
  std::optional<net::RobotStateSample> previous;
  std::int64_t last_calibration_ns = 0;
  std::int64_t last_camera_tf_ns = 0;
  std::uint32_t sequence = 0;
  // The view's ghost (ghost_from_state_stream false): the last one written, and when.
  struct ViewGhost {
    Eigen::VectorXd q;
    double gripper = 1.0;
    std::int64_t written_ns = 0;
  };
  std::optional<ViewGhost> view_ghost;
  static constexpr std::int64_t kGhostRefillNs = 15'000'000;

  explicit Impl(McapWriter w) : writer(std::move(w)) {}

  std::int64_t wall(std::int64_t client_ns) const { return client_ns + wall_minus_monotonic_ns; }

  void channel(std::string_view topic, const SchemaInfo& schema) {
    const std::uint16_t schema_id =
        writer.add_schema(schema.name, schema.encoding, mcap_bytes(schema.data));
    channels.emplace(std::string(topic), writer.add_channel(schema_id, topic, kProtobufEncoding));
  }

  // Writer thread (or create(), before it starts): one message.
  void write(std::string_view topic, std::int64_t log_wall_ns, std::int64_t publish_wall_ns,
             const google::protobuf::Message& message) {
    const auto it = channels.find(topic);
    const std::string bytes = message.SerializeAsString();
    Status s = writer.write(it->second, ++sequence, static_cast<std::uint64_t>(log_wall_ns),
                            static_cast<std::uint64_t>(publish_wall_ns), mcap_bytes(bytes));
    std::lock_guard lock(mutex);
    if (!s && !write_error) write_error = s;
    if (s) ++counts.written[std::string(topic)];
  }

  void enqueue(std::string topic, std::size_t bytes, std::function<void()> write_item) {
    {
      std::lock_guard lock(mutex);
      if (stopping) return;
      if (queued_bytes + bytes > options.queue_bytes && !queue.empty()) {
        ++counts.dropped[topic];
        return;
      }
      queued_bytes += bytes;
      queue.push_back({std::move(topic), bytes, std::move(write_item)});
    }
    cv.notify_one();
  }

  void run() {
    while (true) {
      Item item;
      {
        std::unique_lock lock(mutex);
        cv.wait(lock, [&] { return stopping || !queue.empty(); });
        if (queue.empty()) return;  // stopping, drained
        item = std::move(queue.front());
        queue.pop_front();
        queued_bytes -= item.bytes;
      }
      item.write();
    }
  }

  void write_log(LogLevel level, const std::string& text, std::int64_t wall_ns) {
    foxglove::Log log;
    set_time(log.mutable_timestamp(), wall_ns);
    log.set_level(level == LogLevel::kDebug     ? foxglove::Log::DEBUG
                  : level == LogLevel::kInfo    ? foxglove::Log::INFO
                  : level == LogLevel::kWarning ? foxglove::Log::WARNING
                                                : foxglove::Log::ERROR);
    log.set_message(text);
    log.set_name("telear");
    write(kTopicEvents, wall_ns, wall_ns, log);
  }

  void write_plan_event(telear::record::v1::PlanEvent::Kind kind, const std::string& text,
                        const std::string& plan_id, std::int64_t wall_ns,
                        const std::string& plan_hash = {}) {
    telear::record::v1::PlanEvent event;
    set_time(event.mutable_timestamp(), wall_ns);
    event.set_kind(kind);
    event.set_text(text);
    event.set_plan_id(plan_id);
    event.set_plan_hash(plan_hash);
    write(kTopicPlanEvents, wall_ns, wall_ns, event);
    write_log(
        kind == telear::record::v1::PlanEvent::FAULT || kind == telear::record::v1::PlanEvent::ESTOP
            ? LogLevel::kWarning
            : LogLevel::kInfo,
        text, wall_ns);
  }

  // /ghost/joint_states at `wall_ns`, its ghost/ frames into `tf` (the caller's message) or,
  // when null, on /tf as a message of their own.
  void write_view_ghost(const Eigen::VectorXd& q, double gripper, std::int64_t wall_ns,
                        foxglove::FrameTransforms* tf) {
    write(kTopicGhostJointStates, wall_ns, wall_ns, joint_states(q, nullptr, gripper, wall_ns));
    view_ghost = ViewGhost{q, gripper, wall_ns};
    if (tf != nullptr) {
      add_link_transforms(*tf, q, gripper, kGhostFramePrefix, wall_ns);
    } else {
      foxglove::FrameTransforms frames;
      add_link_transforms(frames, q, gripper, kGhostFramePrefix, wall_ns);
      write(kTopicTransforms, wall_ns, wall_ns, frames);
    }
  }

  void add_link_transforms(foxglove::FrameTransforms& tf, const Eigen::VectorXd& q, double gripper,
                           std::string_view prefix, std::int64_t wall_ns) {
    core::forward_kinematics(*description.model, *kinematics, q);
    for (std::size_t i = 0; i < description.links.size(); ++i) {
      const core::RobotLink& link = description.links[i];
      if (link.name == description.root_link) continue;
      const Eigen::Isometry3d T = kinematics->T_base_link[static_cast<std::size_t>(link.frame)] *
                                  description.T_frame_link(i, gripper);
      foxglove::FrameTransform* t = tf.add_transforms();
      set_time(t->mutable_timestamp(), wall_ns);
      t->set_parent_frame_id(description.root_link);
      t->set_child_frame_id(std::string(prefix) + link.name);
      set_pose(T, t->mutable_translation(), t->mutable_rotation());
    }
  }

  foxglove::JointStates joint_states(const Eigen::VectorXd& q, const Eigen::VectorXd* qd,
                                     double gripper, std::int64_t wall_ns) const {
    foxglove::JointStates states;
    set_time(states.mutable_timestamp(), wall_ns);
    for (Eigen::Index i = 0; i < q.size(); ++i) {
      foxglove::JointState* j = states.add_joints();
      j->set_name(joint_names[static_cast<std::size_t>(i)]);
      j->set_position(q[i]);
      if (qd != nullptr && qd->size() == q.size()) j->set_velocity((*qd)[i]);
    }
    // The gripper as one joint: its opening fraction, 0 closed .. 1 open.
    foxglove::JointState* g = states.add_joints();
    g->set_name("gripper");
    g->set_position(gripper);
    return states;
  }

  void write_state(const net::RobotStateSample& s, std::int64_t log_wall_ns) {
    const core::RobotState& state = s.state;
    const std::int64_t wall_ns = wall(s.capture_client_ns());
    if (state.q.size() == static_cast<Eigen::Index>(joint_names.size()) && state.q.allFinite()) {
      write(kTopicRobotJointStates, log_wall_ns, wall_ns,
            joint_states(state.q, &state.qd, state.gripper, wall_ns));
      // The servo's command beside the measurement: the tracking error is their difference.
      if (state.q_commanded.size() == state.q.size() && state.q_commanded.allFinite()) {
        write(kTopicRobotJointCommands, log_wall_ns, wall_ns,
              joint_states(state.q_commanded, &state.qd_commanded, state.gripper_target, wall_ns));
      }
      foxglove::FrameTransforms tf;
      add_link_transforms(tf, state.q, state.gripper, "", wall_ns);
      const bool ghost = options.ghost_from_state_stream && s.ghost_q.size() == state.q.size() &&
                         s.ghost_q.allFinite();
      std::int64_t ghost_wall_ns = wall_ns;
      if (ghost) {
        ghost_wall_ns = wall(s.ghost_ns - s.clock_offset_ns);
        write(kTopicGhostJointStates, log_wall_ns, ghost_wall_ns,
              joint_states(s.ghost_q, nullptr, s.ghost_gripper, ghost_wall_ns));
        add_link_transforms(tf, s.ghost_q, s.ghost_gripper, kGhostFramePrefix, wall_ns);
      } else if (view_ghost && log_wall_ns - view_ghost->written_ns >= kGhostRefillNs) {
        // A display slower than the state stream: the ghost it still draws, at the state's
        // time, so the topic keeps the state stream's rate.
        const ViewGhost still = *view_ghost;
        write_view_ghost(still.q, still.gripper, log_wall_ns, &tf);
      }
      if (setup.cameras && wall_ns - last_camera_tf_ns >= kSecondNs) {
        last_camera_tf_ns = wall_ns;
        for (const auto& [camera, frame] : {std::pair{&setup.cameras->left, kLeftCameraFrame},
                                            std::pair{&setup.cameras->right, kRightCameraFrame}}) {
          foxglove::FrameTransform* t = tf.add_transforms();
          set_time(t->mutable_timestamp(), wall_ns);
          t->set_parent_frame_id(description.root_link);
          t->set_child_frame_id(std::string(frame));
          set_pose(camera->T_cam_base.inverse(), t->mutable_translation(), t->mutable_rotation());
        }
      }
      write(kTopicTransforms, log_wall_ns, wall_ns, tf);
    }
    write_state_events(s, wall_ns);
    previous = s;
  }

  // What a passive recorder can tell from the state stream alone: who holds the lease, the
  // e-stop, faults, trajectories starting and ending.
  void write_state_events(const net::RobotStateSample& s, std::int64_t wall_ns) {
    using Kind = telear::record::v1::PlanEvent;
    const net::RobotStateSample* p = previous ? &*previous : nullptr;
    const std::string holder = p ? p->lease_holder : std::string();
    if (s.lease_holder != holder) {
      if (!holder.empty())
        write_plan_event(Kind::LEASE_RELEASED, holder + " released the lease", "", wall_ns);
      if (!s.lease_holder.empty())
        write_plan_event(Kind::LEASE_ACQUIRED, s.lease_holder + " holds the lease", "", wall_ns);
    }
    const bool was_estop = p && p->state.estop;
    if (s.state.estop != was_estop) {
      write_plan_event(s.state.estop ? Kind::ESTOP : Kind::ESTOP_RESET,
                       s.state.estop ? "e-stop: " + s.state.estop_reason : "e-stop reset", "",
                       wall_ns);
    }
    const std::string fault = s.state.fault.value_or("");
    const std::string was_fault = p ? p->state.fault.value_or("") : std::string();
    if (!fault.empty() && fault != was_fault) {
      write_plan_event(Kind::FAULT, "fault: " + fault, "", wall_ns);
    }
    const std::string running = p ? p->state.trajectory_id : std::string();
    if (!s.state.trajectory_id.empty() && s.state.trajectory_id != running) {
      write_plan_event(Kind::EXECUTE, "executing " + s.state.trajectory_id, s.state.trajectory_id,
                       wall_ns);
    }
    const bool finished = !s.last_trajectory_id.empty() &&
                          s.last_trajectory_status != core::TrajectoryStatus::kRunning;
    const bool was_finished = p && p->last_trajectory_id == s.last_trajectory_id &&
                              p->last_trajectory_status == s.last_trajectory_status;
    if (finished && !was_finished) {
      std::string text = s.last_trajectory_id + " " + core::to_string(s.last_trajectory_status);
      if (!s.last_trajectory_message.empty()) text += ": " + s.last_trajectory_message;
      write_plan_event(Kind::EXECUTE, text, s.last_trajectory_id, wall_ns);
    }
  }

  void write_workspace(std::int64_t wall_ns) {
    if (setup.robot.workspace_yaml.empty()) return;
    auto workspace = core::parse_workspace_yaml(setup.robot.workspace_yaml, "the robot server's");
    if (!workspace) {
      write_log(LogLevel::kWarning, "workspace not recorded: " + workspace.error().message,
                wall_ns);
      return;
    }
    foxglove::SceneUpdate update;
    for (const core::WorkspaceObject& o : workspace->objects) {
      foxglove::SceneEntity* e = update.add_entities();
      set_time(e->mutable_timestamp(), wall_ns);
      e->set_frame_id(description.root_link);
      e->set_id(o.name);
      const auto colour = [&o](foxglove::Color* c) {
        c->set_r(o.colour.x());
        c->set_g(o.colour.y());
        c->set_b(o.colour.z());
        c->set_a(1.0);
      };
      switch (o.shape) {
        case core::ShapeKind::kBox: {
          foxglove::CubePrimitive* cube = e->add_cubes();
          set_pose(o.T_base_object, cube->mutable_pose()->mutable_position(),
                   cube->mutable_pose()->mutable_orientation());
          cube->mutable_size()->set_x(o.size_m.x());
          cube->mutable_size()->set_y(o.size_m.y());
          cube->mutable_size()->set_z(o.size_m.z());
          colour(cube->mutable_color());
          break;
        }
        case core::ShapeKind::kCylinder: {
          foxglove::CylinderPrimitive* cylinder = e->add_cylinders();
          set_pose(o.T_base_object, cylinder->mutable_pose()->mutable_position(),
                   cylinder->mutable_pose()->mutable_orientation());
          cylinder->mutable_size()->set_x(2 * o.radius_m);
          cylinder->mutable_size()->set_y(2 * o.radius_m);
          cylinder->mutable_size()->set_z(o.length_m);
          cylinder->set_bottom_scale(1.0);
          cylinder->set_top_scale(1.0);
          colour(cylinder->mutable_color());
          break;
        }
        case core::ShapeKind::kSphere: {
          foxglove::SpherePrimitive* sphere = e->add_spheres();
          set_pose(o.T_base_object, sphere->mutable_pose()->mutable_position(),
                   sphere->mutable_pose()->mutable_orientation());
          sphere->mutable_size()->set_x(2 * o.radius_m);
          sphere->mutable_size()->set_y(2 * o.radius_m);
          sphere->mutable_size()->set_z(2 * o.radius_m);
          colour(sphere->mutable_color());
          break;
        }
        default: {
          // A mesh object: its file is the robot server's; named so a reader knows it is there.
          foxglove::TextPrimitive* text = e->add_texts();
          set_pose(o.T_base_object, text->mutable_pose()->mutable_position(),
                   text->mutable_pose()->mutable_orientation());
          text->set_text(o.name + " (mesh " + o.mesh_file + ")");
          text->set_billboard(true);
          text->set_font_size(12);
          text->set_scale_invariant(true);
          colour(text->mutable_color());
          break;
        }
      }
    }
    write(kTopicWorkspace, wall_ns, wall_ns, update);
  }
};

SessionRecorder::SessionRecorder(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

SessionRecorder::~SessionRecorder() {
  if (impl_ && !impl_->closed) (void)close();
}

Result<std::unique_ptr<SessionRecorder>> SessionRecorder::create(
    const SessionRecorderOptions& options, const RecordedSetup& setup) {
  if (setup.robot.urdf.empty()) {
    return Error{"recording: the robot server sent no URDF (its links name the transforms)"};
  }
  auto description = core::parse_urdf_description(setup.robot.urdf, "the robot server's URDF",
                                                  setup.robot.tip_link);
  if (!description) return Error{"recording: " + description.error().message};
  if (static_cast<std::size_t>(description->model->dof()) != setup.robot.joints.size()) {
    return Error{"recording: the robot server's URDF has " +
                 std::to_string(description->model->dof()) + " joints to its tip, its info " +
                 std::to_string(setup.robot.joints.size())};
  }
  McapWriterOptions mcap = options.mcap;
  if (mcap.library == "telear" || mcap.library.empty()) mcap.library = "telear session recorder";
  auto writer = McapWriter::open(options.path, mcap);
  if (!writer) return Error{"recording: " + writer.error().message};

  auto impl = std::make_unique<Impl>(std::move(writer).value());
  impl->options = options;
  impl->setup = setup;
  impl->description = std::move(description).value();
  impl->kinematics = std::make_unique<core::KinematicsData>(*impl->description.model);
  for (const net::JointInfo& j : setup.robot.joints) impl->joint_names.push_back(j.name);
  const auto wall_now = std::chrono::system_clock::now().time_since_epoch();
  impl->wall_minus_monotonic_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(wall_now).count() - core::monotonic_ns();

  // Channels in the order of recording_topics.hpp.
  const SchemaInfo image = schema_for<foxglove::CompressedImage>();
  const SchemaInfo calibration = schema_for<foxglove::CameraCalibration>();
  const SchemaInfo joints = schema_for<foxglove::JointStates>();
  impl->channel(kTopicLeftImage, image);
  impl->channel(kTopicRightImage, image);
  impl->channel(kTopicLeftCalibration, calibration);
  impl->channel(kTopicRightCalibration, calibration);
  impl->channel(kTopicRobotJointStates, joints);
  impl->channel(kTopicRobotJointCommands, joints);
  impl->channel(kTopicGhostJointStates, joints);
  impl->channel(kTopicTransforms, schema_for<foxglove::FrameTransforms>());
  impl->channel(kTopicWorkspace, schema_for<foxglove::SceneUpdate>());
  impl->channel(kTopicEvents, schema_for<foxglove::Log>());
  impl->channel(kTopicPlanEvents, schema_for<telear::record::v1::PlanEvent>());
  impl->channel(kTopicLatency, schema_for<telear::record::v1::LatencyStages>());

  const std::int64_t now_wall = impl->wall(core::monotonic_ns());
  const auto now = static_cast<std::uint64_t>(now_wall);
  Status attached =
      impl->writer.attach("robot.urdf", "application/xml", now, now, mcap_bytes(setup.robot.urdf));
  // The cameras as a calibration file: the server's own text, or the model written out (replay
  // draws through it; a reader needs no telear to open it: OpenCV FileStorage YAML).
  const std::string calibration_yaml = !setup.calibration_yaml.empty() ? setup.calibration_yaml
                                       : setup.cameras
                                           ? vision::opencv_stereo_camera_yaml(*setup.cameras)
                                           : std::string();
  if (attached && !calibration_yaml.empty()) {
    attached = impl->writer.attach("calibration.yaml", "application/yaml", now, now,
                                   mcap_bytes(calibration_yaml));
  }
  if (attached && !setup.robot.workspace_yaml.empty()) {
    attached = impl->writer.attach("workspace.yaml", "application/yaml", now, now,
                                   mcap_bytes(setup.robot.workspace_yaml));
  }
  if (!attached) return Error{"recording: " + attached.error().message};
  std::map<std::string, std::string> session = options.metadata;
  session["robot"] = setup.robot.model_name;
  session["tip_link"] = impl->description.tip_link;
  session["root_link"] = impl->description.root_link;
  session["robot_driver"] = setup.robot.driver;
  session["cameras_calibrated"] = setup.cameras ? "true" : "false";
  if (Status s = impl->writer.metadata("telear.session", session); !s) {
    return Error{"recording: " + s.error().message};
  }
  impl->write_workspace(now_wall);
  impl->thread = std::thread([raw = impl.get()] { raw->run(); });
  return std::unique_ptr<SessionRecorder>(new SessionRecorder(std::move(impl)));
}

void SessionRecorder::add_frame(const net::ReceivedStereoFrame& f) {
  Impl* impl = impl_.get();
  const std::int64_t log_wall = impl->wall(f.receive_ns);
  struct Eye {
    std::string jpeg;
    std::int64_t wall_ns;
  };
  auto left = std::make_shared<Eye>(Eye{*f.jpeg_left, impl->wall(f.capture_ns_left)});
  auto right = std::make_shared<Eye>(Eye{*f.jpeg_right, impl->wall(f.capture_ns_right)});
  const std::size_t bytes = left->jpeg.size() + right->jpeg.size();
  impl->enqueue(std::string(kTopicLeftImage), bytes, [impl, left, right, log_wall] {
    for (const auto& [eye, topic, frame] :
         {std::tuple{left.get(), kTopicLeftImage, kLeftCameraFrame},
          std::tuple{right.get(), kTopicRightImage, kRightCameraFrame}}) {
      foxglove::CompressedImage image;
      set_time(image.mutable_timestamp(), eye->wall_ns);
      image.set_frame_id(std::string(frame));
      image.set_data(std::move(eye->jpeg));
      image.set_format("jpeg");
      impl->write(topic, log_wall, eye->wall_ns, image);
    }
    if (impl->setup.cameras && left->wall_ns - impl->last_calibration_ns >= kSecondNs) {
      impl->last_calibration_ns = left->wall_ns;
      foxglove::CameraCalibration l =
          calibration_message(impl->setup.cameras->left, kLeftCameraFrame);
      foxglove::CameraCalibration r =
          calibration_message(impl->setup.cameras->right, kRightCameraFrame);
      set_time(l.mutable_timestamp(), left->wall_ns);
      set_time(r.mutable_timestamp(), right->wall_ns);
      impl->write(kTopicLeftCalibration, log_wall, left->wall_ns, l);
      impl->write(kTopicRightCalibration, log_wall, right->wall_ns, r);
    }
  });
}

void SessionRecorder::add_state(const net::RobotStateSample& sample) {
  Impl* impl = impl_.get();
  const std::int64_t log_wall = impl->wall(sample.receive_ns);
  auto copy = std::make_shared<net::RobotStateSample>(sample);
  const std::size_t bytes = sizeof(net::RobotStateSample) + 16 * 8 * sample.state.q.size();
  impl->enqueue(std::string(kTopicRobotJointStates), bytes,
                [impl, copy, log_wall] { impl->write_state(*copy, log_wall); });
}

void SessionRecorder::add_latency(const net::DecodedStereoFrame& frame,
                                  std::optional<std::int64_t> shown_ns) {
  Impl* impl = impl_.get();
  const std::int64_t capture_wall =
      impl->wall(std::max(frame.capture_ns_left, frame.capture_ns_right));
  const std::int64_t log_wall = impl->wall(shown_ns.value_or(frame.decoded_ns));
  telear::record::v1::LatencyStages stages;
  set_time(stages.mutable_timestamp(), capture_wall);
  stages.set_frame_id(frame.frame_id);
  stages.set_capture_to_encode_s(frame.latency.capture_to_encode_s);
  stages.set_encode_s(frame.latency.encode_s);
  stages.set_send_queue_s(frame.latency.send_queue_s);
  stages.set_network_s(frame.latency.network_s);
  stages.set_decode_s(frame.latency.decode_s);
  stages.set_total_s(frame.latency.total_s);
  impl->enqueue(std::string(kTopicLatency), sizeof(stages), [impl, stages, capture_wall, log_wall] {
    impl->write(kTopicLatency, log_wall, capture_wall, stages);
  });
}

void SessionRecorder::add_log(LogLevel level, const std::string& text, std::int64_t client_ns) {
  Impl* impl = impl_.get();
  const std::int64_t wall_ns = impl->wall(client_ns);
  impl->enqueue(std::string(kTopicEvents), text.size() + 64,
                [impl, level, text, wall_ns] { impl->write_log(level, text, wall_ns); });
}

void SessionRecorder::add_plan_event(PlanEventKind kind, const std::string& text,
                                     const std::string& plan_id, const std::string& plan_hash,
                                     std::int64_t client_ns) {
  Impl* impl = impl_.get();
  const std::int64_t wall_ns = impl->wall(client_ns);
  const auto proto_kind = static_cast<telear::record::v1::PlanEvent::Kind>(kind);
  impl->enqueue(std::string(kTopicPlanEvents), text.size() + plan_hash.size() + 96,
                [impl, proto_kind, text, plan_id, plan_hash, wall_ns] {
                  impl->write_plan_event(proto_kind, text, plan_id, wall_ns, plan_hash);
                });
}

void SessionRecorder::add_ghost(const Eigen::VectorXd& q, double gripper, std::int64_t client_ns) {
  Impl* impl = impl_.get();
  if (impl->options.ghost_from_state_stream) return;
  if (q.size() != static_cast<Eigen::Index>(impl->joint_names.size()) || !q.allFinite()) return;
  const std::int64_t wall_ns = impl->wall(client_ns);
  impl->enqueue(
      std::string(kTopicGhostJointStates), 16 * 8 * q.size() + 64,
      [impl, q, gripper, wall_ns] { impl->write_view_ghost(q, gripper, wall_ns, nullptr); });
}

std::int64_t SessionRecorder::wall_ns(std::int64_t client_ns) const {
  return impl_->wall(client_ns);
}

RecordingCounts SessionRecorder::counts() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->counts;
}

Result<RecordingCounts> SessionRecorder::close() {
  Impl& impl = *impl_;
  if (!impl.closed) {
    impl.closed = true;
    {
      std::lock_guard lock(impl.mutex);
      impl.stopping = true;
    }
    impl.cv.notify_all();
    if (impl.thread.joinable()) impl.thread.join();
    // The drops, in the file: what a reader of it is missing, and why.
    std::uint64_t dropped = 0;
    std::map<std::string, std::string> entries;
    for (const auto& [topic, n] : impl.counts.dropped) {
      dropped += n;
      entries["dropped " + topic] = std::to_string(n);
    }
    entries["dropped_total"] = std::to_string(dropped);
    entries["queue_bytes"] = std::to_string(impl.options.queue_bytes);
    const std::int64_t now_wall = impl.wall(core::monotonic_ns());
    if (dropped > 0) {
      impl.write_log(LogLevel::kWarning,
                     "the recorder dropped " + std::to_string(dropped) +
                         " items: its queue was full (the writer could not keep up)",
                     now_wall);
    }
    Status s = impl.writer.metadata("telear.recording", entries);
    if (s) s = impl.writer.close();
    if (!s && !impl.write_error) impl.write_error = s;
    impl.counts.bytes = impl.writer.bytes_written();
  }
  if (impl.write_error) return Error{"recording: " + impl.write_error->error().message};
  return impl.counts;
}

}  // namespace telear::record
