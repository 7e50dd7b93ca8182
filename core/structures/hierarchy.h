#pragma once
// The binary bounding volume hierarchy shared by the AABB tree's binary layout (bvh.h,
// BinaryBvh) and the sphere tree (sphere_tree.h): the same builders (bvh_builders.h), the
// same flat node layout and the same three traversal orders of the lecture, written once as
// templates over the bounding volume. The 4-wide AABB layout (wide_bvh.h) shares the
// parameters and the orders, not the nodes. Index:
//   [SECTION] Parameters and traversal order
//   [SECTION] Node layout
//   [SECTION] Hierarchy: build, stats, views
//   [SECTION] Traversals: depth-first, ordered, priority queue
//   [SECTION] Refit (defined in hierarchy_refit.cpp)
#include <algorithm>
#include <cmath>
#include <functional>
#include <type_traits>
#include <vector>

#include "structures/bvh_build_types.h"
#include "structures/hierarchy_params.h"
#include "check.h"
#include "structure.h"

namespace accel {

// ============================================================================
// [SECTION] Parameters and traversal order
// ============================================================================

/// The builder and traversal order, as lines of the statistics (every hierarchy layout's).
void add_hierarchy_option_lines(const BvhBuildOptions& options, TraversalOrder order, BuildStats* stats);

/// Refit's precondition, for every hierarchy layout (hierarchy_refit.cpp): the `held`
/// distinct triangles of the structure (each once, or several times under sbvh) are exactly
/// scene.valid_prims(). The layout scans its triangles and passes the first that is out of
/// range or degenerate in `scene` (`bad`, or ~0u if none); the counts settle the rest.
/// The error names `structure` and tells the caller to rebuild.
Status check_refit_prims(const std::string& structure, const Scene& scene, size_t held, uint32_t bad);
/// Whether triangle `prim` may stay in a refitted hierarchy over `scene`.
inline bool refit_keeps(const Scene& scene, uint32_t prim) {
  return prim < scene.triangle_count() && !scene.degenerate(prim);
}

// ============================================================================
// [SECTION] Node layout
// ============================================================================

/// One flattened node, in depth-first order. Inner node: the first child is the next node
/// (this + 1), `index` is the second child, `count` is 0. Leaf: `count` > 0 triangles at
/// prims_[index, index + count). `Volume` is an Aabb (32-byte node) or a BoundingSphere.
template <class Volume>
struct HierarchyNode {
  Volume volume;
  uint32_t index = 0;
  uint32_t count = 0;
  bool leaf() const { return count != 0; }
};
static_assert(sizeof(HierarchyNode<Aabb>) == 32, "BVH nodes should stay 32 bytes (two per cache line)");
static_assert(sizeof(HierarchyNode<BoundingSphere>) == 24);

// ============================================================================
// [SECTION] Hierarchy: build, stats, views
// ============================================================================

/// CRTP base. VolumeRay is the per-ray precomputation of the volume test, constructed from
/// the Ray. Derived provides
///   static Volume fit(const Scene&, const uint32_t* prims, size_t n, const Aabb& box);
///   static float volume_area(const Volume&);      // SAH surface area
///   static bool hit(const Volume&, const VolumeRay&, const Ray&, float tmin, float tmax, float* t0, float* t1);
///   static void describe(const Volume&, NodeView*);
template <class Derived, class Volume, class VolumeRay>
class Hierarchy : public StructureWithTraversal<Derived> {
 public:
  using Node = HierarchyNode<Volume>;

  void for_each_node(const std::function<void(const NodeView&)>& fn) const override {
    for (NodeId i = 0; i < nodes_.size(); ++i) fn(node_view(i));
  }
  NodeView node_view(NodeId id) const override {
    NodeView v;
    if (id >= nodes_.size()) return v;
    const Node& n = nodes_[id];
    v.id = id;
    v.depth = depth_[id];
    v.leaf = n.leaf();
    v.prim_count = n.count;
    v.box = boxes_[id];
    Derived::describe(n.volume, &v);
    return v;
  }
  std::vector<uint32_t> node_prims(NodeId id) const override {
    if (id >= nodes_.size() || !nodes_[id].leaf()) return {};
    return {prims_.begin() + nodes_[id].index, prims_.begin() + nodes_[id].index + nodes_[id].count};
  }
  std::vector<NodeId> node_children(NodeId id) const override {
    if (id >= nodes_.size() || nodes_[id].leaf()) return {};
    return {id + 1, nodes_[id].index};
  }
  TraversalOrder order() const { return order_; }
  const std::vector<Node>& nodes() const { return nodes_; }

