#pragma once
// The catalogue of every script verb, in the order the docs show them: each module's
// registrations (commands.h) read by VerbCatalogue, which keeps name, usage, help and parse
// and drops the runs, so the parser, `accelviz --list commands` and their tests need no
// window and no tool. The tools bind the same registrations to themselves (add_verbs());
// App checks that its table has exactly these verbs, in this order.
//
// Each module's registration function and its argument types, one header per module:
//   global_verbs.h                     App's: window size, camera, panels, lecture mode,
//                                      colours, screenshots, the saved state, frame time
//   tools/structure_session_verbs.h    the scene, the structure and how it is built
//   tools/ray_debugger_verbs.h         the debug ray and its traversal
//   tools/blackboard_verbs.h           the 2D mode (App's too)
//   tools/node_display_verbs.h         which nodes are drawn, the mesh
//   tools/heatmap_verbs.h              the cost heat map
//   tools/compare_verbs.h, sweep_verbs.h, build_player_verbs.h, tree_diagram_verbs.h,
//   trap_verbs.h, playlist_verbs.h, recorder_verbs.h, bench_chart_verbs.h
#include "bench_chart_verbs.h"
#include "commands.h"
#include "global_verbs.h"
#include "tools/blackboard_verbs.h"
#include "tools/build_player_verbs.h"
#include "tools/compare_verbs.h"
#include "tools/heatmap_verbs.h"
#include "tools/node_display_verbs.h"
#include "tools/playlist_verbs.h"
#include "tools/ray_debugger_verbs.h"
#include "tools/recorder_verbs.h"
#include "tools/structure_session_verbs.h"
#include "tools/sweep_verbs.h"
#include "tools/trap_verbs.h"
#include "tools/tree_diagram_verbs.h"

namespace viz {

/// Every verb without its run: the global ones, then each tool's.
const VerbTable& script_verbs();

}  // namespace viz
