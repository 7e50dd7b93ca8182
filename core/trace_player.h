#pragma once
// Playback of a recorded traversal (TraceRecorder's events) for the viewer's animation, and
// what each step shows. Both are plain logic with no GL, so the tests drive them without a
// window:
//   TracePlayer       time -> step (a PlaybackClock over the events), jump to the hit
//   trace_highlight() events + step -> current node and its t interval, tested triangles,
//                     skipped nodes with reasons, closest hit, pending stack/queue contents
// The events come from the structure's one real traversal (intersect_traced); nothing here
// re-implements a traversal.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "playback_clock.h"
#include "trace.h"

namespace accel {

/// Steps through a recorded trace: a PlaybackClock over its events (play, pause, speed,
/// single steps, seek), plus the trace and the jump to the hit. The current step is an index
/// into the events, in [0, size() - 1] (0 when there are none): the event at that index has
/// just happened.
class TracePlayer : public PlaybackClock {
 public:
  /// Replaces the trace. keep_step = false: back to step 0, paused. keep_step = true (the
  /// same ray replayed on a rebuilt structure): the step index stays, clamped to the new
  /// trace's last step, and playing goes on.
  void load(std::vector<TraceEvent> events, bool keep_step = false);
  /// Drops the trace (size() = 0, step 0, paused).
  void clear() { load({}); }
  /// Step 0, paused.
  void reset() { restart(events_.size()); }

  /// Goes to hit_step(). Pauses.
  bool jump_to_hit();

  /// The step where the final hit was found: the NewClosest event that set the answer
  /// reported by Done, or the Done event on a miss (or the last event without a Done).
  size_t hit_step() const;

  size_t size() const { return events_.size(); }
  /// The current event, or nullptr without a trace.
  const TraceEvent* current() const { return events_.empty() ? nullptr : &events_[step()]; }
  const std::vector<TraceEvent>& events() const { return events_; }

 private:
  std::vector<TraceEvent> events_;
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
