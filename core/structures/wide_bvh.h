#pragma once
// The AABB tree's wide layouts as a structure of their own (WideBvhOf<W>: bvh width=4 and
// width=8; bvh.h has the parameters, the factory and the binary layout): the binary tree of
// any builder collapsed into nodes of up to W children, whose W boxes are tested against
// the ray at once, and the leaves' triangles copied in leaf order so a leaf reads one
// contiguous block. The 4-wide nodes use SSE2 (every x86-64 CPU); the 8-wide nodes use the
// AVX-512 or AVX2 kernel this CPU runs (wide_bvh_isa.h), or SSE2 on two halves. This is how production tracers lay out a BVH for single rays
// (Dammertz et al. 2008, "Shallow Bounding Volume Hierarchies for Fast SIMD Ray Tracing of
// Incoherent Rays"; Wald et al. 2008, "Getting Rid of Packets"). The node order, the
// recorder calls and the cull rules are those of hierarchy.h's traversals, so the viewer
// animates this very loop, whichever kernel runs it. Index:
//   [SECTION] Node layout and the SSE2 slab test
//   [SECTION] WideBvh: build, views, stats
//   [SECTION] Traversals: stack (dfs / ordered) and priority queue
#include <emmintrin.h>  // SSE2 only: every x86-64 CPU has it, so no -m flag is needed

#include <xmmintrin.h>  // _mm_prefetch

#include <algorithm>
#include <array>
#include <type_traits>
#include <vector>

#include "isa.h"
#include "structures/bvh_build_types.h"
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

/// An inner node of the W-wide tree: its children's boxes in structure-of-arrays form (one
/// SIMD register per bound) and references. An unused slot has an empty box (min = +inf,
/// max = -inf), which every ray misses. Two cache lines for W = 4, four for W = 8; the
/// children's node ids, needed only when a traversal is observed, are kept apart
/// (WideBvhOf::child_ids_).
template <int W>
struct alignas(64) WideNodeOf {
  static constexpr int kWidth = W;
  float bounds[6][W];  ///< rows: min x, min y, min z, max x, max y, max z; columns: child slots
  ChildRef ref[W];     ///< see ChildRef; an empty leaf for an unused slot
};
using WideNode = WideNodeOf<4>;
using WideNode8 = WideNodeOf<8>;

static_assert(sizeof(WideNodeOf<4>) == 128, "a 4-wide node should stay two cache lines");
static_assert(sizeof(WideNodeOf<8>) == 256, "an 8-wide node should stay four cache lines");

/// Per-ray constants of the wide slab test for instruction set `Tag` (the AVX ones are in
/// wide_bvh_isa.h), taken from BoxTester so every test shares the reciprocal direction
/// (-0.0 -> -inf) and the choice of near and far slab.
template <class Tag>
struct WideRayFor;

template <>
struct WideRayFor<Sse2Tag> {
  explicit WideRayFor(const BoxTester& box_ray) {
    for (int axis = 0; axis < 3; ++axis) {
      org[axis] = _mm_set1_ps(box_ray.org[axis]);
      inv_dir[axis] = _mm_set1_ps(box_ray.inv_dir[axis]);
      inv_dir_far[axis] = _mm_set1_ps(box_ray.inv_dir_far[axis]);
      near_row[axis] = box_ray.near_index[axis];  // a node's rows are ordered as an Aabb's floats
      far_row[axis] = box_ray.far_index[axis];
    }
  }
  __m128 org[3], inv_dir[3], inv_dir_far[3];
  int near_row[3], far_row[3];
};

