// clang-format off
#include <epoxy/gl.h>  // before anything that includes GL/gl.h
// clang-format on
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "gui_context.hpp"
#include "telear/render/egl_context.hpp"
#include "telear/render/framebuffer_readback.hpp"

namespace telear::console {

GuiContext::~GuiContext() {
  if (context_) (void)context_->make_current();
  if (imgui_gl_) ImGui_ImplOpenGL3_Shutdown();
  if (imgui_glfw_) ImGui_ImplGlfw_Shutdown();
  if (ImGui::GetCurrentContext()) ImGui::DestroyContext();
}

Result<std::unique_ptr<GuiContext>> GuiContext::create(const GuiOptions& options) {
  std::unique_ptr<GuiContext> gui(new GuiContext());
  gui->options_ = options;
  if (options.headless) {
    auto context = render::create_headless_context();
    if (!context) return Error{"no headless OpenGL context: " + context.error().message};
    gui->context_ = std::move(*context);
    auto target = render::OffscreenTarget::create(options.width, options.height);
    if (!target) return target.error();
    gui->headless_target_ = std::move(*target);
  } else {
    render::GlfwOptions window_options;
    window_options.width = options.width;
    window_options.height = options.height;
    window_options.title = options.title;
    window_options.request_stereo = options.request_stereo;
    window_options.vsync = true;
    auto window = render::GlfwContext::create(window_options);
    if (!window) {
      return Error{"no window (" + window.error().message +
                   "); use --headless, or run under xvfb-run -a -s \"-screen 0 1600x1000x24\""};
    }
    gui->window_ = window->get();
    gui->context_ = std::move(*window);
  }
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // reproducible layout (screenshots, tests)
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 3.0f;
  if (gui->window_) {
    gui->imgui_glfw_ = ImGui_ImplGlfw_InitForOpenGL(gui->window_->window(), true);
  } else {
    io.DisplaySize = ImVec2(static_cast<float>(options.width), static_cast<float>(options.height));
    // Headless has no platform back-end: ImGui's navigation keys get GLFW's codes, so that
    // tests and the keyboard device use the same key numbers as a window.
    io.KeyMap[ImGuiKey_Space] = GLFW_KEY_SPACE;
    io.KeyMap[ImGuiKey_Escape] = GLFW_KEY_ESCAPE;
  }
  gui->imgui_gl_ = ImGui_ImplOpenGL3_Init("#version 330");
  if (!gui->imgui_gl_) return Error{"Dear ImGui's OpenGL 3 backend did not start"};
  return gui;
}

bool GuiContext::begin_frame(double dt) {
  (void)context_->make_current();
  if (window_) {
    glfwPollEvents();
    if (window_->should_close()) return false;
    ImGui_ImplGlfw_NewFrame();
  } else {
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize =
        ImVec2(static_cast<float>(options_.width), static_cast<float>(options_.height));
    io.DeltaTime = static_cast<float>(dt);
  }
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
  return true;
}

void GuiContext::bind_output(int& width, int& height) {
  width = options_.width;
  height = options_.height;
  if (window_) {
    window_->framebuffer_size(width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  } else {
    headless_target_.bind();
  }
  glViewport(0, 0, width, height);
}

core::Image GuiContext::read_output(int width, int height) const {
  return render::read_bound_framebuffer_rgb(width, height);
}

void GuiContext::present() {
  if (window_) window_->swap_buffers();
}

}  // namespace telear::console
