#pragma once
// Playback of a recorded traversal (TraceRecorder's events) for the viewer's animation, and
// what each step shows. Both are plain logic with no GL, so the tests drive them without a
// window:
//   TracePlayer       time -> step: play/pause, speed, single steps, jump to the hit
//   trace_highlight() events + step -> current node and its t interval, tested triangles,
//                     skipped nodes with reasons, closest hit, pending stack/queue contents
// The events come from the structure's one real traversal (intersect_traced); nothing here
// re-implements a traversal.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "trace.h"

namespace accel {

/// Steps through a recorded trace. The current step is an index into the events, in
/// [0, size() - 1] (0 when there are none): the event at that index has just happened.
class TracePlayer {
 public:
  /// Default and limits of the playback speed, in steps per second.
  static constexpr double kDefaultSpeed = 4.0;
  static constexpr double kMinSpeed = 0.25;
  static constexpr double kMaxSpeed = 2000.0;

  /// Replaces the trace. keep_step = false: back to step 0, paused. keep_step = true (the
  /// same ray replayed on a rebuilt structure): the step index stays, clamped to the new
  /// trace's last step, and playing goes on.
  void load(std::vector<TraceEvent> events, bool keep_step = false);
  /// Drops the trace (size() = 0, step 0, paused).
  void clear();
  /// Step 0, paused.
  void reset();

  /// Starts playing; at the last step it starts over from step 0.
  void play();
  void pause() { playing_ = false; }
  void toggle() { playing_ ? pause() : play(); }
  bool playing() const { return playing_; }

  /// Steps per second, clamped to [kMinSpeed, kMaxSpeed].
  void set_speed(double steps_per_second);
  double speed() const { return speed_; }

  /// Advances by `seconds` of playing time (nothing while paused). Whole steps are taken,
  /// the remainder carried to the next call; playing stops at the last step. Returns true
  /// when the step changed.
  bool advance(double seconds);
  /// Moves `n` steps forward / back, clamped to the trace. Returns true when the step changed.
  bool step_forward(size_t n = 1);
  bool step_back(size_t n = 1);
  /// Goes to `step`, clamped. Returns true when the step changed.
  bool seek(size_t step);
  /// Goes to the last step (the Done event).
  bool jump_to_end() { return seek(size() ? size() - 1 : 0); }
  /// Goes to hit_step(). Pauses.
  bool jump_to_hit();

  /// The step where the final hit was found: the NewClosest event that set the answer
  /// reported by Done, or the Done event on a miss (or the last event without a Done).
  size_t hit_step() const;

  size_t step() const { return step_; }
  size_t size() const { return events_.size(); }
  bool empty() const { return events_.empty(); }
  bool at_end() const { return events_.empty() || step_ + 1 >= events_.size(); }
  /// The current event, or nullptr without a trace.
  const TraceEvent* current() const { return events_.empty() ? nullptr : &events_[step_]; }
  const std::vector<TraceEvent>& events() const { return events_; }

 private:
  std::vector<TraceEvent> events_;
  size_t step_ = 0;
  bool playing_ = false;
  double speed_ = kDefaultSpeed;
  double carry_ = 0.0;  ///< fraction of a step accumulated by advance()
};

/// A ray/triangle test of the current node.
struct TestedPrim {
  int32_t prim = -1;
  bool hit = false;
  float t = kInf;  ///< hit distance (inf on a miss)
};

/// A node or cell that was skipped, with the reason.
struct CulledNode {
  NodeId node = kNoNode;
  int depth = 0;
  CullReason reason = CullReason::None;
  float t = 0.0f;   ///< entry distance when known (the event's t0)
  size_t step = 0;  ///< step at which it was skipped
};

/// A node waiting on the stack / priority queue.
struct PendingNode {
  NodeId node = kNoNode;
  int depth = 0;
  float key = 0.0f;  ///< the push's key (entry distance)
};

/// Everything the viewer highlights at one step.
struct TraceHighlight {
  bool valid = false;  ///< false for an empty trace
  size_t step = 0;
  TraceEvent event;    ///< the current event
  /// The node or cell being processed: the last Visit / EnterCell at or before the step
  /// (kNoNode before the first), with the ray's interval inside it.
  NodeId node = kNoNode;
  int node_depth = 0;
  float t0 = 0.0f, t1 = 0.0f;
  size_t node_step = 0;  ///< step of that Visit / EnterCell
  /// Triangles tested since that Visit / EnterCell, in test order.
  std::vector<TestedPrim> tested;
  /// Every node / cell visited so far (Visit / EnterCell), in order, the current one last:
  /// the path the ray has taken.
  std::vector<NodeId> visited;
  /// Every node skipped so far, in order.
  std::vector<CulledNode> culled;
  /// Nodes pushed and neither popped nor skipped yet, in push order (the top of a stack is
  /// the last one; a priority queue's front is the smallest key).
  std::vector<PendingNode> pending;
  /// Closest hit so far (prim -1 and t inf before the first).
  int32_t closest_prim = -1;
  float closest_t = kInf;
  /// Counters up to and including the step (same rules as StatsSink; max_stack is the
  /// largest pending set).
  QueryStats counters;
  bool done = false;  ///< the Done event has been reached
};

/// The highlight state after events[0..step] (step clamped to the last event).
TraceHighlight trace_highlight(std::span<const TraceEvent> events, size_t step);

/// `pending` ordered for a priority-queue display: smallest key first (ties: lower node id).
std::vector<PendingNode> sorted_by_key(std::vector<PendingNode> pending);

}  // namespace accel
