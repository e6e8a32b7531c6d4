// clang-format off
#include <epoxy/gl.h>  // before anything that includes GL/gl.h
// clang-format on
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "telear/console/replay_app.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "gui_context.hpp"
#include "imgui_texture.hpp"
#include "telear/console/ui_state.hpp"
#include "telear/core/angles.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/render/ar_view.hpp"
#include "telear/render/image_io.hpp"
#include "telear/render/scene_objects.hpp"
#include "telear/session/display_mode.hpp"

namespace telear::console {

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kMinSpeed = 1.0 / 16.0, kMaxSpeed = 16.0;

// The view options the console starts with (ui_state.hpp's defaults): the replayed image is
// the live one.
render::ArViewOptions console_view_options() {
  render::ArViewOptions options;
  options.layout = render::StereoLayout::kSideBySide;
  return with_view_settings(options, UiState{});
}

std::string joints_text(const Eigen::VectorXd& q) {
  std::string text;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    if (i > 0) text += " ";
    text += core::format_number(core::degrees_from_radians(q[i]), "%.1f");
  }
  return text;
}

}  // namespace

struct ReplayApp::Impl {
  ReplayOptions options;
  std::ostream* log = nullptr;
  std::optional<record::RecordingPlayback> playback;
  core::RobotModelPtr model;
  std::unique_ptr<GuiContext> gui;  // before view: the view's GL objects need its context
  std::optional<render::ArView> view;
  Clock::time_point last_frame = Clock::now();
  std::string status;  // the last error drawing a frame (shown in the panel)
};

ReplayApp::ReplayApp(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

ReplayApp::~ReplayApp() {
  if (impl_ && impl_->gui) (void)impl_->gui->make_current();
  if (impl_) impl_->view.reset();
}

Result<std::unique_ptr<ReplayApp>> ReplayApp::create(const ReplayOptions& options,
                                                     std::ostream& log) {
  if (options.width < 320 || options.height < 240 || options.width > 8192 ||
      options.height > 8192) {
    return Error{"the replay's size must be within 320x240 .. 8192x8192"};
  }
  if (!(options.speed >= kMinSpeed && options.speed <= kMaxSpeed)) {
    return Error{"speed " + core::format_number(options.speed, "%g") + ": within 1/16 .. 16"};
  }
  if (!std::isfinite(options.at) || options.at < 0.0) {
    return Error{"at " + core::format_number(options.at, "%g") + ": seconds from the start, >= 0"};
  }
  if (options.frames < 0) return Error{"frames must be >= 0"};
  auto impl = std::make_unique<Impl>();
  impl->options = options;
  impl->log = &log;
  auto playback = record::RecordingPlayback::open(options.path);
  if (!playback) return playback.error();
  impl->playback.emplace(std::move(*playback));
  record::RecordingPlayback& p = *impl->playback;

  // [SECTION] the arm: the recording's, unless given
  core::RobotSpec spec = options.arm;
  if (spec.name_or_path.empty()) {
    spec.name_or_path = p.robot_spec();
    if (spec.tip.empty()) spec.tip = p.robot_tip();
  }
  if (spec.name_or_path.empty()) {
    return Error{"'" + options.path + "' does not name its robot; give --robot"};
  }
  auto arm = geometry::load_robot_assets(spec, options.geometry);
  if (!arm) return Error{"the recording's robot: " + arm.error().message + " (give --robot)"};
  for (const std::string& warning : arm->warnings) log << "telear replay: " << warning << "\n";
  impl->model = arm->model();
  const std::vector<std::string>& recorded =
      p.series().robot.names.empty() ? p.series().ghost.names : p.series().robot.names;
  if (!recorded.empty() && static_cast<int>(recorded.size()) != impl->model->dof()) {
    return Error{"robot '" + spec.name_or_path + "' has " + std::to_string(impl->model->dof()) +
                 " joints, the recording " + std::to_string(recorded.size()) +
                 " (give the recorded arm with --robot)"};
  }

  // [SECTION] the cameras at the recorded frames' size (what the live view was drawn at)
  vision::StereoCameraModel cameras = p.cameras();
  std::unique_ptr<ReplayApp> app(new ReplayApp(std::move(impl)));
  Impl& m = *app->impl_;
  GuiOptions gui_options;
  gui_options.headless = options.headless;
  gui_options.width = options.width;
  gui_options.height = options.height;
  gui_options.title = "telear replay: " + options.path;
  auto gui = GuiContext::create(gui_options);
  if (!gui) return gui.error();
  m.gui = std::move(*gui);
  if (!p.series().frames[0].empty()) {
    auto first = m.playback->frame(0);
    if (!first) return first.error();
    const core::Image& image = (*first)->left;
    cameras.left = vision::resized_camera(cameras.left, image.width, image.height);
    cameras.right = vision::resized_camera(cameras.right, image.width, image.height);
  }

  // [SECTION] the view: the console's
  std::vector<render::SceneObject> objects = {render::make_floor(3.0f, 12)};
  if (!p.workspace_yaml().empty()) {
    auto workspace = core::parse_workspace_yaml(p.workspace_yaml(), options.path + " (workspace)");
    if (workspace) {
      if (Status s = geometry::load_workspace_meshes(*workspace); !s.ok()) {
        log << "telear replay: workspace meshes not drawn: " << s.error().message << "\n";
        std::erase_if(workspace->objects,
                      [](const core::WorkspaceObject& o) { return !o.mesh_file.empty(); });
      }
      for (render::SceneObject& o : render::workspace_scene_objects(*workspace)) {
        objects.push_back(std::move(o));
      }
    } else {
      log << "telear replay: workspace not drawn: " << workspace.error().message << "\n";
    }
  }
  const core::ArmBody body = core::build_arm_body(arm->body, {});
  auto view = render::ArView::create(*m.model, body, cameras, objects, console_view_options());
  if (!view) return view.error();
  m.view.emplace(std::move(*view));

  app->speed_ = options.speed;
  app->playing_ = options.headless ? options.frames > 1 : options.play;
  app->seek(options.at);
  log << "telear replay: " << options.path << ": " << core::format_number(p.duration_s(), "%.1f")
      << " s, " << p.series().frames[0].size() << " stereo frames, "
      << p.series().ghost.samples.size() << " ghost and " << p.series().robot.samples.size()
      << " robot states" << (p.series().complete ? "" : " (an unfinished file)") << "\n";
  return app;
}

const record::RecordingPlayback& ReplayApp::playback() const {
  return *impl_->playback;
}

double ReplayApp::duration() const {
  return impl_->playback->duration_s();
}

void ReplayApp::seek(double t) {
  t_ = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, duration());
  moment_ = impl_->playback->at(t_);
}

