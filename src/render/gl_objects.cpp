#include "telear/render/gl_objects.hpp"

#include <cassert>
#include <vector>

namespace telear::render {

Buffer Buffer::create() {
  GLuint id = 0;
  glGenBuffers(1, &id);
  Buffer b;
  b.id_ = id;
  return b;
}

void Buffer::set_data(GLenum target, GLsizeiptr bytes, const void* data, GLenum usage) {
  glBindBuffer(target, id_);
  glBufferData(target, bytes, data, usage);
}

void Buffer::set_sub_data(GLenum target, GLintptr offset, GLsizeiptr bytes, const void* data) {
  glBindBuffer(target, id_);
  glBufferSubData(target, offset, bytes, data);
}

VertexArray VertexArray::create() {
  GLuint id = 0;
  glGenVertexArrays(1, &id);
  VertexArray v;
  v.id_ = id;
  return v;
}

Texture Texture::create_2d(int width, int height, GLenum internal_format) {
  assert(width > 0 && height > 0 && "Texture::create_2d(): empty texture");
  GLuint id = 0;
  glGenTextures(1, &id);
  glBindTexture(GL_TEXTURE_2D, id);
  // Immutable storage would need GL 4.2; glTexImage2D with a null pointer allocates.
  GLenum format = GL_RGBA;
  GLenum type = GL_UNSIGNED_BYTE;
  switch (internal_format) {
    case GL_RGB8:
      format = GL_RGB;
      break;
    case GL_R8:
      format = GL_RED;
      break;
    case GL_RG32F:
      format = GL_RG;
      type = GL_FLOAT;
      break;
    case GL_RGBA32F:
      type = GL_FLOAT;
      break;
    default:
      break;
  }
  glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internal_format), width, height, 0, format,
               type, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  Texture t;
  t.id_ = id;
  t.width_ = width;
  t.height_ = height;
  return t;
}

void Texture::bind(GLenum unit) const {
  glActiveTexture(unit);
  glBindTexture(GL_TEXTURE_2D, id_);
}

void Texture::upload(GLenum format, GLenum type, const void* pixels) {
  glBindTexture(GL_TEXTURE_2D, id_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width_, height_, format, type, pixels);
}

Renderbuffer Renderbuffer::create(int width, int height, GLenum internal_format) {
  GLuint id = 0;
  glGenRenderbuffers(1, &id);
  glBindRenderbuffer(GL_RENDERBUFFER, id);
  glRenderbufferStorage(GL_RENDERBUFFER, internal_format, width, height);
  Renderbuffer r;
  r.id_ = id;
  return r;
}

Renderbuffer Renderbuffer::create_multisample(int width, int height, int samples,
                                              GLenum internal_format) {
  GLuint id = 0;
  glGenRenderbuffers(1, &id);
  glBindRenderbuffer(GL_RENDERBUFFER, id);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, internal_format, width, height);
  Renderbuffer r;
  r.id_ = id;
  return r;
}

Framebuffer Framebuffer::create() {
  GLuint id = 0;
  glGenFramebuffers(1, &id);
  Framebuffer f;
  f.id_ = id;
  return f;
}

Result<Shader> Shader::compile(GLenum stage, const std::string& source, const std::string& name) {
  Shader s;
  s.id_ = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(s.id_, 1, &text, nullptr);
  glCompileShader(s.id_);
  GLint ok = GL_FALSE;
  glGetShaderiv(s.id_, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetShaderiv(s.id_, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
    glGetShaderInfoLog(s.id_, static_cast<GLsizei>(log.size()), nullptr, log.data());
    return Error{"shader '" + name + "' (" + (stage == GL_VERTEX_SHADER ? "vertex" : "fragment") +
                 ") does not compile: " + std::string(log.data())};
  }
  return s;
}

Result<Program> Program::link(const std::string& vertex_source, const std::string& fragment_source,
                              const std::string& name) {
  auto vs = Shader::compile(GL_VERTEX_SHADER, vertex_source, name);
  if (!vs) return vs.error();
  auto fs = Shader::compile(GL_FRAGMENT_SHADER, fragment_source, name);
  if (!fs) return fs.error();
  Program p;
  p.id_ = glCreateProgram();
  glAttachShader(p.id_, vs->id());
  glAttachShader(p.id_, fs->id());
  glLinkProgram(p.id_);
  GLint ok = GL_FALSE;
  glGetProgramiv(p.id_, GL_LINK_STATUS, &ok);
  glDetachShader(p.id_, vs->id());
  glDetachShader(p.id_, fs->id());
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetProgramiv(p.id_, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
    glGetProgramInfoLog(p.id_, static_cast<GLsizei>(log.size()), nullptr, log.data());
    return Error{"program '" + name + "' does not link: " + std::string(log.data())};
  }
  return p;
}

std::string gl_errors() {
  std::string out;
  for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
    if (!out.empty()) out += ", ";
    switch (e) {
      case GL_INVALID_ENUM:
        out += "GL_INVALID_ENUM";
        break;
      case GL_INVALID_VALUE:
        out += "GL_INVALID_VALUE";
        break;
      case GL_INVALID_OPERATION:
        out += "GL_INVALID_OPERATION";
        break;
      case GL_INVALID_FRAMEBUFFER_OPERATION:
        out += "GL_INVALID_FRAMEBUFFER_OPERATION";
        break;
      case GL_OUT_OF_MEMORY:
        out += "GL_OUT_OF_MEMORY";
        break;
      default:
        out += "GL error " + std::to_string(e);
        break;
    }
  }
  return out;
}

}  // namespace telear::render
