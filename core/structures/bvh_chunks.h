#pragma once
// How the parallel top-down BVH builders (bvh_top_down.h, binned SAH, SBVH) put their tasks'
// work together: a subtree too large for one task splits its root and hands the two
// children to two tasks; a small one is built serially into a chunk of its own, in local
// pre-order. stitch_chunks() then numbers the tree in the serial recursion's pre-order (node,
// left subtree, right subtree) from the chunks' sizes and copies every serial chunk to its
// place in parallel, so the tree does not depend on the thread count.
#include <cstdint>
#include <memory>
#include <vector>

#include "structures/bvh_builders.h"

namespace accel {

/// A subtree built by one task.
struct BuildChunk {
  /// Parallel (left and right set): its root node, whose children are the chunks left and right.
  BuildNode node;
  std::unique_ptr<BuildChunk> left, right;
  /// Serial (no children): the whole subtree in local pre-order, child links relative to
  /// nodes[0]...
  std::vector<BuildNode> nodes;
  /// ...and, for builders whose leaves list triangles of their own (SBVH: a triangle may be
  /// in several leaves), those triangles, leaf `first` relative to prims[0]. Empty for
  /// builders whose leaves index one shared triangle order.
  std::vector<uint32_t> prims;
  size_t size = 0;        ///< nodes in the subtree
  size_t prim_count = 0;  ///< leaf triangles in the subtree (chunks with prims of their own)
};

/// Lays out the chunk tree in pre-order into `nodes` (resized to root.size). With `prims`
/// (chunks with triangles of their own) the chunks' triangles are concatenated in the same
/// order into *prims (resized to root.prim_count) and each leaf's `first` moved along.
void stitch_chunks(const BuildChunk& root, std::vector<BuildNode>& nodes, std::vector<uint32_t>* prims = nullptr);

}  // namespace accel
