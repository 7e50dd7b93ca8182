#pragma once
// The parameter sweep ("tune at the end"): which parameter, its range and steps, the
// background job building and tracing once per value, its points, and the sweep window
// with its two plots.
#include <memory>
#include <string>

#include "commands.h"
#include "job.h"
#include "ray_gen.h"
#include "registry.h"
#include "result.h"
#include "tool_host.h"
#include "tools/sweep_model.h"
#include "tools/tool.h"
#include "view_layout.h"

namespace viz {

/// The sweep's settings, job and results.
class SweepTool final : public Tool {
 public:
  // ---- The tool (tool.h)
  const char* name() const override { return "sweep"; }
  /// `sweep`; `host` gives the structure and starts the run.
  void add_verbs(VerbTable& table, ToolHost& host) override;
  void wait() override { job_.wait(); }
  void on_event(ToolEvent event, ToolHost& host) override;
  /// Own: the "Parameter sweep" section.
  void section(ToolHost& host, PanelSection section) override;
  /// The plots, along the bottom (above the compare table when it is open).
  void panels(ToolHost& host) override;
  bool set_panel(const std::string& name, bool on) override;

  /// Chooses numeric parameter `param` of `info`, its range and steps (the sweep command).
  accel::Status configure(const accel::StructureInfo& info, const std::string& param, float lo, float hi, int steps);
  /// Sweeps the chosen parameter of `info` from `base` (the editor's request) over the
  /// primary rays of `camera`; opens the window. Synchronous in script mode; the error
  /// (also shown in the section) when nothing can be swept or the run failed.
  accel::Status start(const accel::StructureInfo& info, std::shared_ptr<const accel::Scene> scene,
                      const StructureRequest& base, const accel::PinholeCamera& camera, bool synchronous);

  /// The main panel's "Parameter sweep" section; true when "Run sweep" was pressed.
  bool settings_section(const accel::StructureInfo& info);
  /// Whether the window is shown.
  bool open() const { return open_; }
  /// Shows or hides the window.
  void set_open(bool open) { open_ = open; }
  /// The window with the build-time and trace-time plots.
  void panel(const PanelPlace& place);

 private:
  Job<accel::Status> job_;
  std::shared_ptr<SweepProgress> progress_;
  SweepRequest request_;
  std::string error_;
  int param_ = 0;  // index among the numeric parameters
  float lo_ = 0.5f, hi_ = 4.0f;
  int steps_ = 10;
  bool log_ = false;
  bool open_ = false;
};

}  // namespace viz