  /// The one query of this hierarchy; the traversal order was chosen at build time.
  template <TraversalSink Sink>
  Hit traverse(const Ray& ray, Sink& sink) const {
    Hit closest = no_hit(ray);
    if (!nodes_.empty()) {
      const TriangleTester tester(ray, this->kernel_);
      const VolumeRay vray(ray);
      switch (order_) {
        case TraversalOrder::Dfs: traverse_dfs(ray, vray, tester, closest, sink); break;
        case TraversalOrder::Ordered: traverse_ordered(ray, vray, tester, closest, sink); break;
        case TraversalOrder::PriorityQueue: traverse_pqueue(ray, vray, tester, closest, sink); break;
      }
    }
    return finish_query(closest, sink);
  }

 protected:
  /// Progress: the builder reports the triangles it has placed in leaves as [0,
  /// kTreeBuiltFraction] (and stops when cancelled), then the flattening and volume fitting
  /// report nodes emitted (the sphere tree's fits are a real share of its build). Cancel is
  /// also checked before and after the tree build and per node while flattening.
  Status build_impl(const Scene& scene, const ParamSet& params, BuildControl* control, BuildRecorder* recorder) override {
    if (build_cancelled(control)) return cancel_build();
    const size_t layout_bytes = sizeof(Node) + sizeof(Aabb) + sizeof(uint16_t);  // nodes_, boxes_, depth_
    if (Status fits = check_bvh_memory(this->name(), scene, hierarchy_options(params).build, layout_bytes,
                                       build_memory_limit(control));
        !fits)
      return fits;
    ProgressSpan tree_span(control, 0.0, kTreeBuiltFraction);
    BuildTree tree = build_tree(scene, params, 1, &tree_span, recorder);
    if (build_cancelled(control)) return cancel_build();
    tree_span.finish();
    ProgressSpan span(control, kTreeBuiltFraction, 1.0);
    if (!store_binary(tree, &span, recorder)) return cancel_build();
    if (recorder) recorder->done(nodes_.size());
    return {};
  }

  /// The share of a hierarchy's build reported once the builder's binary tree exists.
  static constexpr double kTreeBuiltFraction = 0.8;

  /// Leaves the hierarchy empty (every ray misses) and returns cancelled_error().
  Error cancel_build() {
    nodes_.clear();
    boxes_.clear();
    depth_.clear();
    prims_.clear();
    triangles_ = 0;
    return cancelled_error();
  }

  /// Reads the options and runs the chosen builder (whose SAH counts `prims_per_test`
  /// triangles per leaf test); the nodes stay empty until store_binary().
  BuildTree build_tree(const Scene& scene, const ParamSet& params, int prims_per_test = 1,
                       ProgressSpan* progress = nullptr, BuildRecorder* recorder = nullptr) {
    scene_ = &scene;
    const HierarchyOptions options = hierarchy_options(params);
    options_ = options.build;
    options_.prims_per_test = prims_per_test;
    order_ = options.traversal;
    nodes_.clear();
    boxes_.clear();
    depth_.clear();
    prims_.clear();
    return build_bvh_tree(scene, options_, progress, recorder);
  }

