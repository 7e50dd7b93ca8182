#pragma once
// GL-free: the numbers the "Variables" panel, the t-axis strip and `print-vars` show for the
// debug ray's current step. Everything comes from the recorded trace -- the events and the
// loop variables the traversal itself recorded (accel::RecordedVars) -- so nothing here
// recomputes what the structure computed; it only selects and orders it for display.
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "pseudo_code.h"
#include "trace.h"
#include "trace_player.h"
#include "traps.h"

namespace viz {

/// "vars: name=value ..." for the step of `highlight` (print-vars): the loop variables
/// recorded at or before it since the node / cell was entered (describe_vars), then
/// closest_hit, then for the stack- and queue-driven traversals (kd-tree, octree, BVH,
/// sphere tree) the pending nodes as `stack=NODE:KEY,...` (top first) or `queue=...`
/// (nearest first); `-` when empty.
std::string vars_line(std::span<const accel::RecordedVars> vars, std::span<const accel::TraceEvent> events,
                      const accel::TraceHighlight& highlight, TraversalKind kind);

/// The pending nodes in the order the traversal takes them: a priority queue nearest
/// first, a stack top first.
std::vector<accel::PendingNode> pending_in_pop_order(const accel::TraceHighlight& highlight, TraversalKind kind);

/// True for the traversals that keep pending nodes (stack or queue).
bool keeps_pending(TraversalKind kind);

/// The t-axis strip at one step: the ray's parameter range and, up to the step, the
/// interval of every node or cell visited, the recorded split distances, the push keys and
/// the closest hit so far.
struct TStrip {
  float t_lo = 0.0f, t_hi = 1.0f;  ///< the axis: fixed for the whole trace (does not jump)
  struct Interval {
    float t0 = 0.0f, t1 = 0.0f;
    bool current = false;  ///< the node / cell of the current step
  };
  std::vector<Interval> intervals;  ///< visited so far, in order (the current one last)
  struct Split {
    float t = 0.0f;
    bool current = false;  ///< recorded at the current node
  };
  std::vector<Split> splits;  ///< kd-tree t_split so far (KdSplitVars and KdExitVars)
  struct Key {
    float t = 0.0f;
    bool pending = false;  ///< still on the stack / queue at this step
  };
  std::vector<Key> keys;         ///< entry keys of the pushes so far
  float closest = accel::kInf;   ///< closest hit so far (inf: none)
  float event_t = std::numeric_limits<float>::quiet_NaN();   ///< the current event's own distance (a test's hit, a key), NaN if none
};

/// The axis range of a trace: to the farthest finite distance any event records (exits of
/// visited nodes, hits), so every interval fits; from the ray's tmin, or from a little before
/// the first node's entry when the ray starts far from the scene; [tmin, tmin + 1] when
/// nothing is finite.
void t_strip_range(std::span<const accel::TraceEvent> events, float tmin, float& t_lo, float& t_hi);

/// The strip at `highlight`'s step, on the axis [t_lo, t_hi].
TStrip t_strip_at(std::span<const accel::TraceEvent> events, std::span<const accel::RecordedVars> vars,
                  const accel::TraceHighlight& highlight, float t_lo, float t_hi);

}  // namespace viz
