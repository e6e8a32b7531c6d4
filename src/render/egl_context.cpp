#include "telear/render/egl_context.hpp"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdlib>
#include <cstring>
#include <vector>

namespace telear::render {
namespace {

bool has_extension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  }
  return false;
}

std::string egl_error_name(EGLint error) {
  switch (error) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    default:
      return "EGL error " + std::to_string(error);
  }
}

struct Candidate {
  EGLDisplay display = EGL_NO_DISPLAY;
  std::string description;
};

// Hardware devices of the EGL device platform first; Mesa's software device only when
// `allow_software` (the surfaceless platform is the better route to llvmpipe).
std::vector<Candidate> device_displays(bool allow_software, std::string& why_not) {
  std::vector<Candidate> out;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_extension(client, "EGL_EXT_platform_device") ||
      !has_extension(client, "EGL_EXT_device_enumeration")) {
    why_not += " device platform: EGL_EXT_platform_device / EGL_EXT_device_enumeration missing;";
    return out;
  }
  EGLint count = 0;
  if (!eglQueryDevicesEXT(0, nullptr, &count) || count <= 0) {
    why_not += " device platform: no EGL devices;";
    return out;
  }
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  eglQueryDevicesEXT(count, devices.data(), &count);
  std::vector<Candidate> software;
  for (EGLint i = 0; i < count; ++i) {
    const char* ext = eglQueryDeviceStringEXT(devices[static_cast<std::size_t>(i)], EGL_EXTENSIONS);
    const bool is_software = has_extension(ext, "EGL_MESA_device_software");
    if (is_software && !allow_software) continue;
    EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT,
                                            devices[static_cast<std::size_t>(i)], nullptr);
    if (d == EGL_NO_DISPLAY) continue;
    Candidate c{d, "EGL device " + std::to_string(i) + (is_software ? " (software)" : "")};
    (is_software ? software : out).push_back(c);
  }
  out.insert(out.end(), software.begin(), software.end());
  if (out.empty()) why_not += " device platform: no hardware EGL device;";
  return out;
}

std::vector<Candidate> surfaceless_display(std::string& why_not) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_extension(client, "EGL_MESA_platform_surfaceless")) {
    why_not += " surfaceless platform: EGL_MESA_platform_surfaceless missing;";
    return {};
  }
  EGLDisplay d =
      eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (d == EGL_NO_DISPLAY) {
    why_not += " surfaceless platform: no display;";
    return {};
  }
  return {Candidate{d, "EGL surfaceless (Mesa)"}};
}

}  // namespace

Result<std::unique_ptr<EglContext>> EglContext::create(const EglOptions& options) {
  EglOptions::Platform platform = options.platform;
  if (const char* env = std::getenv("TELEAR_EGL_PLATFORM")) {
    if (std::strcmp(env, "device") == 0) platform = EglOptions::Platform::kDevice;
    if (std::strcmp(env, "surfaceless") == 0) platform = EglOptions::Platform::kSurfaceless;
  }
  // epoxy aborts when libEGL cannot be loaded; eglQueryString is the first EGL call, and
  // returns null (not an abort) when EGL has no client extensions at all.
  std::string why_not;
  std::vector<Candidate> candidates;
  if (platform != EglOptions::Platform::kSurfaceless) {
    candidates = device_displays(platform == EglOptions::Platform::kDevice, why_not);
  }
  if (platform != EglOptions::Platform::kDevice) {
    auto s = surfaceless_display(why_not);
    candidates.insert(candidates.end(), s.begin(), s.end());
  }

  for (const Candidate& c : candidates) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(c.display, &major, &minor)) {
      why_not +=
          " " + c.description + ": eglInitialize failed (" + egl_error_name(eglGetError()) + ");";
      continue;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
      why_not += " " + c.description + ": no desktop OpenGL API;";
      continue;
    }
    EGLConfig config = nullptr;
    EGLint found = 0;
    for (EGLint surface_type : {EGL_PBUFFER_BIT, 0}) {
      const EGLint attributes[] = {EGL_SURFACE_TYPE,
                                   surface_type,
                                   EGL_RENDERABLE_TYPE,
                                   EGL_OPENGL_BIT,
                                   EGL_RED_SIZE,
                                   8,
                                   EGL_GREEN_SIZE,
                                   8,
                                   EGL_BLUE_SIZE,
                                   8,
                                   EGL_ALPHA_SIZE,
                                   8,
                                   EGL_DEPTH_SIZE,
                                   24,
                                   EGL_NONE};
      if (eglChooseConfig(c.display, attributes, &config, 1, &found) && found > 0) break;
    }
    if (found == 0) {
      why_not += " " + c.description + ": no RGBA8 / depth-24 OpenGL config;";
      continue;
    }
    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                         3,
                                         EGL_CONTEXT_MINOR_VERSION,
                                         3,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_CONTEXT_OPENGL_DEBUG,
                                         options.debug ? EGL_TRUE : EGL_FALSE,
                                         EGL_NONE};
    EGLContext context = eglCreateContext(c.display, config, EGL_NO_CONTEXT, context_attributes);
    if (context == EGL_NO_CONTEXT) {
      why_not += " " + c.description + ": no OpenGL 3.3 core context (" +
                 egl_error_name(eglGetError()) + ");";
      continue;
    }
    if (!eglMakeCurrent(c.display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
      why_not += " " + c.description + ": cannot make current without a surface (" +
                 egl_error_name(eglGetError()) + ");";
      eglDestroyContext(c.display, context);
      continue;
    }
    std::unique_ptr<EglContext> result(new EglContext());
    result->display_ = c.display;
    result->context_ = context;
    result->description_ = c.description + ", EGL " + std::to_string(major) + "." +
                           std::to_string(minor) + ", " + gl_renderer();
    return result;
  }
  if (candidates.empty() && why_not.empty()) why_not = " no EGL display";
  return Error{"cannot create a headless OpenGL 3.3 context:" + why_not};
}

EglContext::~EglContext() {
  if (context_ == nullptr) return;
  // The display is not terminated: EGL displays are per-process singletons that other
  // contexts on the same device may still be using.
  if (eglGetCurrentContext() == context_) {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  eglDestroyContext(display_, context_);
}

Status EglContext::make_current() {
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
    return Error{"eglMakeCurrent failed: " + egl_error_name(eglGetError())};
  }
  return Status::Ok();
}

Result<std::unique_ptr<GlContext>> create_headless_context(const EglOptions& options) {
  auto context = EglContext::create(options);
  if (!context) return context.error();
  return std::unique_ptr<GlContext>(std::move(context.value()));
}

}  // namespace telear::render
