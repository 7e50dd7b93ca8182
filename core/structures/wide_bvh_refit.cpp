// WideBvhOf::refit: the wide trees' boxes recomputed bottom-up from moved vertices, the
// leaves' triangle copies refreshed, the topology untouched (wide_bvh.h).
#include "structures/wide_bvh.h"

#include "parallel.h"

namespace accel {
namespace {

/// Subtrees of at most this many nodes are refitted by one task, bottom-up in one loop:
/// below it a task's overhead outweighs the work of its nodes.
constexpr NodeId kRefitGrain = 1024;

}  // namespace

template <int W>
Status WideBvhOf<W>::refit_impl(const Scene& scene) {
  // The first held triangle that may not stay, by block (the lowest, whatever the thread count).
  const size_t bad_at = par::parallel_reduce(
      par::blocked_range<size_t>(0, blocks_.size(), 4096), blocks_.size(),
      [&](const par::blocked_range<size_t>& r, size_t first) {
        for (size_t b = r.begin(); b < r.end() && b < first; ++b)
          for (uint32_t prim : blocks_[b].prim)
            if (prim != TriangleBlock::kNoPrim && !refit_keeps(scene, prim)) return b;
        return first;
      },
      [](size_t a, size_t b) { return std::min(a, b); });
  uint32_t bad = ~0u;
  if (bad_at < blocks_.size())
    for (uint32_t prim : blocks_[bad_at].prim)
      if (bad == ~0u && prim != TriangleBlock::kNoPrim && !refit_keeps(scene, prim)) bad = prim;
  if (Status s = check_refit_prims(this->name(), scene, triangle_count_, bad); !s) return s;
  if (!entries_.empty()) refit_subtree(scene, 0, NodeId(entries_.size()));
  return {};
}

template <int W>
void WideBvhOf<W>::refit_subtree(const Scene& scene, NodeId node, NodeId end) {
  if (end - node <= kRefitGrain) {
    // Children have larger ids than their parent: a reverse sweep is bottom-up.
    for (NodeId k = end; k-- > node;) refit_node(scene, k);
    return;
  }
  // More than one node: an inner node whose children, in slot order, start its consecutive
  // subtrees (emit() fills the slots from 0 and numbers each child's subtree in turn).
  const std::array<NodeId, W>& kids = child_ids_[entries_[node].index];
  int n = 0;
  while (n < W && kids[n] != kNoNode) ++n;
  par::parallel_for(0, n, [&](int s) { refit_subtree(scene, kids[s], s + 1 < n ? kids[s + 1] : end); });
  refit_node(scene, node);
}

template <int W>
void WideBvhOf<W>::refit_node(const Scene& scene, NodeId id) {
  const Entry e = entries_[id];
  Aabb box;
  if (e.leaf()) {
    // The leaf's blocks as add_blocks() wrote them, with the new vertices; unused lanes keep
    // their zeros and kNoPrim.
    for (uint32_t b = e.index; b < e.index + (e.count + 3) / 4; ++b) {
      TriangleBlock& block = blocks_[b];
      for (int lane = 0; lane < 4; ++lane) {
        const uint32_t prim = block.prim[lane];
        if (prim == TriangleBlock::kNoPrim) continue;
        box.extend(scene.triangle_bounds(prim));
        for (int k = 0; k < 3; ++k) {
          const Vec3& p = scene.vertex(prim, k);
          for (int axis = 0; axis < 3; ++axis) block.v[3 * k + axis][lane] = p[axis];
        }
      }
    }
  } else {
    // Each used slot takes its child's new box; unused slots stay empty boxes.
    Node& node = nodes_[e.index];
    const std::array<NodeId, W>& kids = child_ids_[e.index];
    for (int s = 0; s < W; ++s) {
      if (kids[s] == kNoNode) continue;
      const Aabb& child = boxes_[kids[s]];
      box.extend(child);
      for (int axis = 0; axis < 3; ++axis) {
        node.bounds[axis][s] = child.min[axis];
        node.bounds[3 + axis][s] = child.max[axis];
      }
    }
  }
  boxes_[id] = box;
}

// The class is instantiated in wide_bvh.cpp (extern template in wide_bvh.h); its members
// defined here are instantiated here.
template Status WideBvhOf<4>::refit_impl(const Scene&);
template Status WideBvhOf<8>::refit_impl(const Scene&);
template void WideBvhOf<4>::refit_subtree(const Scene&, NodeId, NodeId);
template void WideBvhOf<8>::refit_subtree(const Scene&, NodeId, NodeId);
template void WideBvhOf<4>::refit_node(const Scene&, NodeId);
template void WideBvhOf<8>::refit_node(const Scene&, NodeId);

}  // namespace accel
