#pragma once
// The AABB tree's 4-wide layout as a structure of its own (WideBvh: bvh width=4, the
// default; bvh.h has the parameters, the factory and the binary layout): the binary tree of
// any builder collapsed into nodes of up to four children, whose four boxes are tested
// against the ray at once with SSE, and the leaves' triangles copied in leaf order so a leaf
// reads one contiguous block. This is how production tracers lay out a BVH for single rays
// (Dammertz et al. 2008, "Shallow Bounding Volume Hierarchies for Fast SIMD Ray Tracing of
// Incoherent Rays"; Wald et al. 2008, "Getting Rid of Packets"). The node order, the
// recorder calls and the cull rules are those of hierarchy.h's traversals, so the viewer
// animates this very loop. Index:
//   [SECTION] Node layout and the 4-wide slab test
//   [SECTION] WideBvh: build, views, stats
//   [SECTION] Traversals: stack (dfs / ordered) and priority queue
#include <emmintrin.h>  // SSE2 only: every x86-64 CPU has it, so no -m flag is needed

#include <xmmintrin.h>  // _mm_prefetch

#include <algorithm>
#include <array>
#include <vector>

#include "structures/bvh_builders.h"
#include "structures/hierarchy.h"

namespace accel {

// ============================================================================
// [SECTION] Node layout and the 4-wide slab test
// ============================================================================

/// Where a child's data is, so descending needs no lookup by node id: an inner child's
/// WideNode index, or for a leaf kLeafBit | count << 32 | first: its `count` triangles fill
/// WideBvh's triangle blocks from block `first` on, four per block.
using ChildRef = uint64_t;
inline constexpr ChildRef kLeafBit = ChildRef(1) << 63;
inline bool ref_is_leaf(ChildRef r) { return (r & kLeafBit) != 0; }
inline uint32_t ref_first(ChildRef r) { return uint32_t(r); }
inline uint32_t ref_count(ChildRef r) { return uint32_t(r >> 32) & 0xffffu; }
inline ChildRef leaf_ref(uint32_t first, uint32_t count) { return kLeafBit | ChildRef(count) << 32 | first; }

/// An inner node of the 4-wide tree: its children's boxes in structure-of-arrays form (one
/// SSE register per bound) and references. An unused slot has an empty box (min = +inf,
/// max = -inf), which every ray misses. Two cache lines; the children's node ids, needed
/// only when a traversal is observed, are kept apart (WideBvh::child_ids_).
struct alignas(64) WideNode {
  float bounds[6][4];  ///< rows: min x, min y, min z, max x, max y, max z; columns: child slots
  ChildRef ref[4];     ///< see ChildRef; an empty leaf for an unused slot
};

static_assert(sizeof(WideNode) == 128, "a 4-wide node should stay two cache lines");

/// Per-ray constants of the 4-wide slab test, taken from BoxTester so both tests share the
/// reciprocal direction (-0.0 -> -inf) and the choice of near and far slab.
struct WideRay {
  explicit WideRay(const BoxTester& box_ray) {
    for (int axis = 0; axis < 3; ++axis) {
      org[axis] = _mm_set1_ps(box_ray.org[axis]);
      inv_dir[axis] = _mm_set1_ps(box_ray.inv_dir[axis]);
      near_row[axis] = box_ray.negative[axis] ? 3 + axis : axis;
      far_row[axis] = box_ray.negative[axis] ? axis : 3 + axis;
    }
  }
  __m128 org[3], inv_dir[3];
  int near_row[3], far_row[3];
};

/// BoxTester::intersect on the four child boxes of `node` at once, lane by lane with the
/// same float operations in the same order, so exactly the boxes the binary tree would
/// accept are accepted (conservative far distance, NaN-safe). Returns the mask of hit slots
/// and writes each slot's clipped [t_enter, t_exit].
ACCEL_FORCE_INLINE int intersect_children(const WideNode& node, const WideRay& r, float tmin, float tmax,
                                          float* t_enter, float* t_exit) {
  const __m128 widen = _mm_set1_ps(1.0f + 2.0f * gamma_bound(3));
  __m128 t0 = _mm_set1_ps(tmin), t1 = _mm_set1_ps(tmax);
  for (int axis = 0; axis < 3; ++axis) {
    const __m128 t_near = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.near_row[axis]]), r.org[axis]), r.inv_dir[axis]);
    const __m128 t_far = _mm_mul_ps(
        _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.far_row[axis]]), r.org[axis]), r.inv_dir[axis]), widen);
    // maxps/minps return the second operand when either is NaN: a NaN slab distance (origin
    // on the slab plane, zero direction) leaves the interval unchanged, as in BoxTester.
    t0 = _mm_max_ps(t_near, t0);
    t1 = _mm_min_ps(t_far, t1);
  }
  _mm_storeu_ps(t_enter, t0);
  _mm_storeu_ps(t_exit, t1);
  return _mm_movemask_ps(_mm_cmple_ps(t0, t1));
}

