#pragma once
// The construction mode ("watch it being built"): records the current structure's build
// (accel::build_structure_recorded, on a background Job with its own BuildControl: progress
// and cancel), plays its steps (BuildStepPlayer), draws the partly built structure of the
// current step (tools/build_playback.h) and shows the "Construction", "Construction steps"
// and "Construction code" panels in the places of the traversal panels while the mode is on.
// A student's failed build is replayed up to the fault (construct-until): its build stopped
// at the check's count of build-log calls, the failure said in red in the Construction panel.
// Gets the scene and structure request passed in; App only wires it.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "built_structure.h"
#include "commands.h"
#include "job.h"
#include "registry.h"
#include "renderer.h"
#include "result.h"
#include "tool_host.h"
#include "tools/build_playback.h"
#include "tools/tool.h"
#include "tools/transport_controls.h"
#include "view_layout.h"

struct ImFont;

namespace viz {

class BuildPlayer final : public Tool {
 public:
  // ---- The tool (tool.h)
  const char* name() const override { return "construction"; }
  /// B records or leaves the mode; play, step, first / last, speed.
  std::vector<KeyBinding> keys(ToolHost& host) override;
  /// construct, construct-until, build-step, print-build-step, sah-plot; `host` gives the
  /// structure.
  void add_verbs(VerbTable& table, ToolHost& host) override;
  void init_gl() override { gl_.create(); }
  void release_gl() override { gl_.release(); }
  /// A new scene or structure forgets the recording (it was of another one).
  void on_event(ToolEvent event, ToolHost& host) override;
  /// A finished recording; the animation's clock.
  void update(ToolHost& host, float dt) override;
  /// Structure: Construct (B) and the mode's switch.
  void section(ToolHost& host, PanelSection section) override;
  /// In the construction mode its panels take the traversal's places.
  void panels(ToolHost& host) override;
  void late_update(ToolHost&) override { refresh(); }
  void sync_gl(Renderer&, ToolHost&) override { gl_.sync(view_.segments, view_.triangles, view_.lines); }
  /// In the construction mode: the partly built structure instead of the finished one.
  void draw(Renderer& renderer, ToolHost& host, DrawLayer layer) override;

  /// Records the build of `request` over `scene` and turns the mode on; `synchronous`
  /// (script mode) records before returning. A recording in progress is cancelled first.
  void construct(std::shared_ptr<const accel::Scene> scene, const StructureRequest& request, bool synchronous);
  /// A student's failed build replayed up to the fault (construct-until): records the build
  /// of `request` stopped right after its `calls`-th build-log call and opens it on that
  /// call's step; `note` is what the check said of the failure (its state file's comments),
  /// shown in the Construction panel with the stop. A build of fewer calls is played whole
  /// (opened at its end).
  void construct_until(std::shared_ptr<const accel::Scene> scene, StructureRequest request, size_t calls,
                       std::vector<std::string> note, bool synchronous);
  /// Takes a finished recording (per frame).
  void poll();
  /// Cancels a recording in progress.
  void cancel();
  /// Forgets the recording and leaves the mode (a new scene or structure).
  void reset();
  /// Waits for the recording thread (shutdown).
  void wait() override;

  /// The mode is on: its panels and drawing replace the traversal's.
  bool active() const { return active_; }
  void set_active(bool on) { active_ = on && trace_ != nullptr; }
  bool recording() const { return job_.busy(); }
  double recording_fraction() const { return control_ ? control_->fraction() : 0.0; }
  double recording_seconds() const { return job_.seconds(); }

  /// The step player (keys and scripts step it).
  BuildStepPlayer& player() { return player_; }
  /// Success, or why there are no steps (nothing recorded, or the recording failed).
  accel::Status need_trace() const;
  /// "build step K/N: TEXT" (print-build-step).
  std::string step_line() const;
  /// The SAH cost plot on or off (sah-plot).
  void set_sah_plot(bool on) { sah_plot_ = on; }
  /// Plays on by `seconds`.
  void advance(double seconds) { player_.advance(seconds); }
  /// The partly built structure as of the current step (nullptr: nothing recorded), for
  /// the tree diagram.
  const accel::BuildReplay* replay() const { return replay_.get(); }
  /// Applies the player's step to the replay and rebuilds the view when it changed.
  void refresh();

  /// The "Construction" panel (controls, counters, cost plot) at the ray panel's place.
  void control_panel(const PanelPlace& place, const std::shared_ptr<const accel::Scene>& scene,
                     const StructureRequest& request);
  /// The "Construction steps" list.
  void steps_panel(const PanelPlace& place);
  /// The "Construction code" panel in `mono`.
  void code_panel(const PanelPlace& place, ImFont* mono);


 private:
  void record(std::shared_ptr<const accel::Scene> scene, const StructureRequest& request,
              std::vector<std::string> note, bool synchronous);
  void cost_plot_widget();
  void replay_lines();

  /// A recording's outcome, and why its build stopped when it was a failed build's replay
  /// stopped at its build-log call limit ("" otherwise).
  struct Recording {
    accel::Result<accel::RecordedBuild> build;
    std::string stopped;
  };

  Job<Recording> job_;
  std::shared_ptr<accel::BuildControl> control_;
  std::shared_ptr<const accel::Scene> scene_;          // the recorded build's scene
  std::shared_ptr<const accel::Scene> pending_scene_;  // of the recording in progress
  StructureRequest request_, pending_request_;
  std::shared_ptr<const accel::BuildTrace> trace_;
  size_t attempts_ = 0;  ///< recordings the trace took (more than 1: the step budget ran out)
  std::unique_ptr<accel::BuildReplay> replay_;
  double sah_ct_ = 1.0, sah_ci_ = 1.0;  ///< the structure's SAH constants, for the cost so far
  int sah_prims_per_test_ = 1;           ///< and its triangles per leaf test (4: wide layouts)
  std::string error_;
  // A failed build's replay: why the recorded build stopped ("" when it ran to its end), and
  // what the check said of the failure (shown with it; pending_: of the recording in progress).
  std::string stopped_;
  std::vector<std::string> note_, pending_note_;
  size_t fault_step_ = 0;  ///< the step a replay opens at: its last call's
  BuildCodeKind code_kind_ = BuildCodeKind::Unknown;
  BuildStepPlayer player_;
  bool active_ = false;
  bool sah_plot_ = true;
  bool dirty_ = true;
  size_t view_step_ = ~size_t(0);
  BuildView view_;
  StepListState steps_;  // the steps list: following the step, where it scrolled to
  int code_scrolled_ = -2;
  HighlightLayer gl_;  // the highlights on the GPU
};

}  // namespace viz
