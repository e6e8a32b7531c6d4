// clang-format off
#include <epoxy/gl.h>  // before anything that includes GL/gl.h
// clang-format on
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "telear/console/console_app.hpp"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <sstream>
#include <thread>

#include "gui_context.hpp"
#include "telear/console/console_actions.hpp"
#include "telear/console/eye_windows.hpp"
#include "telear/console/gamepad_input.hpp"
#include "telear/console/keyboard_input.hpp"
#include "telear/console/mouse_input.hpp"
#include "telear/console/panels.hpp"
#include "telear/core/angles.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/clock.hpp"
#include "telear/core/image_size.hpp"
#include "telear/core/marker_mount.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/version.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/net/token_file.hpp"
#include "telear/record/server_recorder.hpp"
#include "telear/render/ar_view.hpp"
#include "telear/render/frame_code_readback.hpp"
#include "telear/render/gl_objects.hpp"
#include "telear/render/glfw_context.hpp"
#include "telear/render/image_io.hpp"
#include "telear/render/offscreen_target.hpp"
#include "telear/render/scene_objects.hpp"
#include "telear/render/stereo_composer.hpp"
#include "telear/session/capture_session.hpp"
#include "telear/session/session_recording.hpp"
#include "telear/view/ar_view_input.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/stereo_camera_file.hpp"

namespace telear::console {

namespace {

using Clock = std::chrono::steady_clock;

render::StereoLayout view_layout(const UiState& ui) {
  switch (ui.layout) {
    case ViewLayout::kSideBySide:
      return render::StereoLayout::kSideBySide;
    case ViewLayout::kTopBottom:
      return render::StereoLayout::kTopBottom;
    case ViewLayout::kAnaglyph:
      return render::StereoLayout::kAnaglyph;
    case ViewLayout::kPageFlip:
      return ui.page_flip_granted ? render::StereoLayout::kSeparate
                                  : render::StereoLayout::kSideBySide;
    default:
      return render::StereoLayout::kSeparate;
  }
}

}  // namespace

struct ConsoleApp::Impl {
  ConsoleOptions options;
  core::RobotModelPtr model;
  session::SessionOptions session_options;
  vision::StereoCameraModel cameras;  // at the video's resolution
  core::BodyDescription body;
  core::Workspace workspace;              // the operator's copy of the scene
  std::unique_ptr<GuiContext> gui;        // the window (GLFW) or headless target, ImGui
  render::GlfwContext* window = nullptr;  // gui's window, when windowed
  std::optional<render::ArView> view;
  // The registration capture's coverage image, uploaded when the capture changes.
  render::Texture coverage_texture;
  const session::CaptureSession* coverage_owner = nullptr;
  int coverage_revision = -1;
  render::StereoLayout built_layout = render::StereoLayout::kSideBySide;
  int built_segments = -1;
  KeyboardInput keyboard;
  MouseInput mouse;
  std::optional<GamepadInput> gamepad;
  std::unique_ptr<EyeWindows> eyes;
  Clock::time_point last_frame = Clock::now();
  double fps_accumulator = 0.0;
  int fps_frames = 0;
  bool auto_take_control = false;
  std::unique_ptr<record::ServerRecorder> recorder;  // --record
  std::uint64_t recorded_frame = 0;                  // the last frame whose latency it has
  std::ostream* log = nullptr;

  ~Impl() {
    if (gui) (void)gui->make_current();
    view.reset();
    eyes.reset();
    gui.reset();
  }

