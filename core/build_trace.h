#pragma once
// Observers of the one real build of each structure, as trace.h is for the traversal. Every
// builder is written once as a template over a build sink and calls it at each construction
// step of the lecture (../shared/seed/): NullBuildSink compiles to nothing (the fast path,
// the benchmarks), BuildRecorder keeps every step for the viewer's construction playback, the
// CLI's --build-trace and the tests. Recording runs the build single-threaded, through the
// same code; build_replay.h turns the steps back into the (partly) built structure.
//
// Node ids in the events are the builder's own (any numbering, unique within one build);
// the replay and the viewer only relate events to each other through them.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <limits>
#include <utility>
#include <string>
#include <vector>

#include "geometry.h"
#include "result.h"

namespace accel {

/// "No node": the root's parent, an unknown id.
inline constexpr uint32_t kNoBuildNode = std::numeric_limits<uint32_t>::max();

/// Why a builder made a leaf (or an octree stopped subdividing).
enum class LeafReason : uint8_t {
  FewPrims,   ///< at most the maximum primitives per leaf
  MaxDepth,   ///< the depth limit was reached
  NoGain,     ///< SAH: no split is cheaper than the leaf; octree: subdividing multiplies the references
  Cluster,    ///< bottom-up / insertion: a triangle enters the tree as a leaf
  NoProgress, ///< the split would keep every triangle on both sides (kd), or a child keeps all its parent's (octree)
  BadRefines, ///< kd middle/median: the third split on the path that did not pay by the SAH
  TooThin,    ///< the node is too thin to put a plane inside / too small to halve in float
};

enum class BuildEventKind : uint8_t {
  SceneBox,        ///< box = the scene's bounds (first step of every build)
  GridResolution,  ///< grid: box = grid box; values = {lambda, N, volume, cube root}; a,b,count = cells per axis
  GridInsert,      ///< grid: prim; lo/hi = cell range of its bbox; list = cells that hold it (exact may reject some)
  Node,            ///< a node with its triangles: node, parent, depth, box, centroids, list = its triangles
  Axis,            ///< the split axis of node chosen: axis (0..2, 3 = PCA with direction dir)
  Candidates,      ///< node: the candidate splits along `axis` evaluated (candidates[first, first+count))
  Split,           ///< node split: axis, pos, cost = C(B), values[0] = leaf cost; a,b = left,right counts; count = straddling
                   ///< (kd; sbvh: references on both sides); values[1] = 1 for a BVH spatial split (sbvh), else 0
  Leaf,            ///< node becomes a leaf: reason, list = its triangles
  Subdivide,       ///< octree: node split into 8 (quadtree: 4); list = child ids in octant order (children follow as Node)
  Merge,           ///< bottom-up: node = new cluster of a and b, box, cost = its area
  InsertStep,      ///< insertion: prim sifting at node, box = node's grown box: values = {cost here, cost left, cost right}; a = choice (0 here, 1 left, 2 right)
  Collapse,        ///< wide BVH: node adopts the children of its child a (a disappears)
  Replace,         ///< node (a subtree just built) takes the place of node a, whose subtree is dropped (depth limit)
  Fit,             ///< node's final bounding volume: box, sphere (sphere tree) -- after the topology
  Unrecorded,      ///< node is below the recorded depth: its subtree (count triangles) was built but not recorded
  Done,            ///< the build finished: count = nodes or cells
};

/// One candidate split plane with its SAH cost C(B) (sweep: one per position; binned: one
/// per bin boundary; kd: one per event plane).
struct SplitCandidate {
  float pos = 0.0f;    ///< plane position along the axis (PCA: along the direction)
  float cost = 0.0f;   ///< C(B) of splitting here
  uint32_t left = 0;   ///< triangles left of the plane
  uint32_t right = 0;  ///< triangles right of it
};

/// One recorded step. Plain data; fields that do not apply keep their defaults.
struct BuildEvent {
  BuildEventKind kind = BuildEventKind::SceneBox;
  LeafReason reason = LeafReason::FewPrims;
  int8_t axis = -1;
  uint16_t depth = 0;
  uint32_t node = kNoBuildNode;
  uint32_t parent = kNoBuildNode;
  uint32_t prim = kNoBuildNode;
  uint32_t a = 0, b = 0, count = 0;
  int32_t lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  float pos = 0.0f;
  float cost = 0.0f;
  float values[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  Vec3 dir{0.0f};
  Aabb box;
  Aabb centroids;
  BoundingSphere sphere;
  uint32_t first = 0;       ///< into BuildTrace::lists (list) or ::candidates (Candidates)
  uint32_t list_count = 0;  ///< entries in the list / candidates
};

/// Everything one recorded build produced.
struct BuildTrace {
  std::vector<BuildEvent> events;
  std::vector<uint32_t> lists;               ///< triangle, cell and child lists of the events
  std::vector<SplitCandidate> candidates;    ///< the Candidates events' planes
  int depth_limit = std::numeric_limits<int>::max();  ///< nodes deeper than this were not recorded
  int max_depth_seen = 0;                    ///< deepest node the builder created (recorded or not)
  bool truncated = false;                    ///< the step budget ran out: later steps are missing
  size_t bytes() const {
    return events.size() * sizeof(BuildEvent) + lists.size() * sizeof(uint32_t) +
           candidates.size() * sizeof(SplitCandidate);
  }
  /// The list of event `e` (its triangles, cells or children).
  const uint32_t* list(const BuildEvent& e) const { return lists.data() + e.first; }
  const SplitCandidate* candidates_of(const BuildEvent& e) const { return candidates.data() + e.first; }
  /// "recorded to depth D of E", or "complete", or "stopped at the step budget after K steps".
  std::string coverage() const;
};

const char* build_event_kind_name(BuildEventKind kind);
const char* leaf_reason_name(LeafReason reason);
/// One line describing step `e`, e.g. "split node 3 on y at 0.25, C(B) = 12.5 (leaf 40)".
std::string describe_build_event(const BuildTrace& trace, const BuildEvent& e);
/// Writes the trace as JSON lines: a header line, then one object per step.
void write_build_trace_jsonl(const BuildTrace& trace, std::ostream& out);

/// The fast path: every callback is empty and inlined away. Builders guard argument
/// preparation that costs anything (lists, candidate arrays) with `if constexpr (Sink::kRecords)`.
struct NullBuildSink {
  static constexpr bool kRecords = false;
  /// Whether steps of a node at `depth` are kept (builders skip preparing their arguments).
  bool records(int) { return false; }
  void scene_box(const Aabb&) {}
  void grid_resolution(const Aabb&, const double*, const int*) {}
  void grid_insert(uint32_t, const int*, const int*, const uint32_t*, size_t) {}
  void node(uint32_t, uint32_t, int, const Aabb&, const Aabb&, const uint32_t*, size_t) {}
  void axis(uint32_t, int, const Vec3&) {}
  void candidates(uint32_t, int, const SplitCandidate*, size_t) {}
  void split(uint32_t, int, float, float, float, uint32_t, uint32_t, uint32_t, bool = false) {}
  void leaf(uint32_t, LeafReason, const uint32_t*, size_t) {}
  void subdivide(uint32_t, const uint32_t*, uint32_t = 8) {}
  void merge(uint32_t, uint32_t, uint32_t, const Aabb&, float) {}
  void insert_step(uint32_t, uint32_t, int, const Aabb&, const float*, int) {}
  void collapse(uint32_t, uint32_t) {}
  void replace(uint32_t, uint32_t) {}
  void fit(uint32_t, const Aabb&, const BoundingSphere&) {}
  void done(size_t) {}
};

/// Keeps every step, up to a depth limit and a memory budget. Not thread-safe: builders run
/// single-threaded when recording (Structure::build_recorded()).
class BuildRecorder {
 public:
  static constexpr bool kRecords = true;
  /// Default budget: 512 MB of steps, enough for every level of a 1M-triangle sweep SAH to depth ~10.
  static constexpr size_t kDefaultBudgetBytes = size_t(512) << 20;

