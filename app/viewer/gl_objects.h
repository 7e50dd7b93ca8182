#pragma once
// Move-only RAII wrappers for the few OpenGL objects the renderer needs. Each owns one GL
// name and deletes it in its destructor, so the objects must die while the GL context is
// still current (App::shutdown() destroys the renderer before main() destroys the window).
#include <cstddef>
#include <string>
#include <unordered_map>

#include <glm/glm.hpp>

#include "gl_api.h"
#include "result.h"

namespace viz {

/// A linked vertex + fragment shader program. Move-only; a moved-from Shader owns nothing.
class Shader {
 public:
  Shader() = default;
  ~Shader();
  Shader(Shader&& other) noexcept;
  Shader& operator=(Shader&& other) noexcept;
  Shader(const Shader&) = delete;
  Shader& operator=(const Shader&) = delete;

  /// Compiles and links GLSL sources. The error names `label` (e.g. the file names) and
  /// carries the first line of the driver's log, so it fits the one-line Error contract.
  static accel::Result<Shader> from_source(const std::string& vertex_source,
                                           const std::string& fragment_source,
                                           const std::string& label);
  /// Reads `dir`/`vertex_file` and `dir`/`fragment_file`, then from_source().
  /// A missing file gives "cannot read shader PATH".
  static accel::Result<Shader> from_files(const std::string& dir, const std::string& vertex_file,
                                          const std::string& fragment_file);

  /// Makes this the current program (glUseProgram).
  void use() const;
  /// Uniform setters; the program must be current. Unknown names are ignored (GLSL
  /// compilers drop unused uniforms, which must not turn into errors while editing shaders).
  void set(const char* name, const glm::mat4& value);
  void set(const char* name, const glm::vec4& value);
  void set(const char* name, const glm::vec3& value);
  /// A vec3 array uniform (`name` as declared, e.g. "u_palette"), `count` values.
  void set(const char* name, const glm::vec3* values, int count);
  void set(const char* name, const glm::vec2& value);
  void set(const char* name, float value);
  void set(const char* name, int value);

  GLuint id() const { return program_; }

 private:
  explicit Shader(GLuint program) : program_(program) {}
  GLint location(const char* name);

  GLuint program_ = 0;
  std::unordered_map<std::string, GLint> locations_;  // glGetUniformLocation is not free
};

/// A GL buffer object (vertex or index data). Move-only.
class Buffer {
 public:
  /// Creates the GL name; `target` is GL_ARRAY_BUFFER or GL_ELEMENT_ARRAY_BUFFER.
  explicit Buffer(GLenum target = GL_ARRAY_BUFFER);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  /// Binds the buffer to its target.
  void bind() const;
  /// Replaces the whole content (glBufferData). `usage` is GL_STATIC_DRAW for scene data
  /// and GL_DYNAMIC_DRAW for data re-uploaded while animating (highlights, rays).
  void upload(const void* data, size_t bytes, GLenum usage = GL_STATIC_DRAW);
  /// Bytes held by the last upload().
  size_t size() const { return bytes_; }
  GLenum target() const { return target_; }
  GLuint id() const { return buffer_; }

 private:
  GLenum target_ = GL_ARRAY_BUFFER;
  GLuint buffer_ = 0;
  size_t bytes_ = 0;
};

/// A vertex array object: the attribute layout of one drawable. Move-only.
class VertexArray {
 public:
  VertexArray();
  ~VertexArray();
  VertexArray(VertexArray&& other) noexcept;
  VertexArray& operator=(VertexArray&& other) noexcept;
  VertexArray(const VertexArray&) = delete;
  VertexArray& operator=(const VertexArray&) = delete;

  /// Binds the VAO (needed before draw calls and before binding an index buffer into it).
  void bind() const;
  /// Declares float attribute `index` with `components` floats read from `buffer` at
  /// `offset` bytes with `stride` bytes between vertices. `divisor` 1 makes it per
  /// instance (for instanced boxes). Leaves this VAO bound.
  void attribute(GLuint index, const Buffer& buffer, int components, size_t stride, size_t offset,
                 GLuint divisor = 0);
  GLuint id() const { return vao_; }

 private:
  GLuint vao_ = 0;
};

}  // namespace viz
