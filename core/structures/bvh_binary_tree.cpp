// The end of the bottom-up builders (bvh_binary_tree.h): bound the depth, collapse subtrees
// into leaves by the SAH, lay the tree out in pre-order.
#include "structures/bvh_binary_tree.h"

#include <algorithm>
#include <utility>

namespace accel::bottom_up {
namespace {

/// Per node of a binary tree: subtree height (leaf = 0), triangle count, SAH cost, and
/// whether the subtree becomes one leaf (ci*n*A <= the subtree's cost, n <= leaf_size).
struct SubtreeCosts {
  std::vector<uint32_t> height, count;
  std::vector<float> cost;
  std::vector<uint8_t> collapse;
};

/// One post-order pass, without recursion (trees may be chains): everything the final
/// layout needs, and the heights limit_depth() needs, so the tree is walked once.
void compute_subtree_costs(const std::vector<BinaryNode>& nodes, uint32_t root, const BvhBuildOptions& o,
                           SubtreeCosts& c) {
  const size_t n = nodes.size();
  c.height.assign(n, 0);
  c.count.assign(n, 0);
  c.cost.assign(n, 0.0f);
  c.collapse.assign(n, 0);
  std::vector<std::pair<uint32_t, bool>> stack{{root, false}};
  while (!stack.empty()) {
    auto [i, expanded] = stack.back();
    stack.pop_back();
    const BinaryNode& nd = nodes[i];
    if (nd.is_leaf()) {
      c.count[i] = 1;
      c.cost[i] = o.leaf_cost(1) * nd.box.area();
      c.collapse[i] = 1;
    } else if (!expanded) {
      stack.push_back({i, true});
      stack.push_back({nd.left, false});
      stack.push_back({nd.right, false});
    } else {
      c.height[i] = 1 + std::max(c.height[nd.left], c.height[nd.right]);
      c.count[i] = c.count[nd.left] + c.count[nd.right];
      const float split_cost = o.ct * nd.box.area() + c.cost[nd.left] + c.cost[nd.right];
      const float leaf_cost = o.leaf_cost(c.count[i]) * nd.box.area();
      c.collapse[i] = c.count[i] <= uint32_t(o.leaf_size) && leaf_cost <= split_cost;
      c.cost[i] = c.collapse[i] ? leaf_cost : split_cost;
    }
  }
}

/// Triangles below node i, in tree order, appended to `out`; `stack` is scratch.
void gather_prims(const std::vector<BinaryNode>& nodes, uint32_t i, std::vector<uint32_t>& out,
                  std::vector<uint32_t>& stack) {
  stack.assign(1, i);
  while (!stack.empty()) {
    const uint32_t k = stack.back();
    stack.pop_back();
    if (nodes[k].is_leaf()) {
      out.push_back(nodes[k].prim());
    } else {
      stack.push_back(nodes[k].right);
      stack.push_back(nodes[k].left);
    }
  }
}

/// Balanced median-split subtree over prims[begin, end) (height ~ log2 n); returns its root.
/// The sink sees it as bottom-up steps: each triangle a cluster, each inner node a merge.
template <class Sink>
uint32_t build_median_binary(const Scene& scene, std::vector<BinaryNode>& nodes, std::vector<uint32_t>& prims,
                             size_t begin, size_t end, Sink& sink) {
  if (end - begin == 1) {
    nodes.push_back(BinaryNode::leaf_of(scene.triangle_bounds(prims[begin]), prims[begin]));
    const uint32_t id = uint32_t(nodes.size() - 1);
    if constexpr (Sink::kRecords) record_cluster(scene, id, nodes[id].box, prims[begin], sink);
    return id;
  }
  Aabb cb;
  for (size_t i = begin; i < end; ++i) cb.extend(scene.centroid(prims[i]));
  const int axis = cb.longest_axis();
  const size_t mid = begin + (end - begin) / 2;
  std::nth_element(prims.begin() + long(begin), prims.begin() + long(mid), prims.begin() + long(end),
                   [&](uint32_t a, uint32_t b) {
                     const float ca = scene.centroid(a)[axis], cb_ = scene.centroid(b)[axis];
                     return ca < cb_ || (ca == cb_ && a < b);
                   });
  const uint32_t l = build_median_binary(scene, nodes, prims, begin, mid, sink);
  const uint32_t r = build_median_binary(scene, nodes, prims, mid, end, sink);
  nodes.push_back(BinaryNode::inner(merge(nodes[l].box, nodes[r].box), l, r));
  const uint32_t id = uint32_t(nodes.size() - 1);
  if constexpr (Sink::kRecords) sink.merge(id, l, r, nodes[id].box, nodes[id].box.area());
  return id;
}

/// Depth bound of limit_depth(): trees up to 2 * kDepthCut high are left alone.
constexpr uint32_t kDepthCut = 32;
static_assert(2 * kDepthCut + 2 < uint32_t(kMaxBvhDepth));

/// Bounds the depth: an adversarial order (e.g. identical triangles) can make insertion
/// grow a chain. Every subtree hanging at depth kCut that is taller than kCut is rebuilt by
/// median split, so no leaf is deeper than about kCut + log2(n) + 1. `height` is the
/// subtree heights of the tree as it is. The sink sees each rebuilt subtree, then its
/// Replace step.
template <class Sink>
void limit_depth(const Scene& scene, std::vector<BinaryNode>& nodes, uint32_t root,
                 const std::vector<uint32_t>& height, Sink& sink) {
  constexpr uint32_t kCut = kDepthCut;
  std::vector<std::pair<uint32_t, uint32_t>> stack{{root, 0}};  // (node, depth)
  std::vector<uint32_t> prims, gather_stack;
  while (!stack.empty()) {
    auto [i, depth] = stack.back();
    stack.pop_back();
    if (nodes[i].is_leaf()) continue;
    for (int side = 0; side < 2; ++side) {
      const uint32_t child = side == 0 ? nodes[i].left : nodes[i].right;
      if (depth + 1 == kCut && height[child] > kCut) {
        prims.clear();
        gather_prims(nodes, child, prims, gather_stack);
        // build_median_binary appends to `nodes`: take no references across it.
        const uint32_t rebuilt = build_median_binary(scene, nodes, prims, 0, prims.size(), sink);
        sink.replace(rebuilt, child);
        (side == 0 ? nodes[i].left : nodes[i].right) = rebuilt;
      } else if (depth + 1 < kCut) {
        stack.push_back({child, depth + 1});
      }
    }
  }
}

}  // namespace

template <class Sink>
BuildTree finalize_binary_tree(const Scene& scene, std::vector<BinaryNode>& nodes, uint32_t root,
                               const BvhBuildOptions& o, Sink& sink) {
  SubtreeCosts costs;
  compute_subtree_costs(nodes, root, o, costs);
  if (costs.height[root] > 2 * kDepthCut) {  // rare: only then is the tree walked twice
    limit_depth(scene, nodes, root, costs.height, sink);
    compute_subtree_costs(nodes, root, o, costs);
  }
  const size_t n = nodes.size();
  const std::vector<uint32_t>& count = costs.count;
  const std::vector<uint8_t>& collapse = costs.collapse;
  BuildTree tree;
  tree.nodes.reserve(n);
  tree.prims.reserve(count[root]);
  struct Item {
    uint32_t src, dst;
  };
  tree.nodes.emplace_back();
  if constexpr (Sink::kRecords) tree.event_ids.resize(n);
  std::vector<Item> work{{root, 0}};
  std::vector<uint32_t> gather_stack;
  while (!work.empty()) {
    const Item it = work.back();
    work.pop_back();
    const BinaryNode& nd = nodes[it.src];
    tree.nodes[it.dst].box = nd.box;
    if constexpr (Sink::kRecords) tree.event_ids[it.dst] = it.src;
    if (collapse[it.src]) {
      tree.nodes[it.dst].first = uint32_t(tree.prims.size());
      gather_prims(nodes, it.src, tree.prims, gather_stack);
      tree.nodes[it.dst].count = uint32_t(tree.prims.size()) - tree.nodes[it.dst].first;
      if constexpr (Sink::kRecords)
        if (!nd.is_leaf())
          sink.leaf(it.src, LeafReason::NoGain, tree.prims.data() + tree.nodes[it.dst].first,
                    tree.nodes[it.dst].count);
      continue;
    }
    const uint32_t l = uint32_t(tree.nodes.size());
    tree.nodes.emplace_back();
    tree.nodes.emplace_back();
    tree.nodes[it.dst].left = l;
    tree.nodes[it.dst].right = l + 1;
    work.push_back({nd.right, l + 1});
    work.push_back({nd.left, l});
  }
  if constexpr (Sink::kRecords) tree.event_ids.resize(tree.nodes.size());
  tree.root = 0;
  return tree;
}

template BuildTree finalize_binary_tree(const Scene&, std::vector<BinaryNode>&, uint32_t, const BvhBuildOptions&,
                                        NullBuildSink&);
template BuildTree finalize_binary_tree(const Scene&, std::vector<BinaryNode>&, uint32_t, const BvhBuildOptions&,
                                        BuildRecorder&);

}  // namespace accel::bottom_up
