#pragma once
// Renderer: draws the scene mesh, the structure's nodes, highlights and the heat map with
// five small shader programs. Everything it draws arrives as plain lists (structure_view.h):
//
//   pass              data                        shader           state
//   mesh              MeshBuffers (scene)         mesh             solid / translucent / wireframe
//   nodes             InstancedNodes              nodes + lines    one instanced draw per shape;
//                                                                  depth/leaf filter on the GPU
//   highlighted tris  ColorBatch (triangles)      mesh             depth LEQUAL + polygon offset
//   thin lines        ColorBatch (lines)          lines            optional hidden ("x-ray") pass
//   thick lines       SegmentBatch                segments + lines screen-space quads, instanced
//   heat map          HeatmapTexture              overlay          fullscreen, blended
//
// Instancing: a structure's 200k boxes are one glDrawArraysInstanced of the unit cube's 24
// edge vertices with per-instance min/max/depth/leaf/count; the depth range and leaves-only
// filters are uniforms the vertex shader applies, so changing them uploads nothing.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl_objects.h"
#include "vec_math.h"
#include "result.h"
#include "scene.h"
#include "structure_view.h"

namespace viz {

/// Camera matrices and viewport of one frame.
struct FrameView {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
  glm::vec3 eye{0.0f};        // camera position in world space (for lighting)
  glm::ivec2 viewport{1, 1};  // size of the 3D view, framebuffer pixels
  glm::ivec2 origin{0, 0};    // its lower-left corner in the framebuffer (GL convention)
};

/// How the scene mesh is drawn.
struct MeshStyle {
  enum class Mode { Solid, Translucent, Wireframe, Hidden };
  Mode mode = Mode::Solid;
  glm::vec4 color{0.70f, 0.77f, 0.88f, 1.0f};  // light grey-blue: reads on dark projectors
  float translucent_alpha = 0.45f;
};

/// How a ColorBatch of lines or a SegmentBatch is drawn.
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

/// Which instanced nodes are shown and how they are coloured (uniforms, no upload).
struct NodeStyle {
  /// Circle: a sphere-tree node in 2D (one circle in the plane z = 0).
  enum class Shape { Box = 0, Sphere = 1, Plane = 2, Circle = 3 };
  enum class Coloring { Depth = 0, Prims = 1, Flat = 2 };
  Shape shape = Shape::Box;
  Coloring coloring = Coloring::Depth;
  int depth_min = 0, depth_max = 1 << 20;  ///< inclusive
  bool leaves_only = false;
  bool hide_empty = false;                 ///< hide leaves / cells without triangles
  float max_depth = 1.0f;                  ///< colour scale of Depth
  float max_prims = 1.0f;                  ///< colour scale of Prims (logarithmic)
  float alpha = 0.6f;
  glm::vec4 flat_color{1.0f};
  float hidden_alpha = 0.0f;               ///< > 0: also draw nodes behind the mesh, this faint
  float depth_bias = 0.0005f;
};

/// How the heat map overlay is drawn.
struct OverlayStyle {
  float scale_min = 0.0f;  ///< value mapped to the bottom of the colour map
  float scale_max = 1.0f;  ///< value mapped to the top of the colour map
  /// kColormapSamples colours instead of the current colour map (the difference view's
  /// diverging map); nullptr: the colour scheme's map.
  const glm::vec3* palette = nullptr;
  float alpha = 0.75f;
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
  /// Draws every triangle's three edges as GL_LINES: the wireframe where GL has no polygon
  /// mode (WebGL2). Empty natively (gl::kHasPolygonMode), where nothing is uploaded for it.
  void draw_edges() const;

 private:
  VertexArray vao_;
  Buffer positions_{GL_ARRAY_BUFFER};
  Buffer indices_{GL_ELEMENT_ARRAY_BUFFER};
  size_t index_count_ = 0;
  VertexArray edge_vao_;
  Buffer edge_indices_{GL_ELEMENT_ARRAY_BUFFER};
  size_t edge_index_count_ = 0;
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

/// One unit shape drawn once per NodeInstance.
class InstancedNodes {
 public:
  /// `shape` picks the unit mesh: cube edges, three circles, a square (triangles), or one
  /// circle in z = 0.
  explicit InstancedNodes(NodeStyle::Shape shape);
  /// Replaces the instances (only when the structure or the node list changes).
  void upload(std::span<const NodeInstance> instances);
  size_t instance_count() const { return count_; }
  NodeStyle::Shape shape() const { return shape_; }
  void draw() const;

 private:
  NodeStyle::Shape shape_;
  GLenum mode_;
  VertexArray vao_;
  Buffer unit_{GL_ARRAY_BUFFER};
  Buffer instances_{GL_ARRAY_BUFFER};
  size_t unit_vertices_ = 0;
  size_t count_ = 0;
};

/// Thick line segments (screen-space quads, instanced): the debug ray, the current node.
class SegmentBatch {
 public:
  SegmentBatch();
  void upload(std::span<const Segment> segments);
  size_t segment_count() const { return count_; }
  void draw() const;

