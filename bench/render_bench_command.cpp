#include "bench/render_bench_command.hpp"

#include <nlohmann/json.hpp>

#include <stdlib.h>
#include <time.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <ostream>
#include <sstream>

#include "telear/core/arm_body.hpp"
#include "telear/core/arm_body_pose.hpp"
#include "telear/core/image_size.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/geometry/robot_assets.hpp"
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
            {where + ", " + name, arm, cube, segments, wire, video, stereo, std::move(seed), ""});
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

std::string generate_arms_script() {
  return TELEAR_GENERATE_ARMS_SCRIPT;
}

RenderBenchCase mesh_arm_case(const std::string& name, const std::string& robot_file,
                              double visual_tolerance_m) {
  const std::string detail =
      visual_tolerance_m > 0.0
          ? " (level of detail " + core::format_fixed(visual_tolerance_m * 1000.0, 2) + " mm)"
          : " (as loaded)";
  return {"video, mesh " + name + detail,
          true,
          false,
          0,
          false,
          true,
          true,
          "",
          robot_file,
          visual_tolerance_m};
}

std::string mesh_arm_baseline_case() {
  return "video, arm, 8 seg";
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
  if (c.robot_file.empty()) {
    auto model = core::load_robot("puma560");
    if (!model) return model.error();
    m.model = *model;
    auto description = core::body_description_for(*m.model);
    if (!description) return description.error();
    m.body = core::build_arm_body(*description, {.segments_override = c.segments});
    m.q0 = *m.model->named_configuration("qn");
  } else {
    core::RobotSpec spec;
    spec.name_or_path = c.robot_file;
    geometry::GeometryOptions geometry_options;
    geometry_options.visual_tolerance_m = c.visual_tolerance_m;
    auto assets = geometry::load_robot_assets(spec, geometry_options);
    if (!assets) return assets.error();
    m.model = assets->model();
    m.body = core::build_arm_body(assets->body);
    // The generated arms' "ready": the gripper down above the table, in the cameras' view.
    m.q0 = m.model->named_configuration("ready").value_or(Eigen::VectorXd::Zero(m.model->dof()));
  }
  m.pose = std::make_unique<core::ArmBodyPose>(*m.model, m.body);
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
  if (!m.c.robot_file.empty() && m.body.has_gripper()) {
    m.pose->set_gripper_opening(m.body.max_gripper_opening() * float(0.5 + 0.4 * std::sin(t)));
  }
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

std::size_t RenderBenchScene::triangle_count() const {
  return impl_->arm.triangle_count();
}

std::size_t RenderBenchScene::vertex_count() const {
  std::size_t n = 0;
  for (const core::BodyPart& part : impl_->body.parts) n += part.mesh.vertices.size();
  return n;
}

std::vector<unsigned char> RenderBenchScene::last_image() {
  if (!impl_->c.video) impl_->target.read_pixels(3, impl_->readback.data());
  return impl_->readback;
}

namespace {

constexpr const char* kPython = "/usr/bin/python3";

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

// A temporary directory, removed with everything in it when this goes out of scope.
class TemporaryDirectory {
 public:
  static Result<TemporaryDirectory> create(const std::string& prefix) {
    std::error_code ec;
    const std::filesystem::path base = std::filesystem::temp_directory_path(ec);
    if (ec) return Error{"no temporary directory: " + ec.message()};
    std::string pattern = (base / (prefix + "XXXXXX")).string();
    if (mkdtemp(pattern.data()) == nullptr) {
      return Error{"cannot create a directory like " + pattern + ": " + std::strerror(errno)};
    }
    TemporaryDirectory d;
    d.path_ = pattern;
    return d;
  }
  TemporaryDirectory() = default;
  TemporaryDirectory(TemporaryDirectory&& other) noexcept : path_(std::move(other.path_)) {
    other.path_.clear();
  }
  TemporaryDirectory& operator=(TemporaryDirectory&& other) noexcept {
    std::swap(path_, other.path_);
    return *this;
  }
  ~TemporaryDirectory() {
    if (path_.empty()) return;
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// The mesh arm of --mesh-arm: the generator's command line, where it wrote the arm, and the
// generator's own report (its triangle counts).
struct MeshArm {
  TemporaryDirectory directory;
  std::string command;
  std::string robot_file;
  std::string generator_output;
};

// Runs scripts/generate_arms.py --detail D --out TMPDIR and returns the robot file of `name`.
Result<MeshArm> generate_mesh_arm(const std::string& name, int detail) {
  const std::string script = generate_arms_script();
  if (!std::filesystem::is_regular_file(script)) {
    return Error{"--mesh-arm: the generator " + script +
                 " is not there (it is in telear's source tree, not installed)"};
  }
  auto directory = TemporaryDirectory::create("telear-bench-render-");
  if (!directory) return Error{"--mesh-arm: " + directory.error().message};
  MeshArm arm;
  arm.directory = std::move(directory.value());
  arm.command = std::string(kPython) + " " + script + " --detail " + std::to_string(detail) +
                " --out " + arm.directory.path();
  // Paths come from the build (script) and mkdtemp under $TMPDIR, the detail is an int; both
  // paths are single-quoted for the shell, so one holding a quote is refused.
  if ((script + arm.directory.path()).find('\'') != std::string::npos) {
    return Error{"--mesh-arm: cannot quote a path holding ' for the shell: " + arm.command};
  }
  const std::string shell = std::string(kPython) + " '" + script + "' --detail " +
                            std::to_string(detail) + " --out '" + arm.directory.path() + "' 2>&1";
  FILE* pipe = popen(shell.c_str(), "r");
  if (pipe == nullptr) return Error{"--mesh-arm: cannot run " + arm.command};
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) arm.generator_output += buffer;
  const int status = pclose(pipe);
  while (!arm.generator_output.empty() &&
         std::isspace(static_cast<unsigned char>(arm.generator_output.back()))) {
    arm.generator_output.pop_back();
  }
  if (status != 0) {
    return Error{"--mesh-arm: " + arm.command + " failed: " + arm.generator_output};
  }
  arm.robot_file = arm.directory.path() + "/" + name + ".yaml";
  return arm;
}

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
  if (!options.mesh_arm.empty() && options.mesh_arm != "ur6" && options.mesh_arm != "arm7") {
    err << "telear bench render: --mesh-arm must be ur6 or arm7, got '" << options.mesh_arm
        << "'\n";
    return 2;
  }
  auto context = create_headless_context();
  if (!context) {
    err << "telear bench render: " << context.error().message << "\n";
    return 1;
  }
  const std::string device = (*context)->description();

  // The cases to run: the seed's (filtered by --only), and with --mesh-arm the mesh arm and
  // the PUMA case it is compared with, whatever --only says.
  std::vector<RenderBenchCase> cases;
  std::optional<MeshArm> mesh_arm;
  const auto selected = [&](const std::string& name) {
    return options.only.empty() || name.find(options.only) != std::string::npos;
  };
  const bool with_mesh_arm = !options.mesh_arm.empty();
  for (const RenderBenchCase& c : render_bench_cases()) {
    const bool baseline =
        with_mesh_arm && c.video && c.stereo && c.name == mesh_arm_baseline_case();
    if (selected(c.name) || baseline) cases.push_back(c);
  }
  if (with_mesh_arm) {
    auto generated = generate_mesh_arm(options.mesh_arm, options.mesh_detail);
    if (!generated) {
      err << "telear bench render: " << generated.error().message << "\n";
      return 1;
    }
    mesh_arm.emplace(std::move(generated.value()));
    if (!options.json) {
      out << "mesh arm: generated with " << mesh_arm->command << " (removed after the run)\n";
    }
    cases.push_back(mesh_arm_case(options.mesh_arm, mesh_arm->robot_file, 0.0));
    if (options.mesh_tolerance_m > 0.0) {
      cases.push_back(
          mesh_arm_case(options.mesh_arm, mesh_arm->robot_file, options.mesh_tolerance_m));
    }
  }

  std::vector<Measured> results;
  // Triangles and vertices per view of the mesh arm as loaded ([0]) and at its level of
  // detail ([1]).
  std::size_t mesh_triangles[2] = {0, 0}, mesh_vertices[2] = {0, 0};
  for (const RenderBenchCase& c : cases) {
    auto scene = RenderBenchScene::create(c, options.width, options.height);
    if (!scene) {
      err << "telear bench render: " << c.name << ": " << scene.error().message << "\n";
      return 1;
    }
    if (!c.robot_file.empty()) {
      const int level = c.visual_tolerance_m > 0.0 ? 1 : 0;
      mesh_triangles[level] = (*scene)->triangle_count();
      mesh_vertices[level] = (*scene)->vertex_count();
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

  // The mesh arm beside the PUMA's case of the same frame (stereo, video, read-back).
  // `mesh` is the arm as drawn (its level of detail when there is one), `as_loaded` the
  // same arm with every triangle of its files.
  const Measured* mesh = nullptr;
  const Measured* as_loaded = nullptr;
  const Measured* puma = nullptr;
  for (const Measured& m : results) {
    if (!m.c.robot_file.empty() && m.c.visual_tolerance_m <= 0.0) as_loaded = &m;
    if (!m.c.robot_file.empty()) mesh = &m;
    if (m.c.robot_file.empty() && m.c.video && m.c.stereo && m.c.name == mesh_arm_baseline_case())
      puma = &m;
  }
  const double ratio = mesh && puma && puma->fps() > 0 ? mesh->fps() / puma->fps() : 0.0;
  double load[3] = {0, 0, 0};
  const bool has_load = getloadavg(load, 3) == 3;

  if (options.json) {
    nlohmann::json j;
    j["device"] = device;
    j["width"] = options.width;
    j["height"] = options.height;
    if (has_load) j["load_average"] = {load[0], load[1], load[2]};
    for (const Measured& m : results) {
      j["cases"].push_back({{"name", m.c.name},
                            {"view", m.c.stereo ? "stereo" : "mono"},
                            {"frames", m.frames},
                            {"fps", m.fps()},
                            {"ms_per_frame", m.ms()},
                            {"cpu_ms_per_frame", m.cpu_ms()},
                            {"seed", m.c.seed}});
    }
    if (mesh && puma) {
      j["mesh_arm"] = {{"robot", options.mesh_arm},
                       {"detail", options.mesh_detail},
                       {"triangles", mesh_triangles[0]},
                       {"vertices", mesh_vertices[0]},
                       {"tolerance_m", mesh->c.visual_tolerance_m},
                       {"triangles_drawn", mesh_triangles[mesh == as_loaded ? 0 : 1]},
                       {"vertices_drawn", mesh_vertices[mesh == as_loaded ? 0 : 1]},
                       {"fps_as_loaded", as_loaded ? as_loaded->fps() : 0.0},
                       {"generator", mesh_arm->command},
                       {"fps", mesh->fps()},
                       {"baseline", mesh_arm_baseline_case() + ", stereo"},
                       {"baseline_fps", puma->fps()},
                       {"ratio_to_baseline", ratio}};
    }
    out << j.dump(2) << "\n";
    return 0;
  }
  out << "telear bench render: " << core::to_string(core::ImageSize{options.width, options.height})
      << " per view, " << core::format_fixed(options.seconds, 1) << " s per case\n"
      << "device: " << device << "\n";
  if (has_load) {
    out << "load average: " << core::format_fixed(load[0], 2) << " "
        << core::format_fixed(load[1], 2) << " " << core::format_fixed(load[2], 2)
        << " (1, 5, 15 min)\n";
  }
  out << "seed: Pentium 4 2 GHz, Direct3D, 2006 (REFERENCES.md)\n\n"
      << "| case | view | fps | ms/frame | CPU ms/frame | seed |\n"
      << "|---|---|---:|---:|---:|---|\n";
  for (const Measured& m : results) {
    out << "| " << m.c.name << " | " << (m.c.stereo ? "stereo" : "mono") << " | "
        << core::format_fixed(m.fps(), 0) << " | " << core::format_fixed(m.ms(), 3) << " | "
        << core::format_fixed(m.cpu_ms(), 3) << " | " << (m.c.seed.empty() ? "-" : m.c.seed)
        << " |\n";
  }
  if (mesh && puma) {
    out << "\nmesh arm " << options.mesh_arm << ": " << mesh_triangles[0] << " triangles, "
        << mesh_vertices[0] << " vertices (generate_arms.py --detail " << options.mesh_detail
        << ")";
    if (mesh != as_loaded) {
      out << ", drawn as " << mesh_triangles[1] << " triangles, " << mesh_vertices[1]
          << " vertices (level of detail "
          << core::format_fixed(mesh->c.visual_tolerance_m * 1000.0, 2) << " mm)";
    }
    out << ", stereo AR frame at " << core::format_fixed(mesh->fps(), 0)
        << " fps = " << core::format_fixed(ratio, 2) << " x the PUMA's '"
        << mesh_arm_baseline_case() << "' stereo (" << core::format_fixed(puma->fps(), 0)
        << " fps)\n";
  }
  return 0;
}

}  // namespace telear::cli
