// kd-tree build: clipping triangles to boxes (perfect splits), the sorted event lists, the
// middle, median and SAH split choices, distribution, and the recursion, parallel over
// subtrees (see kd_builder.h).
//
// Index
//   [SECTION] Depth limit and names
//   [SECTION] Clipping triangles to boxes
//   [SECTION] Events
//   [SECTION] Builder: state and output
//   [SECTION] Builder: split choice (middle, median, sah)
//   [SECTION] Builder: distribution
//   [SECTION] Builder: recursion and tasks
//   [SECTION] Builder: stitching and the whole build
#include "structures/kd_builder.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "check.h"
#include "parallel.h"

namespace accel {

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

//-----------------------------------------------------------------------------
// [SECTION] Clipping triangles to boxes
//-----------------------------------------------------------------------------

/// Largest float <= x.
float round_down(double x) {
  float f = float(x);
  if (double(f) > x) f = std::nextafter(f, -kInf);
  return f;
}
/// Smallest float >= x.
float round_up(double x) {
  float f = float(x);
  if (double(f) < x) f = std::nextafter(f, kInf);
  return f;
}

/// Bounds of the part of triangle `prim` inside the closed box `box`, for perfect splits
/// (Havran 2000; Wald & Havran 2006 sec. 4.3): Sutherland-Hodgman clipping against the six
/// slabs, in double. Conservative both ways rounding could hurt:
///  * the box is enlarged by delta = 2^-30 of the largest coordinate involved (far above the
///    double rounding of the clip, far below a float ulp), so a triangle touching the box is
///    never clipped away;
///  * the polygon's bounds are widened by delta and rounded outward to float, then cut to
///    the triangle's own box and to `box` (both exact bounds of the true clipped part).
/// Returns false only when the triangle certainly misses the box.
bool clip_triangle_bounds(const Scene& scene, uint32_t prim, const Aabb& box, Aabb* out) {
  const Aabb& tri = scene.triangle_bounds(prim);
  Aabb cut;
  cut.min = glm::max(tri.min, box.min);
  cut.max = glm::min(tri.max, box.max);
  if (cut.empty()) return false;
  if (box.contains(tri)) {  // nothing to clip
    *out = tri;
    return true;
  }
  double m = 0.0;
  for (int k = 0; k < 3; ++k) {
    m = std::max({m, std::abs(double(tri.min[k])), std::abs(double(tri.max[k])), std::abs(double(box.min[k])),
                  std::abs(double(box.max[k]))});
  }
  const double delta = std::max(m, 1e-30) * 0x1p-30;  // exact, as ldexp(., -30)

  // A triangle clipped by 6 planes has at most 3 + 6 vertices. A plane that every vertex lies
  // inside would copy the polygon unchanged, so it is skipped (most planes of a straddler's
  // clip: only the split plane and the region's faces it crosses cut it).
  DVec3 buf[2][10];
  DVec3* poly = buf[0];
  DVec3* next = buf[1];
  int n = 3;
  for (int k = 0; k < 3; ++k) poly[k] = DVec3(scene.vertex(prim, k));
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const double plane = side == 0 ? double(box.min[axis]) - delta : double(box.max[axis]) + delta;
      bool in[10];
      int inside = 0;
      for (int i = 0; i < n; ++i) {
        in[i] = side == 0 ? poly[i][axis] >= plane : poly[i][axis] <= plane;
        inside += in[i];
      }
      if (inside == n) continue;
      if (inside == 0) return false;  // the enlarged box misses the triangle
      int m_out = 0;
      for (int i = 0; i < n; ++i) {
        const int j = i + 1 == n ? 0 : i + 1;
        const DVec3& a = poly[i];
        const DVec3& b = poly[j];
        if (in[i]) next[m_out++] = a;
        if (in[i] != in[j]) {
          const double s = (plane - a[axis]) / (b[axis] - a[axis]);
          DVec3 q = a + s * (b - a);
          q[axis] = plane;
          next[m_out++] = q;
        }
      }
      n = m_out;
      std::swap(poly, next);
    }
  }
  DVec3 lo = poly[0], hi = poly[0];
  for (int i = 1; i < n; ++i) {
    lo = glm::min(lo, poly[i]);
    hi = glm::max(hi, poly[i]);
  }
  Aabb b;
  for (int k = 0; k < 3; ++k) {
    b.min[k] = std::max(round_down(lo[k] - delta), cut.min[k]);
    b.max[k] = std::min(round_up(hi[k] + delta), cut.max[k]);
  }
  if (b.empty()) return false;  // the enlarged clip lies outside the exact bounds: a miss
  *out = b;
  return true;
}

