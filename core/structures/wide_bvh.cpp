#include "structures/wide_bvh.h"

#include <cstring>

#include "check.h"
#include "parallel.h"
#include "structures/wide_bvh_isa.h"
#include "structures/wide_collapse.h"

namespace accel {

template <int W>
void WideBvhOf<W>::clear() {
  nodes_.clear();
  entries_.clear();
  boxes_.clear();
  depth_.clear();
  child_ids_.clear();
  blocks_.clear();
  prim_count_ = 0;
  triangle_count_ = 0;
}

template <int W>
Status WideBvhOf<W>::build_impl(const Scene& scene, const ParamSet& params, BuildControl* control, BuildRecorder* recorder) {
  // Progress as in the binary layouts (hierarchy.h): the builder reports the triangles it
  // has placed as [0, 0.8] and stops when cancelled; then the collapse (parallel, a small
  // share of the build) ends at 1.
  clear();
  if (build_cancelled(control)) return cancelled_error();
  const HierarchyOptions options = hierarchy_options(params);
  // Per binary node: its entry, box and depth, its share of a wide node (W - 1 binary
  // inner nodes collapse into one at best) and the collapse's cost table.
  const size_t layout_bytes = sizeof(Entry) + sizeof(Aabb) + sizeof(uint16_t) +
                              (sizeof(Node) + sizeof(std::array<NodeId, W>)) / (W - 1) +
                              WideCollapse<W>::kBytesPerNode;
  if (Status fits = check_bvh_memory(name(), scene, options.build, layout_bytes, build_memory_limit(control));
      !fits)
    return fits;
  options_ = options.build;
  // The wide layouts test a leaf's triangles four at a time: the SAH builders know it.
  options_.prims_per_test = 4;
  order_ = options.traversal;
  // The fast path of an 8-wide tree runs the best kernel this CPU has; the priority queue
  // keeps the SSE2 one (its heap, not the box test, is what it spends its time on).
  fast_ = nullptr;
  fast_batch_ = nullptr;
  fast_isa_ = Isa::Sse2;
  if constexpr (W == 8) {
    if (order_ != TraversalOrder::PriorityQueue) {
      fast_isa_ = active_isa();
      const FastWidePaths paths = fast_wide8_paths(fast_isa_);
      fast_ = paths.one;
      fast_batch_ = paths.batch;
    }
  }
  ProgressSpan tree_span(control, 0.0, 0.8);
  const BuildTree tree = build_bvh_tree(scene, options_, &tree_span, recorder);
  if (build_cancelled(control)) return cancelled_error();
  tree_span.finish();
  if (build_cancelled(control)) return cancelled_error();  // e.g. cancelled from the callback
  collapse(scene, tree, recorder);
  root_ref_ = entries_.empty() ? 0 : ref_of(0);
  if (recorder) recorder->done(entries_.size());
  return {};
}

// ----------------------------------------------------------------------------
// Collapse, in parallel: the SAH-optimal choice of each wide node's children is solved
// first (wide_collapse.h); then the top of the binary tree is planned serially; every subtree
// below it is counted by its own task, placed at its pre-order offsets from the counts, and
// emitted by its task straight into the final arrays there. The result is the serial
// emission's, for any thread count: each node's children depend only on its binary
// subtree, and the offsets follow from the subtrees' sizes. (Emitting each task into arrays
// of its own and copying them into place cost a large scene's cold build a sixth of its
// time in fresh memory: issue #51, docs/performance.md.)
// ----------------------------------------------------------------------------
namespace {

/// Binary subtrees of at least this many nodes are planned at the top; smaller ones (and
/// leaves) are one task each.
constexpr uint32_t kCollapseTaskNodes = 2048;

/// Records the collapse steps: the same choices the collapse makes, wide node by wide node
/// from the root, each one's openings in pre-order.
template <int W>
void record_collapse(const BuildTree& tree, const WideCollapse<W>& choice, BuildRecorder& recorder) {
  std::vector<uint32_t> stack{tree.root};
  while (!stack.empty()) {
    const uint32_t src = stack.back();
    stack.pop_back();
    if (tree.nodes[src].count) continue;
    uint32_t kids[W];
    const int n = choice.children(src, kids, recorder);
    for (int s = n; s-- > 0;) stack.push_back(kids[s]);
  }
}

/// The top of the binary tree, planned serially: wide nodes over binary subtrees of
/// kCollapseTaskNodes or more. A child below that size (or a leaf) becomes a task.
template <int W>
struct CollapsePlan {
  struct TopNode {
    uint32_t src;
    int depth, n;
    uint32_t kids[W];
    int32_t child[W];  ///< >= 0: index into `top`; < 0: task -child - 1
  };
  struct Task {
    uint32_t src;
    int depth;
  };
  std::vector<TopNode> top;
  std::vector<Task> tasks;

