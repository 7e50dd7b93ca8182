#pragma once
// How the top-down driver (top_down_tasks.h) stitches BuildNode chunks: beside the BVH
// builders' one recursion that runs on it (bvh_top_down.h), so the node type's header
// (bvh_build_types.h) needs neither the driver nor TBB.
#include <cstdint>

#include "structures/bvh_build_types.h"
#include "structures/top_down_tasks.h"

namespace accel {

namespace top_down {
/// Stitching BuildNode chunks (top_down_tasks.h): a node names both children; a leaf's
/// `first` moves by the triangles of the chunks before its own (every BVH chunk lists its
/// leaves' triangles).
template <>
struct ChunkLinks<BuildNode> {
  static void link(BuildNode& inner, uint32_t left, uint32_t right) {
    inner.left = left;
    inner.right = right;
  }
  static void relocate(BuildNode& n, uint32_t node_offset, uint32_t prim_offset) {
    if (n.count) {
      n.first += prim_offset;
    } else {
      n.left += node_offset;
      n.right += node_offset;
    }
  }
};
}  // namespace top_down

}  // namespace accel
