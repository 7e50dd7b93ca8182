#include "structures/wide_bvh.h"

#include <cstring>

#include "check.h"

namespace accel {

void WideBvh::clear() {
  nodes_.clear();
  entries_.clear();
  boxes_.clear();
  depth_.clear();
  child_ids_.clear();
  blocks_.clear();
  prim_count_ = 0;
}

Status WideBvh::build_impl(const Scene& scene, const ParamSet& params, BuildControl* control) {
  // Progress by phase, as the binary layouts (hierarchy.h): the builder reports nothing, so
  // 0 before the binary tree, 0.8 after it, 1 once collapsed; cancel is checked between.
  clear();
  if (build_cancelled(control)) return cancelled_error();
  const HierarchyOptions options = hierarchy_options(params);
  options_ = options.build;
  // The 4-wide layout tests a leaf's triangles four at a time: the SAH builders know it.
  options_.prims_per_test = 4;
  order_ = options.traversal;
  ProgressSpan tree_span(control, 0.0, 0.8);
  const BuildTree tree = build_bvh_tree(scene, options_, &tree_span);
  tree_span.finish();
  if (build_cancelled(control)) return cancelled_error();
  collapse(scene, tree);
  return {};
}

void WideBvh::collapse(const Scene& scene, const BuildTree& tree) {
  clear();
  if (tree.empty()) return;
  prim_count_ = tree.prims.size();
  entries_.reserve(tree.nodes.size());
  emit(scene, tree, tree.root, 0);
}

uint32_t WideBvh::add_blocks(const Scene& scene, const uint32_t* prims, uint32_t count) {
  // Copies of the triangles in leaf order: a leaf is one contiguous read, four triangles per
  // SSE test, instead of an index lookup and three scattered vertex loads per triangle.
  const uint32_t first = uint32_t(blocks_.size());
  for (uint32_t done = 0; done < count; done += 4) {
    TriangleBlock block{};
    for (uint32_t lane = 0; lane < 4; ++lane) {
      const bool used = done + lane < count;
      block.prim[lane] = used ? prims[done + lane] : TriangleBlock::kNoPrim;
      for (int k = 0; k < 3; ++k) {
        const Vec3 p = used ? scene.vertex(prims[done + lane], k) : Vec3(0.0f);
        for (int axis = 0; axis < 3; ++axis) block.v[3 * k + axis][lane] = p[axis];
      }
    }
    blocks_.push_back(block);
  }
  return first;
}

NodeId WideBvh::emit(const Scene& scene, const BuildTree& tree, uint32_t src, int depth) {
  ACCEL_CHECK(depth < kMaxBvhDepth);  // collapsing only makes the tree shallower
  const NodeId id = NodeId(entries_.size());
  const BuildNode& b = tree.nodes[src];
  entries_.emplace_back();
  boxes_.push_back(b.box);
  depth_.push_back(uint16_t(depth));
  if (b.count) {
    entries_[id] = {add_blocks(scene, tree.prims.data() + b.first, b.count), b.count};
    return id;
  }
  // Open the largest inner child in place (its two children take its slot, keeping tree
  // order) until there are four children or only leaves are left.
  uint32_t kids[4] = {b.left, b.right, 0, 0};
  int n = 2;
  while (n < 4) {
    int widest = -1;
    float widest_area = -1.0f;
    for (int k = 0; k < n; ++k) {
      const BuildNode& c = tree.nodes[kids[k]];
      if (!c.count && c.box.area() > widest_area) {
        widest = k;
        widest_area = c.box.area();
      }
    }
    if (widest < 0) break;
    const BuildNode& c = tree.nodes[kids[widest]];
    for (int k = n; k > widest + 1; --k) kids[k] = kids[k - 1];
    kids[widest] = c.left;
    kids[widest + 1] = c.right;
    ++n;
  }
  const uint32_t w = uint32_t(nodes_.size());
  entries_[id] = {w, 0};
  WideNode node;
  for (int s = 0; s < 4; ++s) {
    for (int axis = 0; axis < 3; ++axis) {
      node.bounds[axis][s] = kInf;
      node.bounds[3 + axis][s] = -kInf;
    }
    node.ref[s] = leaf_ref(0, 0);
  }
  nodes_.push_back(node);
  child_ids_.push_back({kNoNode, kNoNode, kNoNode, kNoNode});
  for (int s = 0; s < n; ++s) {
    const NodeId child = emit(scene, tree, kids[s], depth + 1);  // may reallocate nodes_: index, not reference
    const Aabb& box = tree.nodes[kids[s]].box;
    for (int axis = 0; axis < 3; ++axis) {
      nodes_[w].bounds[axis][s] = box.min[axis];
      nodes_[w].bounds[3 + axis][s] = box.max[axis];
    }
    nodes_[w].ref[s] = ref_of(child);
    child_ids_[w][s] = child;
  }
  return id;
}

void WideBvh::for_each_node(const std::function<void(const NodeView&)>& fn) const {
  for (NodeId i = 0; i < entries_.size(); ++i) fn(node_view(i));
}

NodeView WideBvh::node_view(NodeId id) const {
  NodeView v;
  if (id >= entries_.size()) return v;
  v.id = id;
  v.depth = depth_[id];
  v.leaf = entries_[id].leaf();
  v.prim_count = entries_[id].count;
  v.box = boxes_[id];
  return v;
}

std::vector<uint32_t> WideBvh::node_prims(NodeId id) const {
  if (id >= entries_.size() || !entries_[id].leaf()) return {};
  std::vector<uint32_t> prims;
  for (uint32_t k = 0; k < entries_[id].count; ++k) prims.push_back(blocks_[entries_[id].index + k / 4].prim[k % 4]);
  return prims;
}

size_t WideBvh::memory_bytes() const {
  return nodes_.size() * (sizeof(WideNode) + sizeof(child_ids_[0])) + entries_.size() * sizeof(Entry) +
         blocks_.size() * sizeof(TriangleBlock);
}

BuildStats WideBvh::compute_stats() const {
  BuildStats s;
  s.nodes = entries_.size();
  s.prims = prim_count_;
  s.prim_references = prim_count_;
  s.memory_bytes = memory_bytes();
  s.sah_ct = options_.ct;
  s.sah_ci = options_.ci;
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
  s.extra.push_back({"width", "4"});
  return s;
}

}  // namespace accel