  /// Plans the wide node of binary node `src` at `depth` and, recursively, its large
  /// children; returns its index in `top`.
  int32_t plan(const BuildTree& tree, const WideCollapse<W>& choice, const std::vector<uint32_t>& size, uint32_t src,
               int depth) {
    const int32_t index = int32_t(top.size());
    top.push_back({src, depth, 0, {}, {}});
    TopNode node = top.back();
    NullBuildSink no_steps;
    node.n = choice.children(src, node.kids, no_steps);
    for (int s = 0; s < node.n; ++s) {
      const uint32_t kid = node.kids[s];
      if (!tree.nodes[kid].count && size[kid] >= kCollapseTaskNodes) {
        node.child[s] = plan(tree, choice, size, kid, depth + 1);
      } else {
        node.child[s] = -int32_t(tasks.size()) - 1;
        tasks.push_back({kid, depth + 1});
      }
    }
    top[size_t(index)] = node;
    return index;
  }
};

/// Where the nodes go in the final arrays: entries, wide nodes and triangle blocks.
struct CollapseOffsets {
  uint32_t entry = 0, node = 0, block = 0;
};

/// Pre-order placement: a top node, then each child's subtree in slot order.
struct CollapsePlacement {
  std::vector<CollapseOffsets> part_at;  ///< by task: where its subtree starts
  std::vector<NodeId> top_id;            ///< by top node: its node id
  std::vector<uint32_t> top_wide;        ///< by top node: its wide node
  CollapseOffsets total;                 ///< the arrays' sizes

  /// Places top node `t` and everything below it (`parts`: each task's counts).
  template <int W>
  void place(const CollapsePlan<W>& plan, const std::vector<CollapseOffsets>& parts, int32_t t) {
    top_id[size_t(t)] = total.entry++;
    top_wide[size_t(t)] = total.node++;
    const auto& node = plan.top[size_t(t)];
    for (int s = 0; s < node.n; ++s) {
      if (node.child[s] >= 0) {
        place(plan, parts, node.child[s]);
        continue;
      }
      const size_t k = size_t(-node.child[s] - 1);
      part_at[k] = total;
      total.entry += parts[k].entry;
      total.node += parts[k].node;
      total.block += parts[k].block;
    }
  }
};

}  // namespace

/// The arrays of WideBvhOf being filled: sized for the whole tree first, then every task
/// emits its subtree into them at its own offsets.
template <int W>
struct WideBvhOf<W>::Layout {
  std::vector<Node> nodes;
  std::vector<std::array<NodeId, W>> child_ids;
  std::vector<Entry> entries;
  std::vector<Aabb> boxes;
  std::vector<uint16_t> depth;
  std::vector<TriangleBlock> blocks;

  /// What the emit of binary node `src`'s subtree adds: its entries, wide nodes and blocks.
  static CollapseOffsets count(const BuildTree& tree, const WideCollapse<W>& choice, uint32_t src) {
    CollapseOffsets n;
    add_count(tree, choice, src, n);
    return n;
  }

