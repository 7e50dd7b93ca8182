#pragma once
// GL-free half of the construction mode (tools/build_player.h is the tool): recording a
// build with a depth-limit retry, stepping through its steps, and what one step shows --
// the partly built structure (from accel::BuildReplay), the current node, its triangles
// and the candidate / chosen plane, the grid cells of an insertion, and the SAH cost curves
// of the current node. Plain data, so tests/app/test_build_player.cpp drives it without a window.
#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "build_control.h"
#include "build_replay.h"
#include "build_trace.h"
#include "result.h"
#include "scene.h"
#include "structure_view.h"
#include "workbench.h"

namespace viz {

/// Steps through a recorded build. step() = steps applied, in [0, size()]: 0 shows nothing
/// built yet, size() the finished structure. Controls as accel::TracePlayer's.
class BuildStepPlayer {
 public:
  static constexpr double kDefaultSpeed = 4.0;
  static constexpr double kMinSpeed = 0.25;
  static constexpr double kMaxSpeed = 5000.0;

  /// A trace of `steps` steps: step 0, paused.
  void load(size_t steps);
  void clear() { load(0); }
  /// Starts playing; at the end it starts over from step 0.
  void play();
  void pause() { playing_ = false; }
  void toggle() { playing_ ? pause() : play(); }
  bool playing() const { return playing_; }
  /// Steps per second, clamped to [kMinSpeed, kMaxSpeed].
  void set_speed(double steps_per_second);
  double speed() const { return speed_; }
  /// Plays on by `seconds` (whole steps, the rest carried); stops at the end. True when the step changed.
  bool advance(double seconds);
  /// Moves `n` steps, clamped. True when the step changed.
  bool step_forward(size_t n = 1);
  bool step_back(size_t n = 1);
  /// Goes to `step` (clamped to [0, size()]). True when the step changed.
  bool seek(size_t step);
  bool jump_to_end() { return seek(size_); }
  size_t step() const { return step_; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  bool at_end() const { return step_ >= size_; }

 private:
  size_t size_ = 0;
  size_t step_ = 0;
  bool playing_ = false;
  double speed_ = kDefaultSpeed;
  double carry_ = 0.0;
};

/// A recorded build: the trace and how it was obtained.
struct RecordedBuild {
  std::shared_ptr<const accel::BuildTrace> trace;
  std::vector<accel::RecordAttempt> attempts;
  /// The structure's SAH constants (BuildStats::sah_ct, sah_ci, sah_prims_per_test; 1 where
  /// it has none), for the cost of the tree so far (BuildReplay::sah_cost).
  double sah_ct = 1.0, sah_ci = 1.0;
  int sah_prims_per_test = 1;
};

/// Runs one recorded build into the recorder it is given.
using RecordFn = std::function<accel::Status(accel::BuildRecorder&)>;

/// Scenes with more triangles than this start recording at a depth limit (see record_with_retry).
inline constexpr size_t kLargeSceneTriangles = 200000;

/// Records with `record` within the budget (accel::record_within_budget). The first attempt
/// records every depth, or, for scenes over kLargeSceneTriangles, half the depth a balanced
/// binary tree over them would have (ceil(log2 N) / 2), so a huge scene is not recorded in
/// full only to be recorded again.
accel::Result<RecordedBuild> record_with_retry(const RecordFn& record, size_t triangles,
                                               size_t budget_bytes = accel::BuildRecorder::kDefaultBudgetBytes);

/// Records the build of `request` over `scene` (any thread) with record_with_retry.
accel::Result<RecordedBuild> record_structure(const accel::Scene& scene, const StructureRequest& request,
                                              accel::BuildControl* control,
                                              size_t budget_bytes = accel::BuildRecorder::kDefaultBudgetBytes);

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