Status ReplayApp::set_speed(double speed) {
  if (!(speed >= kMinSpeed && speed <= kMaxSpeed)) {
    return Error{"speed " + core::format_number(speed, "%g") + ": within 1/16 .. 16"};
  }
  speed_ = speed;
  return Status::Ok();
}

void ReplayApp::step(int frames) {
  playing_ = false;
  const auto& left = impl_->playback->series().frames[0];
  if (left.empty()) return;
  long index = moment_.frame ? static_cast<long>(*moment_.frame) : -1;
  index = std::clamp(index + frames, 0L, static_cast<long>(left.size()) - 1);
  seek(left[static_cast<std::size_t>(index)].t);
}

Status ReplayApp::draw_view() {
  Impl& m = *impl_;
  render::ArViewInput input;
  input.mode = moment_.vr ? render::ViewMode::kVr : render::ViewMode::kAr;
  // Stale as the live view judged it: older than the display's late threshold, or no frame.
  input.stale =
      !moment_.frame_age_s || *moment_.frame_age_s > session::DisplayModeOptions{}.late_threshold_s;
  const record::PlaybackFrame* frame = nullptr;
  if (moment_.frame) {
    auto decoded = m.playback->frame(*moment_.frame);
    if (!decoded) return decoded.error();
    frame = *decoded;
    input.left = &frame->left;
    input.right = &frame->right;
  }
  if (moment_.ghost) {
    input.ghost_q = moment_.ghost->position;
    input.ghost_gripper = moment_.ghost->gripper.value_or(1.0);
  } else if (moment_.robot) {
    input.ghost_q = moment_.robot->position;  // before the first ghost: where the arm is
  } else {
    input.ghost_q = Eigen::VectorXd::Zero(m.model->dof());
  }
  if (moment_.robot) {
    input.reported_q = moment_.robot->position;
    input.reported_gripper = moment_.robot->gripper.value_or(1.0);
  }
  m.view->render(input);
  return Status::Ok();
}

Result<core::Image> ReplayApp::render_view() {
  (void)impl_->gui->make_current();
  if (Status s = draw_view(); !s.ok()) return s.error();
  return impl_->view->read_composed_rgb();
}