//-----------------------------------------------------------------------------
// [SECTION] Events
//-----------------------------------------------------------------------------

/// Event types in sweep order: at one position, ends come before planars before starts
/// (Wald & Havran 2006 sec. 4.2), so a triangle ending at a plane counts left only and one
/// starting there right only.
enum EventType : uint32_t { kEnd = 0, kPlanar = 1, kStart = 2 };

/// One boundary of a triangle's (clipped) extent along one axis. 8 bytes: the triangle id
/// and the type share one word (ids < 2^30).
struct Event {
  float pos;
  uint32_t prim_type;  // prim << 2 | type

  /// Leaves both fields unset: resizing a list that a filter then overwrites costs nothing
  /// (a defaulted constructor would be zero-filled by vector::resize first).
  Event() {}
  Event(float p, uint32_t pt) : pos(p), prim_type(pt) {}
  uint32_t prim() const { return prim_type >> 2; }
  uint32_t type() const { return prim_type & 3u; }
};
static_assert(sizeof(Event) == 8);

bool event_less(const Event& a, const Event& b) {
  return a.pos < b.pos || (a.pos == b.pos && a.type() < b.type());
}

/// event_less as a type, so std::sort inlines it. The order std::sort leaves equivalent
/// events in (ties of position and type) is part of the result -- the first event of a
/// position gives the split its bits, -0 or +0 -- so every list is sorted by the same
/// std::sort on the same input order as ever.
struct EventLess {
  bool operator()(const Event& a, const Event& b) const { return event_less(a, b); }
};

/// The events of one node: per axis, sorted by event_less.
struct EventLists {
  std::vector<Event> axis[3];
  size_t size() const { return axis[0].size() + axis[1].size() + axis[2].size(); }
};

/// Appends the events of `prim` with extent `b` (one planar event on an axis where the extent
/// is flat, else an end and a start).
void add_events(EventLists& lists, uint32_t prim, const Aabb& b) {
  for (int k = 0; k < 3; ++k) {
    if (b.min[k] == b.max[k]) {
      lists.axis[k].emplace_back(b.min[k], prim << 2 | kPlanar);
    } else {
      lists.axis[k].emplace_back(b.min[k], prim << 2 | kStart);
      lists.axis[k].emplace_back(b.max[k], prim << 2 | kEnd);
    }
  }
}

/// Spare event lists of one thread, handed to the children of the next nodes: most nodes are
/// small, and a malloc and free per list and node cost more than sweeping them. Lists longer
/// than kMaxPooled events are freed instead, which bounds what a pool holds.
class EventPool {
 public:
  /// An empty list, with the capacity of a spare one when there is one.
  std::vector<Event> take() {
    if (spare_.empty()) return {};
    std::vector<Event> list = std::move(spare_.back());
    spare_.pop_back();
    return list;
  }
  /// Takes `list` back (leaving it empty).
  void give(std::vector<Event>& list) {
    if (list.capacity() > 0 && list.capacity() <= kMaxPooled && spare_.size() < kMaxSpare) {
      list.clear();
      spare_.push_back(std::move(list));
    }
    list = std::vector<Event>();
  }
  void give(EventLists& lists) {
    for (std::vector<Event>& list : lists.axis) give(list);
  }

 private:
  static constexpr size_t kMaxPooled = size_t(1) << 13;  // 64 KiB
  static constexpr size_t kMaxSpare = 256;  // well above the ~3 * (depth + 3) lists alive at once
  std::vector<std::vector<Event>> spare_;
};

/// Merges the sorted `fresh` events into `list`, whose first `kept` entries are sorted and
/// whose size is at least kept + fresh.size(); leaves exactly the merged kept + fresh. The
/// same sequence as std::merge(kept, fresh) -- on ties the kept event first -- written from
/// the back, so it needs no second buffer and stops when `fresh` is used up.
void merge_fresh(std::vector<Event>& list, size_t kept, const std::vector<Event>& fresh) {
  size_t i = kept, j = fresh.size(), out = kept + fresh.size();
  ACCEL_DCHECK(list.size() >= out);
  Event* dst = list.data();
  while (j > 0 && i > 0) {  // without a branch on the comparison (random)
    const Event f = fresh[j - 1], k = dst[i - 1];
    const bool take_kept = (f.pos < k.pos) | ((f.pos == k.pos) & (f.type() < k.type()));  // event_less(f, k)
    dst[--out] = take_kept ? k : f;
    i -= take_kept;
    j -= !take_kept;
  }
  while (j > 0) dst[--out] = fresh[--j];
  list.resize(kept + fresh.size());
}