  /// Flattens the builder's tree into the binary node layout, then fits the volumes
  /// (fit_volumes()), reporting nodes fitted / nodes to `span`. False when cancelled (the
  /// nodes are then incomplete: the caller clears them). A `recorder` receives every
  /// node's fitted volume, by the builder's event id.
  bool store_binary(const BuildTree& tree, ProgressSpan* span = nullptr, BuildRecorder* recorder = nullptr) {
    prims_ = tree.prims;
    // Every builder places each valid triangle (sbvh: at least once; prims_ counts references).
    triangles_ = tree.empty() ? 0 : scene_->valid_prims().size();
    if (tree.empty()) return true;
    nodes_.reserve(tree.nodes.size());
    std::vector<uint32_t> sources;
    flatten(tree, tree.root, 0, recorder ? &sources : nullptr);
    if (!fit_volumes(span)) return false;
    if (recorder) {
      for (size_t i = 0; i < nodes_.size(); ++i) {
        if constexpr (std::is_same_v<Volume, BoundingSphere>)
          recorder->fit(sources[i], boxes_[i], nodes_[i].volume);
        else
          recorder->fit(sources[i], nodes_[i].volume, BoundingSphere{});
      }
    }
    return true;
  }

  BuildStats compute_stats() const override {
    BuildStats s;
    s.nodes = nodes_.size();
    s.prims = triangles_;
    s.prim_references = prims_.size();
    s.memory_bytes = nodes_.size() * sizeof(Node) + prims_.size() * sizeof(uint32_t);
    s.sah_ct = options_.ct;
    s.sah_ci = options_.ci;
    double cost = 0.0;
    const double root_area = nodes_.empty() ? 0.0 : double(Derived::volume_area(nodes_[0].volume));
    for (size_t i = 0; i < nodes_.size(); ++i) {
      const double rel = root_area > 0.0 ? double(Derived::volume_area(nodes_[i].volume)) / root_area : 1.0;
      if (nodes_[i].leaf()) {
        s.add_leaf(nodes_[i].count);
        cost += double(options_.leaf_cost(nodes_[i].count)) * rel;
      } else {
        cost += double(options_.ct) * rel;
      }
      s.max_depth = std::max(s.max_depth, int(depth_[i]));
    }
    if (!nodes_.empty()) s.sah_cost = cost;
    add_option_lines(&s);
    return s;
  }

  /// The builder and traversal order, as lines of the statistics.
  void add_option_lines(BuildStats* s) const { add_hierarchy_option_lines(options_, order_, s); }

  const Scene* scene_ = nullptr;
  BvhBuildOptions options_;
  TraversalOrder order_ = TraversalOrder::Ordered;
  std::vector<Node> nodes_;
  std::vector<Aabb> boxes_;        ///< subtree boxes, for drawing (the sphere tree's volume is a sphere)
  std::vector<uint16_t> depth_;
  std::vector<uint32_t> prims_;
  size_t triangles_ = 0;  ///< distinct triangles in prims_ (fewer than prims_.size() after spatial splits)

 private:
  /// Depth-first flattening of the topology (the first child directly follows its
  /// parent); the volumes come after, from fit_volumes().
  /// `sources` (recorded builds) receives each flat node's event id.
  uint32_t flatten(const BuildTree& tree, uint32_t src, int depth, std::vector<uint32_t>* sources) {
    const uint32_t dst = uint32_t(nodes_.size());
    const BuildNode& b = tree.nodes[src];
    if (sources) sources->push_back(tree.event_id(src));
    nodes_.emplace_back();
    boxes_.push_back(b.box);
    depth_.push_back(uint16_t(depth));
    ACCEL_CHECK(depth < kMaxBvhDepth);
    if (b.count) {
      nodes_[dst].index = b.first;
      nodes_[dst].count = b.count;
      return dst;
    }
    flatten(tree, b.left, depth + 1, sources);
    nodes_[dst].index = flatten(tree, b.right, depth + 1, sources);
    return dst;
  }

  /// Fits every node's volume to all triangles below it: a box is its own (set by
  /// flatten()); spheres go through fit_levels(). Reports nodes fitted / nodes to `span`
  /// between batches; false when cancelled. Defined in hierarchy_refit.cpp, which fits
  /// refitted volumes the same way.
  bool fit_volumes(ProgressSpan* span);

  // ==========================================================================
  // [SECTION] Traversals
  // ==========================================================================

  struct Pending {
    uint32_t node;
    uint32_t depth;
    float t0, t1;  ///< the ray's interval inside the node's volume (when known)
  };
  static constexpr int kStackSize = kMaxBvhDepth + 4;