  explicit BuildRecorder(int depth_limit = std::numeric_limits<int>::max(),
                         size_t budget_bytes = kDefaultBudgetBytes);

  /// Whether steps of a node at `depth` are kept (depth limit + 1: the first level below
  /// the limit still gets its Unrecorded step; the budget not exhausted). Builders call it
  /// for every node before preparing its arguments: it also notes the depth reached, for
  /// coverage() ("recorded to depth D of E").
  bool records(int depth) {
    trace_.max_depth_seen = std::max(trace_.max_depth_seen, depth);
    return !trace_.truncated && int64_t(depth) <= int64_t(trace_.depth_limit) + 1;
  }

  void scene_box(const Aabb& box);
  /// values = {lambda, N, volume, cube root term}, cells = cells per axis (3).
  void grid_resolution(const Aabb& grid_box, const double* values, const int* cells);
  /// Triangle `prim` whose bbox covers cells [lo, hi] (inclusive) is stored in `cells`.
  void grid_insert(uint32_t prim, const int* lo, const int* hi, const uint32_t* cells, size_t n);
  /// Node `id` (child of `parent`, kNoBuildNode for the root) at `depth` over `prims`.
  void node(uint32_t id, uint32_t parent, int depth, const Aabb& box, const Aabb& centroids, const uint32_t* prims,
            size_t n);
  void axis(uint32_t id, int axis, const Vec3& dir);
  void candidates(uint32_t id, int axis, const SplitCandidate* c, size_t n);
  /// `spatial`: a BVH spatial split (sbvh), whose `straddling` references were split in two
  /// (values[1] = 1); otherwise an object split or a kd plane.
  void split(uint32_t id, int axis, float pos, float cost, float leaf_cost, uint32_t left, uint32_t right,
             uint32_t straddling, bool spatial = false);
  void leaf(uint32_t id, LeafReason reason, const uint32_t* prims, size_t n);
  /// Octree: `id` subdivided into the `count` nodes `children` (octant order): 8, or the
  /// 4 quadrants of a quadtree (a 2D scene; its other octants stay empty and unrecorded).
  void subdivide(uint32_t id, const uint32_t* children, uint32_t count = 8);
  /// Bottom-up: `id` is the new cluster of `a` and `b` (whose depths are unknown until the end).
  void merge(uint32_t id, uint32_t a, uint32_t b, const Aabb& box, float cost);
  /// Insertion: `prim` sifting through node `at` (depth), whose box grows to `grown`;
  /// costs = {make a sibling here, descend left, descend right}, choice 0/1/2.
  void insert_step(uint32_t prim, uint32_t at, int depth, const Aabb& grown, const float* costs, int choice);
  void collapse(uint32_t parent, uint32_t child);
  /// `id` (the root of a subtree recorded as clusters and merges) replaces `old` and its subtree.
  void replace(uint32_t id, uint32_t old);
  void fit(uint32_t id, const Aabb& box, const BoundingSphere& sphere);
  void done(size_t nodes);

