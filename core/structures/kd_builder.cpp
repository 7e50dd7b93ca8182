// kd-tree build (lecture, kd-tree, "the procedure (top down)": choose an axis-aligned plane
// to split the cell, distribute the geometry among the two children -- some polygons go to
// both -- and recurse until the stopping criterion is met). This file assembles the tree: the
// middle and median planes, the recursion with its guards and budgets, and what the
// top-down driver (top_down_tasks.h) asks of a builder to run it in parallel tasks. The SAH
// plane search is kd_sah_sweep.cpp, the sorted event lists and their distribution
// kd_events.cpp, the clipping (perfect splits) kd_clipping.cpp -- after Wald & Havran 2006, "On building fast kd-trees for ray tracing,
// and on doing that in O(N log N)".
//
// Index
//   [SECTION] Depth limit and names
//   [SECTION] Builder: state and output
//   [SECTION] Builder: split choice (middle, median; sah: kd_sah_sweep.cpp)
//   [SECTION] Builder: recursion and tasks
//   [SECTION] Builder: the driver's tasks and the whole build
#include "structures/kd_builder.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>

#include "check.h"
#include "parallel.h"
#include "structures/kd_events.h"
#include "structures/kd_sah_sweep.h"
#include "structures/top_down_tasks.h"

namespace accel {

namespace top_down {
/// Stitching the kd-tree's chunks (top_down_tasks.h): an inner node stores only its above
/// child (the below child is the next node), a leaf the offset of its triangles.
template <>
struct ChunkLinks<KdNode> {
  static void link(KdNode& inner, uint32_t, uint32_t right) {
    inner = KdNode::make_inner(inner.axis(), inner.split(), right);
  }
  static void relocate(KdNode& n, uint32_t node_offset, uint32_t prim_offset) {
    if (n.leaf())
      n.payload += prim_offset;
    else
      n.bits += node_offset << 2;
  }
};
}  // namespace top_down

//-----------------------------------------------------------------------------
// [SECTION] Depth limit and names
//-----------------------------------------------------------------------------

int kd_auto_max_depth(size_t n) {
  const double d = 8.0 + 1.3 * std::log2(double(std::max<size_t>(n, 1)));
  return std::min(kKdMaxDepth, int(std::lround(d)));
}

const char* kd_split_name(KdSplit s) {
  switch (s) {
    case KdSplit::Middle: return "middle";
    case KdSplit::Median: return "median";
    case KdSplit::Sah: return "sah";
  }
  return "?";
}

namespace {

using namespace kd;

//-----------------------------------------------------------------------------
// [SECTION] Builder: state and output
//-----------------------------------------------------------------------------

/// What one thread needs to split nodes. The per-triangle arrays are indexed by triangle id
/// and written for a node's triangles before they are read. A task uses its thread's
/// workspace only between points where it never waits for other tasks, so a task stolen
/// while it waits never finds the workspace half used.
struct Workspace : DistributeScratch, SahSweepScratch {
  std::vector<float> lo, hi;   // per triangle id: extent along the median axis
  std::vector<float> centres;  // split_median(): the clipped box centres
};

/// A node to build: its events (consumed), what the guards, the budget and the progress
/// need to know about its path.
struct NodeTask {
  EventLists events;
  size_t n = 0;         // triangles (one start or planar event each per axis)
  Aabb box;             // region
  int depth = 0;
  int bad_refines = 0;  // middle/median: splits on the path that did not pay by SAH
  double share = 0.0;   // share of the progress its leaves complete
  size_t pending = 0;   // events the serial build would hold meanwhile: the above lists on the path
};

/// What a chunk of the tree (top_down_tasks.h) counts besides its nodes.
struct KdChunkStats {
  KdLeafReasons leaf_reasons;
  int depth = 0;  // deepest leaf
};

/// The part of the tree one task builds (top_down_tasks.h): in local pre-order, above
/// children and leaf offsets relative to the chunk's own arrays until the stitching moves it.
using Subtree = top_down::Chunk<KdNode, KdChunkStats>;

/// One node's outcome: the split and the children's events, or the reason it is a leaf.
/// (ChildEvents: the children's events and triangle counts.)
struct Decision : ChildEvents {
  SplitChoice s;
  size_t KdLeafReasons::*reason = nullptr;  // the leaf's counter when s.axis < 0
  int bad_refines = 0;                      // of the children's paths
};

class KdBuilder {
 public:
  /// Reports into [progress_from, 1] of `control` (a retry continues where the last
  /// stopped). `parallel` = build subtrees as TBB tasks (the result is the same either way).
  /// `exact_errors` = a failed build returns the very error the serial order meets first.
  /// `std_sort` = sort the root's lists with std::sort even where the radix sort's tie order
  /// cannot show (the retry when it could after all, see run()).
  KdBuilder(const Scene& scene, const KdBuildOptions& options, BuildControl* control, double progress_from,
            bool parallel, bool exact_errors, bool std_sort = false)
      : scene_(scene),
        o_(options),
        control_(control),
        progress_(control, progress_from, 1.0),
        parallel_(parallel),
        exact_errors_(exact_errors),
        std_sort_(std_sort),
        leaves_done_(&progress_, ProgressCounter::kWhole) {}
  /// `recorder` (nullptr = none): every step is recorded into it (the builder must be serial).
  Result<KdTreeData> run(BuildRecorder* recorder = nullptr);
  /// The last fraction reported.
  double progress_reached() const { return progress_.last(); }

