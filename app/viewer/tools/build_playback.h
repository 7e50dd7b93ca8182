#pragma once
// GL-free half of the construction mode (tools/build_player.h is the tool; the recording
// itself is accel::build_structure_recorded): stepping through a build's steps, and what one
// step shows -- the partly built structure (from accel::BuildReplay), the current node, its
// triangles and the candidate / chosen plane, the grid cells of an insertion, and the SAH
// cost curves of the current node. Plain data, so tests/app/test_build_player.cpp drives it
// without a window.
#include <cstddef>
#include <string>
#include <vector>

#include "build_replay.h"
#include "build_trace.h"
#include "playback_clock.h"
#include "scene.h"
#include "structure_view.h"

namespace viz {

/// Steps through a recorded build: a PlaybackClock over its steps (play, pause, speed,
/// single steps, seek). step() = steps applied, in [0, size()]: 0 shows nothing built yet,
/// size() the finished structure.
class BuildStepPlayer : public accel::PlaybackClock {
 public:
  /// A build of `steps` steps: step 0, paused. (Positions 0..steps; none without steps.)
  void load(size_t steps) {
    steps_ = steps;
    restart(steps ? steps + 1 : 0);
  }
  void clear() { load(0); }
  size_t size() const { return steps_; }

 private:
  size_t steps_ = 0;
};

/// "build step K/N: TEXT" (print-build-step): K steps applied, TEXT the last applied step's
/// describe_build_event ("nothing built yet" at step 0).
std::string build_step_line(const accel::BuildTrace& trace, size_t applied);

/// The node the current step is about (kNoBuildNode: none, e.g. scene box, grid steps, done).
uint32_t build_event_node(const accel::BuildEvent& e);

/// The SAH cost curves of one node so far: one per axis evaluated (x, y, z, PCA).
struct CostCurve {
  int axis = 0;             ///< 0..2, 3 = PCA
  std::vector<float> pos;   ///< plane positions, as recorded
  std::vector<float> cost;  ///< C(B) at each
  size_t best = 0;          ///< index of the minimum
};
struct CostPlot {
  uint32_t node = accel::kNoBuildNode;
  std::vector<CostCurve> curves;  ///< in the order evaluated
  bool has_leaf_cost = false;     ///< the node's Split is applied: its values[0]
  float leaf_cost = 0.0f;
  int best_curve = -1;            ///< curve holding the overall minimum (-1: none)
  float min_cost = 0.0f, max_cost = 0.0f;  ///< over all curves and the leaf cost
};
/// The cost plot after `applied` steps: the Candidates events of the current step's node
/// up to and including the current step (looked for back to that node's Node event).
CostPlot cost_plot(const accel::BuildTrace& trace, size_t applied);

/// What one construction step draws, ready to upload.
struct BuildView {
  std::vector<ColorVertex> lines;      ///< thin: the nodes so far, the grid's cells so far, the insertion's bbox cells
  std::vector<Segment> segments;       ///< thick: the current node, the cells kept, triangle outlines
  std::vector<ColorVertex> triangles;  ///< filled: the current node's triangles, the plane
  size_t nodes_drawn = 0;
  bool nodes_capped = false;           ///< more than kMaxNodes nodes exist; the deepest are left out
  static constexpr size_t kMaxNodes = 20000;
  static constexpr size_t kMaxTriangles = 20000;
};
/// The view of `replay`'s current step (replay over `trace`, triangles from `scene`).
BuildView build_view(const accel::BuildTrace& trace, const accel::BuildReplay& replay, const accel::Scene& scene);

}  // namespace viz
