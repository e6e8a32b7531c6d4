#include "bench/render_bench_command.hpp"

#include <nlohmann/json.hpp>

#include <time.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <ostream>
#include <sstream>

#include "telear/core/arm_body.hpp"
#include "telear/core/arm_body_pose.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/render/arm_renderer.hpp"
#include "telear/render/egl_context.hpp"
#include "telear/render/offscreen_target.hpp"
#include "telear/render/scene_objects.hpp"
#include "telear/render/video_background.hpp"
#include "telear/render/view_math.hpp"

namespace telear::cli {

using namespace telear::render;

std::vector<RenderBenchCase> render_bench_cases() {
  std::vector<RenderBenchCase> cases;
  for (bool video : {false, true}) {
    for (bool stereo : {false, true}) {
      const std::string where = video ? "video" : "graphics";
      auto add = [&](std::string name, bool arm, bool cube, int segments, bool wire,
                     std::string seed) {
        cases.push_back(
            {where + ", " + name, arm, cube, segments, wire, video, stereo, std::move(seed)});
      };
      const std::string stereo_video_seed = video && stereo ? "11.3-11.5 fps" : "";
      add("no drawing", false, false, 8, false,
          !video && !stereo ? "273.4 fps" : stereo_video_seed);
      add("cube and arm, 8 seg", true, true, 8, false, stereo_video_seed);
      add("arm, 8 seg", true, false, 8, false,
          video ? (stereo ? stereo_video_seed : "105.0 ms") : (stereo ? "" : "253.6 fps, 64.1 ms"));
      add("arm, 50 seg", true, false, 50, false,
          video ? (stereo ? stereo_video_seed : "105.4 ms") : (stereo ? "" : "239.8 fps, 65.0 ms"));
      add("arm, 50 seg, wire-frame", true, false, 50, true, stereo_video_seed);
    }
  }
  return cases;
}

struct RenderBenchScene::Impl {
  RenderBenchCase c;
  int width = 0, height = 0;
  core::RobotModelPtr model;
  core::ArmBody body;
  std::unique_ptr<core::ArmBodyPose> pose;
  ArmRenderer arm;
  MeshSetRenderer scene;
  OffscreenTarget target;
  VideoBackground backgrounds[2];
  std::vector<unsigned char> frames[2];  // synthetic left / right video frames, RGB
  std::vector<unsigned char> readback;
  Eigen::Matrix4f projection;
  Eigen::Matrix4f T_cam_base[2];
  Eigen::VectorXd q0;
  long frame_index = 0;
};

RenderBenchScene::RenderBenchScene() : impl_(std::make_unique<Impl>()) {}
RenderBenchScene::~RenderBenchScene() = default;

Result<std::unique_ptr<RenderBenchScene>> RenderBenchScene::create(const RenderBenchCase& c,
                                                                   int width, int height) {
  std::unique_ptr<RenderBenchScene> s(new RenderBenchScene());
  Impl& m = *s->impl_;
  m.c = c;
  m.width = width;
  m.height = height;
  auto model = core::load_robot("puma560");
  if (!model) return model.error();
  m.model = *model;
  auto description = core::body_description_for(*m.model);
  if (!description) return description.error();
  m.body = core::build_arm_body(*description, {.segments_override = c.segments});
  m.pose = std::make_unique<core::ArmBodyPose>(*m.model, m.body);
  m.q0 = *m.model->named_configuration("qn");
  auto arm = ArmRenderer::create(m.body);
  if (!arm) return arm.error();
  m.arm = std::move(arm.value());
  auto scene = create_scene_renderer({make_cube(0.1f, {0.55f, 0.25f, 0.05f})});
  if (!scene) return scene.error();
  m.scene = std::move(scene.value());
  const int views = c.stereo ? 2 : 1;
  auto target = OffscreenTarget::create(views * width, height);
  if (!target) return target.error();
  m.target = std::move(target.value());
  m.readback.resize(static_cast<std::size_t>(views) * width * height * 3);
  if (c.video) {
    for (int eye = 0; eye < views; ++eye) {
      auto bg = VideoBackground::create(width, height);
      if (!bg) return bg.error();
      m.backgrounds[eye] = std::move(bg.value());
      // A textured frame (not a flat colour) so that the upload moves real data.
      m.frames[eye].resize(static_cast<std::size_t>(width) * height * 3);
      for (std::size_t i = 0; i < m.frames[eye].size(); ++i) {
        m.frames[eye][i] =
            static_cast<unsigned char>((i * 7 + static_cast<std::size_t>(eye) * 31) % 251);
      }
    }
  }
  // The cameras of the seed's rig: 6 cm apart, looking at the arm's workspace.
  m.projection = perspective_cv(std::numbers::pi_v<float> / 4, float(width) / height, 0.05f, 20.0f);
  const Eigen::Isometry3f T_left_base = look_at_cv({2.2f, -1.6f, 1.4f}, {0.2f, 0, 0.6f});
  Eigen::Isometry3f T_right_left = Eigen::Isometry3f::Identity();
  T_right_left.translation() = Eigen::Vector3f(-0.06f, 0, 0);
  m.T_cam_base[0] = T_left_base.matrix();
  m.T_cam_base[1] = (T_right_left * T_left_base).matrix();
  return s;
}

void RenderBenchScene::frame() {
  Impl& m = *impl_;
  const int views = m.c.stereo ? 2 : 1;
  // Move every joint a little, as a ghost being jogged does: every matrix is re-uploaded.
  const double t = static_cast<double>(m.frame_index++) / 60.0;
  Eigen::VectorXd q = m.q0;
  for (int i = 0; i < q.size(); ++i) q[i] += 0.3 * std::sin(t + i);
  m.pose->set_configuration(q);
  m.arm.update(*m.pose);

  if (m.c.video) {
    for (int eye = 0; eye < views; ++eye) {
      m.backgrounds[eye].upload(m.frames[eye].data(), ChannelOrder::kBgr);
    }
  }
  if (m.c.video) {
    m.target.clear_depth();  // the video frames cover every pixel
  } else {
    m.target.clear(0.1f, 0.1f, 0.15f);
  }
  DrawOptions options;
  if (m.c.wireframe) options.style = DrawOptions::Style::kWireframe;
  for (int eye = 0; eye < views; ++eye) {
    m.target.bind_viewport(eye * m.width, 0, m.width, m.height);
    if (m.c.video) m.backgrounds[eye].draw();
    if (m.c.draw_cube) m.scene.draw(m.projection, m.T_cam_base[eye], options);
    if (m.c.draw_arm) m.arm.draw(m.projection, m.T_cam_base[eye], options);
  }
  if (m.c.video) {
    m.target.read_pixels(3, m.readback.data());
  } else {
    glFinish();
  }
}

std::vector<unsigned char> RenderBenchScene::last_image() {
  if (!impl_->c.video) impl_->target.read_pixels(3, impl_->readback.data());
  return impl_->readback;
}

namespace {

struct Measured {
  RenderBenchCase c;
  long frames = 0;
  double seconds = 0.0;
  double cpu_seconds = 0.0;  // all threads of the process (llvmpipe's rasterisers too)
  double cpu_ms() const {
    return frames > 0 ? 1000.0 * cpu_seconds / static_cast<double>(frames) : 0.0;
  }
  double fps() const { return seconds > 0 ? static_cast<double>(frames) / seconds : 0.0; }
  double ms() const { return frames > 0 ? 1000.0 * seconds / static_cast<double>(frames) : 0.0; }
};

// CPU time of the whole process: on a loaded machine wall-clock rates fall while the work
// per frame does not, so both are reported.
double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

int run_bench_render(const RenderBenchOptions& options, std::ostream& out, std::ostream& err) {
  if (!(options.seconds > 0.0) || options.seconds > 600.0) {
    err << "telear bench render: --seconds must be in (0, 600], got " << options.seconds << "\n";
    return 2;
  }
  if (options.width < 16 || options.height < 16 || options.width > 4096 || options.height > 4096) {
    err << "telear bench render: --width and --height must be in [16, 4096]\n";
    return 2;
  }
  auto context = create_headless_context();
  if (!context) {
    err << "telear bench render: " << context.error().message << "\n";
    return 1;
  }
  const std::string device = (*context)->description();

  std::vector<Measured> results;
  for (const RenderBenchCase& c : render_bench_cases()) {
    if (!options.only.empty() && c.name.find(options.only) == std::string::npos) continue;
    auto scene = RenderBenchScene::create(c, options.width, options.height);
    if (!scene) {
      err << "telear bench render: " << c.name << ": " << scene.error().message << "\n";
      return 1;
    }
    for (int i = 0; i < 10; ++i) (*scene)->frame();  // warm-up: shaders, caches
    Measured m{c};
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = process_cpu_seconds();
    do {
      for (int i = 0; i < 10; ++i) (*scene)->frame();
      m.frames += 10;
      m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    } while (m.seconds < options.seconds);
    m.cpu_seconds = process_cpu_seconds() - cpu_start;
    results.push_back(m);
  }
  if (results.empty()) {
    err << "telear bench render: no case matches '" << options.only << "'\n";
    return 2;
  }

  if (options.json) {
    nlohmann::json j;
    j["device"] = device;
    j["width"] = options.width;
    j["height"] = options.height;
    for (const Measured& m : results) {
      j["cases"].push_back({{"name", m.c.name},
                            {"view", m.c.stereo ? "stereo" : "mono"},
                            {"frames", m.frames},
                            {"fps", m.fps()},
                            {"ms_per_frame", m.ms()},
                            {"cpu_ms_per_frame", m.cpu_ms()},
                            {"seed", m.c.seed}});
    }
    out << j.dump(2) << "\n";
    return 0;
  }
  out << "telear bench render: " << options.width << "x" << options.height << " per view, "
      << core::format_fixed(options.seconds, 1) << " s per case\n"
      << "device: " << device << "\n"
      << "seed: Pentium 4 2 GHz, Direct3D, 2006 (REFERENCES.md)\n\n"
      << "| case | view | fps | ms/frame | CPU ms/frame | seed |\n"
      << "|---|---|---:|---:|---:|---|\n";
  for (const Measured& m : results) {
    out << "| " << m.c.name << " | " << (m.c.stereo ? "stereo" : "mono") << " | "
        << core::format_fixed(m.fps(), 0) << " | " << core::format_fixed(m.ms(), 3) << " | "
        << core::format_fixed(m.cpu_ms(), 3) << " | " << (m.c.seed.empty() ? "-" : m.c.seed)
        << " |\n";
  }
  return 0;
}

}  // namespace telear::cli
