#pragma once
// The lecture's traps (core/traps.h): loads a demonstration (scene, structure, ray) and
// shows, for the debug ray, what a naive traversal that stops at the first leaf or cell
// with a hit would answer -- computed from the recorded steps, for display only -- next to
// the traversal's answer and brute force. The "Lecture trap" block (top of the Variables
// panel) explains the demonstration while its scene and its structure (with the demo's
// parameters: the explanation's numbers are that tree's) are shown, and appears for any ray
// on which the naive answer would be wrong.
#include <optional>
#include <string>

#include "accuracy.h"
#include "built_structure.h"
#include "commands.h"
#include "scene.h"
#include "tool_host.h"
#include "tools/debug_ray.h"
#include "tools/tool.h"
#include "traps.h"
#include "view_layout.h"

namespace viz {

class TrapTool final : public Tool {
 public:
  // ---- The tool (tool.h)
  const char* name() const override { return "traps"; }
  void add_verbs(VerbTable& table, ToolHost& host) override;
  void on_event(ToolEvent event, ToolHost& host) override;
  /// The naive answer on the current ray, and its step marked in the ray's steps list.
  void update(ToolHost& host, float dt) override;
  /// Own: the "Lecture traps" section.
  void section(ToolHost& host, PanelSection section) override;
  bool set_panel(const std::string& name, bool on) override;

  /// Marks `demo` as the one shown (after its scene, structure and ray were loaded).
  void set_demo(const accel::TrapDemo& demo);
  /// A scene other than the demonstration's was loaded.
  void on_scene_loaded(const std::string& spec) {
    if (demo_ && demo_->scene != spec) demo_.reset();
  }
  /// Recomputes the naive answer (and brute force, when it is shown) when the debug ray or
  /// its trace changed; `built` (may be null) is the structure the ray was traced on: the
  /// demonstration's explanation is shown only while it is the demonstration's.
  void check_ray(const DebugRay& ray, const accel::Scene& scene, const BuiltStructure* built);
  /// Whether the demonstration's explanation applies to `built`: the demonstration's
  /// structure with the same parameters, over its scene.
  bool demo_applies(const BuiltStructure* built) const;

  /// The naive answer for the current trace.
  const accel::NaiveAnswer& naive() const { return naive_; }
  /// The naive answer differs from the traversal's (a different triangle, or a miss/hit).
  bool misleads() const { return misleads_; }
  /// "naive hit PRIM T" or "naive miss" (print-naive).
  std::string naive_line() const { return accel::naive_line(naive_); }
  /// "trap NAME: TITLE" while a demonstration's explanation applies to `built`, else
  /// "trap: none" (print-trap).
  std::string trap_line(const BuiltStructure* built) const;
  /// The step the steps list marks ("naive stop"), or nothing.
  std::optional<size_t> marked_step() const;

  /// The "Lecture traps" buttons (main panel); returns the name of the one pressed, or "".
  std::string traps_section() const;
  /// Show the block (panel trap on|off).
  void set_open(bool open) { open_ = open; }
  /// Whether block() draws anything for `ray` now.
  bool shown(const DebugRay& ray) const;
  /// The "Lecture trap" block at the top of the Variables panel (inside its window): the
  /// demonstration's explanation and the naive, traversal and brute-force answers; its
  /// "go to the naive stop" button seeks `player`.
  void block(const DebugRay& ray, accel::TracePlayer& player);

 private:
  std::optional<accel::TrapDemo> demo_;
  std::string demo_params_;    // the demo's every parameter, as BuiltStructure::params_text
  bool demo_applies_ = false;  // demo_applies() of the structure update() last saw
  bool open_ = true;
  accel::NaiveAnswer naive_;
  bool misleads_ = false;
  // What naive_ and brute_ were computed for.
  accel::Ray ray_;
  const accel::TraceEvent* events_ = nullptr;
  size_t event_count_ = 0;
  const accel::Scene* scene_ = nullptr;
  bool computed_ = false;
  bool brute_for_demo_ = false;  // demo_applies_ when brute_ was decided on
  std::optional<accel::ReferenceHit> brute_;
};

}  // namespace viz