// ============================================================================
// [SECTION] WideBvh: build, views, stats
// ============================================================================

/// The collapsed tree, registered as "bvh" with width=4 (same parameters, builders and
/// traversal orders as BinaryBvh). Node ids number every node, inner and leaf, in
/// depth-first order (root 0), as in the binary layout, so the viewer draws and highlights
/// them alike.
class WideBvh final : public StructureWithTraversal<WideBvh> {
 public:
  /// What a node id stands for. Inner node: `index` is its WideNode, `count` is 0. Leaf:
  /// `count` > 0 triangles in the triangle blocks from block `index` on.
  struct Entry {
    uint32_t index = 0;
    uint32_t count = 0;
    bool leaf() const { return count != 0; }
  };

  /// The registry name both layouts share.
  std::string name() const override { return "bvh"; }
  void for_each_node(const std::function<void(const NodeView&)>& fn) const override;
  NodeView node_view(NodeId id) const override;
  std::vector<uint32_t> node_prims(NodeId id) const override;

  /// Number of nodes, inner and leaf.
  size_t size() const { return entries_.size(); }
  /// The WideNode of inner node `id` (for tests of the tree's shape).
  const WideNode& wide_node(NodeId id) const { return nodes_[entries_[id].index]; }
  /// Nodes, entries, triangle references and the leaf-ordered triangle copies.
  size_t memory_bytes() const;

  /// The one query, visiting nodes in the traversal order chosen at build time.
  template <TraversalSink Sink>
  Hit traverse(const Ray& ray, Sink& sink) const;

 protected:
  Status build_impl(const Scene& scene, const ParamSet& params, BuildControl* control, BuildRecorder* recorder) override;
  /// The node counters, the SAH cost (ct per inner node, the options' leaf cost per leaf, by
  /// area relative to the root) and the builder, traversal and width lines.
  BuildStats compute_stats() const override;
  /// Same nodes, new boxes bottom-up, the leaves' triangle blocks re-copied from the moved
  /// vertices; subtrees in parallel (wide_bvh_refit.cpp).
  Status refit_impl(const Scene& scene) override;

 private:
  /// Refits the subtree whose node ids are [node, end) (depth-first ids: contiguous).
  void refit_subtree(const Scene& scene, NodeId node, NodeId end);
  void refit_node(const Scene& scene, NodeId node);
  /// Collapses a builder's binary tree: each inner node adopts the children of its largest
  /// inner child (by surface area, the child most rays enter) until it has four.
  void collapse(const Scene& scene, const BuildTree& tree);
  void clear();
  struct Layout;  // a subtree being emitted by one task (wide_bvh.cpp)

  struct Pending {
    ChildRef ref;
    NodeId node;   ///< for the sink only (kNoNode in the fast path)
    float t0, t1;  ///< the ray's interval inside the node's box
  };
  /// Node id of a child for the sink; the fast path never reads the id table.
  template <TraversalSink Sink>
  NodeId child_id(uint32_t wide, int slot) const {
    if constexpr (kObservesNothing<Sink>) return kNoNode;
    else return child_ids_[wide][slot];
  }
  template <TraversalSink Sink>
  int node_depth(NodeId id) const {
    if constexpr (kObservesNothing<Sink>) return 0;
    else return depth_[id];
  }
  /// Starts fetching what a pushed child will read when it is popped.
  void prefetch(ChildRef r) const {
    const char* p = ref_is_leaf(r) ? reinterpret_cast<const char*>(&blocks_[ref_first(r)])
                                   : reinterpret_cast<const char*>(&nodes_[r]);
    _mm_prefetch(p, _MM_HINT_T0);
    _mm_prefetch(p + 64, _MM_HINT_T0);
    if (ref_is_leaf(r)) _mm_prefetch(p + 128, _MM_HINT_T0);
  }
  // Each pop pushes at most four children in place of one node: 3 per level, plus slack.
  static constexpr int kStackSize = 3 * kMaxBvhDepth + 4;

