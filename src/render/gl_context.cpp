#include "telear/render/gl_context.hpp"

#include <epoxy/gl.h>

namespace telear::render {
namespace {

std::string gl_string(GLenum name) {
  const GLubyte* s = glGetString(name);
  return s ? reinterpret_cast<const char*>(s) : "";
}

}  // namespace

std::string GlContext::gl_vendor() {
  return gl_string(GL_VENDOR);
}
std::string GlContext::gl_renderer() {
  return gl_string(GL_RENDERER);
}
std::string GlContext::gl_version() {
  return gl_string(GL_VERSION);
}

bool is_software_renderer(const std::string& gl_renderer) {
  for (const char* name :
       {"llvmpipe", "softpipe", "SwiftShader", "Software Rasterizer", "GDI Generic"}) {
    if (gl_renderer.find(name) != std::string::npos) return true;
  }
  return false;
}

}  // namespace telear::render
