// The list of the viewer's tools: adding a tool is its own files and one line here.
//
// The order is the viewer's: the blackboard's Scene line comes before the session's; the
// debug ray updates before the trap reads it; the playlist's PgDn / PgUp are offered before
// the construction's; the sections follow as the main panel lists them (traps, playlist,
// recording, heat map, sweep, chart); the Variables panel's t-axis strip goes last among the
// docked windows (it fits between them); the status notices go on top of everything.
#include "tools/tool_list.h"

#include "tools/bench_chart_tool.h"
#include "tools/blackboard_tool.h"
#include "tools/build_player.h"
#include "tools/compare_tool.h"
#include "tools/heatmap_tool.h"
#include "tools/node_display.h"
#include "tools/playlist_tool.h"
#include "tools/ray_debugger.h"
#include "tools/recorder.h"
#include "tools/status_overlay.h"
#include "tools/structure_session.h"
#include "tools/sweep_tool.h"
#include "tools/trap_tool.h"
#include "tools/tree_diagram.h"
#include "tools/vars_panel.h"

namespace viz {

std::vector<std::unique_ptr<Tool>> make_tools() {
  std::vector<std::unique_ptr<Tool>> tools;
  tools.push_back(std::make_unique<BlackboardTool>());
  tools.push_back(std::make_unique<StructureSession>());
  tools.push_back(std::make_unique<NodeDisplay>());
  tools.push_back(std::make_unique<RayDebugger>());
  tools.push_back(std::make_unique<CompareTool>());
  tools.push_back(std::make_unique<TrapTool>());
  tools.push_back(std::make_unique<PlaylistTool>());
  tools.push_back(std::make_unique<BuildPlayer>());
  tools.push_back(std::make_unique<Recorder>());
  tools.push_back(std::make_unique<HeatmapTool>());
  tools.push_back(std::make_unique<SweepTool>());
  tools.push_back(std::make_unique<TreeDiagram>());
  tools.push_back(std::make_unique<BenchChartTool>());
  tools.push_back(std::make_unique<VarsPanel>());
  tools.push_back(std::make_unique<StatusOverlay>());
  return tools;
}

}  // namespace viz
