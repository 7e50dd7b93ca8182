#pragma once
// The speed-against-error chart as a tool (bench_chart.h computes it): the "Speed vs
// error" window, the main panel's section that loads a file and opens it, and the chart's
// script verbs (bench_chart_verbs.h).
#include <glm/vec2.hpp>

#include "bench_chart.h"
#include "commands.h"
#include "tool_host.h"
#include "tools/tool.h"

namespace viz {

class BenchChartTool final : public Tool {
 public:
  const char* name() const override { return "speed vs error chart"; }
  void add_verbs(VerbTable& table, ToolHost& host) override;
  void section(ToolHost& host, PanelSection section) override;
  void panels(ToolHost& host) override;

  /// Loads a bench JSON file (accelviz-cli bench --out-json) and opens the chart; on
  /// failure the previous chart stays and the one-line error ("PATH: ...") is returned and
  /// shown in the chart's file row.
  accel::Status load(const std::string& path) { return load_bench_into(state_, path); }

 private:
  BenchChartState state_;
};

/// Draws the "Speed vs error" window when state.open (its close button clears it): the
/// file row, the group / x-metric / speed controls, a caption, and the chart with its
/// legend and hover tooltips. `pos` and `size` (window coordinates) are applied when
/// `apply_layout` is set and the first time the window appears; otherwise the user may
/// move it. Call between ImGui::NewFrame() and ImGui::Render().
void bench_chart_window(BenchChartState& state, glm::vec2 pos, glm::vec2 size, bool apply_layout);

/// The main panel's section: a path field with Load (opens the window on success, shows
/// the error otherwise) and a button that shows or hides the window.
void bench_chart_section(BenchChartState& state);

}  // namespace viz