  // The top-down driver's interface (top_down_tasks.h).
  using Node = KdNode;
  using Task = NodeTask;
  using Stats = KdChunkStats;
  size_t refs(const NodeTask& t) const { return t.n; }
  bool all_serial() const { return recorder_ || !parallel_; }
  bool stopped();
  void build_serial(NodeTask& t, Subtree& out);
  top_down::RootSplit split_root(NodeTask& t, Subtree& out, NodeTask& left, NodeTask& right);

 private:
  Workspace& workspace();
  bool enter_node();
  template <class Sink>
  void decide(Workspace& ws, const NodeTask& t, Decision& d) const;
  bool accept_split(Workspace& ws, NodeTask& t, const Decision& d);
  NodeTask child_task(NodeTask& t, Decision& d, bool above) const;
  template <class Sink>
  void build_serial(Workspace& ws, Subtree& out, NodeTask& t);
  void record_node(Workspace& ws, const NodeTask& t, uint32_t id);
  void record_split(const Workspace& ws, const NodeTask& t, const Decision& d, uint32_t id) const;
  void make_leaf(Workspace& ws, Subtree& out, NodeTask& t, size_t KdLeafReasons::*reason);
  void gather(const Subtree& root);
  double split_cost(const Aabb& box, const SplitChoice& s, size_t nl, size_t nr) const;
  int choose_axis(const Aabb& box, int depth) const;
  SplitChoice split_middle(const Aabb& box, int depth) const;
  SplitChoice split_median(Workspace& ws, const EventLists& events, const Aabb& box, int depth, size_t n) const;
  void over_budget(const char* what, size_t limit);
  void fail(Error error);
  bool failed() const { return failed_.load(std::memory_order_relaxed); }