bool ReplayApp::frame() {
  Impl& m = *impl_;
  const auto now = Clock::now();
  double dt = std::chrono::duration<double>(now - m.last_frame).count();
  m.last_frame = now;
  if (frames_ == 0 || dt <= 0.0) dt = 1.0 / 60.0;
  if (!m.gui->begin_frame(dt)) return false;
  if (playing_) {
    seek(t_ + dt * speed_);
    if (t_ >= duration()) playing_ = false;
  }
  if (Status s = draw_view(); !s.ok()) {
    m.status = s.error().message;
  } else {
    m.status.clear();
  }

  // [SECTION] panels: the view, the transport
  const ImGuiIO& io = ImGui::GetIO();
  const float panel_h = 150.0f;
  ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(io.DisplaySize.x, io.DisplaySize.y - panel_h),
                           ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Stereo AR view (replay)")) {
    const render::OffscreenTarget& composed = m.view->composed();
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const float scale = std::min(avail.x / static_cast<float>(composed.width()),
                                 avail.y / static_cast<float>(composed.height()));
    if (scale > 0.0f) {
      ImGui::Image(texture(composed.colour_texture().id()),
                   ImVec2(composed.width() * scale, composed.height() * scale), ImVec2(0, 1),
                   ImVec2(1, 0));
    }
  }
  ImGui::End();
  ImGui::SetNextWindowPos(ImVec2(0, io.DisplaySize.y - panel_h), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(io.DisplaySize.x, panel_h), ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Replay")) {
    if (ImGui::Button(playing_ ? "pause" : "play")) {
      if (playing_) {
        pause();
      } else {
        if (t_ >= duration()) seek(0.0);
        play();
      }
    }
    ImGui::SameLine();
    if (ImGui::Button("<")) step(-1);
    ImGui::SameLine();
    if (ImGui::Button(">")) step(1);
    ImGui::SameLine();
    static const double speeds[] = {0.25, 0.5, 1.0, 2.0, 4.0};
    static const char* speed_names[] = {"0.25x", "0.5x", "1x", "2x", "4x"};
    int speed_index = 2;
    for (int i = 0; i < 5; ++i) {
      if (std::abs(speeds[i] - speed_) < 1e-9) speed_index = i;
    }
    ImGui::SetNextItemWidth(80);
    if (ImGui::Combo("speed", &speed_index, speed_names, 5)) (void)set_speed(speeds[speed_index]);
    ImGui::SameLine();
    float t = static_cast<float>(t_);
    ImGui::SetNextItemWidth(-1);
    if (ImGui::SliderFloat("##time", &t, 0.0f, static_cast<float>(duration()), "%.2f s")) {
      seek(t);
    }
    const record::RecordingSeries& s = m.playback->series();
    ImGui::Text("%s  |  %.2f / %.2f s  |  frame %s / %zu  |  %s%s", m.options.path.c_str(), t_,
                duration(), moment_.frame ? std::to_string(*moment_.frame + 1).c_str() : "-",
                s.frames[0].size(), moment_.vr ? "VR" : "AR",
                s.complete ? "" : "  |  unfinished file (read to its last complete chunk)");
    ImGui::Text("ghost (deg): %s",
                moment_.ghost ? joints_text(moment_.ghost->position).c_str() : "not recorded yet");
    ImGui::Text("real  (deg): %s",
                moment_.robot ? joints_text(moment_.robot->position).c_str() : "not recorded yet");
    if (!m.status.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "%s", m.status.c_str());
  }
  ImGui::End();
  ImGui::Render();

  int w = 0, h = 0;
  m.gui->bind_output(w, h);
  if (m.gui->window()) glDrawBuffer(GL_BACK);
  glClearColor(0.08f, 0.08f, 0.1f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  ++frames_;
  const bool last = m.gui->headless() ? frames_ >= std::max(1, m.options.frames)
                                      : m.options.frames > 0 && frames_ >= m.options.frames;
  if (last && !m.options.screenshot.empty()) {
    if (m.gui->window()) glReadBuffer(GL_BACK);
    last_image_ = m.gui->read_output(w, h);
  }
  m.gui->present();
  return !last;
}

int ReplayApp::run() {
  while (frame()) {
  }
  Impl& m = *impl_;
  if (m.options.screenshot.empty()) return 0;
  if (last_image_.empty()) {
    *m.log << "telear replay: no image to write to " << m.options.screenshot << "\n";
    return 1;
  }
  if (Status s = render::write_png(m.options.screenshot, last_image_); !s.ok()) {
    *m.log << "telear replay: " << s.error().message << "\n";
    return 1;
  }
  *m.log << "telear replay: wrote " << m.options.screenshot << " (at "
         << core::format_number(t_, "%.2f") << " s)\n";
  return 0;
}

}  // namespace telear::console