/// BoxTester::intersect on four child boxes of `node` at once (slots [first, first + 4)),
/// lane by lane with the same float operations in the same order, so exactly the boxes the
/// binary tree would accept are accepted (conservative far distance, NaN-safe; no fused
/// multiply-add, which would break the bound: the project compiles with -ffp-contract=off).
/// Returns the mask of hit slots and writes each slot's clipped [t_enter, t_exit].
template <int W>
ACCEL_FORCE_INLINE int intersect_four(const WideNodeOf<W>& node, int first, const WideRayFor<Sse2Tag>& r, float tmin,
                                      float tmax, float* t_enter, float* t_exit) {
  __m128 t0 = _mm_set1_ps(tmin), t1 = _mm_set1_ps(tmax);
  for (int axis = 0; axis < 3; ++axis) {
    const __m128 t_near =
        _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.near_row[axis]] + first), r.org[axis]), r.inv_dir[axis]);
    const __m128 t_far =
        _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.far_row[axis]] + first), r.org[axis]), r.inv_dir_far[axis]);
    // maxps/minps return the second operand when either is NaN: a NaN slab distance (origin
    // on the slab plane, zero direction) leaves the interval unchanged, as in BoxTester.
    t0 = _mm_max_ps(t_near, t0);
    t1 = _mm_min_ps(t_far, t1);
  }
  _mm_storeu_ps(t_enter, t0);
  _mm_storeu_ps(t_exit, t1);
  return _mm_movemask_ps(_mm_cmple_ps(t0, t1));
}

/// The SSE2 kernel of a W-wide node: the mask of hit slots (bit s = slot s) and each slot's
/// [t_enter, t_exit]; an 8-wide node is tested as two halves.
template <int W>
ACCEL_FORCE_INLINE int intersect_children(const WideNodeOf<W>& node, const WideRayFor<Sse2Tag>& r, float tmin,
                                          float tmax, float* t_enter, float* t_exit) {
  int mask = 0;
  for (int first = 0; first < W; first += 4)
    mask |= intersect_four(node, first, r, tmin, tmax, t_enter + first, t_exit + first) << first;
  return mask;
}

/// The slots whose entry distance orders before slot s's: strictly nearer, or as near and
/// earlier in tree order (the order of a stable sort by distance). Slots beyond the hit
/// ones give bits the caller masks off. SSE2, four slots at a time; the ISA units overload
/// it for their tag with one eight-slot compare (wide_bvh_isa_unit.h). The traversal calls
/// it unqualified with its tag, so the overload is found where the tag is an ISA unit's.
template <int W>
ACCEL_FORCE_INLINE int nearer_slots(Sse2Tag, std::integral_constant<int, W>, const float* t0, int s) {
  const __m128 key = _mm_set1_ps(t0[s]);
  int lt = 0, eq = 0;
  for (int first = 0; first < W; first += 4) {
    const __m128 t = _mm_load_ps(t0 + first);
    lt |= _mm_movemask_ps(_mm_cmplt_ps(t, key)) << first;
    eq |= _mm_movemask_ps(_mm_cmpeq_ps(t, key)) << first;
  }
  return lt | (eq & ((1 << s) - 1));
}

// ============================================================================
// [SECTION] WideBvhOf: build, views, stats
// ============================================================================

template <int W>
class WideBvhOf;
/// The fast traversal (nothing observed) of an 8-wide tree with the AVX2 or AVX-512 kernel;
/// defined in wide_bvh_avx2.cpp / wide_bvh_avx512.cpp, compiled with those flags.
using FastWideTraversal = Hit (*)(const WideBvhOf<8>& bvh, const Ray& ray);
/// The same over a batch: hits[i] is the closest hit of rays[i], for i < n, the loop inside
/// the unit (its register saves and stack frame paid once a batch, not once a ray).
using FastWideBatch = void (*)(const WideBvhOf<8>& bvh, const Ray* rays, size_t n, Hit* hits);

/// The collapsed tree, registered as "bvh" with width=4 or 8 (same parameters, builders and
/// traversal orders as BinaryBvh). Node ids number every node, inner and leaf, in
/// depth-first order (root 0), as in the binary layout, so the viewer draws and highlights
/// them alike.
template <int W>
class WideBvhOf final : public StructureWithTraversal<WideBvhOf<W>> {
  static_assert(W == 4 || W == 8, "4 (SSE2) or 8 (AVX2, AVX-512, or SSE2 in halves) children per node");

