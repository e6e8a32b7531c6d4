#pragma once
// One interface over the two ways telear gets an OpenGL 3.3 core context:
//   - EglContext (egl_context.hpp): headless, no X server; the renderer, the CLI, the
//     benchmarks and the CI tests draw into an OffscreenTarget;
//   - GlfwContext (glfw_context.hpp): a window (the operator console, page-flipped stereo).
//
// GL calls go through libepoxy, which resolves entry points against the CURRENT context:
// make the context current before creating any GL object or calling any GL function, and
// keep it alive (and current on the calling thread) for as long as GL objects exist.

#include <string>

#include "telear/core/result.hpp"

namespace telear::render {

class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes the context current on the calling thread.
  virtual Status make_current() = 0;
  // Presents the back buffer (a window); a no-op for a headless context.
  virtual void swap_buffers() {}
  // "EGL device (NVIDIA ...)", "EGL surfaceless (Mesa)", "GLFW window": how it was made.
  virtual std::string description() const = 0;

  // GL_VENDOR / GL_RENDERER / GL_VERSION of the current context (call after make_current).
  static std::string gl_vendor();
  static std::string gl_renderer();
  static std::string gl_version();

 protected:
  GlContext() = default;
};

// Whether a GL_RENDERER string names a software rasteriser (Mesa's llvmpipe or softpipe,
// SwiftShader, Microsoft's GDI renderer): there the "GPU" is the CPU.
bool is_software_renderer(const std::string& gl_renderer);

}  // namespace telear::render