//-----------------------------------------------------------------------------
// [SECTION] Builder: state and output
//-----------------------------------------------------------------------------

/// Where to split a node; axis < 0 = make a leaf.
struct SplitChoice {
  int axis = -1;
  float pos = 0.0f;
  bool planar_left = true;  ///< triangles lying in the plane go left (else right)
};

enum Side : uint8_t { kBoth = 0, kLeft = 1, kRight = 2 };

/// Nodes of at least this many triangles have their two children built as tasks of their
/// own; smaller ones build their whole subtree serially (a few hundred microseconds of work,
/// far above the cost of a task).
constexpr size_t kTaskMinPrims = 2048;

/// Child lists longer than this many events are trimmed to their size (see distribute()).
constexpr size_t kShrinkMin = size_t(1) << 16;

/// The sweep's counts at one distinct event position (Wald & Havran's N_L, N_R, N_P): the
/// triangles starting or lying before it, ending or lying after it, lying in it.
struct PlaneCounts {
  float pos;  // the first event's position (its bits, -0 or +0, become the split's)
  uint32_t left, right, planar;
};

/// The counts at every distinct position of the sorted `events` of a node of `n` triangles,
/// into `planes` (grown as needed); returns how many. Without a branch per event: positions
/// shared by a few events (mesh vertices) make "same position as the next?" random, so every
/// event writes the running counts and only the last one of a position advances the output.
size_t count_planes(const std::vector<Event>& events, size_t n, std::vector<PlaneCounts>& planes) {
  const size_t count = events.size();
  if (planes.size() < count) planes.resize(count);
  if (count == 0) return 0;
  const Event* ev = events.data();
  PlaneCounts* out = planes.data();
  uint32_t before = 0, starts_planars = 0, ends_planars = 0, planars = 0;  // before = of earlier positions
  float first = ev[0].pos;
  size_t g = 0;
  for (size_t i = 0; i < count; ++i) {
    const uint32_t type = ev[i].type();
    starts_planars += type != kEnd;
    ends_planars += type != kStart;
    planars += type == kPlanar;
    out[g] = {first, before, uint32_t(n) - ends_planars, planars};
    const float next = i + 1 < count ? ev[i + 1].pos : first;
    const bool last = i + 1 == count || !(next == ev[i].pos);
    g += last;
    before = last ? starts_planars : before;
    planars = last ? 0 : planars;
    first = last ? next : first;
  }
  return g;
}

/// What one thread needs to split nodes. The per-triangle arrays are indexed by triangle id
/// and written for a node's triangles before they are read. A task uses its thread's
/// workspace only between points where it never waits for other tasks, so a task stolen
/// while it waits never finds the workspace half used.
struct Workspace {
  std::vector<uint8_t> side;   // per triangle id: Side in the node being split
  std::vector<float> lo, hi;   // per triangle id: extent along the median axis
  std::vector<float> centres;  // split_median(): the clipped box centres
  std::vector<uint32_t> straddlers;  // distribute(): triangles on both sides
  std::vector<PlaneCounts> planes;   // split_sah(): the counts of one axis
  EventLists fresh[2];         // distribute(): events of re-clipped straddlers, per side
  EventPool pool;
  // Recording only (build_trace.h; untouched by the NullBuildSink build): whether the node
  // being split is recorded, and split_sah()'s planes of it with their costs, per axis swept.
  bool record = false;
  bool swept[3] = {false, false, false};
  std::vector<SplitCandidate> candidates[3];
  double best_cost = 0.0;  // split_sah(): the chosen plane's cost
  size_t both = 0;         // distribute(): triangles stored in both children (after clipping)
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

/// The part of the tree one task builds, in pre-order: node 0 is the task's node, above
/// children and leaf offsets are relative to the part's own arrays until stitch() moves it
/// into place. A node whose children were tasks of their own holds only itself, with the
/// children's parts in `below` and `above`.
struct Subtree {
  std::vector<KdNode> nodes;
  std::vector<uint32_t> prim_ids;
  KdLeafReasons leaf_reasons;
  int depth = 0;  // deepest leaf
  std::unique_ptr<Subtree> below, above;
  size_t node_count = 0, prim_count = 0;    // stitch(): of the part with its children's parts
  size_t node_offset = 0, prim_offset = 0;  // stitch(): where the part goes in KdTreeData
};

/// One node's outcome: the split and the children's events, or the reason it is a leaf.
struct Decision {
  SplitChoice s;
  size_t KdLeafReasons::*reason = nullptr;  // the leaf's counter when s.axis < 0
  EventLists left, right;
  size_t nl = 0, nr = 0;  // triangles of each child
  int bad_refines = 0;    // of the children's paths
};

class KdBuilder {
 public:
  /// Reports into [progress_from, 1] of `control` (a retry continues where the last
  /// stopped). `parallel` = build subtrees as TBB tasks (the result is the same either way).
  /// `exact_errors` = a failed build returns the very error the serial order meets first.
  KdBuilder(const Scene& scene, const KdBuildOptions& options, BuildControl* control, double progress_from,
            bool parallel, bool exact_errors)
      : scene_(scene),
        o_(options),
        control_(control),
        progress_(control, progress_from, 1.0),
        parallel_(parallel),
        exact_errors_(exact_errors) {}
  /// `recorder` (nullptr = none): every step is recorded into it (the builder must be serial).
  Result<KdTreeData> run(BuildRecorder* recorder = nullptr);
  /// The last fraction reported.
  double progress_reached() const { return progress_.last(); }

