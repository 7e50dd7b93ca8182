#pragma once
// The traversal's numbers at the debug ray's current step: the "Variables" panel (the
// active pseudo code's variables, named as in the lecture) and the t-axis strip under the
// 3D view (the ray's parameter range with every visited interval, the split distances,
// the entry keys and the closest hit so far). Both show what the traversal recorded
// (tools/traversal_numbers.h selects it); neither recomputes the structure's work. A
// student's logged claim that the kit's audit found false is said so, with the truth
// (tools/false_claims.h), never narrated as the lecture's.
#include <functional>

#include "commands.h"
#include "pseudo_code.h"
#include "tools/debug_ray.h"
#include "tools/tool.h"
#include "trace_player.h"
#include "traps.h"
#include "view_layout.h"

struct ImFont;

namespace viz {

class VarsPanel final : public Tool {
 public:
  // ---- The tool (tool.h)
  const char* name() const override { return "Variables"; }
  /// V: the panel and the strip, together.
  std::vector<KeyBinding> keys(ToolHost& host) override;
  void on_event(ToolEvent event, ToolHost& host) override;
  /// The panel shares the left column with the controls in the traversal mode only.
  void update(ToolHost& host, float dt) override;
  /// The panel, and the strip along the bottom of the view between the docked panels.
  void panels(ToolHost& host) override;
  bool set_panel(const std::string& name, bool on) override;

  /// The Variables window and the t-axis strip shown (`panel vars|strip on|off`, key V).
  bool shown() const { return shown_; }
  bool strip_shown() const { return strip_shown_; }
  void set_shown(bool on) { shown_ = on; }
  void set_strip_shown(bool on) { strip_shown_ = on; }

  /// The "Variables" window for `ray` at `highlight`'s step, traversal `kind`, on the
  /// blackboard (2D mode) or not (`board`: how a ray is shot); `mono` (may be null) for the
  /// numbers. `top_block` (optional) draws first inside the window (the lecture trap's answers).
  void panel(const PanelPlace& place, const DebugRay& ray, const accel::TraceHighlight& highlight, TraversalKind kind,
             bool board, ImFont* mono, const std::function<void()>& top_block = {});
  /// The t-axis strip in `rect` (window coordinates). `naive` (may be null): the answer a
  /// naive first-leaf traversal gives, marked on the axis when it differs from the answer.
  void strip(const WindowRect& rect, const DebugRay& ray, const accel::TraceHighlight& highlight,
             const accel::NaiveAnswer* naive);
  /// Height of the strip at font size `em` (window units).
  static float strip_height(float em) { return 5.6f * em; }

 private:
  bool shown_ = true;
  bool strip_shown_ = true;
};

}  // namespace viz