 public:
  using Node = WideNodeOf<W>;
  /// What a node id stands for. Inner node: `index` is its Node, `count` is 0. Leaf:
  /// `count` > 0 triangles in the triangle blocks from block `index` on.
  struct Entry {
    uint32_t index = 0;
    uint32_t count = 0;
    bool leaf() const { return count != 0; }
  };

  /// The registry name every layout shares.
  std::string name() const override { return "bvh"; }
  void for_each_node(const std::function<void(const NodeView&)>& fn) const override;
  NodeView node_view(NodeId id) const override;
  std::vector<uint32_t> node_prims(NodeId id) const override;
  std::vector<NodeId> node_children(NodeId id) const override;

  /// Number of nodes, inner and leaf.
  size_t size() const { return entries_.size(); }
  /// The Node of inner node `id` (for tests of the tree's shape).
  const Node& wide_node(NodeId id) const { return nodes_[entries_[id].index]; }
  /// Nodes, entries, triangle references and the leaf-ordered triangle copies.
  size_t memory_bytes() const;
  /// The kernel the fast path (nothing observed) runs: for 8-wide trees the best the CPU
  /// has (isa.h, capped by ACCEL_ISA), SSE2 for 4-wide ones. Observed traversals (counters,
  /// the recorder) run SSE2 kernels, which take the same decisions bit for bit
  /// (tests/test_wide_isa.cpp), so the viewer animates the query the fast path makes.
  Isa fast_isa() const { return fast_ ? fast_isa_ : Isa::Sse2; }
  TraversalOrder order() const { return order_; }

  /// The one query, visiting nodes in the traversal order chosen at build time.
  template <TraversalSink Sink>
  Hit traverse(const Ray& ray, Sink& sink) const {
    if constexpr (kObservesNothing<Sink> && W == 8) {
      if (fast_) return fast_(*this, ray);
    }
    return traverse_with<Sse2Tag>(ray, sink);
  }
  /// intersect() on each ray, the 8-wide fast path's loop inside its ISA unit.
  void intersect_batch(const Ray* rays, size_t n, Hit* hits) const override {
    if constexpr (W == 8) {
      if (fast_batch_) return fast_batch_(*this, rays, n, hits);
    }
    StructureWithTraversal<WideBvhOf<W>>::intersect_batch(rays, n, hits);
  }
  /// The same query with the kernels of instruction set `Tag` (the ISA units instantiate
  /// it with their tag; everything else with Sse2Tag).
  template <class Tag, TraversalSink Sink>
  Hit traverse_with(const Ray& ray, Sink& sink) const;

 protected:
  Status build_impl(const Scene& scene, const ParamSet& params, BuildControl* control, BuildRecorder* recorder) override;
  /// The node counters, the SAH cost (ct per inner node, the options' leaf cost per leaf, by
  /// area relative to the root) and the builder, traversal, width and kernel lines.
  BuildStats compute_stats() const override;
  /// Same nodes, new boxes bottom-up, the leaves' triangle blocks re-copied from the moved
  /// vertices; subtrees in parallel (wide_bvh_refit.cpp).
  Status refit_impl(const Scene& scene) override;

 private:
  /// Refits the subtree whose node ids are [node, end) (depth-first ids: contiguous).
  void refit_subtree(const Scene& scene, NodeId node, NodeId end);
  void refit_node(const Scene& scene, NodeId node);
  /// Collapses a builder's binary tree into the W-wide tree of least SAH cost
  /// (wide_collapse.h); `recorder` (optional) gets its Collapse steps.
  void collapse(const Scene& scene, const BuildTree& tree, BuildRecorder* recorder);
  void clear();
  struct Layout;  // a subtree being emitted by one task (wide_bvh.cpp)

