#pragma once
// Renderer: draws the scene mesh and batches of coloured lines/triangles with two shader
// programs (mesh.*, lines.*). Everything it draws arrives as plain world-space vertex
// lists, so the core's DrawData (node boxes, split planes, rays) maps onto it directly:
//
//   pass              data                       shader   state
//   mesh              MeshBuffers (scene)        mesh     depth test, flat shading
//   highlighted tris  TriangleBatch              mesh     depth LEQUAL + polygon offset
//   lines             LineBatch (boxes, rays)    lines    depth test, optional hidden pass
//
// Planned next (not yet here): instanced boxes, i.e. one unit-cube edge list drawn once
// per node with per-instance min/max/colour attributes (VertexArray::attribute already
// takes a divisor), for structures with millions of nodes.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl_objects.h"
#include "math.h"
#include "result.h"
#include "scene.h"

namespace viz {

/// One end of a line segment, or one corner of a highlighted triangle.
struct ColorVertex {
  glm::vec3 position{0.0f};
  glm::vec4 color{1.0f};
};
static_assert(sizeof(ColorVertex) == 28, "ColorVertex is uploaded as 7 tightly packed floats");

/// Appends the 12 edges of `box` as 24 line vertices. An empty box appends nothing.
void append_box_edges(std::vector<ColorVertex>& lines, const accel::Aabb& box, const glm::vec4& color);

/// Camera matrices and viewport of one frame.
struct FrameView {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
  glm::vec3 eye{0.0f};        // camera position in world space (for lighting)
  glm::ivec2 viewport{1, 1};  // framebuffer pixels
};

/// How the scene mesh is drawn.
struct MeshStyle {
  glm::vec4 color{0.70f, 0.77f, 0.88f, 1.0f};  // light grey-blue: reads on dark projectors
};

/// How a LineBatch is drawn.
struct LineStyle {
  glm::vec4 tint{1.0f};  ///< multiplies every vertex colour
  bool depth_test = true;  ///< false: lines draw over everything (e.g. the debug ray)
  /// Fraction of clip w the lines are pulled towards the camera; 0..0.01. Keeps edges
  /// lying on faces visible.
  float depth_bias = 0.0005f;
  /// If alpha > 0 (and depth_test), lines hidden behind the mesh are drawn too, with
  /// this tint: "x-ray" view of structure nodes inside a model.
  glm::vec4 hidden_tint{0.0f};
};

/// The scene's triangles on the GPU: its positions and an index buffer, drawn indexed.
/// Degenerate triangles are uploaded too; they cover no pixels.
class MeshBuffers {
 public:
  MeshBuffers();
  /// Replaces the content with `scene`'s positions and triangles.
  void upload(const accel::Scene& scene);
  /// Number of indices (3 per triangle) of the last upload.
  size_t index_count() const { return index_count_; }
  /// Issues the indexed draw call; the caller has set the program and state.
  void draw() const;

 private:
  VertexArray vao_;
  Buffer positions_{GL_ARRAY_BUFFER};
  Buffer indices_{GL_ELEMENT_ARRAY_BUFFER};
  size_t index_count_ = 0;
};

/// A list of ColorVertex on the GPU, drawn as GL_LINES (pairs) or GL_TRIANGLES (triples).
class ColorBatch {
 public:
  /// `mode` is GL_LINES or GL_TRIANGLES.
  explicit ColorBatch(GLenum mode);
  /// Replaces the content. Use GL_DYNAMIC_DRAW for data that changes every few frames
  /// (animated highlights), GL_STATIC_DRAW otherwise.
  void upload(std::span<const ColorVertex> vertices, GLenum usage = GL_STATIC_DRAW);
  size_t vertex_count() const { return count_; }
  GLenum mode() const { return mode_; }
  /// Issues the draw call; the caller has set the program and state.
  void draw() const;

 private:
  GLenum mode_;
  VertexArray vao_;
  Buffer vertices_{GL_ARRAY_BUFFER};
  size_t count_ = 0;
};

/// Draws the passes of one frame. Create it with a current GL 3.3 core context whose
/// functions glad has loaded; destroy it while that context is still current.
class Renderer {
 public:
  /// Compiles mesh.vert/.frag and lines.vert/.frag from `shader_dir`. The error is one
  /// line naming the shader file and the first compiler message.
  static accel::Result<Renderer> create(const std::string& shader_dir);

  /// Uploads the scene mesh (replacing the previous one).
  void set_scene(const accel::Scene& scene);

  /// Sets the viewport, clears colour and depth to `background`, and remembers `view`
  /// for the draw calls that follow.
  void begin_frame(const FrameView& view, const glm::vec4& background);
  /// Draws the scene mesh uploaded by set_scene().
  void draw_mesh(const MeshStyle& style);
  /// Draws coloured triangles over the mesh (highlighted primitives); they win the depth
  /// test against the mesh faces they lie on.
  void draw_triangles(const ColorBatch& triangles, const glm::vec4& tint = glm::vec4(1.0f));
  /// Draws coloured line segments.
  void draw_lines(const ColorBatch& lines, const LineStyle& style);
  /// Restores the GL state ImGui's backend expects (it sets most state itself).
  void end_frame();

 private:
  Renderer(Shader mesh, Shader lines) : mesh_shader_(std::move(mesh)), line_shader_(std::move(lines)) {}

  Shader mesh_shader_;
  Shader line_shader_;
  MeshBuffers mesh_;
  FrameView frame_;
};

}  // namespace viz
