#include "renderer.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "color_scheme.h"

namespace viz {
namespace {

// Attribute locations shared by the programs (layout(location = N) in the shaders).
constexpr GLuint kPositionAttribute = 0;
constexpr GLuint kColorAttribute = 1;
constexpr GLuint kInstance0 = 2;
constexpr GLuint kInstance1 = 3;
constexpr GLuint kInstance2 = 4;
constexpr GLuint kInstance3 = 5;

// Unit quad of a thick segment: x = 0 at end a, 1 at end b; y = side (-1 / +1).
constexpr std::array<glm::vec2, 6> kSegmentQuad = {
    glm::vec2(0, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(0, -1), glm::vec2(1, 1), glm::vec2(0, 1)};

}  // namespace

// ---------------------------------------------------------------------------------------
// MeshBuffers

MeshBuffers::MeshBuffers() {
  vao_.attribute(kPositionAttribute, positions_, 3, sizeof(accel::Vec3), 0);
  // The index buffer binding is VAO state: bind it while this VAO is bound.
  indices_.bind();
  edge_vao_.attribute(kPositionAttribute, positions_, 3, sizeof(accel::Vec3), 0);
  edge_indices_.bind();
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
  if (!gl::kHasPolygonMode) {
    std::vector<uint32_t> edges;
    edges.reserve(scene.triangles().size() * 6);
    for (const accel::UVec3& t : scene.triangles()) edges.insert(edges.end(), {t.x, t.y, t.y, t.z, t.z, t.x});
    edge_vao_.bind();
    edge_indices_.upload(edges.data(), edges.size() * sizeof(uint32_t));
    glBindVertexArray(0);
    edge_index_count_ = edges.size();
  }
}

void MeshBuffers::draw() const {
  if (index_count_ == 0) return;
  vao_.bind();
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(index_count_), GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
}

void MeshBuffers::draw_edges() const {
  if (edge_index_count_ == 0) return;
  edge_vao_.bind();
  glDrawElements(GL_LINES, static_cast<GLsizei>(edge_index_count_), GL_UNSIGNED_INT, nullptr);
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
// InstancedNodes

InstancedNodes::InstancedNodes(NodeStyle::Shape shape)
    : shape_(shape), mode_(shape == NodeStyle::Shape::Plane ? GL_TRIANGLES : GL_LINES) {
  const std::vector<glm::vec3> unit = shape == NodeStyle::Shape::Box      ? unit_cube_edges()
                                      : shape == NodeStyle::Shape::Sphere ? unit_sphere_circles(24)
                                      : shape == NodeStyle::Shape::Circle ? unit_circle(48)
                                                                          : unit_square_triangles();
  unit_.upload(unit.data(), unit.size() * sizeof(glm::vec3));
  unit_vertices_ = unit.size();
  vao_.attribute(kPositionAttribute, unit_, 3, sizeof(glm::vec3), 0);
  vao_.attribute(kInstance0, instances_, 3, sizeof(NodeInstance), offsetof(NodeInstance, lo), 1);
  vao_.attribute(kInstance1, instances_, 3, sizeof(NodeInstance), offsetof(NodeInstance, hi), 1);
  vao_.attribute(kInstance2, instances_, 4, sizeof(NodeInstance), offsetof(NodeInstance, depth), 1);
  glBindVertexArray(0);
}

void InstancedNodes::upload(std::span<const NodeInstance> instances) {
  instances_.upload(instances.data(), instances.size_bytes(), GL_STATIC_DRAW);
  count_ = instances.size();
}

void InstancedNodes::draw() const {
  if (count_ == 0) return;
  vao_.bind();
  glDrawArraysInstanced(mode_, 0, static_cast<GLsizei>(unit_vertices_), static_cast<GLsizei>(count_));
  glBindVertexArray(0);
}

// ---------------------------------------------------------------------------------------
// SegmentBatch

SegmentBatch::SegmentBatch() {
  unit_.upload(kSegmentQuad.data(), sizeof(kSegmentQuad));
  vao_.attribute(kPositionAttribute, unit_, 2, sizeof(glm::vec2), 0);
  vao_.attribute(kInstance0, instances_, 3, sizeof(Segment), offsetof(Segment, a), 1);
  vao_.attribute(kInstance1, instances_, 3, sizeof(Segment), offsetof(Segment, b), 1);
  vao_.attribute(kInstance2, instances_, 4, sizeof(Segment), offsetof(Segment, color), 1);
  vao_.attribute(kInstance3, instances_, 1, sizeof(Segment), offsetof(Segment, width), 1);
  glBindVertexArray(0);
}

void SegmentBatch::upload(std::span<const Segment> segments) {
  instances_.upload(segments.data(), segments.size_bytes(), GL_DYNAMIC_DRAW);
  count_ = segments.size();
}

void SegmentBatch::draw() const {
  if (count_ == 0) return;
  vao_.bind();
  glDrawArraysInstanced(GL_TRIANGLES, 0, static_cast<GLsizei>(kSegmentQuad.size()), static_cast<GLsizei>(count_));
  glBindVertexArray(0);
}

// ---------------------------------------------------------------------------------------
// HeatmapTexture

HeatmapTexture::HeatmapTexture() { glGenTextures(1, &texture_); }

HeatmapTexture::~HeatmapTexture() {
  if (texture_ != 0) glDeleteTextures(1, &texture_);
}

HeatmapTexture::HeatmapTexture(HeatmapTexture&& other) noexcept
    : texture_(std::exchange(other.texture_, 0u)), width_(std::exchange(other.width_, 0)),
      height_(std::exchange(other.height_, 0)) {}

HeatmapTexture& HeatmapTexture::operator=(HeatmapTexture&& other) noexcept {
  if (this != &other) {
    if (texture_ != 0) glDeleteTextures(1, &texture_);
    texture_ = std::exchange(other.texture_, 0u);
    width_ = std::exchange(other.width_, 0);
    height_ = std::exchange(other.height_, 0);
  }
  return *this;
}

void HeatmapTexture::upload(const float* values, int width, int height) {
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, width, height, 0, GL_RED, GL_FLOAT, values);
  // Nearest: each texel is one traced ray; blurring would invent costs between them.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
  width_ = width;
  height_ = height;
}

void HeatmapTexture::bind(int unit) const {
  glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
  glBindTexture(GL_TEXTURE_2D, texture_);
}

// ---------------------------------------------------------------------------------------
// Renderer

std::vector<std::string> Renderer::shader_files() {
  return {"mesh.vert", "mesh.frag", "lines.vert", "lines.frag", "nodes.vert", "segments.vert", "overlay.vert",
          "overlay.frag"};
}

accel::Result<Renderer> Renderer::create(const std::string& shader_dir) {
  auto mesh = Shader::from_files(shader_dir, "mesh.vert", "mesh.frag");
  if (!mesh) return mesh.error();
  auto lines = Shader::from_files(shader_dir, "lines.vert", "lines.frag");
  if (!lines) return lines.error();
  auto nodes = Shader::from_files(shader_dir, "nodes.vert", "lines.frag");
  if (!nodes) return nodes.error();
  auto segments = Shader::from_files(shader_dir, "segments.vert", "lines.frag");
  if (!segments) return segments.error();
  auto overlay = Shader::from_files(shader_dir, "overlay.vert", "overlay.frag");
  if (!overlay) return overlay.error();
  return Renderer(std::move(mesh.value()), std::move(lines.value()), std::move(nodes.value()),
                  std::move(segments.value()), std::move(overlay.value()));
}

Renderer::Renderer(Shader mesh, Shader lines, Shader nodes, Shader segments, Shader overlay)
    : mesh_shader_(std::move(mesh)), line_shader_(std::move(lines)), node_shader_(std::move(nodes)),
      segment_shader_(std::move(segments)), overlay_shader_(std::move(overlay)) {}

void Renderer::set_scene(const accel::Scene& scene) { mesh_.upload(scene); }

void Renderer::set_camera(Shader& shader) {
  shader.set("u_view", frame_.view);
  shader.set("u_projection", frame_.projection);
}

void Renderer::begin_frame(const FrameView& view, const glm::vec4& background) {
  frame_ = view;
  glViewport(view.origin.x, view.origin.y, view.viewport.x, view.viewport.y);
  glClearColor(background.r, background.g, background.b, background.a);
  gl::clear_depth(1.0f);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);  // triangle soups have no consistent winding
  glDisable(GL_SCISSOR_TEST);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void Renderer::draw_mesh(const MeshStyle& style) {
  if (style.mode == MeshStyle::Mode::Hidden) return;
  mesh_shader_.use();
  set_camera(mesh_shader_);
  mesh_shader_.set("u_eye", frame_.eye);
  glm::vec4 color = style.color;
  // The mesh has no colour array (MeshBuffers leaves attribute 1 disabled), so the
  // shader reads this constant instead: white, and u_tint carries the colour.
  glVertexAttrib4f(kColorAttribute, 1.0f, 1.0f, 1.0f, 1.0f);
  switch (style.mode) {
    case MeshStyle::Mode::Solid:
      glDisable(GL_BLEND);
      mesh_shader_.set("u_tint", color);
      mesh_.draw();
      break;
    case MeshStyle::Mode::Translucent:
      // Depth is written by a colourless pass first, so only the nearest surface blends:
      // no sorting, and the back faces of a closed mesh do not double its opacity.
      glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
      mesh_shader_.set("u_tint", color);
      mesh_.draw();
      glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      glEnable(GL_BLEND);
      glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
      glDepthMask(GL_FALSE);
      color.a = style.translucent_alpha;
      mesh_shader_.set("u_tint", color);
      mesh_.draw();
      glDepthMask(GL_TRUE);
      glDisable(GL_BLEND);
      break;
    case MeshStyle::Mode::Wireframe:
      glEnable(GL_BLEND);
      glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
      color.a = 0.5f;
      if (gl::kHasPolygonMode) {
        mesh_shader_.set("u_tint", color);
        gl::polygon_mode_lines(true);
        mesh_.draw();
        gl::polygon_mode_lines(false);
      } else {
        // Unlit lines: the mesh shader's face normal needs a triangle's derivatives.
        line_shader_.use();
        set_camera(line_shader_);
        line_shader_.set("u_tint", color);
        line_shader_.set("u_depth_bias", 0.0f);
        mesh_.draw_edges();
      }
      glDisable(GL_BLEND);
      break;
    case MeshStyle::Mode::Hidden: break;
  }
}

void Renderer::draw_triangles(const ColorBatch& triangles, const glm::vec4& tint, bool depth_test) {
  if (triangles.vertex_count() == 0) return;
  mesh_shader_.use();
  set_camera(mesh_shader_);
  mesh_shader_.set("u_eye", frame_.eye);
  mesh_shader_.set("u_tint", tint);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  if (!depth_test) glDisable(GL_DEPTH_TEST);
  // Highlights coincide with scene faces; pull them forward so they win the depth test.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(-1.0f, -4.0f);
  glDepthMask(GL_FALSE);
  triangles.draw();
  glDepthMask(GL_TRUE);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
}

void Renderer::draw_lines(const ColorBatch& lines, const LineStyle& style) {
  if (lines.vertex_count() == 0) return;
  line_shader_.use();
  set_camera(line_shader_);
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

void Renderer::draw_segments(const SegmentBatch& segments, const LineStyle& style) {
  if (segments.segment_count() == 0) return;
  segment_shader_.use();
  set_camera(segment_shader_);
  segment_shader_.set("u_viewport", glm::vec2(frame_.viewport));
  segment_shader_.set("u_depth_bias", std::clamp(style.depth_bias, 0.0f, 0.01f));
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);
  if (!style.depth_test) {
    glDisable(GL_DEPTH_TEST);
    segment_shader_.set("u_tint", style.tint);
    segments.draw();
    glEnable(GL_DEPTH_TEST);
  } else {
    if (style.hidden_tint.a > 0.0f) {
      glDepthFunc(GL_GREATER);
      segment_shader_.set("u_tint", style.hidden_tint);
      segments.draw();
      glDepthFunc(GL_LEQUAL);
    }
    segment_shader_.set("u_tint", style.tint);
    segments.draw();
  }
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
}

void Renderer::draw_nodes(const InstancedNodes& nodes, NodeStyle style) {
  if (nodes.instance_count() == 0) return;
  style.shape = nodes.shape();
  node_shader_.use();
  set_camera(node_shader_);
  node_shader_.set("u_shape", static_cast<int>(style.shape));
  node_shader_.set("u_color_mode", static_cast<int>(style.coloring));
  node_shader_.set("u_depth_min", static_cast<float>(style.depth_min));
  node_shader_.set("u_depth_max", static_cast<float>(style.depth_max));
  node_shader_.set("u_leaves_only", style.leaves_only ? 1 : 0);
  node_shader_.set("u_hide_empty", style.hide_empty ? 1 : 0);
  node_shader_.set("u_max_depth", std::max(style.max_depth, 1.0f));
  node_shader_.set("u_max_prims", std::max(style.max_prims, 1.0f));
  node_shader_.set("u_flat_color", style.flat_color);
  node_shader_.set("u_alpha", style.alpha);
  node_shader_.set("u_depth_bias", std::clamp(style.depth_bias, 0.0f, 0.01f));
  const auto palette = colormap_samples(color_scheme().map);
  node_shader_.set("u_palette", palette.data(), kColormapSamples);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);
  if (style.hidden_alpha > 0.0f) {
    glDepthFunc(GL_GREATER);
    node_shader_.set("u_tint", glm::vec4(1.0f, 1.0f, 1.0f, style.hidden_alpha));
    nodes.draw();
    glDepthFunc(GL_LEQUAL);
  }
  node_shader_.set("u_tint", glm::vec4(1.0f));
  nodes.draw();
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
}

void Renderer::draw_overlay(const HeatmapTexture& texture, const OverlayStyle& style) {
  if (texture.empty()) return;
  overlay_shader_.use();
  texture.bind(0);
  overlay_shader_.set("u_values", 0);
  overlay_shader_.set("u_scale_min", style.scale_min);
  overlay_shader_.set("u_scale_max", std::max(style.scale_max, style.scale_min + 1e-6f));
  overlay_shader_.set("u_alpha", style.alpha);
  const auto palette = colormap_samples(color_scheme().map);
  overlay_shader_.set("u_palette", style.palette ? style.palette : palette.data(), kColormapSamples);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  empty_vao_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
}

void Renderer::end_frame() {
  glUseProgram(0);
  glBindVertexArray(0);
  glDisable(GL_DEPTH_TEST);
}

void HighlightBatches::upload(std::span<const Segment> segments, std::span<const ColorVertex> triangles,
                              std::span<const ColorVertex> lines) {
  segments_.upload(segments);
  triangles_.upload(triangles, GL_DYNAMIC_DRAW);
  lines_.upload(lines, GL_DYNAMIC_DRAW);
}

void HighlightBatches::draw(Renderer& renderer) const {
  LineStyle thin;
  thin.hidden_tint = glm::vec4(1.0f, 1.0f, 1.0f, 0.35f);
  renderer.draw_lines(lines_, thin);
  renderer.draw_triangles(triangles_);
  LineStyle thick;
  thick.hidden_tint = glm::vec4(1.0f, 1.0f, 1.0f, 0.4f);
  thick.depth_bias = 0.001f;
  renderer.draw_segments(segments_, thick);
}

}  // namespace viz