  template <TraversalSink Sink>
  void report_misses(uint32_t wide, int hit_mask, const WideRay& wray, float tmin, Sink& sink) const;
  /// Tests a leaf's triangles four at a time. Lanes are taken in order with the same rule
  /// as test_triangle (first hit, then strictly closer), so ties resolve as in the binary tree.
  template <TraversalSink Sink>
  void test_leaf(ChildRef r, const TriangleTester& tester, Hit& closest, Sink& sink) const {
    const TriangleBlock* block = blocks_.data() + ref_first(r);
    for (uint32_t left = ref_count(r); left > 0; left -= std::min(left, 4u), ++block) {
      const int lanes = left >= 4 ? 0xf : (1 << left) - 1;
      alignas(16) float t[4], u[4], v[4];
      const int hits = tester.intersect4(*block, lanes, closest.t, t, u, v);
      // The fast path looks at hit lanes only; an observer sees every test.
      const int seen = kObservesNothing<Sink> ? hits : lanes;
      for (int lane = 0; lane < 4; ++lane) {
        if (!((seen >> lane) & 1)) continue;
        const bool hit = (hits >> lane) & 1;
        take_triangle_result(block->prim[lane], hit,
                             hit ? TriangleHit{t[lane], u[lane], v[lane]} : TriangleHit{kInf, 0.0f, 0.0f}, closest,
                             sink);
      }
    }
  }
  template <TraversalSink Sink>
  bool enter_root(const Ray& ray, const BoxTester& box_ray, const Hit& closest, Sink& sink, Pending* root) const;
  template <TraversalSink Sink>
  void traverse_stack(const Ray& ray, const WideRay& wray, const TriangleTester& tester, bool nearest_first,
                      Pending root, Hit& closest, Sink& sink) const;
  template <TraversalSink Sink>
  void traverse_pqueue(const Ray& ray, const WideRay& wray, const TriangleTester& tester, Pending root,
                       Hit& closest, Sink& sink) const;

  ChildRef ref_of(NodeId id) const {
    return entries_[id].leaf() ? leaf_ref(entries_[id].index, entries_[id].count) : entries_[id].index;
  }

  std::vector<WideNode> nodes_;
  std::vector<std::array<NodeId, 4>> child_ids_;  ///< by WideNode: the children's node ids, kNoNode if unused
  std::vector<Entry> entries_;     ///< by node id
  std::vector<Aabb> boxes_;        ///< by node id: the node's own box (the root's is tested alone)
  std::vector<uint16_t> depth_;    ///< by node id
  std::vector<TriangleBlock> blocks_;  ///< leaf triangles in leaf order, four per block
  size_t prim_count_ = 0;      ///< triangle references in the leaves
  size_t triangle_count_ = 0;  ///< distinct triangles among them (fewer after sbvh's spatial splits)
  BvhBuildOptions options_;
  TraversalOrder order_ = TraversalOrder::Ordered;
};

// ============================================================================
// [SECTION] Traversals
// ============================================================================

template <TraversalSink Sink>
void WideBvh::report_misses(uint32_t wide, int hit_mask, const WideRay& wray, float tmin, Sink& sink) const {
  if constexpr (kObservesNothing<Sink>) {
    return;  // nothing to count: the fast path skips the loop entirely
  } else {
    int beyond_mask = 0;
    float a[4], b[4];
    if constexpr (Sink::kRecords) beyond_mask = intersect_children(nodes_[wide], wray, tmin, kInf, a, b);
    for (int s = 0; s < 4; ++s) {
      const NodeId child = child_ids_[wide][s];
      if ((hit_mask >> s) & 1 || child == kNoNode) continue;
      const bool beyond = (beyond_mask >> s) & 1;
      sink.cull(child, depth_[child], beyond ? CullReason::BeyondClosestHit : CullReason::MissedBounds,
                beyond ? a[s] : 0.0f);
    }
  }
}

template <TraversalSink Sink>
bool WideBvh::enter_root(const Ray& ray, const BoxTester& box_ray, const Hit& closest, Sink& sink,
                         Pending* root) const {
  float t0, t1;
  if (box_ray.intersect(boxes_[0], ray.tmin, closest.t, &t0, &t1)) {
    *root = {ref_of(0), 0, t0, t1};
    return true;
  }
  const bool beyond = Sink::kRecords && box_ray.intersect(boxes_[0], ray.tmin, kInf, &t0, &t1);
  sink.cull(0, 0, beyond ? CullReason::BeyondClosestHit : CullReason::MissedBounds, beyond ? t0 : 0.0f);
  return false;
}

template <TraversalSink Sink>
Hit WideBvh::traverse(const Ray& ray, Sink& sink) const {
  Hit closest = no_hit(ray);
  if (!entries_.empty()) {
    const TriangleTester tester(ray, kernel_);
    const BoxTester box_ray(ray);
    Pending root;
    if (enter_root(ray, box_ray, closest, sink, &root)) {
      const WideRay wray(box_ray);
      if (order_ == TraversalOrder::PriorityQueue)
        traverse_pqueue(ray, wray, tester, root, closest, sink);
      else
        traverse_stack(ray, wray, tester, order_ == TraversalOrder::Ordered, root, closest, sink);
    }
  }
  return finish_query(closest, sink);
}

