#pragma once
// SimRigSource: the simulated stereo rig (telear/sim/stereo_rig.hpp, data/rigs/*.yaml) as a camera
// pair. Each capture renders the "real" scene (telear/sim/scene_renderer.hpp: the arm with its real
// body, table, floor, true lens distortion, sensor noise) for both eyes, with the arm at the
// configuration the state function returns, so the "real" arm in the video follows the robot
// (the vision server wires it to RobotClient::latest_state(), i.e. the robot server).
//
// GL. The renderer needs a current GL context; prepare() creates a headless EGL context on
// the capture thread and keeps it there (a context is current on one thread); release(), on the
// same thread, deletes the renderer's GL objects and then the context.
//
// Timing. capture() is paced at `fps`; each eye is stamped when its render finished (the
// "exposure" of a simulated camera is instantaneous). On llvmpipe a 640x480 eye costs a few
// to tens of ms depending on `supersample`: the achieved rate may be below `fps`.
//
// Frame code. With `frame_code` both eyes carry the pair's number and capture time in their
// pixels (telear/vision/frame_code.hpp: a strip in the bottom-left corner, where the rigs show
// the floor), so the operator's view can measure capture -> shown; the embedded servers the
// console and the demo start turn it on (lab/embedded_servers.hpp).

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "telear/core/robot_model.hpp"
#include "telear/vision/camera_model.hpp"
#include "telear/vision/stereo_source.hpp"

namespace telear::sim {

struct SimRigSourceOptions {
  std::string rig;  // the rig file; empty: default_rig_file() (telear/sim/stereo_rig.hpp)
  double fps = 30.0;
  int supersample = 2;       // anti-aliasing, 1..8 (4 is the stills' quality, slow on a CPU)
  int multisample = 1;       // MSAA samples per pixel (sim::SceneOptions::multisample)
  double noise_sigma = 1.0;  // grey levels
  std::uint64_t seed = 1;
  // Stamp both eyes with the frame code; cameras smaller than 304x64 have no room and are not
  // stamped (the embedded servers ask for it whatever the rig).
  bool frame_code = false;
  // Where the arm is; called once per captured pair. nullopt (or no function): the last
  // known state, initially the robot's "qr" configuration (zeros without one).
  std::function<std::optional<vision::SceneState>()> scene_state;
};

class SimRigSource final : public vision::StereoSource {
 public:
  // Loads the rig, its robot and body (errors name the file); no GL yet.
  static Result<std::unique_ptr<SimRigSource>> create(SimRigSourceOptions options);
  ~SimRigSource() override;

  std::string name() const override { return "sim"; }
  int width() const override;
  int height() const override;
  double fps() const override { return options_.fps; }
  Status prepare() override;
  void release() override;
  Result<vision::StereoCapture> capture() override;

  // The rig's TRUE cameras (what a perfect calibration and registration would give).
  const vision::StereoCameraModel& true_cameras() const;

 private:
  struct Gl;
  SimRigSource() = default;
  SimRigSourceOptions options_;
  struct Loaded;
  std::unique_ptr<Loaded> loaded_;
  std::unique_ptr<Gl> gl_;
  std::unique_ptr<vision::FramePacer> pacer_;
  vision::SceneState last_state_;
  std::uint64_t frame_ = 0;
};

}  // namespace telear::sim