  const BuildTrace& trace() const { return trace_; }
  BuildTrace take() { return std::move(trace_); }

 private:
  bool known(uint32_t id) const { return id < depth_of_.size() && depth_of_[id] >= 0; }
  /// A recorded node within the depth limit (its steps are kept), budget left.
  bool within_limit(uint32_t id) const {
    return !trace_.truncated && known(id) && depth_of_[id] <= trace_.depth_limit;
  }
  int depth_of(uint32_t id) const { return known(id) ? depth_of_[id] : -1; }
  BuildEvent* add(BuildEventKind kind, uint32_t node);
  uint32_t add_list(const uint32_t* items, size_t n);

  BuildTrace trace_;
  size_t budget_bytes_;
  std::vector<int> depth_of_;  ///< recorded nodes' depths by id (-1: not recorded)
};

/// Runs `build(sink)` with `recorder` when there is one, else with a NullBuildSink: a
/// builder's entry picks its two instantiations here.
template <class Build>
auto with_build_sink(BuildRecorder* recorder, Build&& build) {
  if (recorder) return build(*recorder);
  NullBuildSink no_steps;
  return build(no_steps);
}

/// One attempt of record_within_budget().
struct RecordAttempt {
  int depth_limit = 0;  ///< std::numeric_limits<int>::max(): every depth
  bool truncated = false;
  size_t steps = 0;
};

/// A recorded build's steps and how they were obtained.
struct RecordedSteps {
  BuildTrace trace;
  std::vector<RecordAttempt> attempts;
};

/// Records with `record` (one build into the recorder it is given), each attempt in a fresh
/// BuildRecorder(depth_limit, budget_bytes), the first at `first_depth_limit`. While the
/// steps come back truncated (the budget ran out), it records again with the depth limit
/// halved from the depth the attempt saw (max_depth_seen / 2, then / 4, ...), down to 0,
/// so the top levels are complete and coverage() says "recorded to depth D of E". Builds
/// whose overflowing steps have no depth (bottom-up merges) keep their first attempt, as
/// does depth 0. Errors (and cancellation) of `record` are returned as they are.
Result<RecordedSteps> record_within_budget(const std::function<Status(BuildRecorder&)>& record,
                                           int first_depth_limit, size_t budget_bytes);

/// Scenes with more triangles than this start recording at a depth limit
/// (recording_first_depth_limit()).
inline constexpr size_t kLargeRecordingTriangles = 200000;

/// The first attempt's depth limit for a scene of `triangles`: every depth, or, above
/// kLargeRecordingTriangles, half the depth a balanced binary tree over them would have
/// (ceil(log2 N) / 2), so a huge scene is not recorded in full only to be recorded again.
int recording_first_depth_limit(size_t triangles);

}  // namespace accel
