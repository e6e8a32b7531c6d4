#pragma once
// The topics of a telear recording (docs/recording.md): fixed names, so that one Foxglove
// layout serves every recording. Each carries one schema (Foxglove's where one fits).
//
//   /camera/left/image/compressed    foxglove.CompressedImage   each frame's JPEG as received
//   /camera/right/image/compressed   foxglove.CompressedImage
//   /camera/left/calibration         foxglove.CameraCalibration at the start, then every second
//   /camera/right/calibration        foxglove.CameraCalibration
//   /robot/joint_states              foxglove.JointStates       the measured state, every sample
//   /robot/joint_commands            foxglove.JointStates       the servo's command (tracking
//   error) /ghost/joint_states              foxglove.JointStates       the operator's ghost (while
//   sent) /tf                              foxglove.FrameTransforms   every link of the arm, of the
//                                                               ghost (ghost/ frames), cameras
//   /workspace                       foxglove.SceneUpdate       the robot server's workspace
//   /events                          foxglove.Log               lease, faults, e-stop, drops...
//   /telear/plan_events              telear.record.v1.PlanEvent the plan workflow's events
//   /telear/latency                  telear.record.v1.LatencyStages per decoded frame

#include <string_view>

namespace telear::record {

inline constexpr std::string_view kTopicLeftImage = "/camera/left/image/compressed";
inline constexpr std::string_view kTopicRightImage = "/camera/right/image/compressed";
inline constexpr std::string_view kTopicLeftCalibration = "/camera/left/calibration";
inline constexpr std::string_view kTopicRightCalibration = "/camera/right/calibration";
inline constexpr std::string_view kTopicRobotJointStates = "/robot/joint_states";
inline constexpr std::string_view kTopicRobotJointCommands = "/robot/joint_commands";
inline constexpr std::string_view kTopicGhostJointStates = "/ghost/joint_states";
inline constexpr std::string_view kTopicTransforms = "/tf";
inline constexpr std::string_view kTopicWorkspace = "/workspace";
inline constexpr std::string_view kTopicEvents = "/events";
inline constexpr std::string_view kTopicPlanEvents = "/telear/plan_events";
inline constexpr std::string_view kTopicLatency = "/telear/latency";

// Frame ids: the arm's links by their URDF names (parent: the URDF's root link), the ghost's
// as kGhostFramePrefix + name, the cameras' optical frames (z forward, x right, y down).
inline constexpr std::string_view kGhostFramePrefix = "ghost/";
inline constexpr std::string_view kLeftCameraFrame = "camera_left";
inline constexpr std::string_view kRightCameraFrame = "camera_right";

}  // namespace telear::record
