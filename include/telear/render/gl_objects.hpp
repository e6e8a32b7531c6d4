#pragma once
// Move-only RAII owners of OpenGL objects (Magnum's habit): a default-constructed wrapper
// holds id 0 and needs no context, so classes holding them can be built and moved without
// GL; create() generates the object and must be called with a context current. The
// destructor deletes the object; it must run while the same context (or one sharing with
// it) is current. Copying is disabled: exactly one owner deletes each name.

#include <epoxy/gl.h>

#include <string>
#include <utility>

#include "telear/core/result.hpp"

namespace telear::render {

// The shared mechanics: an id and a deleter.
template <typename Traits>
class GlObject {
 public:
  GlObject() = default;
  ~GlObject() { reset(); }
  GlObject(const GlObject&) = delete;
  GlObject& operator=(const GlObject&) = delete;
  GlObject(GlObject&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  GlObject& operator=(GlObject&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }

  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  // Deletes the object (no GL call when the wrapper is empty).
  void reset() {
    if (id_ != 0) Traits::destroy(id_);
    id_ = 0;
  }

 protected:
  explicit GlObject(GLuint id) : id_(id) {}
  GLuint id_ = 0;
};

namespace detail {
struct BufferTraits {
  static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct VertexArrayTraits {
  static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct TextureTraits {
  static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct FramebufferTraits {
  static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct RenderbufferTraits {
  static void destroy(GLuint id) { glDeleteRenderbuffers(1, &id); }
};
struct ShaderTraits {
  static void destroy(GLuint id) { glDeleteShader(id); }
};
struct ProgramTraits {
  static void destroy(GLuint id) { glDeleteProgram(id); }
};
}  // namespace detail

class Buffer : public GlObject<detail::BufferTraits> {
 public:
  Buffer() = default;
  static Buffer create();
  // glBindBuffer(target) + glBufferData: (re)allocates and fills.
  void set_data(GLenum target, GLsizeiptr bytes, const void* data, GLenum usage);
  // glBindBuffer(target) + glBufferSubData.
  void set_sub_data(GLenum target, GLintptr offset, GLsizeiptr bytes, const void* data);
};

class VertexArray : public GlObject<detail::VertexArrayTraits> {
 public:
  VertexArray() = default;
  static VertexArray create();
  void bind() const { glBindVertexArray(id_); }
};

class Texture : public GlObject<detail::TextureTraits> {
 public:
  Texture() = default;
  // A 2-D texture of `internal_format` (GL_RGBA8, GL_RGB8, GL_RG32F ...), storage allocated,
  // contents undefined; linear filtering, clamp to edge.
  static Texture create_2d(int width, int height, GLenum internal_format);
  void bind(GLenum unit = GL_TEXTURE0) const;
  int width() const { return width_; }
  int height() const { return height_; }
  // Replaces all texels from tightly packed rows (GL_UNPACK_ALIGNMENT 1), the first row
  // given going to texture row 0 (t = 0, the bottom in GL's convention).
  void upload(GLenum format, GLenum type, const void* pixels);

 private:
  int width_ = 0;
  int height_ = 0;
};

class Renderbuffer : public GlObject<detail::RenderbufferTraits> {
 public:
  Renderbuffer() = default;
  static Renderbuffer create(int width, int height, GLenum internal_format);
  // Multisample storage (samples > 1), for anti-aliased render targets.
  static Renderbuffer create_multisample(int width, int height, int samples,
                                         GLenum internal_format);
};

class Framebuffer : public GlObject<detail::FramebufferTraits> {
 public:
  Framebuffer() = default;
  static Framebuffer create();
  void bind(GLenum target = GL_FRAMEBUFFER) const { glBindFramebuffer(target, id_); }
};

class Shader : public GlObject<detail::ShaderTraits> {
 public:
  Shader() = default;
  // Compiles; the error holds the driver's info log. `name` labels messages.
  static Result<Shader> compile(GLenum stage, const std::string& source, const std::string& name);
};

class Program : public GlObject<detail::ProgramTraits> {
 public:
  Program() = default;
  // Compiles both stages and links; the error holds the info log of the stage that failed.
  static Result<Program> link(const std::string& vertex_source, const std::string& fragment_source,
                              const std::string& name);
  void use() const { glUseProgram(id_); }
  // -1 when the uniform does not exist or was optimised away.
  GLint uniform_location(const char* name) const { return glGetUniformLocation(id_, name); }
};

// glGetError drained into a readable list ("GL_INVALID_OPERATION, ..."); empty when clean.
std::string gl_errors();

}  // namespace telear::render
