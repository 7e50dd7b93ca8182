#pragma once
// Observers of the one real traversal of each structure. Every structure writes its loop
// once, as `template <TraversalSink Sink> Hit traverse(const Ray&, Sink&) const`, and calls
// the sink at each step. NullSink compiles to nothing (the fast path), StatsSink counts, and
// TraceRecorder keeps every step for the viewer's animation -- so the animation shows
// exactly what the real query does. TraversalSink names the contract.
#include <algorithm>
#include <concepts>
#include <cstddef>
#include <span>
#include <cstdint>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "geometry.h"

namespace accel {

/// A node's array index, or a grid cell's linear index.
using NodeId = uint32_t;
inline constexpr NodeId kNoNode = std::numeric_limits<NodeId>::max();

/// Why a node or cell was skipped.
enum class CullReason : uint8_t {
  None,
  MissedBounds,      ///< the ray does not intersect the node's box/sphere within [tmin, t_closest]
  BeyondClosestHit,  ///< the ray enters the node farther than the closest hit found so far
};

enum class TraceEventKind : uint8_t {
  Visit,       ///< enter a node: node, depth, t interval [t0, t1] of the ray inside it
  EnterCell,   ///< grid: step into a cell: node = linear cell index, [t0, t1] inside it
  Cull,        ///< skip a node or subtree: node, depth, reason, t0 = entry distance if known
  Push,        ///< put a node on the stack / priority queue: node, depth, t0 = its key (entry distance)
  Pop,         ///< take a node from the stack / queue: node, depth, t0 = its key
  TestPrim,    ///< ray/triangle test: prim, hit, t0 = hit distance when hit
  NewClosest,  ///< the closest hit improved: prim, t0 = its distance
  Done,        ///< the query finished: prim = closest hit (-1 = miss), t0 = its distance
};

/// One recorded step. Plain data: the viewer turns it into highlights and text.
struct TraceEvent {
  TraceEventKind kind = TraceEventKind::Visit;
  CullReason reason = CullReason::None;
  bool hit = false;
  uint16_t depth = 0;
  NodeId node = kNoNode;
  int32_t prim = -1;
  float t0 = 0.0f;
  float t1 = 0.0f;
};

/// "visit", "cull", ... for text output.
const char* event_kind_name(TraceEventKind kind);
const char* cull_reason_name(CullReason reason);
/// One line describing the event, e.g. "visit node 12 (depth 3) t=[0.5, 0.8]".
std::string describe_event(const TraceEvent& e);

// ---------------------------------------------------------------------------------------
// The traversal's variables at a step, named as in the lecture's pseudo code. Recorded by
// the traversal itself (sink.vars(), only when Sink::kRecords), right after the event they
// belong to, so the viewer shows the values the real loop computed, never recomputed ones.

/// Grid 3D-DDA (Amanatides & Woo 1987), recorded on entering a cell: the cell (X, Y, Z),
/// the step per axis, tMax (the t of the next boundary crossing per axis; inf on an axis
/// the ray never steps on) and tDelta (t to cross one cell; 0 where it never steps), and
/// the axis that steps next (the smallest tMax).
struct GridDdaVars {
  int cell[3] = {0, 0, 0};
  int step[3] = {0, 0, 0};
  float t_max[3] = {0, 0, 0};
  float t_delta[3] = {0, 0, 0};
  int next_axis = 0;
  int dims = 3;  ///< 2 over a 2D scene: the lecture's 2D DDA, X and Y only (z never steps)
};

/// Which children of a kd-tree inner node the ray visits (the lecture's three cases).
enum class KdCase : uint8_t {
  Both,      ///< (a) t_min <= t_split <= t_max: near child on [t_min, t_split], far on [t_split, t_max]
  NearOnly,  ///< (b) t_split > t_max: the plane lies beyond the interval
  FarOnly,   ///< (c) t_split < t_min: the plane lies before it
};

/// kd-tree inner node, recorded after its visit: the interval, the plane distance, the near
/// and far child (near = the side the ray is on before t_split) and the case.
struct KdSplitVars {
  float t_min = 0, t_split = 0, t_max = 0;
  NodeId near_child = kNoNode, far_child = kNoNode;
  int axis = 0;
  KdCase kase = KdCase::Both;
};

/// kd-tree, recorded when a pending far child is popped: the lecture's early exit
/// "if t_hit < t_split return" (t_split = the far child's entry distance; t_hit = inf
/// while nothing is hit).
struct KdExitVars {
  float t_hit = 0, t_split = 0;
  NodeId far_child = kNoNode;
  bool exits = false;  ///< t_hit < t_split: the far child is skipped
};

/// Octree inner node, recorded after its children were tested: the children in visiting
/// order (octant i ^ mask for i = 0..7; mask = the axes the ray travels down) with their
/// entry and exit distances, and what became of each.
struct OctreeOrderVars {
  enum class Fate : uint8_t { Pushed, Missed, BeyondClosestHit, Empty };
  struct Child {
    NodeId node = kNoNode;
    uint8_t octant = 0;
    Fate fate = Fate::Empty;
    float t_enter = 0, t_exit = 0;
  };
  unsigned mask = 0;
  int count = 0;  ///< children listed (8 for an inner node)
  Child children[8];
};

/// One step's variables.
using StepVars = std::variant<GridDdaVars, KdSplitVars, KdExitVars, OctreeOrderVars>;

/// Variables recorded after events[event] (the event recorded just before them).
struct RecordedVars {
  size_t event = 0;
  StepVars vars;
};

/// "X=3 Y=0 Z=1 stepX=1 ... tMaxX=0.5 ... tDeltaX=0.25 ... next=x" and the like: the
/// variables as name=value pairs, named as in the lecture (print-vars, the panel).
std::string describe_vars(const StepVars& vars);
/// "a (both)", "b (near only)", "c (far only)".
const char* kd_case_name(KdCase c);
/// The variables shown at `step`: the last ones recorded at or before it since the last
/// Visit / EnterCell at or before it (so a new node shows no stale values), or nullptr.
const StepVars* vars_at(std::span<const TraceEvent> events, std::span<const RecordedVars> vars, size_t step);

/// The fast path: every callback is empty and inlined away.
struct NullSink {
  /// Keeps no steps: no extra tests to tell why a node was culled.
  static constexpr bool kRecords = false;
  /// Nothing is counted or kept: traversals may skip work done only for observers.
  static constexpr bool kObserves = false;
  void visit(NodeId, int, float, float) {}
  void enter_cell(NodeId, float, float) {}
  void cull(NodeId, int, CullReason, float) {}
  void push(NodeId, int, float) {}
  void pop(NodeId, int, float) {}
  void test_prim(uint32_t, bool, float) {}
  void new_closest(uint32_t, float) {}
  void done(const Hit&) {}
  void vars(const StepVars&) {}
};

/// Per-query counters, returned per query (never global).
struct QueryStats {
  uint64_t nodes_visited = 0;  ///< nodes entered, or grid cells stepped through
  uint64_t nodes_culled = 0;   ///< nodes skipped (missed or beyond the closest hit)
  uint64_t prims_tested = 0;   ///< ray/triangle tests
  uint64_t max_stack = 0;      ///< deepest stack / largest priority queue
  QueryStats& operator+=(const QueryStats& o) {
    nodes_visited += o.nodes_visited;
    nodes_culled += o.nodes_culled;
    prims_tested += o.prims_tested;
    max_stack = std::max(max_stack, o.max_stack);
    return *this;
  }
};

/// Counts steps; the same calls as the recorder, nothing stored.
struct StatsSink {
  static constexpr bool kRecords = false;  ///< counts only: no extra tests to tell why a node was culled
  static constexpr bool kObserves = true;  ///< the counters are its whole point
  QueryStats stats;
  uint64_t stack_size = 0;
  void visit(NodeId, int, float, float) { ++stats.nodes_visited; }
  void enter_cell(NodeId, float, float) { ++stats.nodes_visited; }
  void cull(NodeId, int, CullReason, float) { ++stats.nodes_culled; }
  void push(NodeId, int, float) { stats.max_stack = std::max(stats.max_stack, ++stack_size); }
  void pop(NodeId, int, float) { if (stack_size) --stack_size; }
  void test_prim(uint32_t, bool, float) { ++stats.prims_tested; }
  void new_closest(uint32_t, float) {}
  void done(const Hit&) {}
  void vars(const StepVars&) {}
};

/// Records every step in order, for the animation and for tests of the traversal order.
/// The recording is bounded (a ray through a grid of 5,000 identical triangles per cell
/// makes millions of steps): past `budget_bytes` further steps are dropped, truncated()
/// says so, and the final Done event is always kept, so the traversal -- which never
/// depends on the recorder -- and its answer stay whole.
class TraceRecorder {
 public:
  static constexpr bool kRecords = true;   ///< keeps every step, cull reasons included
  static constexpr bool kObserves = true;
  /// 256 MiB: about 8 million steps, far more than anyone steps through.
  static constexpr size_t kDefaultBudgetBytes = size_t(256) << 20;