  const Scene& scene_;
  KdBuildOptions o_;
  BuildControl* control_;
  ProgressSpan progress_;  // touched by the reporting thread only (through leaves_done_)
  const bool parallel_, exact_errors_, std_sort_;
  KdTreeData out_;
  size_t node_cap_ = 0;  // nodes allowed: node_limit, and what KdNode's 30 bits hold
  par::enumerable_thread_specific<Workspace> workspaces_;
  // Totals over all tasks. A task reserves its node (and a leaf its references) before
  // making it, so a total above the budget is seen by some task whatever the interleaving:
  // the build fails exactly when the serial one does.
  std::atomic<size_t> nodes_{0}, references_{0};
  ProgressCounter leaves_done_;  // the shares of the build in finished leaves
  std::atomic<bool> failed_{false};
  std::mutex error_mutex_;
  Status status_;  // the first error recorded (budget or cancel); the build stops at it
  // Recording (build_serial<BuildRecorder>() only): the recorder and the parent of the next
  // node the serial recursion enters.
  BuildRecorder* recorder_ = nullptr;
  uint32_t parent_ = kNoBuildNode;
};

/// This thread's workspace, its per-triangle arrays sized on first use.
Workspace& KdBuilder::workspace() {
  Workspace& ws = workspaces_.local();
  if (ws.side.size() != scene_.triangle_count()) {
    ws.side.assign(scene_.triangle_count(), kBoth);
    if (o_.split == KdSplit::Median) {
      ws.lo.assign(scene_.triangle_count(), 0.0f);
      ws.hi.assign(scene_.triangle_count(), 0.0f);
    }
  }
  return ws;
}

/// Records the first error and makes every task stop at its next node.
void KdBuilder::fail(Error error) {
  std::lock_guard<std::mutex> lock(error_mutex_);
  if (failed_.load(std::memory_order_relaxed)) return;
  status_ = std::move(error);
  failed_.store(true, std::memory_order_relaxed);
}

/// Records the budget error: names the parameters that control the tree size.
void KdBuilder::over_budget(const char* what, size_t limit) {
  char depth[48];
  if (o_.max_depth > 0)
    std::snprintf(depth, sizeof depth, "%d", o_.max_depth);
  else
    std::snprintf(depth, sizeof depth, "0 (auto: %d)", out_.max_depth_limit);
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "kdtree parameter 'max_depth' = %s (leaf_size = %d, split = %s): the tree would need more than "
                "%zu %s (limit, within the memory limit of %s); lower max_depth, raise leaf_size, or use split=sah",
                depth, o_.leaf_size, kd_split_name(o_.split), limit, what, format_bytes(double(o_.memory_limit)).c_str());
  fail(make_error(buf));
}

//-----------------------------------------------------------------------------
// [SECTION] Builder: split choice (middle, median, sah)
//-----------------------------------------------------------------------------

int KdBuilder::choose_axis(const Aabb& box, int depth) const {
  const Vec3 e = box.max - box.min;
  if (o_.axis == KdAxis::Longest) return box.longest_axis();
  for (int i = 0; i < 3; ++i) {  // round robin, skipping flat axes (no plane fits inside)
    const int axis = (depth + i) % 3;
    if (e[axis] > 0.0f) return axis;
  }
  return depth % 3;
}

SplitChoice KdBuilder::split_middle(const Aabb& box, int depth) const {
  const int axis = choose_axis(box, depth);
  const float pos = 0.5f * box.min[axis] + 0.5f * box.max[axis];
  if (!(pos > box.min[axis] && pos < box.max[axis])) return {};  // region too thin to halve
  return {axis, pos, true};
}

// Median of the centres of the triangles' clipped extents (inside the region, unlike the
// triangles' own centroids, so the plane lies inside too). Falls back to the middle when
// the median is on the region's boundary (e.g. most triangles touch it).
SplitChoice KdBuilder::split_median(Workspace& ws, const EventLists& events, const Aabb& box, int depth,
                                    size_t n) const {
  const int axis = choose_axis(box, depth);
  std::vector<float>& centres = ws.centres;
  centres.clear();
  centres.reserve(n);
  for (const Event& e : events.axis[axis]) {
    if (e.type() != kEnd) ws.lo[e.prim()] = e.pos;
    if (e.type() != kStart) ws.hi[e.prim()] = e.pos;
  }
  for (const Event& e : events.axis[axis])
    if (e.type() != kEnd) centres.push_back(0.5f * ws.lo[e.prim()] + 0.5f * ws.hi[e.prim()]);
  auto mid = centres.begin() + ptrdiff_t(centres.size() / 2);
  std::nth_element(centres.begin(), mid, centres.end());
  const float pos = *mid;
  if (pos > box.min[axis] && pos < box.max[axis]) return {axis, pos, true};
  return split_middle(box, depth);
}

//-----------------------------------------------------------------------------
// [SECTION] Builder: recursion and tasks
//-----------------------------------------------------------------------------

void KdBuilder::make_leaf(Workspace& ws, Subtree& out, NodeTask& t, size_t KdLeafReasons::*reason) {
  ++(out.stats.leaf_reasons.*reason);
  if (references_.fetch_add(t.n, std::memory_order_relaxed) + t.n > o_.reference_limit) {
    over_budget("triangle references", o_.reference_limit);
    return;
  }
  const size_t offset = out.prims.size();
  for (const Event& e : t.events.axis[0])
    if (e.type() != kEnd) out.prims.push_back(e.prim());
  std::sort(out.prims.begin() + ptrdiff_t(offset), out.prims.end());  // ascending: stable ties, tidy views
  out.nodes.push_back(KdNode::make_leaf(uint32_t(offset), uint32_t(t.n)));
  out.stats.depth = std::max(out.stats.depth, t.depth);
  ws.pool.give(t.events);
  leaves_done_.add_share(t.share);  // the build stops at enter_node()'s cancel check
}

/// SAH cost of splitting `box` at `s` with nl / nr triangles on the sides (the formula of
/// sah_split(), for judging middle and median splits).
double KdBuilder::split_cost(const Aabb& box, const SplitChoice& s, size_t nl, size_t nr) const {
  const double area = box.area();
  if (!(area > 0.0)) return kInf;
  const double pl = kd_child_box(box, s.axis, s.pos, false).area() / area;
  const double pr = kd_child_box(box, s.axis, s.pos, true).area() / area;
  const double c = o_.ct + o_.ci * (pl * double(nl) + pr * double(nr));
  return (nl == 0 || nr == 0) ? c * (1.0 - o_.empty_bonus) : c;
}

/// The checks at every node: an earlier failure or a cancel (stopped(), the driver's check
/// before a task), then the node budget (reserving the node: the serial build's test
/// "nodes made >= limit" before making one).
bool KdBuilder::enter_node() {
  if (stopped()) return false;
  if (nodes_.fetch_add(1, std::memory_order_relaxed) >= node_cap_) {
    over_budget("nodes", node_cap_);
    return false;
  }
  return true;
}

// Guards against explosion (a kd-tree duplicates straddling triangles, so a split that
// separates nothing only multiplies references):
//  * a split that sends every triangle to both sides makes a leaf instead (identical or
//    all-straddling triangles);
//  * middle and median have no cost function to stop them near a vertex or edge shared by
//    more than leaf_size triangles, where no plane ever separates them: a split whose SAH cost
//    is not below the leaf's (ci * N) is a "bad refine", and the third one on a path makes a
//    leaf (pbrt-v4 KdTreeAggregate's badRefines rule). SAH stops at its first such split.
template <class Sink>
void KdBuilder::decide(Workspace& ws, const NodeTask& t, Decision& d) const {
  const size_t n = t.n;
  d.bad_refines = t.bad_refines;
  if (n <= size_t(o_.leaf_size)) {
    d.reason = &KdLeafReasons::few_prims;
    return;
  }
  if (t.depth >= out_.max_depth_limit) {
    d.reason = &KdLeafReasons::max_depth;
    return;
  }
  switch (o_.split) {
    case KdSplit::Middle: d.s = split_middle(t.box, t.depth); break;
    case KdSplit::Median: d.s = split_median(ws, t.events, t.box, t.depth, n); break;
    case KdSplit::Sah: d.s = sah_split<Sink>(o_, ws, t.events, t.box, n); break;
  }
  if (d.s.axis < 0) {
    d.reason = o_.split == KdSplit::Sah ? &KdLeafReasons::no_gain : &KdLeafReasons::thin;
    return;
  }
  classify(ws, t.events, d.s);
  distribute<Sink>(scene_, o_.clip, ws, t.events, d.s, t.box, d);
  if (d.nl == n && d.nr == n) {
    d.s.axis = -1;
    d.reason = &KdLeafReasons::no_progress;
  } else if (o_.split != KdSplit::Sah && split_cost(t.box, d.s, d.nl, d.nr) >= o_.ci * double(n) &&
             ++d.bad_refines >= 3) {
    d.s.axis = -1;
    d.reason = &KdLeafReasons::bad_refines;
  }
  if (d.s.axis < 0) {
    ws.pool.give(d.left);
    ws.pool.give(d.right);
  }
}

/// Frees the node's events and checks the event budget the serial build keeps: the lists it
/// would hold now are the above lists pending on the path plus the two children's.
bool KdBuilder::accept_split(Workspace& ws, NodeTask& t, const Decision& d) {
  ws.pool.give(t.events);
  if (t.pending + d.left.size() + d.right.size() > o_.event_limit) {
    over_budget("build events", o_.event_limit);
    return false;
  }
  return true;
}

/// The below (`above` false) or above child of `t` split by `d`: takes that child's events.
/// An inner node splits its progress share between its children in proportion to the
/// triangles each receives.
NodeTask KdBuilder::child_task(NodeTask& t, Decision& d, bool above) const {
  const double share_left = t.share * double(d.nl) / double(std::max<size_t>(1, d.nl + d.nr));
  NodeTask c;
  c.n = above ? d.nr : d.nl;
  c.box = kd_child_box(t.box, d.s.axis, d.s.pos, above);
  c.depth = t.depth + 1;
  c.bad_refines = d.bad_refines;
  c.share = above ? t.share - share_left : share_left;
  c.pending = above ? t.pending : t.pending + d.right.size();  // the below child runs first (take it first)
  c.events = std::move(above ? d.right : d.left);
  return c;
}

/// The build_trace.h reason of a leaf counted in `reason` (one per KdLeafReasons counter).
LeafReason leaf_reason(size_t KdLeafReasons::*reason) {
  if (reason == &KdLeafReasons::few_prims) return LeafReason::FewPrims;
  if (reason == &KdLeafReasons::max_depth) return LeafReason::MaxDepth;
  if (reason == &KdLeafReasons::no_progress) return LeafReason::NoProgress;
  if (reason == &KdLeafReasons::bad_refines) return LeafReason::BadRefines;
  if (reason == &KdLeafReasons::thin) return LeafReason::TooThin;
  return LeafReason::NoGain;
}

/// Recording: the Node step of `t` (id = its final pre-order index), with its triangles
/// ascending (as a leaf lists them); resets the workspace's per-node recording state.
void KdBuilder::record_node(Workspace& ws, const NodeTask& t, uint32_t id) {
  BuildRecorder& rec = *recorder_;
  ws.record = rec.records(t.depth);
  for (bool& swept : ws.swept) swept = false;
  std::vector<uint32_t> prims;
  if (ws.record) {
    prims.reserve(t.n);
    for (const Event& e : t.events.axis[0])
      if (e.type() != kEnd) prims.push_back(e.prim());
    std::sort(prims.begin(), prims.end());
  }
  rec.node(id, parent_, t.depth, t.box, Aabb{}, prims.data(), ws.record ? prims.size() : t.n);
}

/// Recording: what chose the split of node `id` (sah: the planes of every axis swept; middle,
/// median: the axis rule's choice), then the Split step: its cost C(B) and the leaf's ci * N,
/// the children's triangle counts after clipping and how many are in both.
void KdBuilder::record_split(const Workspace& ws, const NodeTask& t, const Decision& d, uint32_t id) const {
  BuildRecorder& rec = *recorder_;
  if (!ws.record) return;
  const double leaf_cost = o_.ci * double(t.n);
  double cost = std::nan("");
  if (o_.split == KdSplit::Sah) {
    for (int axis = 0; axis < 3; ++axis)
      if (ws.swept[axis]) rec.candidates(id, axis, ws.candidates[axis].data(), ws.candidates[axis].size());
    if (d.s.axis >= 0) cost = ws.best_cost;
  } else if (d.s.axis >= 0 || (d.reason != &KdLeafReasons::few_prims && d.reason != &KdLeafReasons::max_depth)) {
    const int axis = choose_axis(t.box, t.depth);
    Vec3 dir(0.0f);
    dir[axis] = 1.0f;
    rec.axis(id, axis, dir);
    if (d.s.axis >= 0) cost = split_cost(t.box, d.s, d.nl, d.nr);
  }
  if (d.s.axis >= 0)
    rec.split(id, d.s.axis, d.s.pos, float(cost), float(leaf_cost), uint32_t(d.nl), uint32_t(d.nr),
              uint32_t(ws.both));
}

// Depth-first, writing nodes in pre-order: the below child follows its parent, the above
// child's index is patched in once the below subtree is done (pbrt's layout). The node's
// events are freed before the recursion, so only the pending above lists of the current path
// stay alive, which bounds the build's memory. Recording (Sink = BuildRecorder, a serial
// build: `out` is the whole tree), a node's id is its index in `out`, final.
template <class Sink>
void KdBuilder::build_serial(Workspace& ws, Subtree& out, NodeTask& t) {
  if (!enter_node()) return;
  [[maybe_unused]] const uint32_t id = uint32_t(out.nodes.size());
  if constexpr (Sink::kRecords) record_node(ws, t, id);
  Decision d;
  decide<Sink>(ws, t, d);
  if constexpr (Sink::kRecords) {
    if (d.s.axis >= 0 || d.reason != &KdLeafReasons::few_prims) record_split(ws, t, d, id);
  }
  if (d.s.axis < 0) {
    [[maybe_unused]] const size_t offset = out.prims.size();
    make_leaf(ws, out, t, d.reason);
    if constexpr (Sink::kRecords) {
      if (!failed()) recorder_->leaf(id, leaf_reason(d.reason), out.prims.data() + offset, out.prims.size() - offset);
    }
    return;
  }
  if (!accept_split(ws, t, d)) return;
  NodeTask left = child_task(t, d, false);
  NodeTask right = child_task(t, d, true);
  const size_t self = out.nodes.size();
  out.nodes.push_back(KdNode{});
  if constexpr (Sink::kRecords) parent_ = id;
  build_serial<Sink>(ws, out, left);
  if (failed()) return;
  out.nodes[self] = KdNode::make_inner(d.s.axis, d.s.pos, NodeId(out.nodes.size()));
  if constexpr (Sink::kRecords) parent_ = id;
  build_serial<Sink>(ws, out, right);
}

//-----------------------------------------------------------------------------
// [SECTION] Builder: the driver's tasks and the whole build
//-----------------------------------------------------------------------------

// Before every task: an earlier failure (another task's budget) or a cancel.
bool KdBuilder::stopped() {
  if (failed()) return true;
  if (!build_cancelled(control_)) return false;
  fail(cancelled_error());
  return true;
}

void KdBuilder::build_serial(NodeTask& t, Subtree& out) {
  if (recorder_)
    build_serial<BuildRecorder>(workspace(), out, t);
  else
    build_serial<NullBuildSink>(workspace(), out, t);
}

// A task's root: the node decided as the serial recursion decides it, its children handed
// back as tasks. Which nodes are tasks depends on the scene alone, and the driver numbers
// the chunks in pre-order, so the tree does not depend on the thread count (nor on whether
// there is a task at all).
top_down::RootSplit KdBuilder::split_root(NodeTask& t, Subtree& out, NodeTask& left, NodeTask& right) {
  if (!enter_node()) return top_down::RootSplit::Stop;
  Workspace& ws = workspace();
  Decision d;
  decide<NullBuildSink>(ws, t, d);
  if (d.s.axis < 0) {
    make_leaf(ws, out, t, d.reason);
    return failed() ? top_down::RootSplit::Stop : top_down::RootSplit::Leaf;
  }
  if (!accept_split(ws, t, d)) return top_down::RootSplit::Stop;
  left = child_task(t, d, false);
  right = child_task(t, d, true);
  out.node = KdNode::make_inner(d.s.axis, d.s.pos, 0);  // the stitching points it at the above child
  // `ws` is not touched from here on: tasks this thread steals while it waits use it.
  return top_down::RootSplit::Split;
}

// The chunks' leaf reasons and depth, summed over the tree.
void KdBuilder::gather(const Subtree& root) {
  top_down::for_each_chunk(root, [&](const Subtree& part) {
    for (size_t KdLeafReasons::*r : {&KdLeafReasons::few_prims, &KdLeafReasons::max_depth, &KdLeafReasons::no_gain,
                                     &KdLeafReasons::no_progress, &KdLeafReasons::bad_refines, &KdLeafReasons::thin})
      out_.leaf_reasons.*r += part.stats.leaf_reasons.*r;
    out_.depth = std::max(out_.depth, part.stats.depth);
  });
}

// Recording: scene_box, the steps of build_serial<BuildRecorder>(), done.
Result<KdTreeData> KdBuilder::run(BuildRecorder* recorder) {
  ACCEL_CHECK(!recorder || !parallel_);
  recorder_ = recorder;
  parent_ = kNoBuildNode;
  const std::vector<uint32_t>& prims = scene_.valid_prims();
  out_.max_depth_limit = o_.max_depth > 0 ? std::min(o_.max_depth, kKdMaxDepth) : kd_auto_max_depth(prims.size());
  if (prims.empty()) {
    out_.nodes.push_back(KdNode::make_leaf(0, 0));
    ++out_.leaf_reasons.few_prims;
    if (recorder) {
      recorder->scene_box(out_.root_box);
      recorder->node(0, kNoBuildNode, 0, out_.root_box, Aabb{}, nullptr, 0);
      recorder->leaf(0, LeafReason::FewPrims, nullptr, 0);
      recorder->done(1);
    }
    return std::move(out_);
  }
  if (scene_.triangle_count() > kKdMaxIndex) return make_error("kdtree: scene has too many triangles (limit 2^30)");
  node_cap_ = std::min<size_t>(o_.node_limit, kKdMaxIndex);
  // Two events per triangle and axis at the root, checked before they are allocated.
  if (6 * prims.size() > o_.event_limit) {
    const double bytes = double(6 * prims.size()) * sizeof(Event);
    if (o_.event_limit < o_.memory_limit / 2 / sizeof(Event))  // the fixed limit, not the budget
      return make_error("kdtree: " + std::to_string(prims.size()) + " triangles need " +
                        std::to_string(6 * prims.size()) + " build events (limit " + std::to_string(o_.event_limit) +
                        "); use a bvh for scenes this large");
    return make_error("kdtree: " + std::to_string(prims.size()) + " triangles make build events of " +
                      format_bytes(bytes) + ", more than the half of the memory limit (" +
                      format_bytes(double(o_.memory_limit)) + ") they may use; raise the memory limit");
  }
  NodeTask root;
  for (std::vector<Event>& list : root.events.axis) list.reserve(2 * prims.size());
  for (uint32_t prim : prims) {
    out_.root_box.extend(scene_.triangle_bounds(prim));
    add_events(root.events, prim, scene_.triangle_bounds(prim));  // inside the root box: nothing to clip
  }
  if (recorder) recorder->scene_box(out_.root_box);
  if (build_cancelled(control_)) return cancelled_error();
  // The root's lists: millions of events, sorted while the other thread waits (three lists
  // on two threads). std::sort is what every list was ever sorted with, and the order it
  // leaves tied events in can show in the tree only through a -0 (kd_events.h); with none,
  // the radix sort gives the same tree ten times faster. A -0 that clipping makes further
  // down is caught there, and the build made again with std::sort (below). A recorded build
  // takes std::sort: its steps are recorded as it goes, so it is never made again. So does a
  // root too large for the radix sort's second buffers (a list's size each, two lists at a
  // time) to fit the event budget beside the lists.
  const bool radix = !std_sort_ && !recorder && 10 * prims.size() <= o_.event_limit &&
                     !has_negative_zero(root.events.axis[0]) && !has_negative_zero(root.events.axis[1]) &&
                     !has_negative_zero(root.events.axis[2]);
  auto sort_axis = [&root, radix](int k) {
    std::vector<Event>& list = root.events.axis[k];
    if (radix)
      radix_sort_events(list);
    else
      std::sort(list.begin(), list.end(), EventLess{});
  };
  par::parallel_invoke([&] { sort_axis(0); }, [&] { sort_axis(1); }, [&] { sort_axis(2); });

  root.n = prims.size();
  root.box = out_.root_box;
  root.share = 1.0;
  std::unique_ptr<Subtree> tree = top_down::TopDownTasks<KdBuilder>(*this).build(root);
  if (failed()) {
    // Parallel tasks stop at the first budget any of them finds exceeded, which need not be
    // the one the serial order meets first; when the message is returned, that one is found
    // by building serially (only failed builds pay for it).
    const bool had_tasks = parallel_ && prims.size() >= top_down::kTaskMinRefs;
    if (had_tasks && exact_errors_ && !build_cancelled(control_))
      return KdBuilder(scene_, o_, control_, progress_.last(), false, true).run();
    return status_.error();
  }
  bool clipped_negative_zero = false;
  for (const Workspace& ws : workspaces_) clipped_negative_zero |= ws.clipped_negative_zero;
  if (radix && clipped_negative_zero) {
    tree.reset();
    return KdBuilder(scene_, o_, control_, progress_.last(), parallel_, exact_errors_, true).run();
  }
  gather(*tree);
  top_down::stitch(*tree, out_.nodes, &out_.prim_ids);
  ACCEL_CHECK(out_.depth <= kKdMaxDepth);  // the traversal's stack holds kKdMaxDepth entries
  if (recorder) recorder->done(out_.nodes.size());
  return std::move(out_);
}

}  // namespace

