#pragma once
// The ray debugger: the debug ray and its recorded trace, the trace player, the highlights
// of the current step (and their GL buffers), the saved viewpoint, and the "Debug ray",
// "Traversal steps" and "Pseudo code" panels, where a student's false claims are marked
// (tools/false_claims.h). Gets the structure passed in, never reads it.
#include <optional>
#include <string>

#include "built_structure.h"
#include "commands.h"
#include "ray_gen.h"
#include "renderer.h"
#include "result.h"
#include "tool_host.h"
#include "tools/debug_ray.h"
#include "tools/highlights.h"
#include "tools/tool.h"
#include "tools/transport_controls.h"
#include "view_layout.h"

struct ImFont;

namespace viz {

/// The debug ray and everything shown about its traversal.
class RayDebugger final : public Tool {
 public:
  // ---- The tool (tool.h)
  const char* name() const override { return "traversal"; }
  /// Play, step, jump to the hit, speed.
  std::vector<KeyBinding> keys(ToolHost& host) override;
  /// The ray, stepping, frames and the print-* of the ray; `host` gives the camera and the
  /// other tools.
  void add_verbs(VerbTable& table, ToolHost& host) override;
  void init_gl() override { gl_.create(); }
  void release_gl() override { gl_.release(); }
  /// A new scene forgets the ray; a new structure replays it; new colours recolour it.
  void on_event(ToolEvent event, ToolHost& host) override;
  /// A click into the 3D view shoots the ray through that pixel.
  void mouse(const MouseFrame& mouse, ToolHost& host) override;
  /// The animation's clock and the step's highlights.
  void update(ToolHost& host, float dt) override;
  void section(ToolHost& host, PanelSection section) override;
  /// The Debug ray, Traversal steps and Pseudo code panels (the construction's take their
  /// places in its mode).
  void panels(ToolHost& host) override;
  void late_update(ToolHost& host) override;
  /// Uploads highlights rebuilt since the last frame (before the frame begins).
  void sync_gl(Renderer&, ToolHost&) override { gl_.sync(highlights_.segments, highlights_.triangles, highlights_.lines); }
  /// The highlights of the current step (rebuilt only when the step changes).
  void draw(Renderer& renderer, ToolHost& host, DrawLayer layer) override;
  /// The ray and its step (none on the blackboard, nor in a failed build's replay).
  void save_state(std::string& script, const ToolHost& host) const override;

  /// Makes `ray` the debug ray and records its trace on `built` (nullptr: no structure);
  /// a student's structure's walk is audited with it (DebugRay::audit).
  void set_ray(const accel::Ray& ray, const std::string& origin, const BuiltStructure* built);
  /// The ray through framebuffer pixel (px, py) of a view at `view` (x, y, w, h) seen by
  /// `camera`; `from_saved_view` aims from the saved viewpoint at the surface point there.
  void shoot(const accel::PinholeCamera& camera, glm::ivec4 view, float px, float py, bool from_saved_view,
             const BuiltStructure* built);
  /// The same ray on a new structure: the step stays, clamped.
  void replay(const BuiltStructure* built);
  /// Forgets the ray (a new scene).
  void reset();
  /// The colour scheme changed: rebuild the highlights' colours.
  void recolor() { dirty_ = true; }
  /// Plays the animation on by `seconds`.
  void advance(double seconds);
  /// Rebuilds the highlights when the step (or what they show) changed.
  void refresh(const accel::Scene& scene, const BuiltStructure* built);

  /// The debug ray.
  const DebugRay& ray() const { return ray_; }
  /// What the highlights show: the trace's state at the current step (current after update()).
  const accel::TraceHighlight& step_highlight() const { return highlights_.step; }
  /// Marks step `step` in the steps list with `note` (nothing: no mark), e.g. where a naive
  /// traversal would stop.
  void set_marked_step(std::optional<size_t> step, std::string note) {
    marked_step_ = step;
    marked_note_ = std::move(note);
  }
  /// The trace player (keys and scripts step it; the highlights follow).
  accel::TracePlayer& player() { return ray_.player; }
  /// Success, or why there is no trace to step through.
  accel::Status need_trace() const;
  /// Success, or that there is no ray yet.
  accel::Status need_ray() const;
  /// "hit PRIM T" or "miss" (print-hit).
  std::string hit_line() const;
  /// "step I/N: EVENT" (print-step); a student's false claim there as the steps list shows
  /// it (tools/false_claims.h: step_text).
  std::string step_line() const;
  /// The ray in hexadecimal floats, "ox oy oz dx dy dz" (print-ray).
  std::string ray_line() const;

  /// `ray-at-pixel X Y`: shoots through pixel (x, y) from the top-left as a click does, once
  /// the camera is the one drawn; an error when the pixel is outside the window or under a
  /// panel.
  accel::Status ray_at_pixel(ToolHost& host, float x, float y, ScriptHost& script);

  /// Remembers `view` as the saved viewpoint.
  void save_view(const accel::PinholeCamera& view) { saved_view_ = view; }
  /// The saved viewpoint, if any.
  const std::optional<accel::PinholeCamera>& saved_view() const { return saved_view_; }
  /// Clicks shoot from the saved viewpoint ("from saved view").
  bool shoot_from_saved() const { return shoot_from_saved_; }

  /// The "Debug ray" panel; true when its Compare button was pressed. `board`: the
  /// blackboard (2D mode), whose mouse shoots the ray otherwise (input.h: shoot_hint()).
  bool ray_panel(const PanelPlace& place, const BuiltStructure* built, bool board);
  /// The "Traversal steps" panel (`board` as for ray_panel()).
  void steps_panel(const PanelPlace& place, bool board);
  /// The "Pseudo code" panel in `mono` (nullptr: the default font).
  void code_panel(const PanelPlace& place, const BuiltStructure* built, ImFont* mono);
  /// The trail / skipped / pending checkboxes (end of the Display section).
  void highlight_options();

 private:
  /// The ray_panel()'s lines about the trace: the current step, the counters, the answer,
  /// the student's false claims, the stack or queue.
  void trace_lines(const BuiltStructure* built);
  /// The ray_panel()'s "Type a ray" node: an origin and a direction, and Shoot.
  void typed_ray(const BuiltStructure* built);

  DebugRay ray_;
  HighlightOptions options_;
  Highlights highlights_;
  bool dirty_ = true;                   // rebuild the highlights at the next update()
  size_t highlight_step_ = ~size_t(0);  // the step highlights_ shows
  StepListState steps_;                 // the steps list: following the step, where it scrolled to
  int code_scrolled_ = -2;              // code line last scrolled into view
  bool shoot_from_saved_ = false;
  std::optional<size_t> marked_step_;
  std::string marked_note_;
  std::optional<accel::PinholeCamera> saved_view_;
  float typed_ray_[6] = {0, 0, 5, 0, 0, -1};
  HighlightLayer gl_;  // the highlights on the GPU
};

}  // namespace viz
