#include "apps/sim_frame_command.hpp"

#include "apps/command_failure.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/joint_values.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/render/egl_context.hpp"
#include "telear/render/image_io.hpp"
#include "telear/sim/rig_robot.hpp"
#include "telear/sim/scene_renderer.hpp"
#include "telear/sim/stereo_rig.hpp"

namespace telear::cli {

int run_sim_frame(const SimFrameOptions& options, std::ostream& out, std::ostream& err) {
  const CommandFailure fail{err, "telear sim frame"};
  if (options.output.empty()) return fail("-o PREFIX is required", 2);
  if (!(options.gripper >= 0.0 && options.gripper <= 0.2)) {
    return fail("--gripper must be an opening between 0 and 0.2 m", 2);
  }
  auto rig = sim::load_stereo_rig(options.rig);
  if (!rig) return fail(rig.error().message, 2);
  auto loaded = sim::load_rig_robot(*rig);
  if (!loaded) return fail(loaded.error().message, 2);
  const core::RobotModel& robot = *loaded->model();
  auto q = core::parse_joint_values(robot, options.q, "--q", options.degrees);
  if (!q) return fail(q.error().message, 2);
  const core::BodyDescription* body = &loaded->body;

  auto context = render::create_headless_context();
  if (!context) return fail(context.error().message, 1);
  sim::SceneOptions scene_options;
  scene_options.seed = options.seed;
  scene_options.noise_sigma = options.noise;
  scene_options.supersample = options.supersample;
  scene_options.multisample = options.multisample;
  scene_options.marker = loaded->description.marker;
  auto scene = sim::SceneRenderer::create(*rig, robot, *body, scene_options);
  if (!scene) return fail(scene.error().message, 1);
  scene->set_configuration(*q);
  scene->set_gripper_opening(static_cast<float>(options.gripper));
  for (const auto& [eye, suffix] :
       {std::pair{sim::Eye::kLeft, "_left.png"}, std::pair{sim::Eye::kRight, "_right.png"}}) {
    const std::string path = options.output + suffix;
    if (auto written = render::write_png(path, scene->render(eye, 0)); !written) {
      return fail(written.error().message, 1);
    }
    out << "wrote " << path << "\n";
  }
  return 0;
}

}  // namespace telear::cli