  /// Tests a node's volume against [tmin, closest.t]; on a miss tells the sink why.
  template <TraversalSink Sink>
  bool test_volume(uint32_t node, uint32_t depth, const Ray& ray, const VolumeRay& vray,
                   const Hit& closest, Sink& sink, float* t0, float* t1) const {
    if (Derived::hit(nodes_[node].volume, vray, ray, ray.tmin, closest.t, t0, t1)) return true;
    if constexpr (Sink::kRecords) {
      float a, b;
      const bool beyond = Derived::hit(nodes_[node].volume, vray, ray, ray.tmin, kInf, &a, &b);
      sink.cull(node, int(depth), beyond ? CullReason::BeyondClosestHit : CullReason::MissedBounds, beyond ? a : 0.0f);
    } else {
      sink.cull(node, int(depth), CullReason::MissedBounds, 0.0f);
    }
    return false;
  }

  template <TraversalSink Sink>
  void test_leaf(const Node& n, const TriangleTester& tester, Hit& closest, Sink& sink) const {
    for (uint32_t k = n.index; k < n.index + n.count; ++k) test_triangle(*scene_, tester, prims_[k], closest, sink);
  }

  /// Lecture: pure DFS -- the visiting order depends only on the tree's topology.
  template <TraversalSink Sink>
  void traverse_dfs(const Ray& ray, const VolumeRay& vray, const TriangleTester& tester,
                    Hit& closest, Sink& sink) const {
    Pending stack[kStackSize];
    int top = 0;
    stack[top++] = {0, 0, ray.tmin, ray.tmin};
    sink.push(0, 0, ray.tmin);
    while (top > 0) {
      const Pending p = stack[--top];
      sink.pop(p.node, int(p.depth), p.t0);
      float t0, t1;
      if (!test_volume(p.node, p.depth, ray, vray, closest, sink, &t0, &t1)) continue;
      sink.visit(p.node, int(p.depth), t0, t1);
      const Node& n = nodes_[p.node];
      if (n.leaf()) {
        test_leaf(n, tester, closest, sink);
        continue;
      }
      // Right first, so the left (first) child is popped next: tree order.
      stack[top++] = {n.index, p.depth + 1, t0, t0};
      sink.push(n.index, int(p.depth) + 1, t0);
      stack[top++] = {p.node + 1, p.depth + 1, t0, t0};
      sink.push(p.node + 1, int(p.depth) + 1, t0);
    }
  }

  /// Nearer child first: both children's volumes are tested at the parent, the farther one
  /// waits on the stack with its entry distance and is skipped if a hit closer than that
  /// has been found by the time it is popped.
  template <TraversalSink Sink>
  void traverse_ordered(const Ray& ray, const VolumeRay& vray, const TriangleTester& tester,
                        Hit& closest, Sink& sink) const {
    Pending stack[kStackSize];
    int top = 0;
    float t0, t1;
    if (!test_volume(0, 0, ray, vray, closest, sink, &t0, &t1)) return;
    stack[top++] = {0, 0, t0, t1};
    sink.push(0, 0, t0);
    while (top > 0) {
      const Pending p = stack[--top];
      sink.pop(p.node, int(p.depth), p.t0);
      if (p.t0 > closest.t) {
        sink.cull(p.node, int(p.depth), CullReason::BeyondClosestHit, p.t0);
        continue;
      }
      sink.visit(p.node, int(p.depth), p.t0, p.t1);
      const Node& n = nodes_[p.node];
      if (n.leaf()) {
        test_leaf(n, tester, closest, sink);
        continue;
      }
      const uint32_t left = p.node + 1, right = n.index, d = p.depth + 1;
      float l0, l1, r0, r1;
      const bool hit_l = test_volume(left, d, ray, vray, closest, sink, &l0, &l1);
      const bool hit_r = test_volume(right, d, ray, vray, closest, sink, &r0, &r1);
      if (hit_l && hit_r) {
        const bool left_first = l0 <= r0;
        const Pending near = left_first ? Pending{left, d, l0, l1} : Pending{right, d, r0, r1};
        const Pending far = left_first ? Pending{right, d, r0, r1} : Pending{left, d, l0, l1};
        stack[top++] = far;
        sink.push(far.node, int(d), far.t0);
        stack[top++] = near;
        sink.push(near.node, int(d), near.t0);
      } else if (hit_l || hit_r) {
        stack[top++] = hit_l ? Pending{left, d, l0, l1} : Pending{right, d, r0, r1};
        sink.push(stack[top - 1].node, int(d), stack[top - 1].t0);
      }
    }
  }