  CoverageTexture coverage(const session::Session& session) {
    const session::CaptureSession* capture = session.capture();
    if (!capture) {
      coverage_owner = nullptr;
      return {};
    }
    if (capture != coverage_owner || capture->revision() != coverage_revision) {
      coverage_owner = capture;
      coverage_revision = capture->revision();
      const cv::Mat bgr = capture->coverage();
      if (bgr.empty() || bgr.type() != CV_8UC3) return {};
      std::vector<std::uint8_t> rgb(bgr.total() * 3);
      for (int y = 0; y < bgr.rows; ++y) {
        const cv::Vec3b* row = bgr.ptr<cv::Vec3b>(y);
        for (int x = 0; x < bgr.cols; ++x) {
          std::uint8_t* out = &rgb[(static_cast<std::size_t>(y) * bgr.cols + x) * 3];
          out[0] = row[x][2];
          out[1] = row[x][1];
          out[2] = row[x][0];
        }
      }
      if (coverage_texture.width() != bgr.cols || coverage_texture.height() != bgr.rows) {
        coverage_texture = render::Texture::create_2d(bgr.cols, bgr.rows, GL_RGB8);
      }
      coverage_texture.upload(GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    }
    return {coverage_texture.id(), coverage_texture.width(), coverage_texture.height()};
  }

  Status build_view(const UiState& ui) {
    core::ArmBodyOptions body_options;
    body_options.segments_override = ui.segments;
    const core::ArmBody arm_body = core::build_arm_body(body, body_options);
    render::ArViewOptions view_options;
    view_options.layout = view_layout(ui);
    view.reset();
    std::vector<render::SceneObject> objects = {render::make_floor(3.0f, 12)};
    for (render::SceneObject& o : render::workspace_scene_objects(workspace)) {
      objects.push_back(std::move(o));
    }
    auto created = render::ArView::create(*model, arm_body, cameras, objects, view_options);
    if (!created) return created.error();
    view.emplace(std::move(*created));
    built_layout = view_options.layout;
    built_segments = ui.segments;
    return Status::Ok();
  }
};

ConsoleApp::ConsoleApp(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

ConsoleApp::~ConsoleApp() {
  if (session_) session_->disconnect();
  session_.reset();
  if (impl_ && impl_->recorder) (void)impl_->recorder->stop();
  servers_.reset();
}

Result<std::unique_ptr<ConsoleApp>> ConsoleApp::create(const ConsoleOptions& options,
                                                       std::ostream& log) {
  auto impl = std::make_unique<Impl>();
  impl->options = options;
  impl->log = &log;
  if (options.width < 320 || options.height < 240 || options.width > 8192 ||
      options.height > 8192) {
    return Error{"the console's size must be within 320x240 .. 8192x8192"};
  }
  if (!options.fullscreen_eyes.empty() && options.fullscreen_eyes != "two-windows" &&
      options.fullscreen_eyes != "sbs") {
    return Error{"fullscreen_eyes '" + options.fullscreen_eyes + "': two-windows or sbs"};
  }
  if (options.video_planes != "auto" && options.video_planes != "on" &&
      options.video_planes != "off") {
    return Error{"video_planes '" + options.video_planes + "': auto, on or off"};
  }
  if (options.headless && !options.fullscreen_eyes.empty()) {
    return Error{"fullscreen_eyes needs a display; it cannot be combined with headless"};
  }
  const bool embedded = options.robot.empty() && options.vision.empty();
  if (!embedded && (options.robot.empty() || options.vision.empty())) {
    return Error{"give both the robot and the vision server's address, or neither (local servers)"};
  }
  if (embedded && !options.start_local_servers) {
    return Error{"no robot and vision server addresses, and no local servers to start"};
  }
  auto resolution = core::parse_image_size(options.resolution, {64, 48}, {1920, 1080});
  if (!resolution) return Error{"resolution: " + resolution.error().message};
  const auto [width, height] = *resolution;

  auto arm = geometry::load_robot_assets(options.arm, options.geometry);
  if (!arm) return arm.error();
  for (const std::string& warning : arm->warnings) log << "telear console: " << warning << "\n";
  impl->model = arm->model();
  impl->body = arm->body;
  const std::string workspace_file = options.workspace.empty()
                                         ? core::default_workspace_file(arm->description.name)
                                         : options.workspace;
  if (!options.workspace.empty() || std::filesystem::exists(workspace_file)) {
    auto workspace = geometry::load_workspace(workspace_file);  // meshes too: checked
    if (!workspace) return workspace.error();
    impl->workspace = std::move(*workspace);
    // The session checks the plan and the ghost against the operator's copy of the scene.
    impl->session_options.description = arm->description;
    impl->session_options.workspace = impl->workspace;
  }

  // [SECTION] calibration and servers
  std::unique_ptr<ConsoleApp> app(new ConsoleApp(std::move(impl)));
  Impl& m = *app->impl_;
  std::optional<vision::StereoCameraModel> cameras;
  const std::string& calibration_file = options.calibration;
  if (!calibration_file.empty()) {
    auto loaded = vision::load_stereo_cameras(calibration_file);
    if (!loaded) return loaded.error();
    cameras = *loaded;
    app->ui_.calibration_note = "calibration: " + calibration_file;
  }
  net::RobotClientOptions& robot = m.session_options.robot;
  net::VisionClientOptions& vision = m.session_options.vision;
  robot.client_name = "telear-console";
  vision.client_name = "telear-console";
  if (embedded) {
    auto servers = options.start_local_servers(m.model, arm->description, calibration_file, {});
    if (!servers) return servers.error();
    app->servers_ = std::move(*servers);
    if (!cameras) {
      cameras = app->servers_->cameras();
      app->ui_.calibration_note =
          "calibration: the simulator's TRUE cameras (no calibration file; `telear demo` writes a "
          "registered one to out/demo/cache/registered.yaml)";
    }
    robot.address = app->servers_->robot_address();
    vision.address = app->servers_->vision_address();
    robot.token = app->servers_->token();
    app->ui_.embedded = true;
    m.auto_take_control = true;
    m.session_options.lease_heartbeat_s = 1.0;  // see SessionOptions::lease_heartbeat_s
    log << "telear console: embedded simulated servers: robot " << robot.address << ", vision "
        << vision.address << "\n";
  } else {
    robot.address = options.robot;
    vision.address = options.vision;
    robot.tls_root_certificate_file = options.tls_ca_file;
    vision.tls_root_certificate_file = options.tls_ca_file;
    if (!options.token_file.empty()) {
      auto token = net::load_token_file(options.token_file);
      if (!token) return token.error();
      robot.token = *token;
      vision.token = *token;
    }
  }
  if (options.lease_heartbeat_s > 0.0)
    m.session_options.lease_heartbeat_s = options.lease_heartbeat_s;
  vision.token = robot.token;
  vision.width = width;
  vision.height = height;
  if (!cameras) {  // ask the vision server for its calibration
    net::VisionClient probe(vision);
    auto info = probe.get_camera_info();
    if (!info)
      return Error{"no calibration: " + info.error().message + " (give a calibration file)"};
    if (!info->found) {
      return Error{"no calibration: the vision server has none; give a calibration file"};
    }
    cameras = info->cameras;
    app->ui_.calibration_note = "calibration: from the vision server (" + info->source + ")";
  }
  m.cameras.left = vision::resized_camera(cameras->left, width, height);
  m.cameras.right = vision::resized_camera(cameras->right, width, height);
  m.session_options.cameras = m.cameras;
  // The registration marker, when the robot has one (the live overlay check needs it).
  if (auto marker = arm->marker()) {
    m.session_options.marker = session::GripperMarker{marker->id, marker->corners_flange()};
  }
  std::snprintf(app->ui_.robot_address, sizeof app->ui_.robot_address, "%s", robot.address.c_str());
  std::snprintf(app->ui_.vision_address, sizeof app->ui_.vision_address, "%s",
                vision.address.c_str());
  std::snprintf(app->ui_.token, sizeof app->ui_.token, "%s", robot.token.c_str());

  // [SECTION] script (before anything is drawn: a parse error stops here)
  if (!options.script.empty()) {
    auto lines = load_ui_script(options.script, m.model->dof());
    if (!lines) return lines.error();
    app->script_ = ScriptRunner(std::move(*lines));
  }

  // [SECTION] recording (--record): the servers the console starts with, the session's events
  if (!options.record.empty()) {
    record::ServerRecorderOptions recording;
    recording.robot_address = robot.address;
    recording.vision_address = vision.address;
    recording.token = robot.token;
    recording.tls_ca_file = robot.tls_root_certificate_file;
    recording.client_name = "telear-console-record";
    recording.recorder.path = options.record;
    recording.recorder.metadata["recorded_by"] = "telear console";
    recording.recorder.metadata["telear_version"] = std::string(core::version_string());
    recording.recorder.metadata["calibration_file"] = calibration_file;
    recording.recorder.metadata["robot_spec"] = options.arm.name_or_path;  // replay loads it
    recording.recorder.metadata["robot_tip"] = options.arm.tip;
    // What the view draws: the session's stream, the view's ghost, the console's cameras.
    recording.stream_video = false;
    recording.stream_state = false;
    recording.recorder.ghost_from_state_stream = false;
    recording.cameras = m.cameras;
    auto recorder = record::ServerRecorder::start(recording);
    if (!recorder) return recorder.error();
    m.recorder = std::move(*recorder);
    session::record_session_streams(m.session_options, *m.recorder);
    log << "telear console: recording to " << options.record << "\n";
  }

  // [SECTION] GL and ImGui
  GuiOptions gui_options;
  gui_options.headless = options.headless;
  gui_options.width = options.width;
  gui_options.height = options.height;
  gui_options.title = "telear console";
  gui_options.request_stereo = true;
  auto gui = GuiContext::create(gui_options);
  if (!gui) return gui.error();
  m.gui = std::move(*gui);
  m.window = m.gui->window();
  if (m.window) {
    const render::WindowStereo stereo = render::choose_window_stereo(m.window->stereo_granted());
    app->ui_.page_flip_granted = stereo.page_flipped;
    app->ui_.page_flip_message = stereo.message;
    m.gamepad.emplace();
  }
  // The video as decoded JPEG planes, converted by the GPU, where the renderer is one (on a
  // software renderer the CPU's SIMD conversion is cheaper: docs/benchmarks.md, "Video planes").
  const bool hardware = !render::is_software_renderer(render::GlContext::gl_renderer());
  m.session_options.vision.decode_planes =
      options.video_planes == "on" || (options.video_planes == "auto" && hardware);
  log << "telear console: video "
      << (m.session_options.vision.decode_planes ? "decoded to Y'CbCr planes, converted on the GPU"
                                                 : "decoded to RGB")
      << " (renderer " << render::GlContext::gl_renderer() << ")\n";

  auto session = session::Session::create(m.model, m.session_options);
  if (!session) return session.error();
  app->session_ = std::move(*session);
  app->session_->connect();

  if (Status s = m.build_view(app->ui_); !s.ok()) return s.error();

  if (!options.fullscreen_eyes.empty()) {
    auto eyes = EyeWindows::create(*m.window, options.fullscreen_eyes == "two-windows");
    if (!eyes) return eyes.error();
    m.eyes = std::move(*eyes);
  }
  app->ui_.last_message =
      app->ui_.embedded ? "connected to the embedded simulated servers" : "connecting";
  return app;
}

void ConsoleApp::rebuild_session() {
  Impl& m = *impl_;
  ui_.reconnect_requested = false;
  session_->disconnect();
  session::SessionOptions options = m.session_options;
  options.robot.address = ui_.robot_address;
  options.vision.address = ui_.vision_address;
  options.robot.token = ui_.token;
  options.vision.token = ui_.token;
  // --record records the servers the console started with, not others connected to later.
  if (options.vision.address != m.session_options.vision.address) options.vision.on_received = {};
  if (options.robot.address != m.session_options.robot.address) options.robot.on_state = {};
  auto session = session::Session::create(m.model, options);
  if (!session) {
    ui_.last_message = "connect: " + session.error().message;
    ui_.last_failed = true;
    session_->connect();
    return;
  }
  session_ = std::move(*session);
  m.session_options = options;
  session_->connect();
  m.auto_take_control = ui_.embedded;
  ui_.last_message = "connecting to " + options.robot.address + " and " + options.vision.address;
}

bool ConsoleApp::frame() {
  Impl& m = *impl_;
  const auto now = Clock::now();
  double dt = std::chrono::duration<double>(now - m.last_frame).count();
  m.last_frame = now;
  if (frames_ == 0 || dt <= 0.0) dt = 1.0 / 60.0;
  m.fps_accumulator += dt;
  if (++m.fps_frames >= 10) {
    ui_.fps = m.fps_frames / m.fps_accumulator;
    m.fps_accumulator = 0;
    m.fps_frames = 0;
  }
  if (!m.gui->begin_frame(dt)) return false;

  auto act = [this](const UiAction& a) { (void)apply_action(*session_, ui_, a); };

  // [SECTION] input: the E-STOP shortcut first, then the devices
  const ImGuiIO& io = ImGui::GetIO();
  if (ImGui::IsKeyPressed(io.KeyMap[ImGuiKey_Escape], false) ||
      (!io.WantTextInput && ImGui::IsKeyPressed(io.KeyMap[ImGuiKey_Space], false))) {
    act(simple(ActionKind::kEStop));
  }
  InputSteps steps;
  steps.joint_rad = core::radians_from_degrees(ui_.joint_step_deg);
  steps.cartesian_m = ui_.cartesian_step_mm / 1000.0;
  steps.rotation_rad = core::radians_from_degrees(ui_.rotation_step_deg);
  steps.frame = ui_.frame;
  steps.dof = m.model->dof();
  std::vector<InputDevice*> devices{&m.keyboard, &m.mouse};
  if (m.gamepad) devices.push_back(&*m.gamepad);
  const bool real = ui_.input_target == InputTarget::kReal;
  for (InputDevice* device : devices) {
    if (!device->available()) continue;
    for (const InputIncrement& inc : device->poll(dt, steps)) {
      UiAction a;
      switch (inc.kind) {
        case InputIncrement::Kind::kJoint:
          a = {.kind = real ? ActionKind::kRealJoint : ActionKind::kGhostJoint,
               .index = inc.joint,
               .value = inc.delta};
          break;
        case InputIncrement::Kind::kCartesian:
          a = ghost_cartesian(inc.frame, inc.dX, inc.dM);
          if (real) a.kind = ActionKind::kRealCartesian;
          break;
        case InputIncrement::Kind::kGripper:
          a = {.kind = real ? ActionKind::kRealGripper : ActionKind::kGhostGripper,
               .value = inc.delta};
          break;
      }
      act(a);
    }
  }

  // [SECTION] script, session
  if (!script_.finished()) {
    script_.step(*session_, ui_, session_->now(), [this](const std::string& message) {
      *impl_->log << "script: " << message << "\n";
    });
  }
  if (ui_.reconnect_requested) rebuild_session();
  session_->update(dt);
  if (m.recorder) {
    session::record_session_view(*m.recorder, session_->view(), m.recorded_frame,
                                 session_->state_taken_ns());
  }
  if (m.auto_take_control && session_->view().real && session_->robot_connected()) {
    m.auto_take_control = false;
    if (Status s = session_->take_control(); !s.ok()) {
      ui_.last_message = "take control: " + s.error().message;
      ui_.last_failed = true;
    }
  }

  // [SECTION] the AR view
  if (ui_.segments != m.built_segments || view_layout(ui_) != m.built_layout || ui_.body_dirty) {
    ui_.body_dirty = false;
    if (Status s = m.build_view(ui_); !s.ok()) {
      ui_.last_message = "view: " + s.error().message;
      ui_.last_failed = true;
    }
  }
  m.view->set_options(with_view_settings(m.view->options(), ui_));
  const session::SessionView& v = session_->view();
  render::ArViewInput input = view::ar_view_input(v);
  if (input.ghost_q.size() == 0) input.ghost_q = session_->ghost().q();  // before the first update
  m.view->render(input);
  // Glass to glass: a newly drawn frame's code read back from its eye (docs/latency.md).
  if (v.frame && input.mode == render::ViewMode::kAr && !session_->shown_noted(v.frame->frame_id)) {
    const render::ShownFrameCode shown = render::read_shown_frame_code(m.view->eye(0));
    session_->note_shown(v.frame->frame_id, shown.code, shown.shown_ns);
  }
  ViewTextures textures;
  textures.left = m.view->eye(0).colour_texture().id();
  textures.right = m.view->eye(1).colour_texture().id();
  textures.eye_width = m.view->eye(0).width();
  textures.eye_height = m.view->eye(0).height();
  textures.composed = m.view->composed().colour_texture().id();
  textures.composed_width = m.view->composed().width();
  textures.composed_height = m.view->composed().height();

  // [SECTION] panels
  PanelContext ctx{*session_, ui_, act};
  PanelLayout layout{io.DisplaySize.x, io.DisplaySize.y};
  m.mouse.set_over_view(draw_view_panel(ctx, layout, textures));
  draw_plan_panel(ctx, layout);
  draw_status_panel(ctx, layout);
  draw_connection_panel(ctx, layout);
  draw_ghost_panel(ctx, layout);
  draw_real_robot_panel(ctx, layout);
  draw_registration_panel(ctx, layout, m.coverage(*session_));
  draw_plots_panel(ctx, layout);
  draw_estop_panel(ctx, layout);
  draw_status_bar(ctx, layout);
  ImGui::Render();

  // [SECTION] draw into the window or the frame buffer
  int fb_w = 0, fb_h = 0;
  m.gui->bind_output(fb_w, fb_h);
  const bool page_flip = m.window && ui_.layout == ViewLayout::kPageFlip && ui_.page_flip_granted;
  if (page_flip) {
    // Quad-buffer stereo: the whole UI into both back buffers, the view image being the left
    // eye's texture in the left buffer and the right eye's in the right buffer.
    ImDrawData* data = ImGui::GetDrawData();
    glDrawBuffer(GL_BACK_LEFT);
    glClearColor(0.08f, 0.08f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(data);
    const ImTextureID left_id =
        reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(textures.left));
    const ImTextureID right_id =
        reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(textures.right));
    for (int i = 0; i < data->CmdListsCount; ++i) {
      for (ImDrawCmd& cmd : data->CmdLists[i]->CmdBuffer) {
        if (cmd.TextureId == left_id) cmd.TextureId = right_id;
      }
    }
    glDrawBuffer(GL_BACK_RIGHT);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(data);
    glDrawBuffer(GL_BACK_LEFT);  // read-back (screenshots) shows the left eye
  } else {
    if (m.window) glDrawBuffer(GL_BACK);
    glClearColor(0.08f, 0.08f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  }
  ++frames_;

  // [SECTION] read-back
  const bool final_frame =
      m.options.frames > 0 && frames_ >= m.options.frames && script_.finished();
  const bool want_screenshot =
      ui_.screenshot_request || (final_frame && !m.options.screenshot.empty());
  if (want_screenshot || capture_every_frame_) {
    if (m.window) glReadBuffer(page_flip ? GL_BACK_LEFT : GL_BACK);
    last_image_ = m.gui->read_output(fb_w, fb_h);
  }
  if (ui_.screenshot_request) {
    const std::string path = *ui_.screenshot_request;
    ui_.screenshot_request.reset();
    if (Status s = render::write_png(path, last_image_); !s.ok()) {
      ui_.last_message = "screenshot: " + s.error().message;
      ui_.last_failed = true;
    } else {
      *m.log << "telear console: wrote " << path << "\n";
    }
  }
  m.gui->present();
  if (m.eyes)
    m.eyes->present(m.view->eye(0).colour_texture().id(), m.view->eye(1).colour_texture().id(),
                    textures.eye_width, textures.eye_height);

  // [SECTION] pacing (a window's vsync paces itself)
  if (!m.window && m.options.max_fps > 0) {
    const double spent = std::chrono::duration<double>(Clock::now() - now).count();
    const double period = 1.0 / m.options.max_fps;
    if (spent < period) std::this_thread::sleep_for(std::chrono::duration<double>(period - spent));
  }
  if (ui_.quit) return false;
  if (m.options.frames > 0) return !final_frame;
  if (m.options.headless) return !script_.finished();
  return true;
}

core::Image ConsoleApp::read_view_image() const {
  (void)impl_->gui->make_current();
  return impl_->view->read_composed_rgb();
}

Result<record::RecordingCounts> ConsoleApp::stop_recording() {
  if (!impl_->recorder) return Error{"not recording (no --record)"};
  return impl_->recorder->stop();
}

int ConsoleApp::run() {
  while (frame()) {
  }
  // The video as shown at the end (the status panel's figures over its last 2 s), for scripts
  // and measurements (docs/web.md compares the browser operator with it).
  const session::SessionStats stats = session_->stats();
  *impl_->log << "telear console: video " << core::format_number(stats.video_fps, "%.1f")
              << " fps decoded, " << stats.shown.samples << " frames shown with their code in 2 s";
  if (stats.shown.samples > 0) {
    *impl_->log << ", capture -> shown p50 " << core::format_number(stats.shown.p50_s * 1e3, "%.1f")
                << " ms, p99 " << core::format_number(stats.shown.p99_s * 1e3, "%.1f") << " ms";
  }
  *impl_->log << "\n";
  int status = script_.failures() > 0 ? 1 : 0;
  if (impl_->recorder) {
    auto counts = stop_recording();
    if (!counts) {
      *impl_->log << "telear console: " << counts.error().message << "\n";
      status = 1;
    } else {
      std::uint64_t messages = 0;
      for (const auto& [topic, n] : counts->written) messages += n;
      *impl_->log << "telear console: recorded " << impl_->options.record << ": " << messages
                  << " messages, " << counts->bytes << " bytes\n";
    }
  }
  if (!impl_->options.screenshot.empty()) {
    if (last_image_.empty()) {
      *impl_->log << "telear console: no image to write to " << impl_->options.screenshot << "\n";
      return 1;
    }
    if (Status s = render::write_png(impl_->options.screenshot, last_image_); !s.ok()) {
      *impl_->log << "telear console: " << s.error().message << "\n";
      return 1;
    }
    *impl_->log << "telear console: wrote " << impl_->options.screenshot << " ("
                << core::to_string(core::ImageSize{last_image_.width, last_image_.height}) << ", "
                << frames_ << " frames)\n";
  }
  if (script_.failures() > 0) {
    *impl_->log << "telear console: " << script_.failures() << " script line(s) failed\n";
  }
  return status;
}

}  // namespace telear::console