  /// A pending node of an observed traversal: its id and interval are reported.
  struct Pending {
    ChildRef ref;
    NodeId node;
    float t0, t1;  ///< the ray's interval inside the node's box
  };
  /// A pending node of the fast path: the reference and the entry distance, 16 bytes
  /// instead of 24, as nothing reads the id or the exit distance.
  struct FastPending {
    ChildRef ref;
    float t0;
  };
  template <TraversalSink Sink>
  using PendingFor = std::conditional_t<kObservesNothing<Sink>, FastPending, Pending>;
  template <TraversalSink Sink>
  static PendingFor<Sink> pending(ChildRef ref, NodeId node, float t0, float t1) {
    if constexpr (kObservesNothing<Sink>) return {ref, t0};
    else return {ref, node, t0, t1};
  }
  static NodeId node_of(const FastPending&) { return kNoNode; }
  static NodeId node_of(const Pending& p) { return p.node; }
  static float exit_of(const FastPending&) { return 0.0f; }
  static float exit_of(const Pending& p) { return p.t1; }

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
  /// Where a traversal's prefetches point: the two arrays' addresses, read once per query
  /// (through members, every store of the loop might have changed them).
  struct PrefetchBases {
    uintptr_t nodes, blocks;
  };
  PrefetchBases prefetch_bases() const {
    return {reinterpret_cast<uintptr_t>(nodes_.data()), reinterpret_cast<uintptr_t>(blocks_.data())};
  }
  /// Starts fetching what a pushed child will read when it is popped: the first 192 bytes of
  /// its node or its leaf's first block. The address is selected with a mask, not a branch
  /// on the kind (the compiler turned the plain ?: into a mispredicted branch).
  ACCEL_FORCE_INLINE static void prefetch(ChildRef r, PrefetchBases at) {
    // Integer arithmetic: the address not taken may lie outside its array.
    const uintptr_t leaf = at.blocks + uintptr_t(ref_first(r)) * sizeof(TriangleBlock);
    const uintptr_t inner = at.nodes + uintptr_t(uint32_t(r)) * sizeof(Node);
    const uintptr_t is_leaf = uintptr_t(0) - uintptr_t(ref_is_leaf(r));
    const char* p = reinterpret_cast<const char*>((leaf & is_leaf) | (inner & ~is_leaf));
    for (int k = 0; k < 3; ++k) _mm_prefetch(p + 64 * k, _MM_HINT_T0);
  }
  /// Bits set in an 8-bit mask: the POPCNT instruction in the AVX units (compiled with
  /// -mpopcnt), a few shifts in the SSE2 baseline, which may not have it.
  template <class Tag>
  ACCEL_FORCE_INLINE static int popcount8(unsigned m) {
#if defined(__POPCNT__)
    if constexpr (!std::is_same_v<Tag, Sse2Tag>) return __builtin_popcount(m);
#endif
    m = m - ((m >> 1) & 0x55u);
    m = (m & 0x33u) + ((m >> 2) & 0x33u);
    return int((m + (m >> 4)) & 0x0fu);
  }
  // Each pop pushes at most W children in place of one node: W - 1 per level, plus slack.
  static constexpr int kStackSize = (W - 1) * kMaxBvhDepth + W;

