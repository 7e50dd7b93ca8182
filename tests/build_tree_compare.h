#pragma once
// Exact comparison of two BVH builder outputs, for the tests that check a builder's tree
// does not depend on the thread count or equals a reference implementation's.
#include <cstring>

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

}  // namespace accel::testing
