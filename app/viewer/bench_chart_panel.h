#pragma once
// The ImGui side of the speed-against-error chart (bench_chart.h computes it): the
// "Speed vs error" window, the main panel's section that loads a file and opens it, and the
// chart's script verbs.
#include <glm/vec2.hpp>

#include "bench_chart.h"
#include "commands.h"
#include "tool_host.h"

namespace viz {

/// Draws the "Speed vs error" window when state.open (its close button clears it): the
/// file row, the group / x-metric / speed controls, a caption, and the chart with its
/// legend and hover tooltips. `pos` and `size` (window coordinates) are applied when
/// `apply_layout` is set and the first time the window appears; otherwise the user may
/// move it. Call between ImGui::NewFrame() and ImGui::Render().
void bench_chart_window(BenchChartState& state, glm::vec2 pos, glm::vec2 size, bool apply_layout);

/// The chart's script verbs (load-bench, show-chart: bench_chart_verbs.h) on `state`, bound
/// into `table`; `host` shows the panels.
void add_bench_chart_verbs(VerbTable& table, BenchChartState& state, ToolHost& host);

/// The main panel's section: a path field with Load (opens the window on success, shows
/// the error otherwise) and a button that shows or hides the window.
void bench_chart_section(BenchChartState& state);

}  // namespace viz
