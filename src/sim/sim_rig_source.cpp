#include "telear/sim/sim_rig_source.hpp"

#include "telear/sim/rig_robot.hpp"

#include "telear/core/arm_body.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/render/egl_context.hpp"
#include "telear/sim/grasp_model.hpp"
#include "telear/sim/scene_renderer.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "telear/vision/frame_code.hpp"

namespace telear::sim {

struct SimRigSource::Loaded {
  sim::StereoRig rig;
  core::RobotModelPtr model;
  core::BodyDescription body;
};

// The context is declared first so it is destroyed last, after the renderer's GL objects.
struct SimRigSource::Gl {
  std::unique_ptr<render::GlContext> context;
  sim::SceneRenderer scene;
  std::optional<sim::GraspModel> grasp;  // none when the workspace has no graspable object
};

SimRigSource::~SimRigSource() {
  release();
}

void SimRigSource::release() {
  if (!gl_) return;
  gl_->scene = sim::SceneRenderer();  // its GL objects, while the context is current
  gl_.reset();
}

Result<std::unique_ptr<SimRigSource>> SimRigSource::create(SimRigSourceOptions options) {
  if (!(options.fps > 0.0 && options.fps <= 1000.0)) {
    return Error{"sim rig source: fps must be in (0, 1000]"};
  }
  if (options.supersample < 1 || options.supersample > 8) {
    return Error{"sim rig source: supersample must be in 1..8"};
  }
  if (options.rig.empty()) options.rig = default_rig_file();
  auto rig = sim::load_stereo_rig(options.rig);
  if (!rig) return rig.error();
  auto robot = load_rig_robot(*rig);
  if (!robot) return robot.error();
  if (robot->description.marker) rig->marker = robot->description.marker;

  std::unique_ptr<SimRigSource> source(new SimRigSource());
  source->options_ = std::move(options);
  source->loaded_ = std::make_unique<Loaded>(Loaded{*rig, robot->model(), robot->body});
  source->last_state_.q = rest_configuration(*source->loaded_->model);
  source->last_state_.gripper = 0.5;
  source->pacer_ = std::make_unique<vision::FramePacer>(source->options_.fps);
  return source;
}

const vision::StereoCameraModel& SimRigSource::true_cameras() const {
  return loaded_->rig.cameras;
}

int SimRigSource::width() const {
  return loaded_->rig.cameras.left.width;
}
int SimRigSource::height() const {
  return loaded_->rig.cameras.left.height;
}

Status SimRigSource::prepare() {
  auto context = render::create_headless_context();
  if (!context) return Error{"sim rig source: " + context.error().message};
  sim::SceneOptions scene_options;
  scene_options.supersample = options_.supersample;
  scene_options.multisample = options_.multisample;
  scene_options.noise_sigma = options_.noise_sigma;
  scene_options.seed = options_.seed;
  scene_options.fast_noise = true;  // video: the table noise (telear/sim/scene_renderer.hpp)
  auto scene =
      sim::SceneRenderer::create(loaded_->rig, *loaded_->model, loaded_->body, scene_options);
  if (!scene) return Error{"sim rig source: " + scene.error().message};
  std::optional<sim::GraspModel> grasp;
  if (loaded_->rig.workspace.first_graspable()) {
    auto created = sim::GraspModel::create(loaded_->rig.workspace);
    if (!created) return Error{"sim rig source: " + created.error().message};
    grasp = std::move(*created);
  }
  gl_ = std::make_unique<Gl>(Gl{std::move(*context), std::move(*scene), std::move(grasp)});
  return {};
}

Result<vision::StereoCapture> SimRigSource::capture() {
  if (!gl_) return Error{"sim rig source: capture() before prepare()"};
  pacer_->wait();
  if (options_.scene_state) {
    if (auto state = options_.scene_state()) {
      if (state->q.size() == loaded_->model->dof() && state->q.allFinite()) last_state_ = *state;
    }
  }
  // The box on the table is picked up when the gripper closes on it (telear/sim/grasp_model.hpp).
  gl_->scene.set_configuration(last_state_.q);
  const double opening_m = gl_->scene.gripper_opening_m(last_state_.gripper);
  if (gl_->grasp) {
    gl_->grasp->update(gl_->scene.T_base_grip(), opening_m);
    gl_->scene.set_gripper_opening(static_cast<float>(gl_->grasp->rendered_opening(opening_m)));
    gl_->scene.set_object_pose(gl_->grasp->T_base_object());
  } else {
    gl_->scene.set_gripper_opening(static_cast<float>(opening_m));
  }
  vision::StereoCapture out;
  out.frame_number = ++frame_;
  // Both eyes show the scene at one instant, as a hardware-synchronized stereo rig exposes
  // both sensors at once: one capture time for the pair, taken at that instant (rendering,
  // like a sensor's read-out, comes after the exposure).
  out.capture_ns_left = core::monotonic_ns();
  out.capture_ns_right = out.capture_ns_left;
  out.left = gl_->scene.render(sim::Eye::kLeft, out.frame_number);
  out.right = gl_->scene.render(sim::Eye::kRight, out.frame_number);
  if (options_.frame_code) {  // cameras smaller than 304x64 have no room: not stamped
    const vision::FrameCode code{static_cast<std::uint32_t>(out.frame_number), out.capture_ns_left};
    vision::write_frame_code(out.left, code);
    vision::write_frame_code(out.right, code);
  }
  out.scene = last_state_;
  return out;
}

}  // namespace telear::sim
