#pragma once
// The node display: how the structure's nodes are drawn (depth filter, colouring, opacity,
// x-ray, split planes, empty grid cells), the instances listed from the structure and their
// GL buffers, and the mesh style; the main panel's Display section.
#include <optional>

#include "built_structure.h"
#include "commands.h"
#include "renderer.h"
#include "structure_view.h"
#include "tool_host.h"
#include "tools/depth_filter.h"
#include "tools/tool.h"

namespace viz {

/// The structure's nodes as drawn.
class NodeDisplay final : public Tool {
 public:
  // ---- The tool (tool.h)
  const char* name() const override { return "nodes"; }
  void add_verbs(VerbTable& table, ToolHost& host) override;
  void init_gl() override;
  void release_gl() override;
  /// A new structure's nodes; the defaults again for a playlist going back.
  void on_event(ToolEvent event, ToolHost& host) override;
  /// The lecture mode's brighter mesh and nodes.
  void update(ToolHost& host, float dt) override;
  void section(ToolHost& host, PanelSection section) override;
  void sync_gl(Renderer&, ToolHost&) override { sync_instances(); }
  /// Under: the mesh; Scene: the nodes (not while the construction or an isolated subtree
  /// is shown).
  void draw(Renderer& renderer, ToolHost& host, DrawLayer layer) override;

  /// Shows a newly built structure's nodes (a large one first with its top levels only).
  void install(const BuiltStructure& built);
  /// Shows or hides a grid's empty cells, re-listing `built`'s nodes (nullptr: none yet).
  void set_empty_cells(bool on, const BuiltStructure* built);
  /// Whether a grid's empty cells are listed.
  bool empty_cells() const { return depth_.empty_cells; }
  /// The `show all` script command: every depth.
  void show_all();
  /// `show leaves`.
  void show_leaves();
  /// `show depth LO [HI]`: one depth when lo == hi, else the inclusive range.
  void show_depths(int lo, int hi);
  /// Draws the nodes or not.
  void set_visible(bool on) { show_nodes_ = on; }
  /// The nodes' opacity.
  void set_opacity(float alpha) { node_alpha_ = alpha; }
  /// How the mesh is drawn.
  void set_mesh_mode(MeshStyle::Mode mode) { mesh_style_.mode = mode; }
  /// The lecture mode's brighter mesh and more opaque nodes, or the normal colours.
  void apply_lecture_colors(bool lecture);
  /// How the mesh is drawn.
  const MeshStyle& mesh_style() const { return mesh_style_; }
  /// Instances on the GPU (boxes + spheres), 0 while the nodes are hidden.
  size_t drawn_nodes() const { return show_nodes_ ? drawn_nodes_ : 0; }
  /// The depth controls (for tests and the status line).
  const DepthSettings& depth_settings() const { return depth_; }

  /// The Display section; `built` is the structure shown. True when "empty cells" was
  /// toggled (then the session must list them in its next builds too).
  bool display_section(const BuiltStructure* built);

 private:
  /// Uploads the instances the filter shows when it or the structure changed (before the
  /// frame begins: never per frame otherwise).
  void sync_instances();
  /// Draws `current`'s nodes (nullptr: none for this scene); `dimmed` while a trace is shown.
  void draw_nodes(Renderer& renderer, const BuiltStructure* current, bool dimmed);
  void upload();

  bool lecture_applied_ = false;  // the lecture mode's colours are applied

  DepthSettings depth_;
  bool show_nodes_ = true;
  bool show_planes_ = true;
  int coloring_ = 0;  // 0 auto (count for grids, depth otherwise), 1 depth, 2 count
  float node_alpha_ = 0.55f;
  bool xray_ = true;  // nodes behind the mesh drawn faintly
  MeshStyle mesh_style_;
  StructureGeometry geometry_;  // the shown structure's nodes as instances
  bool geometry_dirty_ = false;  // re-upload the instances
  NodeFilter uploaded_filter_;   // the filter of the instances on the GPU
  size_t drawn_nodes_ = 0;       // instances on the GPU (boxes + spheres)
  size_t filtered_nodes_ = 0;    // what the filter accepts, before the level-of-detail limit
  // The level-of-detail limit (limit_drawn_nodes): a quarter million instances of 24 line
  // vertices each still draw at interactive rates on Mesa's software renderer.
  static constexpr size_t kMaxDrawnNodes = size_t(1) << 18;
  std::optional<InstancedNodes> boxes_gl_;
  std::optional<InstancedNodes> spheres_gl_;  // three circles each, or in 2D one (Shape::Circle)
  std::optional<InstancedNodes> planes_gl_;
};

}  // namespace viz