  /// Lecture: a priority queue of nodes keyed by the distance along the ray to their volume.
  /// Its warning holds: the nearest volume need not hold the nearest triangle, so the search
  /// continues until the nearest pending volume is farther than the closest hit.
  template <TraversalSink Sink>
  void traverse_pqueue(const Ray& ray, const VolumeRay& vray, const TriangleTester& tester,
                       Hit& closest, Sink& sink) const {
    // The queue can outgrow any fixed stack; a per-thread buffer avoids allocating per ray.
    thread_local std::vector<Pending> heap;
    heap.clear();
    const auto later = [](const Pending& a, const Pending& b) { return a.t0 > b.t0 || (a.t0 == b.t0 && a.node > b.node); };
    const auto push = [&](const Pending& p) {
      heap.push_back(p);
      std::push_heap(heap.begin(), heap.end(), later);
      sink.push(p.node, int(p.depth), p.t0);
    };
    float t0, t1;
    if (!test_volume(0, 0, ray, vray, closest, sink, &t0, &t1)) return;
    push({0, 0, t0, t1});
    while (!heap.empty()) {
      std::pop_heap(heap.begin(), heap.end(), later);
      const Pending p = heap.back();
      heap.pop_back();
      sink.pop(p.node, int(p.depth), p.t0);
      if (p.t0 > closest.t) {
        // Every pending node is at least this far: all of them are skipped.
        sink.cull(p.node, int(p.depth), CullReason::BeyondClosestHit, p.t0);
        if constexpr (Sink::kRecords) {
          std::sort_heap(heap.begin(), heap.end(), later);
          for (auto it = heap.rbegin(); it != heap.rend(); ++it)
            sink.cull(it->node, int(it->depth), CullReason::BeyondClosestHit, it->t0);
        }
        break;
      }
      sink.visit(p.node, int(p.depth), p.t0, p.t1);
      const Node& n = nodes_[p.node];
      if (n.leaf()) {
        test_leaf(n, tester, closest, sink);
        continue;
      }
      const uint32_t d = p.depth + 1;
      for (uint32_t child : {p.node + 1, n.index}) {
        float c0, c1;
        if (test_volume(child, d, ray, vray, closest, sink, &c0, &c1)) push({child, d, c0, c1});
      }
    }
  }

  // ==========================================================================
  // [SECTION] Refit (defined in hierarchy_refit.cpp, instantiated for BinaryBvh and SphereTree)
  // ==========================================================================

 protected:
  /// Same nodes, new volumes: boxes bottom-up (a leaf's from its triangles, an inner node's
  /// the union of its children's), then each volume fitted as flatten() fits it, so
  /// refitting unmoved vertices reproduces the build's volumes. Subtrees in parallel.
  Status refit_impl(const Scene& scene) override;

 private:
  /// The triangle range [first, end) of prims_ below a node (what fit_volumes() fits to).
  struct PrimRange {
    uint32_t first, end;
  };
  /// Refits the subtree whose nodes are [node, end) (depth-first layout: a subtree is
  /// contiguous); `ranges` (null when Volume is the box itself) receives each node's range.
  void refit_subtree(const Scene& scene, uint32_t node, uint32_t end, PrimRange* ranges);
  /// Sphere trees: fits the volumes level by level, deepest first (sphere_tree.h: small
  /// subtrees by Derived::fit over their vertices, larger ones by Derived::fit_inner from
  /// their fitted subtrees). Reports levels done to `span`; false when cancelled.
  bool fit_levels(const PrimRange* ranges, ProgressSpan* span);
  void refit_node(const Scene& scene, uint32_t node, PrimRange* ranges);
};

}  // namespace accel