Result<KdTreeData> build_kd_tree(const Scene& scene, const KdBuildOptions& given, BuildControl* control,
                                 BuildRecorder* recorder) {
  if (build_cancelled(control)) return cancelled_error();
  KdBuildOptions options = given;
  const size_t quarter = options.memory_limit / 4;
  options.node_limit = std::min(options.node_limit, std::max<size_t>(1, quarter / sizeof(KdNode)));
  options.reference_limit = std::min(options.reference_limit, std::max<size_t>(1, quarter / sizeof(uint32_t)));
  options.event_limit = std::min(options.event_limit, std::max<size_t>(1, 2 * quarter / sizeof(Event)));
  // Recording builds serially (the steps in depth-first order, the same tree).
  const bool parallel = recorder == nullptr;
  if (options.max_depth > 0) return KdBuilder(scene, options, control, 0.0, parallel, true).run(recorder);
  // Automatic depth: keep the tree within a size proportional to the scene (at most 64
  // references per triangle, or 4M). Scenes that every plane cuts -- thousands of overlapping
  // coplanar triangles -- would otherwise grow to the absolute budget before failing; there
  // the depth limit is lowered until the tree fits, as the lecture's stop criterion intends.
  // Only the last attempt's error is returned, so only it needs the serial order's message.
  KdBuildOptions o = options;
  const size_t n = scene.valid_prims().size();
  o.reference_limit = std::min(options.reference_limit, std::max<size_t>(size_t(1) << 22, 64 * n));
  o.node_limit = std::min(options.node_limit, 2 * o.reference_limit);
  double reached = 0.0;
  for (int depth = kd_auto_max_depth(n);; depth = std::max(1, depth - 4)) {
    o.max_depth = depth;
    KdBuilder builder(scene, o, control, reached, parallel, depth == 1);
    // A recording keeps the steps of the attempt returned only (a copy of the recorder as given).
    std::unique_ptr<BuildRecorder> attempt = recorder ? std::make_unique<BuildRecorder>(*recorder) : nullptr;
    Result<KdTreeData> tree = builder.run(attempt.get());
    if (tree || depth == 1 || build_cancelled(control)) {
      if (recorder) *recorder = std::move(*attempt);
      return tree;
    }
    reached = builder.progress_reached();
  }
}

}  // namespace accel