 private:
  Workspace& workspace();
  bool enter_node();
  template <class Sink>
  void decide(Workspace& ws, const NodeTask& t, Decision& d) const;
  bool accept_split(Workspace& ws, NodeTask& t, const Decision& d);
  NodeTask child_task(NodeTask& t, Decision& d, bool above) const;
  template <class Sink>
  void build_serial(Workspace& ws, Subtree& out, NodeTask& t);
  std::unique_ptr<Subtree> build_task(NodeTask t);
  void record_node(Workspace& ws, const NodeTask& t, uint32_t id);
  void record_split(const Workspace& ws, const NodeTask& t, const Decision& d, uint32_t id) const;
  void make_leaf(Workspace& ws, Subtree& out, NodeTask& t, size_t KdLeafReasons::*reason);
  void stitch(Subtree& root);
  double split_cost(const Aabb& box, const SplitChoice& s, size_t nl, size_t nr) const;
  int choose_axis(const Aabb& box, int depth) const;
  SplitChoice split_middle(const Aabb& box, int depth) const;
  SplitChoice split_median(Workspace& ws, const EventLists& events, const Aabb& box, int depth, size_t n) const;
  template <class Sink>
  SplitChoice split_sah(Workspace& ws, const EventLists& events, const Aabb& box, size_t n) const;
  void classify(Workspace& ws, const EventLists& events, const SplitChoice& s) const;
  template <class Sink>
  void distribute(Workspace& ws, const EventLists& events, const SplitChoice& s, const Aabb& box, Decision& d) const;
  void report_leaf(double share);
  void over_budget(const char* what, size_t limit);
  void fail(Error error);
  bool failed() const { return failed_.load(std::memory_order_relaxed); }