 private:
  VertexArray vao_;
  Buffer unit_{GL_ARRAY_BUFFER};
  Buffer instances_{GL_ARRAY_BUFFER};
  size_t count_ = 0;
};

/// A single-channel float image (the cost image) as a texture. Move-only.
class HeatmapTexture {
 public:
  HeatmapTexture();
  ~HeatmapTexture();
  HeatmapTexture(HeatmapTexture&& other) noexcept;
  HeatmapTexture& operator=(HeatmapTexture&& other) noexcept;
  HeatmapTexture(const HeatmapTexture&) = delete;
  HeatmapTexture& operator=(const HeatmapTexture&) = delete;
  /// Uploads width x height values, the first row being the top of the image.
  void upload(const float* values, int width, int height);
  bool empty() const { return width_ == 0; }
  void bind(int unit) const;

 private:
  GLuint texture_ = 0;
  int width_ = 0, height_ = 0;
};

/// Draws the passes of one frame. Create it with a current GL 3.3 core context whose
/// functions glad has loaded; destroy it while that context is still current.
class Renderer {
 public:
  /// Every shader file the renderer loads (for find_shader_dir).
  static std::vector<std::string> shader_files();
  /// Compiles the programs from `shader_dir`. The error is one line naming the shader file
  /// and the first compiler message.
  static accel::Result<Renderer> create(const std::string& shader_dir);

  /// Uploads the scene mesh (replacing the previous one).
  void set_scene(const accel::Scene& scene);

  /// Sets the viewport, clears colour and depth to `background`, and remembers `view`
  /// for the draw calls that follow.
  void begin_frame(const FrameView& view, const glm::vec4& background);
  /// Draws the scene mesh uploaded by set_scene(). Translucent writes depth too (the nearest
  /// surface), so draw it first, like a solid mesh.
  void draw_mesh(const MeshStyle& style);
  /// Draws coloured triangles over the mesh (highlighted primitives); they win the depth
  /// test against the mesh faces they lie on.
  void draw_triangles(const ColorBatch& triangles, const glm::vec4& tint = glm::vec4(1.0f), bool depth_test = true);
  /// Draws coloured thin line segments.
  void draw_lines(const ColorBatch& lines, const LineStyle& style);
  /// Draws thick segments.
  void draw_segments(const SegmentBatch& segments, const LineStyle& style);
  /// Draws instanced nodes with the filter and colours of `style`.
  void draw_nodes(const InstancedNodes& nodes, NodeStyle style);
  /// Blends the heat map over the whole viewport.
  void draw_overlay(const HeatmapTexture& texture, const OverlayStyle& style);
  /// Restores the GL state ImGui's backend expects (it sets most state itself).
  void end_frame();

 private:
  Renderer(Shader mesh, Shader lines, Shader nodes, Shader segments, Shader overlay);
  void set_camera(Shader& shader);

  Shader mesh_shader_;
  Shader line_shader_;
  Shader node_shader_;
  Shader segment_shader_;
  Shader overlay_shader_;
  MeshBuffers mesh_;
  VertexArray empty_vao_;  // the overlay's fullscreen triangle needs no attributes
  FrameView frame_;
};

/// The highlights of an animation step, as both players draw them: thin lines, filled
/// triangles, thick segments (the ray debugger's trace step, the build player's build step).
class HighlightBatches {
 public:
  /// Replaces the content (GL_DYNAMIC_DRAW: it changes with every step).
  void upload(std::span<const Segment> segments, std::span<const ColorVertex> triangles,
              std::span<const ColorVertex> lines);
  /// Thin lines with hidden parts faint, the triangles, then the thick segments over them.
  void draw(Renderer& renderer) const;

 private:
  SegmentBatch segments_;
  ColorBatch triangles_{GL_TRIANGLES};
  ColorBatch lines_{GL_LINES};
};

/// A tool's highlights on the GPU and whether they need uploading: the lifecycle the ray
/// debugger, the construction player and the tree diagram share. The tool rebuilds its
/// geometry on the CPU and says changed(); sync() uploads it before the next frame.
class HighlightLayer {
 public:
  /// The GL context is up: make the buffers (the next sync() uploads).
  void create() {
    batches_.emplace();
    changed_ = true;
  }
  /// The geometry changed: upload it at the next sync().
  void changed() { changed_ = true; }
  void sync(std::span<const Segment> segments, std::span<const ColorVertex> triangles,
            std::span<const ColorVertex> lines) {
    if (!batches_ || !changed_) return;
    batches_->upload(segments, triangles, lines);
    changed_ = false;
  }
  void draw(Renderer& renderer) const {
    if (batches_) batches_->draw(renderer);
  }
  /// Before the GL context goes.
  void release() { batches_.reset(); }

 private:
  std::optional<HighlightBatches> batches_;
  bool changed_ = false;
};

}  // namespace viz