/// Depth-first. All four child boxes are tested at their parent; the loop descends
/// straight into the first hit child (the nearest one when `nearest_first`, i.e. ordered;
/// the first in tree order for dfs) and pushes the others, farthest first. A popped node
/// entered beyond the closest hit found meanwhile is skipped. Descending without a push and
/// pop is what makes the wide layout pay off (the child was tested against the current
/// closest hit a moment ago).
template <TraversalSink Sink>
void WideBvh::traverse_stack(const Ray& ray, const WideRay& wray, const TriangleTester& tester, bool nearest_first,
                             Pending root, Hit& closest, Sink& sink) const {
  Pending stack[kStackSize];
  int top = 0;
  Pending cur = root;
  for (;;) {
    sink.visit(cur.node, node_depth<Sink>(cur.node), cur.t0, cur.t1);
    if (ref_is_leaf(cur.ref)) {
      test_leaf(cur.ref, tester, closest, sink);
    } else {
      const uint32_t w = uint32_t(cur.ref);
      const WideNode& n = nodes_[w];
      alignas(16) float t0[4], t1[4];
      const int mask = intersect_children(n, wray, ray.tmin, closest.t, t0, t1);
      report_misses(w, mask, wray, ray.tmin, sink);
      if (mask != 0) {
        // Hit slots in tree order, then (ordered) a stable insertion sort by entry distance,
        // so equal distances keep tree order as in the binary traversal.
        int slot[4], hits = 0;
        for (int m = mask; m; m &= m - 1) slot[hits++] = __builtin_ctz(unsigned(m));
        if (nearest_first && hits > 1) {
          for (int i = 1; i < hits; ++i)
            for (int j = i; j > 0 && t0[slot[j]] < t0[slot[j - 1]]; --j) std::swap(slot[j], slot[j - 1]);
        }
        for (int i = hits - 1; i > 0; --i) {  // the rest, farthest (or last in tree order) first
          const int s = slot[i];
          const NodeId child = child_id<Sink>(w, s);
          stack[top++] = {n.ref[s], child, t0[s], t1[s]};
          prefetch(n.ref[s]);
          sink.push(child, node_depth<Sink>(child), t0[s]);
        }
        cur = {n.ref[slot[0]], child_id<Sink>(w, slot[0]), t0[slot[0]], t1[slot[0]]};
        continue;
      }
    }
    // Nothing to descend into: resume at the top of the stack.
    for (;;) {
      if (top == 0) return;
      cur = stack[--top];
      sink.pop(cur.node, node_depth<Sink>(cur.node), cur.t0);
      if (cur.t0 <= closest.t) break;
      sink.cull(cur.node, node_depth<Sink>(cur.node), CullReason::BeyondClosestHit, cur.t0);
    }
  }
}

/// The lecture's priority queue by entry distance, over 4-wide nodes: stops when the
/// nearest pending node is farther than the closest hit.
template <TraversalSink Sink>
void WideBvh::traverse_pqueue(const Ray& ray, const WideRay& wray, const TriangleTester& tester, Pending root,
                              Hit& closest, Sink& sink) const {
  thread_local std::vector<Pending> heap;  // outgrows any fixed stack; reused, not allocated per ray
  heap.clear();
  // Ties broken by the child reference, which the fast path has too (node ids it has not).
  const auto later = [](const Pending& a, const Pending& b) { return a.t0 > b.t0 || (a.t0 == b.t0 && a.ref > b.ref); };
  const auto push = [&](const Pending& p) {
    heap.push_back(p);
    std::push_heap(heap.begin(), heap.end(), later);
    sink.push(p.node, node_depth<Sink>(p.node), p.t0);
  };
  push(root);
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), later);
    const Pending p = heap.back();
    heap.pop_back();
    sink.pop(p.node, node_depth<Sink>(p.node), p.t0);
    if (p.t0 > closest.t) {
      sink.cull(p.node, node_depth<Sink>(p.node), CullReason::BeyondClosestHit, p.t0);
      if constexpr (Sink::kRecords) {
        std::sort_heap(heap.begin(), heap.end(), later);
        for (auto it = heap.rbegin(); it != heap.rend(); ++it)
          sink.cull(it->node, node_depth<Sink>(it->node), CullReason::BeyondClosestHit, it->t0);
      }
      break;
    }
    sink.visit(p.node, node_depth<Sink>(p.node), p.t0, p.t1);
    if (ref_is_leaf(p.ref)) {
      test_leaf(p.ref, tester, closest, sink);
      continue;
    }
    const uint32_t w = uint32_t(p.ref);
    const WideNode& n = nodes_[w];
    alignas(16) float t0[4], t1[4];
    const int mask = intersect_children(n, wray, ray.tmin, closest.t, t0, t1);
    report_misses(w, mask, wray, ray.tmin, sink);
    for (int s = 0; s < 4; ++s)
      if ((mask >> s) & 1) push({n.ref[s], child_id<Sink>(w, s), t0[s], t1[s]});
  }
}

}  // namespace accel