  template <class Tag, TraversalSink Sink>
  void report_misses(uint32_t wide, int hit_mask, const WideRayFor<Tag>& wray, float tmin, Sink& sink) const;
  /// Tests a leaf's triangles four at a time. Lanes are taken in order with the same rule
  /// as test_triangle (first hit, then strictly closer), so ties resolve as in the binary tree.
  template <TraversalSink Sink>
  ACCEL_FORCE_INLINE void test_leaf(ChildRef r, const TriangleTester& tester, Hit& closest, Sink& sink) const {
    const TriangleBlock* block = blocks_.data() + ref_first(r);
    for (uint32_t left = ref_count(r); left > 0; left -= std::min(left, 4u), ++block) {
      const int lanes = left >= 4 ? 0xf : (1 << left) - 1;
      alignas(16) float t[4], u[4], v[4];
      const int hits = tester.intersect4(*block, lanes, closest.t, t, u, v);
      // The fast path looks at hit lanes only; an observer sees every test.
      const int seen = kObservesNothing<Sink> ? hits : lanes;
      for (int rest = seen; rest; rest &= rest - 1) {  // set bits only: no branch per empty lane
        const int lane = __builtin_ctz(unsigned(rest));
        const bool hit = (hits >> lane) & 1;
        take_triangle_result(block->prim[lane], hit,
                             hit ? TriangleHit{t[lane], u[lane], v[lane]} : TriangleHit{kInf, 0.0f, 0.0f}, closest,
                             sink);
      }
    }
  }
  /// Templated on the ISA tag although it runs no SIMD code: a copy the compiler emits in
  /// an ISA unit (it may not inline, e.g. under the sanitizers) must carry that unit's name.
  template <class Tag, TraversalSink Sink>
  bool enter_root(const Ray& ray, const BoxTester& box_ray, const Hit& closest, Sink& sink, Pending* root) const;
  /// Makes its SIMD ray constants itself: a local the compiler keeps in registers or its
  /// own frame (through a reference, every store of the loop might alias them). Inlined into
  /// the query: as a call of its own, its saves and restores cost every ray ~25 instructions.
  template <class Tag, TraversalSink Sink>
  ACCEL_FORCE_INLINE void traverse_stack(const Ray& ray, const BoxTester& box_ray, const TriangleTester& tester,
                                         bool nearest_first, const Pending& root, Hit& closest, Sink& sink) const;
  template <class Tag, TraversalSink Sink>
  void traverse_pqueue(const Ray& ray, const WideRayFor<Tag>& wray, const TriangleTester& tester, Pending root,
                       Hit& closest, Sink& sink) const;

  ChildRef ref_of(NodeId id) const {
    return entries_[id].leaf() ? leaf_ref(entries_[id].index, entries_[id].count) : entries_[id].index;
  }

  std::vector<Node> nodes_;
  std::vector<std::array<NodeId, W>> child_ids_;  ///< by Node: the children's node ids, kNoNode if unused
  std::vector<Entry> entries_;     ///< by node id
  std::vector<Aabb> boxes_;        ///< by node id: the node's own box (the root's is tested alone)
  std::vector<uint16_t> depth_;    ///< by node id
  std::vector<TriangleBlock> blocks_;  ///< leaf triangles in leaf order, four per block
  size_t prim_count_ = 0;      ///< triangle references in the leaves
  size_t triangle_count_ = 0;  ///< distinct triangles among them (fewer after sbvh's spatial splits)
  BvhBuildOptions options_;
  TraversalOrder order_ = TraversalOrder::Ordered;
  /// ref_of(0), kept apart: read from the entries on every query, it cost a load and a
  /// branch on the root's kind (query entry and exit, bench/profile_rays.sh).
  ChildRef root_ref_ = 0;
  FastWideTraversal fast_ = nullptr;  ///< set for 8-wide trees on AVX2 / AVX-512 CPUs (stack orders)
  FastWideBatch fast_batch_ = nullptr;  ///< set with fast_
  Isa fast_isa_ = Isa::Sse2;
};

/// The 4-wide SSE2 layout (width=4) and the 8-wide one (width=8).
using WideBvh = WideBvhOf<4>;
using WideBvh8 = WideBvhOf<8>;
extern template class WideBvhOf<4>;
extern template class WideBvhOf<8>;

// ============================================================================
// [SECTION] Traversals
// ============================================================================

template <int W>
template <class Tag, TraversalSink Sink>
void WideBvhOf<W>::report_misses(uint32_t wide, int hit_mask, const WideRayFor<Tag>& wray, float tmin,
                                 Sink& sink) const {
  if constexpr (kObservesNothing<Sink>) {
    return;  // nothing to count: the fast path skips the loop entirely
  } else {
    int beyond_mask = 0;
    alignas(32) float a[W], b[W];
    if constexpr (Sink::kRecords) beyond_mask = intersect_children(nodes_[wide], wray, tmin, kInf, a, b);
    for (int s = 0; s < W; ++s) {
      const NodeId child = child_ids_[wide][s];
      if ((hit_mask >> s) & 1 || child == kNoNode) continue;
      const bool beyond = (beyond_mask >> s) & 1;
      sink.cull(child, depth_[child], beyond ? CullReason::BeyondClosestHit : CullReason::MissedBounds,
                beyond ? a[s] : 0.0f);
    }
  }
}

