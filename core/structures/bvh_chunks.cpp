// Stitching the parallel builders' chunks into one pre-order tree (bvh_chunks.h).
#include "structures/bvh_chunks.h"

#include <algorithm>

#include "parallel.h"

namespace accel {
namespace {

/// A serial chunk and the offsets of its nodes and triangles in the whole tree.
struct Placed {
  const BuildChunk* chunk;
  uint32_t node, prim;
};

/// Numbers the parallel chunks' roots in pre-order from the subtree sizes and collects the
/// serial chunks with their offsets.
void place(const BuildChunk& c, uint32_t node, uint32_t prim, std::vector<BuildNode>& nodes,
           std::vector<Placed>& serial) {
  if (!c.left) {
    serial.push_back({&c, node, prim});
    return;
  }
  BuildNode& n = nodes[node];
  n = c.node;
  n.left = node + 1;
  n.right = node + 1 + uint32_t(c.left->size);
  place(*c.left, n.left, prim, nodes, serial);
  place(*c.right, n.right, prim + uint32_t(c.left->prim_count), nodes, serial);
}

}  // namespace

void stitch_chunks(const BuildChunk& root, std::vector<BuildNode>& nodes, std::vector<uint32_t>* prims) {
  nodes.resize(root.size);
  if (prims) prims->resize(root.prim_count);
  std::vector<Placed> serial;
  place(root, 0, 0, nodes, serial);
  par::parallel_for(size_t(0), serial.size(), [&](size_t k) {
    const Placed& p = serial[k];
    BuildNode* dst = nodes.data() + p.node;
    for (const BuildNode& src : p.chunk->nodes) {
      *dst = src;
      if (src.count) {
        if (prims) dst->first += p.prim;
      } else {
        dst->left += p.node;
        dst->right += p.node;
      }
      ++dst;
    }
    if (prims) std::copy(p.chunk->prims.begin(), p.chunk->prims.end(), prims->begin() + long(p.prim));
  });
}

}  // namespace accel