  explicit TraceRecorder(size_t budget_bytes = kDefaultBudgetBytes)
      : max_events_(std::max<size_t>(2, budget_bytes / (sizeof(TraceEvent) + sizeof(RecordedVars)))) {}

  void visit(NodeId n, int depth, float t0, float t1) { add(TraceEventKind::Visit, n, depth, t0, t1); }
  void enter_cell(NodeId n, float t0, float t1) { add(TraceEventKind::EnterCell, n, 0, t0, t1); }
  void cull(NodeId n, int depth, CullReason why, float t0) {
    TraceEvent e = make(TraceEventKind::Cull, n, depth, t0, t0);
    e.reason = why;
    keep(e);
  }
  void push(NodeId n, int depth, float key) { add(TraceEventKind::Push, n, depth, key, key); }
  void pop(NodeId n, int depth, float key) { add(TraceEventKind::Pop, n, depth, key, key); }
  void test_prim(uint32_t prim, bool hit, float t) {
    TraceEvent e = make(TraceEventKind::TestPrim, kNoNode, 0, hit ? t : kInf, hit ? t : kInf);
    e.prim = int32_t(prim);
    e.hit = hit;
    keep(e);
  }
  void new_closest(uint32_t prim, float t) {
    TraceEvent e = make(TraceEventKind::NewClosest, kNoNode, 0, t, t);
    e.prim = int32_t(prim);
    e.hit = true;
    keep(e);
  }
  void done(const Hit& h) {
    TraceEvent e = make(TraceEventKind::Done, kNoNode, 0, h.t, h.t);
    e.prim = h.prim;
    e.hit = h.valid();
    events_.push_back(e);  // always: the answer ends every recording, truncated or not
  }
  void vars(const StepVars& v) {
    if (!truncated_) vars_.push_back({events_.empty() ? 0 : events_.size() - 1, v});
  }
  const std::vector<TraceEvent>& events() const { return events_; }
  /// The variables recorded (grid, kd-tree and octree), each after the event it belongs to.
  const std::vector<RecordedVars>& recorded_vars() const { return vars_; }
  /// True when steps were dropped to stay within the budget (the Done event is kept).
  bool truncated() const { return truncated_; }
  void clear() {
    events_.clear();
    vars_.clear();
    truncated_ = false;
  }
  /// Counters derived from the recorded events (equal to StatsSink's by construction, when
  /// not truncated).
  QueryStats stats() const;