template <int W>
template <class Tag, TraversalSink Sink>
bool WideBvhOf<W>::enter_root(const Ray& ray, const BoxTester& box_ray, const Hit& closest, Sink& sink,
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

template <int W>
template <class Tag, TraversalSink Sink>
Hit WideBvhOf<W>::traverse_with(const Ray& ray, Sink& sink) const {
  Hit closest = no_hit(ray);
  if (!entries_.empty()) {
    const TriangleTester tester(ray, this->kernel_);
    const BoxTester box_ray(ray);
    Pending root{root_ref_, 0, ray.tmin, closest.t};
    // The fast path enters the root without testing its box: the root's children are
    // tested at once against the same [tmin, tmax], so a ray that misses the root's box
    // misses them all and the answer is the same, while the scalar box test cost every ray
    // ~40 instructions (callgrind). Observed queries test it, to report its visit or cull.
    if (kObservesNothing<Sink> || enter_root<Tag>(ray, box_ray, closest, sink, &root)) {
      // The priority queue runs on SSE2 kernels only (its heap, not the box test, is what
      // it spends its time on): its std::vector code is compiled once, for the baseline,
      // and no ISA unit emits a copy of it. The ISA units are only called for stack orders.
      if constexpr (std::is_same_v<Tag, Sse2Tag>) {
        if (order_ == TraversalOrder::PriorityQueue) {
          traverse_pqueue<Tag>(ray, WideRayFor<Tag>(box_ray), tester, root, closest, sink);
          return finish_query(closest, sink);
        }
      }
      traverse_stack<Tag>(ray, box_ray, tester, order_ == TraversalOrder::Ordered, root, closest, sink);
    }
  }
  return finish_query(closest, sink);
}

/// Depth-first. All W child boxes are tested at their parent; the loop descends straight
/// into the first hit child (the nearest one when `nearest_first`, i.e. ordered; the first
/// in tree order for dfs) and pushes the others, farthest first. A popped node entered
/// beyond the closest hit found meanwhile is skipped. Descending without a push and pop is
/// what makes the wide layout pay off (the child was tested against the current closest hit
/// a moment ago). One and two hit children, the common cases, take short paths; more are
/// ranked by (entry distance, slot) without branches, the order of a stable sort by
/// distance, so equal distances keep tree order as in the binary traversal. The observed
/// and the fast path run this same code (only the pending entries differ in size), so they
/// visit the same nodes in the same order.
template <int W>
template <class Tag, TraversalSink Sink>
ACCEL_FORCE_INLINE void WideBvhOf<W>::traverse_stack(const Ray& ray, const BoxTester& box_ray,
                                                     const TriangleTester& tester, bool nearest_first,
                                                     const Pending& root, Hit& closest, Sink& sink) const {
  const WideRayFor<Tag> wray(box_ray);
  using Item = PendingFor<Sink>;
  Item stack[kStackSize];
  int top = 0;
  const float tmin = ray.tmin;  // a local: the loop's stores cannot alias it
  const PrefetchBases bases = prefetch_bases();
  // A local: read through the member, the node array's address was loaded again at every
  // node (a store to `closest` might have changed it, for all the compiler knows).
  const Node* const nodes = nodes_.data();
  Item cur = pending<Sink>(root.ref, root.node, root.t0, root.t1);
  for (;;) {
    sink.visit(node_of(cur), node_depth<Sink>(node_of(cur)), cur.t0, exit_of(cur));
    if (ref_is_leaf(cur.ref)) {
      test_leaf(cur.ref, tester, closest, sink);
    } else {
      const uint32_t w = uint32_t(cur.ref);
      const Node& n = nodes[w];
      alignas(32) float t0[W], t1[W];
      int mask = intersect_children(n, wray, tmin, closest.t, t0, t1);
      report_misses<Tag>(w, mask, wray, tmin, sink);
      const auto child = [&](int s) { return pending<Sink>(n.ref[s], child_id<Sink>(w, s), t0[s], t1[s]); };
      const auto push = [&](int s) {
        stack[top++] = child(s);
        prefetch(n.ref[s], bases);
        sink.push(child_id<Sink>(w, s), node_depth<Sink>(child_id<Sink>(w, s)), t0[s]);
      };
      if (mask != 0) {
        const int first = __builtin_ctz(unsigned(mask));
        mask &= mask - 1;
        if (mask == 0) {  // one hit child: descend, nothing to order
          cur = child(first);
          continue;
        }
        const int second = __builtin_ctz(unsigned(mask));
        mask &= mask - 1;
        if (mask == 0) {  // two: the nearer first (ties: tree order), the other pushed
          const bool swap = nearest_first && t0[second] < t0[first];
          push(swap ? first : second);
          cur = child(swap ? second : first);
          continue;
        }
        // Three or more: each hit child's rank in (entry distance, slot) order, which is
        // the order a stable sort by distance gives (dfs: slot order), computed without
        // data-dependent branches -- the insertion sort's compares were the most
        // mispredicted branches of the traversal (callgrind --branch-sim). Rank r goes to
        // stack[top + hits - 1 - r], so the farthest lands deepest and rank 0, the child to
        // descend into, just above the new top, where it is read back from.
        const int hit_mask = mask | (1 << first) | (1 << second);
        const int hits = popcount8<Tag>(unsigned(hit_mask));
        Item* const dst = stack + top + hits - 1;
        for (int rest = hit_mask; rest; rest &= rest - 1) {
          const int s = __builtin_ctz(unsigned(rest));
          const int before = nearest_first ? nearer_slots(Tag{}, std::integral_constant<int, W>{}, t0, s) & hit_mask
                                           : hit_mask & ((1 << s) - 1);
          *(dst - popcount8<Tag>(unsigned(before))) = child(s);
          prefetch(n.ref[s], bases);
        }
        cur = *dst;
        if constexpr (!kObservesNothing<Sink>)  // the pushes in stack order, farthest first
          for (int k = top; k < top + hits - 1; ++k)
            sink.push(node_of(stack[k]), node_depth<Sink>(node_of(stack[k])), stack[k].t0);
        top += hits - 1;
        continue;
      }
    }
    // Nothing to descend into: resume at the top of the stack.
    for (;;) {
      if (top == 0) return;
      cur = stack[--top];
      sink.pop(node_of(cur), node_depth<Sink>(node_of(cur)), cur.t0);
      if (cur.t0 <= closest.t) break;
      sink.cull(node_of(cur), node_depth<Sink>(node_of(cur)), CullReason::BeyondClosestHit, cur.t0);
    }
  }
}

/// The lecture's priority queue by entry distance, over wide nodes: stops when the nearest
/// pending node is farther than the closest hit.
template <int W>
template <class Tag, TraversalSink Sink>
void WideBvhOf<W>::traverse_pqueue(const Ray& ray, const WideRayFor<Tag>& wray, const TriangleTester& tester,
                                   Pending root, Hit& closest, Sink& sink) const {
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
    const Node& n = nodes_[w];
    alignas(32) float t0[W], t1[W];
    const int mask = intersect_children(n, wray, ray.tmin, closest.t, t0, t1);
    report_misses<Tag>(w, mask, wray, ray.tmin, sink);
    for (int s = 0; s < W; ++s)
      if ((mask >> s) & 1) push({n.ref[s], child_id<Sink>(w, s), t0[s], t1[s]});
  }
}

}  // namespace accel
