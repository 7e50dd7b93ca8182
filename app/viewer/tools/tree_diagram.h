#pragma once
// The "Tree" window: the hierarchy as a node-link diagram in step with the debug ray's
// trace (or the construction playback), drawn with ImDrawList; for the grid, the cell walk
// as a table. Owns the layout (tools/tree_layout.h, GL-free), the selection and its 3D
// highlight (the selected node's outline, or its whole subtree when isolated). App only
// passes the structure, the ray and the replay in, and skips its node drawing while isolated.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "built_structure.h"
#include "commands.h"
#include "renderer.h"
#include "result.h"
#include "tool_host.h"
#include "tools/debug_ray.h"
#include "tools/tool.h"
#include "tools/tree_layout.h"
#include "view_layout.h"

namespace viz {

class TreeDiagram final : public Tool {
 public:
  // ---- The tool (tool.h)
  const char* name() const override { return "tree"; }
  /// T shows or hides the window; `host` lays the panels out again.
  std::vector<KeyBinding> keys(ToolHost& host) override;
  /// tree, tree-select; `host` gives the structure.
  void add_verbs(VerbTable& table, ToolHost& host) override;
  void init_gl() override { gl_.create(); }
  void release_gl() override { gl_.release(); }
  void on_event(ToolEvent event, ToolHost& host) override;
  /// Follows the structure, the debug ray and the construction's replay.
  void update(ToolHost& host, float dt) override;
  /// The window, docked along the bottom.
  void panels(ToolHost& host) override;
  /// Uploads the selection's highlight when it changed.
  void sync_gl(Renderer&, ToolHost&) override { gl_.sync(segments_, {}, lines_); }
  /// The selected node (or isolated subtree) over the scene, in the traversal mode.
  void draw(Renderer& renderer, ToolHost& host, DrawLayer layer) override;

  /// The window shown or not (`tree on|off`, key T).
  bool on() const { return on_; }
  void set_on(bool on) { on_ = on; }
  void toggle() { on_ = !on_; }

  /// Follows this frame's structure, debug ray and construction replay (nullptr: the
  /// construction mode is off). Cheap when nothing changed: the layout is remade when the
  /// structure, the trace or the selection changes, the states when the step changes.
  void follow(const BuiltPtr& built, const DebugRay& ray, const accel::BuildReplay* replay);

  /// `tree-select NODE [isolate]`: selects a node of the current structure (errors name
  /// the command and the valid ids).
  accel::Status select(NodeId node, bool isolate);
  /// The node selected (kNoNode: none).
  NodeId selected() const { return selected_; }
  /// Only the selected subtree is drawn in 3D: App leaves the structure's nodes out.
  bool isolating() const { return on_ && isolate_ && selected_ != kNoNode && !replay_mode_; }

  /// The window at `place` (it docks along the bottom: the 3D view ends above it).
  void panel(const PanelPlace& place);

 private:
  /// Draws the selected node (or isolated subtree) over the scene.
  void draw_selection(Renderer& renderer);
  void rebuild_layout();
  void refresh_states();
  void rebuild_highlight();
  // The diagram's canvas, step by step (tree_diagram_canvas.cpp).
  struct Canvas;
  void diagram_canvas(float width, float height);
  void fit_canvas(float width, float height, float margin, float em);
  /// An item out of view is brought to the middle, per axis; one in view stays where it is.
  void bring_into_view(const Canvas& canvas, int item);
  void keep_in_view(const Canvas& canvas);
  void zoom_and_pan(const Canvas& canvas, bool hovered, bool active);
  void draw_edges(const Canvas& canvas) const;
  void draw_nodes(const Canvas& canvas, bool hovered);
  void node_tooltip() const;
  void click_node();
  void selection_numbers();
  void grid_table();
  void legend();

  bool on_ = false;
  // What is followed.
  BuiltPtr built_;
  const accel::Structure* structure_ = nullptr;  // identity of the structure indexed
  std::unique_ptr<StructureTreeShape> shape_;
  TreeIndex index_;
  const DebugRay* ray_ = nullptr;
  const accel::TraceEvent* trace_data_ = nullptr;  // identity of the trace laid out
  size_t trace_size_ = 0;
  TraceStates states_;
  size_t step_ = ~size_t(0);
  bool replay_mode_ = false;
  const accel::BuildReplay* replay_ = nullptr;
  size_t replay_step_ = ~size_t(0);
  NodeId replay_current_ = kNoNode;
  bool grid_ = false;
  std::vector<GridWalkRow> grid_rows_;
  int grid_scrolled_ = -2;
  // The layout and each item's state at the step.
  TreeLayout layout_;
  std::vector<TreeNodeStatus> status_;
  int current_item_ = -1;  // the item of the node being processed (-1: none shown)
  bool layout_dirty_ = true;
  // Selection.
  NodeId selected_ = kNoNode;
  bool isolate_ = false;
  std::optional<SubtreeSummary> summary_;  // of the selected node
  accel::NodeView selected_view_;
  // View: zoom and pan of the canvas; following keeps the current node in view.
  float zoom_ = 1.0f;
  float row_scale_ = 1.0f;  // rows closer than the zoom alone gives, so the path's depth fits
  glm::vec2 pan_{0.0f};
  glm::vec2 canvas_size_{0.0f};  // the canvas's size last frame (a new size fits again)
  bool follow_ = true;
  bool fit_pending_ = true;
  int followed_item_ = -1;           // the current item the view last followed
  bool center_on_selected_ = false;  // tree-select: bring the selection into view
  int hovered_ = -1;
  // 3D.
  bool highlight_dirty_ = true;
  std::vector<Segment> segments_;
  std::vector<ColorVertex> lines_;
  HighlightLayer gl_;  // the highlights on the GPU
};

}  // namespace viz
