#include "gl_objects.h"

#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

namespace viz {
namespace {

// Driver logs are multi-line ("0:12(3): error: ..."); the Error contract is one line, and
// the first error is the one worth reading.
std::string first_line(const std::string& log) {
  const size_t end = log.find_first_of("\r\n");
  std::string line = log.substr(0, end);
  return line.empty() ? std::string("(no log)") : line;
}

std::string shader_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<size_t>(length > 1 ? length : 1), '\0');
  glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
  return log.data();
}

std::string program_log(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<size_t>(length > 1 ? length : 1), '\0');
  glGetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
  return log.data();
}

// Returns 0 and fills `error` on failure.
GLuint compile(GLenum stage, const std::string& source, std::string& error) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    error = first_line(shader_log(shader));
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

bool read_text(const std::string& path, std::string& out) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return false;
  std::ostringstream text;
  text << file.rdbuf();
  out = text.str();
  return true;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Shader

Shader::~Shader() {
  if (program_ != 0) glDeleteProgram(program_);
}

Shader::Shader(Shader&& other) noexcept
    : program_(std::exchange(other.program_, 0u)), locations_(std::move(other.locations_)) {}

Shader& Shader::operator=(Shader&& other) noexcept {
  if (this != &other) {
    if (program_ != 0) glDeleteProgram(program_);
    program_ = std::exchange(other.program_, 0u);
    locations_ = std::move(other.locations_);
  }
  return *this;
}

accel::Result<Shader> Shader::from_source(const std::string& vertex_source,
                                          const std::string& fragment_source,
                                          const std::string& label) {
  std::string error;
  const GLuint vs = compile(GL_VERTEX_SHADER, vertex_source, error);
  if (vs == 0) return accel::make_error("shader " + label + ": vertex stage: " + error);
  const GLuint fs = compile(GL_FRAGMENT_SHADER, fragment_source, error);
  if (fs == 0) {
    glDeleteShader(vs);
    return accel::make_error("shader " + label + ": fragment stage: " + error);
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  // The program keeps the compiled stages alive; our handles are no longer needed.
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    error = first_line(program_log(program));
    glDeleteProgram(program);
    return accel::make_error("shader " + label + ": link: " + error);
  }
  return Shader(program);
}

accel::Result<Shader> Shader::from_files(const std::string& dir, const std::string& vertex_file,
                                         const std::string& fragment_file) {
  std::string vertex_source, fragment_source;
  const std::string vertex_path = dir + "/" + vertex_file;
  const std::string fragment_path = dir + "/" + fragment_file;
  if (!read_text(vertex_path, vertex_source))
    return accel::make_error("cannot read shader " + vertex_path);
  if (!read_text(fragment_path, fragment_source))
    return accel::make_error("cannot read shader " + fragment_path);
  return from_source(gl::glsl_for_this_gl(vertex_source), gl::glsl_for_this_gl(fragment_source),
                     vertex_file + "/" + fragment_file);
}

void Shader::use() const { glUseProgram(program_); }

GLint Shader::location(const char* name) {
  auto it = locations_.find(name);
  if (it == locations_.end()) it = locations_.emplace(name, glGetUniformLocation(program_, name)).first;
  return it->second;
}

// A location of -1 is silently ignored by glUniform*, which is the contract we want.
void Shader::set(const char* name, const glm::mat4& value) {
  glUniformMatrix4fv(location(name), 1, GL_FALSE, glm::value_ptr(value));
}
void Shader::set(const char* name, const glm::vec4& value) {
  glUniform4fv(location(name), 1, glm::value_ptr(value));
}
void Shader::set(const char* name, const glm::vec3& value) {
  glUniform3fv(location(name), 1, glm::value_ptr(value));
}
void Shader::set(const char* name, const glm::vec3* values, int count) {
  glUniform3fv(location(name), count, glm::value_ptr(values[0]));
}
void Shader::set(const char* name, const glm::vec2& value) {
  glUniform2fv(location(name), 1, glm::value_ptr(value));
}
void Shader::set(const char* name, float value) { glUniform1f(location(name), value); }
void Shader::set(const char* name, int value) { glUniform1i(location(name), value); }

// ---------------------------------------------------------------------------------------
// Buffer

Buffer::Buffer(GLenum target) : target_(target) { glGenBuffers(1, &buffer_); }

Buffer::~Buffer() {
  if (buffer_ != 0) glDeleteBuffers(1, &buffer_);
}

Buffer::Buffer(Buffer&& other) noexcept
    : target_(other.target_), buffer_(std::exchange(other.buffer_, 0u)),
      bytes_(std::exchange(other.bytes_, size_t{0})) {}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    if (buffer_ != 0) glDeleteBuffers(1, &buffer_);
    target_ = other.target_;
    buffer_ = std::exchange(other.buffer_, 0u);
    bytes_ = std::exchange(other.bytes_, size_t{0});
  }
  return *this;
}

void Buffer::bind() const { glBindBuffer(target_, buffer_); }

void Buffer::upload(const void* data, size_t bytes, GLenum usage) {
  bind();
  glBufferData(target_, static_cast<GLsizeiptr>(bytes), data, usage);
  bytes_ = bytes;
}

// ---------------------------------------------------------------------------------------
// VertexArray

VertexArray::VertexArray() { glGenVertexArrays(1, &vao_); }

VertexArray::~VertexArray() {
  if (vao_ != 0) glDeleteVertexArrays(1, &vao_);
}

VertexArray::VertexArray(VertexArray&& other) noexcept : vao_(std::exchange(other.vao_, 0u)) {}

VertexArray& VertexArray::operator=(VertexArray&& other) noexcept {
  if (this != &other) {
    if (vao_ != 0) glDeleteVertexArrays(1, &vao_);
    vao_ = std::exchange(other.vao_, 0u);
  }
  return *this;
}

void VertexArray::bind() const { glBindVertexArray(vao_); }

void VertexArray::attribute(GLuint index, const Buffer& buffer, int components, size_t stride,
                            size_t offset, GLuint divisor) {
  bind();
  buffer.bind();
  glEnableVertexAttribArray(index);
  // The offset is a byte offset into the bound buffer, passed through the pointer argument
  // as the GL API requires.
  glVertexAttribPointer(index, components, GL_FLOAT, GL_FALSE, static_cast<GLsizei>(stride),
                        reinterpret_cast<const void*>(offset));
  glVertexAttribDivisor(index, divisor);
}

}  // namespace viz