 private:
  static TraceEvent make(TraceEventKind k, NodeId n, int depth, float t0, float t1) {
    TraceEvent e;
    e.kind = k;
    e.node = n;
    e.depth = uint16_t(depth);
    e.t0 = t0;
    e.t1 = t1;
    return e;
  }
  void add(TraceEventKind k, NodeId n, int depth, float t0, float t1) { keep(make(k, n, depth, t0, t1)); }
  void keep(const TraceEvent& e) {
    if (events_.size() + 1 < max_events_)  // one place stays free for Done
      events_.push_back(e);
    else
      truncated_ = true;
  }
  size_t max_events_;
  bool truncated_ = false;
  std::vector<TraceEvent> events_;
  std::vector<RecordedVars> vars_;
};

/// Receives a traversal's steps through virtual calls: lets a traversal compiled for
/// another instruction set (structures/wide_bvh_avx2.cpp) report to a recorder compiled for
/// the baseline, so tests compare the kernels step by step. Not a fast path.
class StepListener {
 public:
  /// Defined in trace.cpp (the key function): the vtable and type information are emitted
  /// there only, not in the ISA units that call through this interface.
  virtual ~StepListener();
  virtual void visit(NodeId n, int depth, float t0, float t1) = 0;
  virtual void enter_cell(NodeId n, float t0, float t1) = 0;
  virtual void cull(NodeId n, int depth, CullReason why, float t0) = 0;
  virtual void push(NodeId n, int depth, float key) = 0;
  virtual void pop(NodeId n, int depth, float key) = 0;
  virtual void test_prim(uint32_t prim, bool hit, float t) = 0;
  virtual void new_closest(uint32_t prim, float t) = 0;
  virtual void done(const Hit& h) = 0;
  virtual void vars(const StepVars& v) = 0;
};

/// A recording sink (cull reasons included) that forwards every step to a StepListener.
struct ForwardingSink {
  static constexpr bool kRecords = true;
  static constexpr bool kObserves = true;
  StepListener* to;
  void visit(NodeId n, int depth, float t0, float t1) { to->visit(n, depth, t0, t1); }
  void enter_cell(NodeId n, float t0, float t1) { to->enter_cell(n, t0, t1); }
  void cull(NodeId n, int depth, CullReason why, float t0) { to->cull(n, depth, why, t0); }
  void push(NodeId n, int depth, float key) { to->push(n, depth, key); }
  void pop(NodeId n, int depth, float key) { to->pop(n, depth, key); }
  void test_prim(uint32_t prim, bool hit, float t) { to->test_prim(prim, hit, t); }
  void new_closest(uint32_t prim, float t) { to->new_closest(prim, t); }
  void done(const Hit& h) { to->done(h); }
  void vars(const StepVars& v) { to->vars(v); }
};

/// A StepListener that keeps the steps in a TraceRecorder (defined in trace.cpp, so no
/// other unit emits a copy of its functions).
class RecordingListener final : public StepListener {
 public:
  explicit RecordingListener(TraceRecorder& recorder) : r_(recorder) {}
  void visit(NodeId n, int depth, float t0, float t1) override;
  void enter_cell(NodeId n, float t0, float t1) override;
  void cull(NodeId n, int depth, CullReason why, float t0) override;
  void push(NodeId n, int depth, float key) override;
  void pop(NodeId n, int depth, float key) override;
  void test_prim(uint32_t prim, bool hit, float t) override;
  void new_closest(uint32_t prim, float t) override;
  void done(const Hit& h) override;
  void vars(const StepVars& v) override;