  const Scene& scene_;
  KdBuildOptions o_;
  BuildControl* control_;
  ProgressSpan progress_;  // touched by the reporting thread only
  const bool parallel_, exact_errors_;
  KdTreeData out_;
  size_t node_cap_ = 0;  // nodes allowed: node_limit, and what KdNode's 30 bits hold
  par::enumerable_thread_specific<Workspace> workspaces_;
  // Totals over all tasks. A task reserves its node (and a leaf its references) before
  // making it, so a total above the budget is seen by some task whatever the interleaving:
  // the build fails exactly when the serial one does.
  std::atomic<size_t> nodes_{0}, references_{0};
  std::atomic<double> done_{0.0};  // share of the build in finished leaves
  std::thread::id reporter_;       // the thread that runs the build: the one that reports progress
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

/// A finished leaf's share of the progress. Shares are summed by every task, reported only
/// by the thread that started the build (ProgressSpan is not thread-safe); its own reads of
/// the growing sum never go back.
void KdBuilder::report_leaf(double share) {
  if (!control_) return;
  // atomic<double>::fetch_add as a loop: emscripten 3.1.6's libc++ (the web build) lacks it.
  double done = done_.load(std::memory_order_relaxed);
  while (!done_.compare_exchange_weak(done, done + share, std::memory_order_relaxed)) {
  }
  done += share;
  if (std::this_thread::get_id() == reporter_) progress_.advance(done);
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

// Wald & Havran 2006, Algorithm 4 (per axis): sweep the sorted events; at each position p
// the counts are N_L (triangles before), N_P (lying in p), N_R (after); the cost of a plane
// is  lambda * (ct + ci * (A_L/A * N_L + A_R/A * N_R))  with the planar ones added to the
// cheaper side, lambda = 1 - empty_bonus when a side is empty. Planes strictly inside the
// region are candidates; a plane on its boundary only to cut off the triangles lying in it.
// Returns "leaf" when no plane beats the leaf cost ci * N (Wald & Havran's automatic
// termination).
// Recording (Sink::kRecords and ws.record): every plane given a cost, in sweep order, per
// axis into ws.candidates, and the chosen plane's cost into ws.best_cost.
template <class Sink>
SplitChoice KdBuilder::split_sah(Workspace& ws, const EventLists& events, const Aabb& box, size_t n) const {
  SplitChoice best;
  const DVec3 e = DVec3(box.max) - DVec3(box.min);
  const double area = 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
  if (!(area > 0.0)) return best;
  const double inv_area = 1.0 / area;
  double best_cost = o_.ci * double(n);
  auto cost = [&](double pl, double pr, size_t nl, size_t nr) {
    const double c = o_.ct + o_.ci * (pl * double(nl) + pr * double(nr));
    return (nl == 0 || nr == 0) ? c * (1.0 - o_.empty_bonus) : c;
  };
  for (int axis = 0; axis < 3; ++axis) {
    if (!(box.max[axis] > box.min[axis])) continue;
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    const double cross = e[a1] * e[a2], around = e[a1] + e[a2];
    const size_t planes = count_planes(events.axis[axis], n, ws.planes);
    if constexpr (Sink::kRecords) {
      if (ws.record) {
        ws.swept[axis] = true;
        ws.candidates[axis].clear();
      }
    }
    for (size_t g = 0; g < planes; ++g) {
      const float p = ws.planes[g].pos;
      const size_t nl = ws.planes[g].left, nr = ws.planes[g].right, planars = ws.planes[g].planar;
      const double dl = double(p) - double(box.min[axis]), dr = double(box.max[axis]) - double(p);
      const double pl = 2.0 * (cross + dl * around) * inv_area, pr = 2.0 * (cross + dr * around) * inv_area;
      if (p > box.min[axis] && p < box.max[axis]) {
        // Without planars both sides cost the same (and planar_left stays true).
        const double c_left = cost(pl, pr, nl + planars, nr);
        const double c_right = planars > 0 ? cost(pl, pr, nl, nr + planars) : c_left;
        const double c = std::min(c_left, c_right);
        if constexpr (Sink::kRecords) {
          if (ws.record)
            ws.candidates[axis].push_back(c_left <= c_right ? SplitCandidate{p, float(c), uint32_t(nl + planars), uint32_t(nr)}
                                                            : SplitCandidate{p, float(c), uint32_t(nl), uint32_t(nr + planars)});
        }
        if (c < best_cost) {
          best_cost = c;
          best = {axis, p, c_left <= c_right};
        }
      } else if (planars > 0 && planars < n) {
        // A plane on the region's boundary holding planar triangles: cut them off into a
        // flat cell (Wald & Havran 2006 sec. 4.4), e.g. the walls of axis-aligned rooms.
        // Both sides then hold fewer triangles than the node, so this always progresses.
        const bool at_min = p == box.min[axis];
        const double c = at_min ? cost(pl, pr, planars, n - planars) : cost(pl, pr, n - planars, planars);
        if constexpr (Sink::kRecords) {
          if (ws.record)
            ws.candidates[axis].push_back(at_min ? SplitCandidate{p, float(c), uint32_t(planars), uint32_t(n - planars)}
                                                 : SplitCandidate{p, float(c), uint32_t(n - planars), uint32_t(planars)});
        }
        if (c < best_cost) {
          best_cost = c;
          best = {axis, p, at_min};
        }
      }
    }
  }
  if constexpr (Sink::kRecords) ws.best_cost = best_cost;
  return best;
}

//-----------------------------------------------------------------------------
// [SECTION] Builder: distribution
//-----------------------------------------------------------------------------

// Sides by the split axis' events, consistent with the sweep's counts: extent ending at or
// before the plane -> left; starting at or after it -> right; lying in it -> the chosen
// side; crossing it -> both. One pass: a triangle's start precedes its end in the sorted
// list (a start and an end only for a non-flat extent), so the end can overrule the start.
void KdBuilder::classify(Workspace& ws, const EventLists& events, const SplitChoice& s) const {
  uint8_t* side = ws.side.data();
  for (const Event& e : events.axis[s.axis]) {
    const uint32_t prim = e.prim();
    switch (e.type()) {
      case kStart: side[prim] = e.pos >= s.pos ? kRight : kBoth; break;
      case kEnd:
        if (e.pos <= s.pos) side[prim] = kLeft;
        break;
      default:  // planar
        side[prim] = e.pos < s.pos || (e.pos == s.pos && s.planar_left) ? kLeft : kRight;
        break;
    }
  }
}

// Wald & Havran 2006 sec. 5.2: the events of one-sided triangles are filtered into the
// child lists (staying sorted); the straddling triangles are clipped to each child's region
// (perfect splits) or cut to it (clip=off), their new events sorted -- only these, O(s log s)
// -- and merged in. This keeps every list sorted without a sort per node: O(N log N). The
// filter writes each event to both children and advances the side it belongs to, without a
// branch to mispredict; the merge works in place from the back (merge_fresh()).
template <class Sink>
void KdBuilder::distribute(Workspace& ws, const EventLists& events, const SplitChoice& s, const Aabb& box,
                           Decision& d) const {
  EventLists& new_left = ws.fresh[0];
  EventLists& new_right = ws.fresh[1];
  for (int k = 0; k < 3; ++k) {
    new_left.axis[k].clear();
    new_right.axis[k].clear();
  }
  const uint8_t* side = ws.side.data();
  const Aabb box_l = kd_child_box(box, s.axis, s.pos, false), box_r = kd_child_box(box, s.axis, s.pos, true);
  // The triangles by their one start or planar event on axis 0: counted per side, the
  // straddlers listed (in the list's order, as their fresh events are sorted from it).
  std::vector<uint32_t>& straddlers = ws.straddlers;
  if (straddlers.size() < events.axis[0].size()) straddlers.resize(events.axis[0].size());
  size_t nl = 0, nr = 0, straddling = 0;
  if constexpr (Sink::kRecords) ws.both = 0;
  for (const Event& e : events.axis[0]) {
    const uint32_t prim = e.prim();
    const bool first = e.type() != kEnd;
    const uint8_t sd = side[prim];
    nl += first & (sd == kLeft);
    nr += first & (sd == kRight);
    straddlers[straddling] = prim;
    straddling += first & (sd == kBoth);
  }
  for (size_t i = 0; i < straddling; ++i) {
    // The straddlers' triangles are scattered over the scene: fetch ahead what the clip reads.
    if (i + 8 < straddling) {
      __builtin_prefetch(&scene_.triangle_bounds(straddlers[i + 8]));
      __builtin_prefetch(&scene_.triangles()[straddlers[i + 8]]);
    }
    if (i + 4 < straddling)
      for (int k = 0; k < 3; ++k) __builtin_prefetch(&scene_.vertex(straddlers[i + 4], k));
    const uint32_t prim = straddlers[i];
    Aabb b;
    if (o_.clip) {
      const bool in_left = clip_triangle_bounds(scene_, prim, box_l, &b);
      if (in_left) add_events(new_left, prim, b), ++nl;
      const bool in_right = clip_triangle_bounds(scene_, prim, box_r, &b);
      if (in_right) add_events(new_right, prim, b), ++nr;
      if constexpr (Sink::kRecords) ws.both += in_left && in_right;
    } else {
      const Aabb& tri = scene_.triangle_bounds(prim);
      for (const Aabb* child : {&box_l, &box_r}) {
        b.min = glm::max(tri.min, child->min);
        b.max = glm::min(tri.max, child->max);
        add_events(child == &box_l ? new_left : new_right, prim, b);
      }
      ++nl, ++nr;
      if constexpr (Sink::kRecords) ++ws.both;
    }
  }
  d.nl = nl;
  d.nr = nr;
  for (int k = 0; k < 3; ++k) {
    const std::vector<Event>& src = events.axis[k];
    std::vector<Event>& fresh_l = new_left.axis[k];
    std::vector<Event>& fresh_r = new_right.axis[k];
    std::sort(fresh_l.begin(), fresh_l.end(), EventLess{});
    std::sort(fresh_r.begin(), fresh_r.end(), EventLess{});
    std::vector<Event>& left = d.left.axis[k];
    std::vector<Event>& right = d.right.axis[k];
    left = ws.pool.take();
    right = ws.pool.take();
    left.resize(src.size() + fresh_l.size());
    right.resize(src.size() + fresh_r.size());
    Event* l = left.data();
    Event* r = right.data();
    size_t kept_l = 0, kept_r = 0;
    for (const Event& e : src) {
      const uint8_t sd = side[e.prim()];
      l[kept_l] = e;
      r[kept_r] = e;
      kept_l += sd == kLeft;
      kept_r += sd == kRight;
    }
    merge_fresh(left, kept_l, fresh_l);
    merge_fresh(right, kept_r, fresh_r);
    // Long lists were sized for every event going to each side; give back what the other
    // side took (a copy of the kept part), as the above list waits through the below subtree.
    for (std::vector<Event>* list : {&left, &right})
      if (list->capacity() > kShrinkMin && list->size() < list->capacity() / 4 * 3) list->shrink_to_fit();
  }
}

//-----------------------------------------------------------------------------
// [SECTION] Builder: recursion and tasks
//-----------------------------------------------------------------------------

void KdBuilder::make_leaf(Workspace& ws, Subtree& out, NodeTask& t, size_t KdLeafReasons::*reason) {
  ++(out.leaf_reasons.*reason);
  if (references_.fetch_add(t.n, std::memory_order_relaxed) + t.n > o_.reference_limit) {
    over_budget("triangle references", o_.reference_limit);
    return;
  }
  const size_t offset = out.prim_ids.size();
  for (const Event& e : t.events.axis[0])
    if (e.type() != kEnd) out.prim_ids.push_back(e.prim());
  std::sort(out.prim_ids.begin() + ptrdiff_t(offset), out.prim_ids.end());  // ascending: stable ties, tidy views
  out.nodes.push_back(KdNode::make_leaf(uint32_t(offset), uint32_t(t.n)));
  out.depth = std::max(out.depth, t.depth);
  ws.pool.give(t.events);
  report_leaf(t.share);
}

/// SAH cost of splitting `box` at `s` with nl / nr triangles on the sides (the formula of
/// split_sah(), for judging middle and median splits).
double KdBuilder::split_cost(const Aabb& box, const SplitChoice& s, size_t nl, size_t nr) const {
  const double area = box.area();
  if (!(area > 0.0)) return kInf;
  const double pl = kd_child_box(box, s.axis, s.pos, false).area() / area;
  const double pr = kd_child_box(box, s.axis, s.pos, true).area() / area;
  const double c = o_.ct + o_.ci * (pl * double(nl) + pr * double(nr));
  return (nl == 0 || nr == 0) ? c * (1.0 - o_.empty_bonus) : c;
}

/// The checks at every node: an earlier failure, a cancel, the node budget (reserving the
/// node: the serial build's test "nodes made >= limit" before making one).
bool KdBuilder::enter_node() {
  if (failed()) return false;
  if (build_cancelled(control_)) {
    fail(cancelled_error());
    return false;
  }
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
    case KdSplit::Sah: d.s = split_sah<Sink>(ws, t.events, t.box, n); break;
  }
  if (d.s.axis < 0) {
    d.reason = o_.split == KdSplit::Sah ? &KdLeafReasons::no_gain : &KdLeafReasons::thin;
    return;
  }
  classify(ws, t.events, d.s);
  distribute<Sink>(ws, t.events, d.s, t.box, d);
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
    [[maybe_unused]] const size_t offset = out.prim_ids.size();
    make_leaf(ws, out, t, d.reason);
    if constexpr (Sink::kRecords) {
      if (!failed())
        recorder_->leaf(id, leaf_reason(d.reason), out.prim_ids.data() + offset, out.prim_ids.size() - offset);
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

// A node of at least kTaskMinPrims triangles is a part of its own and builds its children as
// two tasks; a smaller one builds its subtree serially. Which nodes are tasks depends on the
// scene alone, and stitch() numbers the parts in pre-order, so the tree does not depend on
// the thread count (nor on whether there is a task at all).
std::unique_ptr<Subtree> KdBuilder::build_task(NodeTask t) {
  auto out = std::make_unique<Subtree>();
  Workspace& ws = workspace();
  if (recorder_) {
    build_serial<BuildRecorder>(ws, *out, t);
    return out;
  }
  if (!parallel_ || t.n < kTaskMinPrims) {
    build_serial<NullBuildSink>(ws, *out, t);
    return out;
  }
  if (!enter_node()) return out;
  Decision d;
  decide<NullBuildSink>(ws, t, d);
  if (d.s.axis < 0) {
    make_leaf(ws, *out, t, d.reason);
    return out;
  }
  if (!accept_split(ws, t, d)) return out;
  NodeTask left = child_task(t, d, false);
  NodeTask right = child_task(t, d, true);
  out->nodes.push_back(KdNode::make_inner(d.s.axis, d.s.pos, 0));  // stitch() points it at `above`
  // `ws` is not touched from here on: tasks this thread steals while it waits use it.
  par::parallel_invoke([&] { out->below = build_task(std::move(left)); },
                       [&] { out->above = build_task(std::move(right)); });
  return out;
}

//-----------------------------------------------------------------------------
// [SECTION] Builder: stitching and the whole build
//-----------------------------------------------------------------------------

namespace stitching {

/// Sizes of every part with its children's parts, bottom-up.
void count(Subtree& part) {
  part.node_count = part.nodes.size();
  part.prim_count = part.prim_ids.size();
  if (!part.below) return;
  count(*part.below);
  count(*part.above);
  part.node_count += part.below->node_count + part.above->node_count;
  part.prim_count += part.below->prim_count + part.above->prim_count;
}

/// Pre-order offsets, top-down: a split part's below child follows it, its above child
/// follows the below child's parts. The split node's above index is made relative to the
/// part like every other, so moving a part is one rule for all its nodes.
void place(Subtree& part, size_t node_offset, size_t prim_offset, std::vector<Subtree*>& parts) {
  part.node_offset = node_offset;
  part.prim_offset = prim_offset;
  parts.push_back(&part);
  if (!part.below) return;
  const KdNode split = part.nodes[0];
  part.nodes[0] = KdNode::make_inner(split.axis(), split.split(), NodeId(1 + part.below->node_count));
  place(*part.below, node_offset + 1, prim_offset, parts);
  place(*part.above, node_offset + 1 + part.below->node_count, prim_offset + part.below->prim_count, parts);
}

}  // namespace stitching

// Moves the parts into out_ in pre-order: inner nodes' above indices shift by the part's
// node offset, leaves' triangle offsets by its triangle offset (both fit: the totals are
// within the budgets checked per node).
void KdBuilder::stitch(Subtree& root) {
  std::vector<Subtree*> parts;
  stitching::count(root);
  stitching::place(root, 0, 0, parts);
  for (const Subtree* part : parts) {
    for (size_t KdLeafReasons::*r : {&KdLeafReasons::few_prims, &KdLeafReasons::max_depth, &KdLeafReasons::no_gain,
                                     &KdLeafReasons::no_progress, &KdLeafReasons::bad_refines, &KdLeafReasons::thin})
      out_.leaf_reasons.*r += part->leaf_reasons.*r;
    out_.depth = std::max(out_.depth, part->depth);
  }
  if (parts.size() == 1) {  // a serial build: already in place
    out_.nodes = std::move(root.nodes);
    out_.prim_ids = std::move(root.prim_ids);
    return;
  }
  out_.nodes.resize(root.node_count);
  out_.prim_ids.resize(root.prim_count);
  par::parallel_for(size_t(0), parts.size(), [&](size_t i) {
    const Subtree& part = *parts[i];
    const uint32_t node_shift = uint32_t(part.node_offset) << 2, prim_shift = uint32_t(part.prim_offset);
    KdNode* nodes = out_.nodes.data() + part.node_offset;
    for (size_t k = 0; k < part.nodes.size(); ++k) {
      KdNode node = part.nodes[k];
      if (node.leaf())
        node.payload += prim_shift;
      else
        node.bits += node_shift;
      nodes[k] = node;
    }
    std::copy(part.prim_ids.begin(), part.prim_ids.end(), out_.prim_ids.begin() + ptrdiff_t(part.prim_offset));
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
  reporter_ = std::this_thread::get_id();
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
  auto sort_axis = [&root](int k) { std::sort(root.events.axis[k].begin(), root.events.axis[k].end(), EventLess{}); };
  par::parallel_invoke([&] { sort_axis(0); }, [&] { sort_axis(1); }, [&] { sort_axis(2); });

  root.n = prims.size();
  root.box = out_.root_box;
  root.share = 1.0;
  std::unique_ptr<Subtree> tree = build_task(std::move(root));
  if (failed()) {
    // Parallel tasks stop at the first budget any of them finds exceeded, which need not be
    // the one the serial order meets first; when the message is returned, that one is found
    // by building serially (only failed builds pay for it).
    const bool had_tasks = parallel_ && prims.size() >= kTaskMinPrims;
    if (had_tasks && exact_errors_ && !build_cancelled(control_))
      return KdBuilder(scene_, o_, control_, progress_.last(), false, true).run();
    return status_.error();
  }
  stitch(*tree);
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
