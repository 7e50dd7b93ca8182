#pragma once
// The SAH-optimal collapse of a builder's binary tree into W-wide nodes (Ylitie, Karras &
// Laine 2017, "Efficient Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs",
// section 3.1). Every binary node of the collapsed tree is one of three things: a wide node
// of its own, a leaf in a slot of a wide node, or "opened": it does not exist in the wide
// tree, its two children take its place among its wide parent's children. A dynamic
// programme over (binary node, slots) finds, for every node, the least SAH cost of its
// subtree when it may fill at most i = 1..W slots of its wide parent:
//   cost(n, 1) = leaf:  A(n) * leaf_cost(count)
//                inner: A(n) * ct + D(n, W)          (a wide node with W slots to fill)
//   cost(n, i) = min(cost(n, 1), D(n, i))            (one slot, or opened into i)
//   D(n, i)    = min over k = 1..i-1 of cost(left, k) + cost(right, i - k)
// (cost(n, i) never rises with i, so D(n, i) is the best of every slot count up to i.)
// The collapse then walks down from the root: a wide node hands its W slots to its binary
// children by the best k, a child opens when D is cheaper than taking one slot.
//
// Greedy collapses (open the child of largest area until W; Wald et al. 2008) leave 8-wide
// nodes half empty (4.4 children on crytek_sponza) because they open by area, not by what
// the opening saves. Leaves are never merged here: every builder stops at leaf_size with a
// leaf whenever the leaf's SAH cost is not above its split's, and a wide node's cost is at
// most the binary one, so a merge could never win (bench/README.md has the measurements).
#include <array>
#include <vector>

#include "parallel.h"
#include "structures/bvh_build_types.h"

namespace accel {

template <int W>
class WideCollapse {
 public:
  /// The table's bytes per binary node, for the memory estimate (check_bvh_memory).
  static constexpr size_t kBytesPerNode = sizeof(std::array<float, W>);

  /// Solves the programme bottom-up, subtrees of at least `parallel_nodes` binary nodes
  /// (`subtree_size`, itself included) in parallel; the result does not depend on the
  /// thread count (each node's costs depend only on its subtree).
  WideCollapse(const BuildTree& tree, const BvhBuildOptions& options, const std::vector<uint32_t>& subtree_size,
               uint32_t parallel_nodes)
      : tree_(tree), options_(options), subtree_size_(subtree_size), parallel_nodes_(parallel_nodes) {
    cost_.resize(tree.nodes.size());
    if (!tree.empty()) solve_subtree(tree.root);
  }

  /// The children of wide node `src` (an inner binary node), in tree order; returns how
  /// many (2..W). `sink` sees each opened binary node in pre-order (a Collapse step: the
  /// wide node adopts that node's two children in its place).
  template <class Sink>
  int children(uint32_t src, uint32_t kids[W], Sink& sink) const {
    int n = 0;
    int left_slots;
    shared_cost(src, W, &left_slots);
    distribute(src, src, W, left_slots, kids, n, sink);
    return n;
  }

  /// The least SAH cost of `node`'s subtree in one slot (area-weighted, not divided by the
  /// root's area).
  float cost(uint32_t node) const { return cost_[node][0]; }

 private:
  /// D(node, slots): the least cost of the node's two children sharing `slots`; `left_slots`
  /// gets the left child's share of the best split (the first best, so ties are stable).
  float shared_cost(uint32_t node, int slots, int* left_slots) const {
    const BuildNode& b = tree_.nodes[node];
    float best = kInf;
    int best_k = 1;
    for (int k = 1; k < slots; ++k) {
      const float c = cost_[b.left][k - 1] + cost_[b.right][slots - k - 1];
      if (c < best) {
        best = c;
        best_k = k;
      }
    }
    *left_slots = best_k;
    return best;
  }

  void solve(uint32_t node) {
    const BuildNode& b = tree_.nodes[node];
    std::array<float, W>& c = cost_[node];
    const float area = b.box.area();
    if (b.count) {
      c.fill(area * options_.leaf_cost(b.count));
      return;
    }
    int k;
    c[0] = area * options_.ct + shared_cost(node, W, &k);
    for (int i = 2; i <= W; ++i) c[i - 1] = std::min(c[0], shared_cost(node, i, &k));
  }

  void solve_subtree(uint32_t node) {
    const BuildNode& b = tree_.nodes[node];
    if (!b.count) {
      if (subtree_size_[node] >= parallel_nodes_) {
        par::parallel_invoke([&] { solve_subtree(b.left); }, [&] { solve_subtree(b.right); });
      } else {
        solve_subtree(b.left);
        solve_subtree(b.right);
      }
    }
    solve(node);
  }

  /// Gives `node`'s two children `slots` slots of wide node `wide`, `left_slots` of them
  /// to the left child (the best split, from shared_cost).
  template <class Sink>
  void distribute(uint32_t wide, uint32_t node, int slots, int left_slots, uint32_t kids[W], int& n,
                  Sink& sink) const {
    const BuildNode& b = tree_.nodes[node];
    place(wide, b.left, left_slots, kids, n, sink);
    place(wide, b.right, slots - left_slots, kids, n, sink);
  }

  /// `node` takes one slot of `wide`, or opens into up to `slots` when that is cheaper.
  template <class Sink>
  void place(uint32_t wide, uint32_t node, int slots, uint32_t kids[W], int& n, Sink& sink) const {
    int left_slots;
    if (!tree_.nodes[node].count && slots > 1 && shared_cost(node, slots, &left_slots) < cost_[node][0]) {
      sink.collapse(tree_.event_id(wide), tree_.event_id(node));
      distribute(wide, node, slots, left_slots, kids, n, sink);
      return;
    }
    kids[n++] = node;
  }

  const BuildTree& tree_;
  const BvhBuildOptions& options_;
  const std::vector<uint32_t>& subtree_size_;
  uint32_t parallel_nodes_;
  /// cost_[node][i - 1] = cost(node, i) above.
  std::vector<std::array<float, W>> cost_;
};

}  // namespace accel