 private:
  TraceRecorder& r_;
};

/// What every traversal may call on its sink, in the order of a query: visit (enter a node)
/// or enter_cell (a grid cell), cull, push / pop (stack or queue), test_prim and
/// new_closest (triangles), done (the answer); vars (the loop's variables, called only
/// when kRecords). kRecords: the sink keeps the steps, so a
/// traversal spends extra tests on telling it why a node was culled. kObserves: the sink
/// counts or keeps anything at all; when it does not, the traversal may skip the work
/// done only to report steps (node ids, missed children), which is what keeps the fast
/// path free.
template <class S>
concept TraversalSink = requires(S& sink, NodeId node, int depth, float t, CullReason why, uint32_t prim, bool hit,
                                 const Hit& answer, const StepVars& vars) {
  { S::kRecords } -> std::convertible_to<bool>;
  { S::kObserves } -> std::convertible_to<bool>;
  sink.visit(node, depth, t, t);
  sink.enter_cell(node, t, t);
  sink.cull(node, depth, why, t);
  sink.push(node, depth, t);
  sink.pop(node, depth, t);
  sink.test_prim(prim, hit, t);
  sink.new_closest(prim, t);
  sink.done(answer);
  sink.vars(vars);
};

/// True for a sink that observes nothing (NullSink): the traversal's fast path.
template <TraversalSink S>
inline constexpr bool kObservesNothing = !S::kObserves;

static_assert(TraversalSink<NullSink> && TraversalSink<StatsSink> && TraversalSink<TraceRecorder> &&
                  TraversalSink<ForwardingSink>,
              "the sinks implement the whole contract");
static_assert(kObservesNothing<NullSink> && !kObservesNothing<StatsSink> && !kObservesNothing<TraceRecorder>,
              "only NullSink is the fast path");

}  // namespace accel
