#include "renderer.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>

namespace viz {
namespace {

// Attribute locations shared by both programs (layout(location = N) in the shaders).
constexpr GLuint kPositionAttribute = 0;
constexpr GLuint kColorAttribute = 1;

}  // namespace

void append_box_edges(std::vector<ColorVertex>& lines, const accel::Aabb& box, const glm::vec4& color) {
  if (box.empty()) return;
  // Corner i has x from bit 0, y from bit 1, z from bit 2; an edge joins corners that
  // differ in exactly one bit.
  std::array<glm::vec3, 8> corners;
  for (int i = 0; i < 8; ++i) {
    corners[i] = {(i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y,
                  (i & 4) ? box.max.z : box.min.z};
  }
  for (int i = 0; i < 8; ++i) {
    for (int bit = 1; bit < 8; bit <<= 1) {
      if ((i & bit) == 0) {
        lines.push_back({corners[i], color});
        lines.push_back({corners[i | bit], color});
      }
    }
  }
}

// ---------------------------------------------------------------------------------------
// MeshBuffers

MeshBuffers::MeshBuffers() {
  vao_.attribute(kPositionAttribute, positions_, 3, sizeof(accel::Vec3), 0);
  // The index buffer binding is VAO state: bind it while this VAO is bound.
  indices_.bind();
  glBindVertexArray(0);
}

void MeshBuffers::upload(const accel::Scene& scene) {
  static_assert(sizeof(accel::Vec3) == 3 * sizeof(float) && sizeof(accel::UVec3) == 3 * sizeof(uint32_t),
                "Scene arrays are uploaded as they are");
  positions_.upload(scene.positions().data(), scene.positions().size() * sizeof(accel::Vec3));
  vao_.bind();
  indices_.upload(scene.triangles().data(), scene.triangles().size() * sizeof(accel::UVec3));
  glBindVertexArray(0);
  index_count_ = scene.triangles().size() * 3;
}

void MeshBuffers::draw() const {
  if (index_count_ == 0) return;
  vao_.bind();
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(index_count_), GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
}

// ---------------------------------------------------------------------------------------
// ColorBatch

ColorBatch::ColorBatch(GLenum mode) : mode_(mode) {
  vao_.attribute(kPositionAttribute, vertices_, 3, sizeof(ColorVertex), offsetof(ColorVertex, position));
  vao_.attribute(kColorAttribute, vertices_, 4, sizeof(ColorVertex), offsetof(ColorVertex, color));
  glBindVertexArray(0);
}

void ColorBatch::upload(std::span<const ColorVertex> vertices, GLenum usage) {
  vertices_.upload(vertices.data(), vertices.size_bytes(), usage);
  count_ = vertices.size();
}

void ColorBatch::draw() const {
  if (count_ == 0) return;
  vao_.bind();
  glDrawArrays(mode_, 0, static_cast<GLsizei>(count_));
  glBindVertexArray(0);
}

// ---------------------------------------------------------------------------------------
// Renderer

accel::Result<Renderer> Renderer::create(const std::string& shader_dir) {
  auto mesh = Shader::from_files(shader_dir, "mesh.vert", "mesh.frag");
  if (!mesh) return mesh.error();
  auto lines = Shader::from_files(shader_dir, "lines.vert", "lines.frag");
  if (!lines) return lines.error();
  return Renderer(std::move(mesh.value()), std::move(lines.value()));
}

void Renderer::set_scene(const accel::Scene& scene) { mesh_.upload(scene); }

void Renderer::begin_frame(const FrameView& view, const glm::vec4& background) {
  frame_ = view;
  glViewport(0, 0, view.viewport.x, view.viewport.y);
  glClearColor(background.r, background.g, background.b, background.a);
  glClearDepth(1.0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);  // triangle soups have no consistent winding
  glDisable(GL_SCISSOR_TEST);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void Renderer::draw_mesh(const MeshStyle& style) {
  mesh_shader_.use();
  mesh_shader_.set("u_view", frame_.view);
  mesh_shader_.set("u_projection", frame_.projection);
  mesh_shader_.set("u_eye", frame_.eye);
  mesh_shader_.set("u_tint", style.color);
  // The mesh has no colour array (MeshBuffers leaves attribute 1 disabled), so the
  // shader reads this constant instead: white, and u_tint carries the colour.
  glVertexAttrib4f(kColorAttribute, 1.0f, 1.0f, 1.0f, 1.0f);
  glDisable(GL_BLEND);
  mesh_.draw();
}

void Renderer::draw_triangles(const ColorBatch& triangles, const glm::vec4& tint) {
  if (triangles.vertex_count() == 0) return;
  mesh_shader_.use();
  mesh_shader_.set("u_view", frame_.view);
  mesh_shader_.set("u_projection", frame_.projection);
  mesh_shader_.set("u_eye", frame_.eye);
  mesh_shader_.set("u_tint", tint);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  // Highlights coincide with scene faces; pull them forward so they win the depth test.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(-1.0f, -1.0f);
  triangles.draw();
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_BLEND);
}

void Renderer::draw_lines(const ColorBatch& lines, const LineStyle& style) {
  if (lines.vertex_count() == 0) return;
  line_shader_.use();
  line_shader_.set("u_view", frame_.view);
  line_shader_.set("u_projection", frame_.projection);
  line_shader_.set("u_depth_bias", std::clamp(style.depth_bias, 0.0f, 0.01f));
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  // Lines do not write depth: overlapping line layers (structure, highlight, ray) then
  // compose in draw order instead of hiding each other.
  glDepthMask(GL_FALSE);
  if (!style.depth_test) {
    glDisable(GL_DEPTH_TEST);
    line_shader_.set("u_tint", style.tint);
    lines.draw();
    glEnable(GL_DEPTH_TEST);
  } else {
    if (style.hidden_tint.a > 0.0f) {
      glDepthFunc(GL_GREATER);
      line_shader_.set("u_tint", style.hidden_tint);
      lines.draw();
      glDepthFunc(GL_LEQUAL);
    }
    line_shader_.set("u_tint", style.tint);
    lines.draw();
  }
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
}

void Renderer::end_frame() {
  glUseProgram(0);
  glBindVertexArray(0);
  glDisable(GL_DEPTH_TEST);
}

}  // namespace viz
