#pragma once
// The blackboard (2D mode, issue #32): a 2D scene (triangles in the plane z = 0,
// docs/hits.md) seen from above by the camera's top-down orthographic view, and built and
// traversed by the very structures of the 3D mode. This tool switches the mode (D), edits
// the scene with the mouse (BlackboardEditor: corners, moves, rays, deletes; Esc forgets the
// corners) and its script verbs (blackboard_verbs.h), saves it, and draws
// the board's grid of world units and the corners placed.
#include <array>
#include <optional>
#include <string>

#include "renderer.h"
#include "tools/blackboard_editor.h"
#include "tools/tool.h"

namespace viz {

class BlackboardTool final : public Tool {
 public:
  const char* name() const override { return "blackboard"; }
  std::vector<KeyBinding> keys(ToolHost& host) override;
  void add_verbs(VerbTable& table, ToolHost& host) override;
  void init_gl() override { lines_.emplace(GL_LINES); }
  void release_gl() override { lines_.reset(); }
  void on_event(ToolEvent event, ToolHost& host) override;
  void mouse(const MouseFrame& mouse, ToolHost& host) override;
  void section(ToolHost& host, PanelSection section) override;
  void draw(Renderer& renderer, ToolHost& host, DrawLayer layer) override;

  /// 2D: the blackboard (the current 2D scene, else an empty one); 3D: back to the last 3D scene.
  accel::Status set_mode_2d(bool on, ToolHost& host);
  /// Loads a 2D scene file (scene2d.h) onto the blackboard.
  accel::Status load_scene2d(const std::string& path, ToolHost& host);
  /// Adds a triangle (x1 y1 x2 y2 x3 y3) to the blackboard's scene and rebuilds.
  accel::Status add_triangle_2d(const std::array<float, 6>& xy, ToolHost& host);
  /// The debug ray in the plane.
  accel::Status set_ray_2d(float ox, float oy, float dx, float dy, ToolHost& host);
  /// Writes the blackboard's scene to `path` as a 2D scene file (never half written).
  accel::Status save_scene2d(const std::string& path, ToolHost& host);

 private:
  /// A right click deletes the triangle under it.
  void delete_under(glm::vec2 point, ToolHost& host);
  /// The grid of world units (under everything), or the corners placed and the ray being
  /// dragged (over the structure).
  void draw_lines(Renderer& renderer, ToolHost& host, bool grid);

  BlackboardEditor editor_;
  std::string last_3d_scene_ = "procedural:cornell";  // what `mode 3d` goes back to
  std::string path_ = "blackboard.scene2d";           // the Scene section's save field
  std::string status_;                                // what the last save said
  std::optional<ColorBatch> lines_;                   // the grid, corners and dragged ray
};

}  // namespace viz