  /// The subtree of binary node `src` at `depth`, in depth-first order, from `at` on (which
  /// it advances past the subtree); returns its node id.
  NodeId emit(const Scene& scene, const BuildTree& tree, const WideCollapse<W>& choice, uint32_t src,
              int depth_of_src, CollapseOffsets& at) {
    ACCEL_CHECK(depth_of_src < kMaxBvhDepth);  // collapsing only makes the tree shallower
    const NodeId id = at.entry++;
    const BuildNode& b = tree.nodes[src];
    boxes[id] = b.box;
    depth[id] = uint16_t(depth_of_src);
    if (b.count) {
      entries[id] = {add_blocks(scene, tree.prims.data() + b.first, b.count, at), b.count};
      return id;
    }
    uint32_t kids[W];
    NullBuildSink no_steps;
    const int n = choice.children(src, kids, no_steps);
    const uint32_t w = at.node++;
    entries[id] = {w, 0};
    nodes[w] = empty_node();
    child_ids[w] = no_children();
    for (int s = 0; s < n; ++s) {
      const NodeId child = emit(scene, tree, choice, kids[s], depth_of_src + 1, at);
      set_slot(nodes[w], s, tree.nodes[kids[s]].box, ref_of(child));
      child_ids[w][s] = child;
    }
    return id;
  }

  ChildRef ref_of(NodeId id) const {
    return entries[id].leaf() ? leaf_ref(entries[id].index, entries[id].count) : entries[id].index;
  }

  /// A node whose W slots are unused (empty boxes, empty leaves).
  static Node empty_node() {
    Node node;
    for (int s = 0; s < W; ++s) {
      for (int axis = 0; axis < 3; ++axis) {
        node.bounds[axis][s] = kInf;
        node.bounds[3 + axis][s] = -kInf;
      }
      node.ref[s] = leaf_ref(0, 0);
    }
    return node;
  }
  static std::array<NodeId, W> no_children() {
    std::array<NodeId, W> ids;
    ids.fill(kNoNode);
    return ids;
  }
  static void set_slot(Node& node, int s, const Aabb& box, ChildRef ref) {
    for (int axis = 0; axis < 3; ++axis) {
      node.bounds[axis][s] = box.min[axis];
      node.bounds[3 + axis][s] = box.max[axis];
    }
    node.ref[s] = ref;
  }

  /// Sized for the whole tree, every part placed.
  void resize(const CollapseOffsets& total) {
    entries.resize(total.entry);
    boxes.resize(total.entry);
    depth.resize(total.entry);
    nodes.resize(total.node);
    child_ids.resize(total.node);
    blocks.resize(total.block);
  }

  /// The top nodes, pointing at their children's global ids; their child references wait
  /// until every entry is final (link_top_nodes()).
  void write_top_nodes(const BuildTree& tree, const CollapsePlan<W>& plan, const CollapsePlacement& at) {
    for (size_t t = 0; t < plan.top.size(); ++t) {
      const auto& node = plan.top[t];
      const NodeId id = at.top_id[t];
      const uint32_t w = at.top_wide[t];
      entries[id] = {w, 0};
      boxes[id] = tree.nodes[node.src].box;
      depth[id] = uint16_t(node.depth);
      nodes[w] = empty_node();
      child_ids[w] = no_children();
      for (int s = 0; s < node.n; ++s) {
        // A task's root is its local node 0.
        child_ids[w][s] = node.child[s] >= 0 ? at.top_id[size_t(node.child[s])]
                                             : at.part_at[size_t(-node.child[s] - 1)].entry;
        set_slot(nodes[w], s, tree.nodes[node.kids[s]].box, 0);  // reference set once all are placed
      }
    }
  }

  /// Now every entry is final: the top nodes' child references.
  void link_top_nodes(const CollapsePlan<W>& plan, const CollapsePlacement& at) {
    for (size_t t = 0; t < plan.top.size(); ++t) {
      const uint32_t w = at.top_wide[t];
      for (int s = 0; s < plan.top[t].n; ++s) nodes[w].ref[s] = ref_of(child_ids[w][s]);
    }
  }

