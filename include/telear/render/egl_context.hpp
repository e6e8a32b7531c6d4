#pragma once
// A headless OpenGL 3.3 core context through EGL, with no window and no X server.
//
// Platforms, tried in order for Platform::kAuto:
//   1. the EGL device platform (EGL_EXT_platform_device): a hardware device is preferred, so
//      that an NVIDIA GPU is used where there is one; Mesa's software device is skipped here;
//   2. Mesa's surfaceless platform (EGL_MESA_platform_surfaceless): llvmpipe on a CPU-only
//      machine, as in CI.
// The context is made current with no surface (EGL_KHR_surfaceless_context): draw into an
// OffscreenTarget (FBO). Environment override: TELEAR_EGL_PLATFORM=device|surfaceless.

#include <memory>
#include <string>

#include "telear/core/result.hpp"
#include "telear/render/gl_context.hpp"

namespace telear::render {

struct EglOptions {
  enum class Platform { kAuto, kDevice, kSurfaceless };
  Platform platform = Platform::kAuto;
  bool debug = false;  // a debug context (GL_KHR_debug messages), for development
};

class EglContext final : public GlContext {
 public:
  // Creates the context and makes it current. The error says which platforms were tried
  // and why each failed (no libEGL, no display, no GL 3.3 core config ...).
  static Result<std::unique_ptr<EglContext>> create(const EglOptions& options = {});
  ~EglContext() override;

  Status make_current() override;
  std::string description() const override { return description_; }

 private:
  EglContext() = default;
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  std::string description_;
};

// The factory callers use: a headless context, current on the calling thread.
Result<std::unique_ptr<GlContext>> create_headless_context(const EglOptions& options = {});

}  // namespace telear::render
