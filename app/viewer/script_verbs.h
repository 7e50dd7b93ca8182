#pragma once
// The GL-free halves of the script verbs (commands.h), one list per module in its
// *_verbs.cpp, and all of them in the order the docs show them. The run halves are in the
// tools; App joins the two by CommandKind.
#include <span>
#include <vector>

#include "commands.h"

namespace viz {

/// Every verb: the global ones, then each tool's.
const std::vector<ScriptVerb>& script_verbs();

/// The global verbs (App's: window size, camera, panels, lecture mode, colours,
/// screenshots, the saved state, frame time), in script.cpp.
std::span<const ScriptVerb> global_verbs();
/// Each tool's, in tools/<tool>_verbs.cpp (the bench chart's in bench_chart_verbs.cpp).
std::span<const ScriptVerb> structure_session_verbs();
std::span<const ScriptVerb> ray_debugger_verbs();
std::span<const ScriptVerb> blackboard_verbs();
std::span<const ScriptVerb> node_display_verbs();
std::span<const ScriptVerb> heatmap_verbs();
std::span<const ScriptVerb> compare_verbs();
std::span<const ScriptVerb> sweep_verbs();
std::span<const ScriptVerb> build_player_verbs();
std::span<const ScriptVerb> tree_diagram_verbs();
std::span<const ScriptVerb> trap_verbs();
std::span<const ScriptVerb> playlist_verbs();
std::span<const ScriptVerb> recorder_verbs();
std::span<const ScriptVerb> bench_chart_verbs();

}  // namespace viz