  /// Writes a leaf's triangles as blocks of four from block `at.block` on; returns the first
  /// block. Copies of the triangles in leaf order: a leaf is one contiguous read, four
  /// triangles per SSE test, instead of an index lookup and three scattered vertex loads
  /// per triangle.
  uint32_t add_blocks(const Scene& scene, const uint32_t* prims, uint32_t count, CollapseOffsets& at) {
    const uint32_t first = at.block;
    for (uint32_t done = 0; done < count; done += 4) {
      TriangleBlock& block = blocks[at.block++];
      for (uint32_t lane = 0; lane < 4; ++lane) {
        const bool used = done + lane < count;
        block.prim[lane] = used ? prims[done + lane] : TriangleBlock::kNoPrim;
        for (int k = 0; k < 3; ++k) {
          const Vec3 p = used ? scene.vertex(prims[done + lane], k) : Vec3(0.0f);
          for (int axis = 0; axis < 3; ++axis) block.v[3 * k + axis][lane] = p[axis];
        }
      }
    }
    return first;
  }

 private:
  static void add_count(const BuildTree& tree, const WideCollapse<W>& choice, uint32_t src, CollapseOffsets& n) {
    ++n.entry;
    const BuildNode& b = tree.nodes[src];
    if (b.count) {
      n.block += (b.count + 3) / 4;
      return;
    }
    ++n.node;
    uint32_t kids[W];
    NullBuildSink no_steps;
    const int k = choice.children(src, kids, no_steps);
    for (int s = 0; s < k; ++s) add_count(tree, choice, kids[s], n);
  }
};

template <int W>
void WideBvhOf<W>::collapse(const Scene& scene, const BuildTree& tree, BuildRecorder* recorder) {
  clear();
  if (tree.empty()) return;
  prim_count_ = tree.prims.size();
  triangle_count_ = scene.valid_prims().size();  // every builder places each valid triangle (sbvh: at least once)
  const std::vector<uint32_t> size = binary_subtree_sizes(tree);
  const WideCollapse<W> choice(tree, options_, size, kCollapseTaskNodes);
  if (recorder) record_collapse(tree, choice, *recorder);

  Layout whole;
  if (tree.nodes[tree.root].count || size[tree.root] < kCollapseTaskNodes) {  // one task
    whole.resize(Layout::count(tree, choice, tree.root));
    CollapseOffsets at;
    whole.emit(scene, tree, choice, tree.root, 0, at);
  } else {
    CollapsePlan<W> plan;
    plan.plan(tree, choice, size, tree.root, 0);
    std::vector<CollapseOffsets> counts(plan.tasks.size());
    par::parallel_for(size_t(0), plan.tasks.size(),
                      [&](size_t t) { counts[t] = Layout::count(tree, choice, plan.tasks[t].src); });
    CollapsePlacement at{std::vector<CollapseOffsets>(counts.size()), std::vector<NodeId>(plan.top.size()),
                         std::vector<uint32_t>(plan.top.size()), {}};
    at.place(plan, counts, 0);
    whole.resize(at.total);
    whole.write_top_nodes(tree, plan, at);
    par::parallel_for(size_t(0), plan.tasks.size(), [&](size_t t) {
      CollapseOffsets cursor = at.part_at[t];
      whole.emit(scene, tree, choice, plan.tasks[t].src, plan.tasks[t].depth, cursor);
      // The emit fills exactly what the count placed: no task writes into another's part.
      ACCEL_CHECK(cursor.entry == at.part_at[t].entry + counts[t].entry &&
                  cursor.node == at.part_at[t].node + counts[t].node &&
                  cursor.block == at.part_at[t].block + counts[t].block);
    });
    whole.link_top_nodes(plan, at);
  }
  nodes_ = std::move(whole.nodes);
  child_ids_ = std::move(whole.child_ids);
  entries_ = std::move(whole.entries);
  boxes_ = std::move(whole.boxes);
  depth_ = std::move(whole.depth);
  blocks_ = std::move(whole.blocks);
}

template <int W>
void WideBvhOf<W>::for_each_node(const std::function<void(const NodeView&)>& fn) const {
  for (NodeId i = 0; i < entries_.size(); ++i) fn(node_view(i));
}

template <int W>
NodeView WideBvhOf<W>::node_view(NodeId id) const {
  NodeView v;
  if (id >= entries_.size()) return v;
  v.id = id;
  v.depth = depth_[id];
  v.leaf = entries_[id].leaf();
  v.prim_count = entries_[id].count;
  v.box = boxes_[id];
  return v;
}

template <int W>
std::vector<uint32_t> WideBvhOf<W>::node_prims(NodeId id) const {
  if (id >= entries_.size() || !entries_[id].leaf()) return {};
  std::vector<uint32_t> prims;
  for (uint32_t k = 0; k < entries_[id].count; ++k) prims.push_back(blocks_[entries_[id].index + k / 4].prim[k % 4]);
  return prims;
}

template <int W>
std::vector<NodeId> WideBvhOf<W>::node_children(NodeId id) const {
  if (id >= entries_.size() || entries_[id].leaf()) return {};
  std::vector<NodeId> children;
  for (NodeId child : child_ids_[entries_[id].index])
    if (child != kNoNode) children.push_back(child);
  return children;
}

template <int W>
size_t WideBvhOf<W>::memory_bytes() const {
  return nodes_.size() * (sizeof(Node) + sizeof(child_ids_[0])) + entries_.size() * sizeof(Entry) +
         blocks_.size() * sizeof(TriangleBlock);
}

template <int W>
BuildStats WideBvhOf<W>::compute_stats() const {
  BuildStats s;
  s.nodes = entries_.size();
  s.prims = triangle_count_;
  s.prim_references = prim_count_;
  s.memory_bytes = memory_bytes();
  s.sah_ct = options_.ct;
  s.sah_ci = options_.ci;
  s.sah_prims_per_test = options_.prims_per_test;
  if (!entries_.empty()) {
    const double root_area = double(boxes_[0].area());
    double cost = 0.0;
    for (size_t i = 0; i < entries_.size(); ++i) {
      const double rel = root_area > 0.0 ? double(boxes_[i].area()) / root_area : 1.0;
      if (entries_[i].leaf()) {
        s.add_leaf(entries_[i].count);
        cost += double(options_.leaf_cost(entries_[i].count)) * rel;
      } else {
        cost += double(options_.ct) * rel;
      }
      s.max_depth = std::max(s.max_depth, int(depth_[i]));
    }
    s.sah_cost = cost;
  }
  add_hierarchy_option_lines(options_, order_, &s);
  s.extra.push_back({"kernel isa", isa_name(fast_isa())});
  s.extra.push_back({"width", std::to_string(W)});
  return s;
}

template class WideBvhOf<4>;
template class WideBvhOf<8>;

FastWidePaths fast_wide8_paths(Isa isa) {
  switch (isa) {
    case Isa::Sse2: return {};
    case Isa::Avx2: return {&wide8_fast_avx2, &wide8_fast_batch_avx2};
    case Isa::Avx512: return {&wide8_fast_avx512, &wide8_fast_batch_avx512};
  }
  return {};
}

int wide8_children_mask(Isa isa, const WideNode8& node, const BoxTester& ray, float tmin, float tmax,
                        float t_enter[8], float t_exit[8]) {
  switch (isa) {
    case Isa::Avx2: return wide8_mask_avx2(node, ray, tmin, tmax, t_enter, t_exit);
    case Isa::Avx512: return wide8_mask_avx512(node, ray, tmin, tmax, t_enter, t_exit);
    case Isa::Sse2: break;
  }
  return intersect_children(node, WideRayFor<Sse2Tag>(ray), tmin, tmax, t_enter, t_exit);
}

Hit wide8_traverse_observed(Isa isa, const WideBvh8& bvh, const Ray& ray, StepListener& listener) {
  if (bvh.order() == TraversalOrder::PriorityQueue) isa = Isa::Sse2;  // the queue has SSE2 kernels only
  switch (isa) {
    case Isa::Avx2: return wide8_observed_avx2(bvh, ray, listener);
    case Isa::Avx512: return wide8_observed_avx512(bvh, ray, listener);
    case Isa::Sse2: break;
  }
  ForwardingSink sink{&listener};
  return bvh.traverse_with<Sse2Tag>(ray, sink);
}

}  // namespace accel
