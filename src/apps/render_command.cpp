#include "apps/render_command.hpp"

#include <cmath>
#include <ostream>
#include <utility>
#include <vector>

#include "telear/core/arm_body.hpp"
#include "telear/core/arm_body_pose.hpp"
#include "telear/core/image_size.hpp"
#include "telear/core/joint_values.hpp"
#include "telear/core/number_format.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/render/arm_snapshot.hpp"
#include "telear/render/egl_context.hpp"
#include "telear/render/image_io.hpp"

namespace telear::cli {
namespace {

constexpr int kBadInput = 2;
constexpr int kGlFailure = 1;
struct Failure {
  std::string message;
};

void check_options(const RenderOptions& options) {
  if (options.output.empty()) throw Failure{"-o is required (the PNG to write)"};
  if (options.segments != 0 &&
      (options.segments < core::kMinCylinderSegments || options.segments > 512)) {
    throw Failure{"--segments must be in [3, 512], got " + std::to_string(options.segments)};
  }
  if (!(options.alpha > 0.0 && options.alpha <= 1.0)) {
    throw Failure{"--alpha must be in (0, 1], got " + core::format_number(options.alpha)};
  }
  if (options.gripper && !(std::isfinite(*options.gripper) && *options.gripper >= 0.0)) {
    throw Failure{"--gripper must be a finite opening >= 0 m"};
  }
  if (options.width < 16 || options.width > 8192 || options.height < 16 || options.height > 8192) {
    throw Failure{"--width and --height must be in [16, 8192]"};
  }
}

}  // namespace

int run_render(const RenderOptions& options, std::ostream& out, std::ostream& err) {
  const std::string prefix = "telear render: ";
  // [SECTION] inputs: everything untrusted is checked before any GL work.
  core::RobotModelPtr model;
  Eigen::VectorXd q;
  std::vector<render::SnapshotEye> eyes;
  std::vector<core::Image> backgrounds;
  render::StereoLayout layout = render::StereoLayout::kSideBySide;
  core::BodyDescription description;
  try {
    check_options(options);
    auto geometry = options.geometry_options();
    if (!geometry) throw Failure{geometry.error().message};
    auto loaded = geometry::load_robot_assets(options.robot_spec(), *geometry);
    if (!loaded) throw Failure{loaded.error().message};
    for (const std::string& warning : loaded->warnings)
      err << prefix << "warning: " << warning << "\n";
    model = loaded->model();
    description = std::move(loaded->body);
    if (options.q.empty()) throw Failure{"--q is required (joint values or a named configuration)"};
    auto joints = core::parse_joint_values(*model, options.q, "--q", options.degrees);
    if (!joints) throw Failure{joints.error().message};
    q = *joints;
    auto read = render::read_snapshot_backgrounds(options.background);
    if (!read) throw Failure{read.error().message};
    backgrounds = std::move(*read);
    const int default_width = backgrounds.empty() ? options.width : backgrounds[0].width;
    const int default_height = backgrounds.empty() ? options.height : backgrounds[0].height;
    auto chosen = render::snapshot_eyes(options.camera, options.eye, *model, q, default_width,
                                        default_height);
    if (!chosen) throw Failure{chosen.error().message};
    eyes = std::move(*chosen);
    if (eyes.size() == 2) {
      auto parsed = render::parse_stereo_layout(options.stereo);
      if (!parsed) throw Failure{"--stereo: " + parsed.error().message};
      layout = *parsed;
    }
    if (Status s = render::check_snapshot_inputs(eyes, backgrounds, layout); !s)
      throw Failure{s.error().message};
  } catch (const Failure& f) {
    err << prefix << f.message << "\n";
    return kBadInput;
  }

  // [SECTION] drawing
  auto context = render::create_headless_context();
  if (!context) {
    err << prefix << "no OpenGL context: " << context.error().message << "\n";
    return kGlFailure;
  }
  const core::ArmBody body =
      core::build_arm_body(description, {.segments_override = options.segments});
  core::ArmBodyPose pose(*model, body);
  pose.set_configuration(q);
  if (options.gripper) pose.set_gripper_opening(static_cast<float>(*options.gripper));
  render::SnapshotOptions snapshot;
  snapshot.undistort = options.undistort;
  snapshot.draw_arm = !options.no_arm;
  snapshot.floor = options.floor;
  snapshot.cube = options.cube;
  snapshot.layout = layout;
  snapshot.draw.style = options.wireframe ? render::DrawOptions::Style::kWireframe
                                          : render::DrawOptions::Style::kSolid;
  snapshot.draw.alpha = static_cast<float>(options.alpha);
  auto drawn = render::draw_arm_snapshot(body, pose, eyes, backgrounds, snapshot);
  if (!drawn) {
    err << prefix << drawn.error().message << "\n";
    return kGlFailure;
  }

  // [SECTION] output
  std::vector<std::pair<std::string, core::Image>> images;
  if (drawn->size() == 1) {
    images.emplace_back(options.output, std::move(drawn->front()));
  } else {
    images.emplace_back(render::snapshot_eye_path(options.output, "left"), std::move((*drawn)[0]));
    images.emplace_back(render::snapshot_eye_path(options.output, "right"), std::move((*drawn)[1]));
  }
  for (const auto& [path, image] : images) {
    if (Status written = render::write_png(path, image); !written) {
      err << prefix << written.error().message << "\n";
      return kBadInput;
    }
    out << "wrote " << path << " (" << core::to_string(core::ImageSize{image.width, image.height});
    if (eyes.size() == 2 && layout != render::StereoLayout::kSeparate) {
      out << ", stereo " << render::stereo_layout_name(layout);
    }
    out << ", " << (options.undistort ? "undistorted" : "raw") << " overlay"
        << (options.camera.empty() ? ", default view" : "") << ")\n";
  }
  return 0;
}

}  // namespace telear::cli
