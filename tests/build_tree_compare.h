#pragma once
// Exact comparison of two BVH builder outputs, for the tests that check a builder's tree
// does not depend on the thread count or equals a reference implementation's, and the
// shape checks every builder's output must pass.
#include <cstring>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "structures/bvh_builders.h"

namespace accel::testing {

/// Same root, same prims, and node by node the same box bits, children and leaf ranges.
inline void expect_same_tree(const BuildTree& a, const BuildTree& b) {
  ASSERT_EQ(a.root, b.root);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  ASSERT_EQ(a.prims, b.prims);
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    const BuildNode &x = a.nodes[i], &y = b.nodes[i];
    ASSERT_EQ(std::memcmp(&x.box, &y.box, sizeof(Aabb)), 0) << "box of node " << i;
    ASSERT_EQ(x.left, y.left) << "node " << i;
    ASSERT_EQ(x.right, y.right) << "node " << i;
    ASSERT_EQ(x.first, y.first) << "node " << i;
    ASSERT_EQ(x.count, y.count) << "node " << i;
  }
}

/// Walks the tree from its root and checks what every builder guarantees about its shape:
/// depth below kMaxBvhDepth, at most `leaf_size` triangles per leaf, children's boxes inside
/// their parent's. Calls on_leaf(node index, node) for every leaf, for the builder's own checks.
template <class OnLeaf>
void expect_valid_tree_shape(const BuildTree& tree, int leaf_size, const OnLeaf& on_leaf) {
  ASSERT_FALSE(tree.empty());
  std::vector<std::pair<uint32_t, int>> stack{{tree.root, 0}};
  while (!stack.empty()) {
    const auto [i, depth] = stack.back();
    stack.pop_back();
    ASSERT_LT(depth, kMaxBvhDepth);
    const BuildNode& n = tree.nodes[i];
    if (n.count) {
      EXPECT_LE(n.count, uint32_t(leaf_size)) << "leaf " << i;
      on_leaf(i, n);
      continue;
    }
    for (uint32_t c : {n.left, n.right}) {
      EXPECT_TRUE(n.box.contains(tree.nodes[c].box)) << "node " << i;
      stack.push_back({c, depth + 1});
    }
  }
}

}  // namespace accel::testing
