// The SAH-optimal collapse (core/structures/wide_collapse.h): its cost is the least over
// every way of choosing wide nodes (checked against an exhaustive search on small trees),
// the collapsed tree has exactly that cost, and its node counts are what the choice says.
#include <algorithm>
#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "registry.h"
#include "scene.h"
#include "structures/bvh.h"
#include "structures/bvh_builders.h"
#include "structures/wide_bvh.h"
#include "structures/wide_collapse.h"
#include "test_support.h"

namespace accel {
namespace {

/// The least SAH cost of the subtree of `node` as one child slot, by exhaustive search:
/// a leaf costs its area times its leaf cost; an inner node is a wide node whose children
/// are any frontier of at most W nodes strictly below it (every binary subtree's frontiers:
/// the node itself, or a frontier of its left child next to one of its right child).
template <int W>
struct ExhaustiveCollapse {
  const BuildTree& tree;
  const BvhBuildOptions& o;
  std::map<uint32_t, double> best;

  /// Every frontier of `node`'s subtree with at most `limit` nodes, as the sum of its
  /// members' costs, keyed by size: the least sum per size is all the search needs.
  std::vector<double> frontier_costs(uint32_t node, int limit) {
    std::vector<double> least(size_t(limit) + 1, INFINITY);
    least[1] = cost(node);
    const BuildNode& b = tree.nodes[node];
    if (!b.count && limit >= 2) {
      const std::vector<double> l = frontier_costs(b.left, limit - 1), r = frontier_costs(b.right, limit - 1);
      for (int i = 1; i < limit; ++i)
        for (int j = 1; i + j <= limit; ++j) least[size_t(i + j)] = std::min(least[size_t(i + j)], l[size_t(i)] + r[size_t(j)]);
    }
    return least;
  }
  double cost(uint32_t node) {
    if (auto it = best.find(node); it != best.end()) return it->second;
    const BuildNode& b = tree.nodes[node];
    double c;
    if (b.count) {
      c = double(b.box.area()) * double(o.leaf_cost(b.count));
    } else {
      const std::vector<double> l = frontier_costs(b.left, W - 1), r = frontier_costs(b.right, W - 1);
      double children = INFINITY;
      for (int i = 1; i < W; ++i)
        for (int j = 1; i + j <= W; ++j) children = std::min(children, l[size_t(i)] + r[size_t(j)]);
      c = double(b.box.area()) * double(o.ct) + children;
    }
    best[node] = c;
    return c;
  }
};

template <int W>
void expect_least_cost(const Scene& scene, BvhBuildOptions o) {
  o.prims_per_test = 4;
  const BuildTree tree = build_bvh_tree(scene, o, nullptr, nullptr);
  ASSERT_FALSE(tree.empty());
  const std::vector<uint32_t> size = binary_subtree_sizes(tree);
  const WideCollapse<W> collapse(tree, o, size, 64);
  ExhaustiveCollapse<W> exhaustive{tree, o, {}};
  const double least = exhaustive.cost(tree.root);
  EXPECT_NEAR(double(collapse.cost(tree.root)), least, 1e-5 * least);
  // The same answer for any parallel split: the costs depend on each subtree alone.
  const WideCollapse<W> serial(tree, o, size, ~0u);
  EXPECT_EQ(serial.cost(tree.root), collapse.cost(tree.root));
}

TEST(WideCollapse, FindsTheLeastSahCostOfEveryCollapse) {
  for (const char* name : {"soup", "cornell", "stadium"}) {
    const Scene scene = make_procedural_scene(name).value();
    for (BvhBuilderKind builder : {BvhBuilderKind::BinnedSah, BvhBuilderKind::Median, BvhBuilderKind::BottomUp}) {
      for (int leaf : {1, 4}) {
        SCOPED_TRACE(std::string(name) + " " + builder_name(builder) + " leaf " + std::to_string(leaf));
        BvhBuildOptions o;
        o.builder = builder;
        o.leaf_size = leaf;
        expect_least_cost<4>(scene, o);
        expect_least_cost<8>(scene, o);
      }
    }
  }
}

/// The built tree's SAH cost (its stats: ct per wide node, the leaf cost per leaf, by area
/// relative to the root) is the cost the collapse computed: the layout follows its choices.
TEST(WideCollapse, TheBuiltTreeHasTheCostTheCollapseComputed) {
  const Scene scene = make_procedural_scene("stadium").value();
  for (const char* width : {"4", "8"}) {
    SCOPED_TRACE(std::string("width ") + width);
    auto bvh = build_structure("bvh", scene, {std::string("width=") + width});
    ASSERT_TRUE(bvh);
    BvhBuildOptions o;
    o.prims_per_test = 4;
    const BuildTree tree = build_bvh_tree(scene, o, nullptr, nullptr);
    const std::vector<uint32_t> size = binary_subtree_sizes(tree);
    const float root_area = tree.nodes[tree.root].box.area();
    const double expected = width[0] == '4' ? WideCollapse<4>(tree, o, size, 64).cost(tree.root)
                                            : WideCollapse<8>(tree, o, size, 64).cost(tree.root);
    const double built = bvh.value()->build_stats().sah_cost;
    EXPECT_NEAR(built, expected / root_area, 1e-4 * built);
  }
}

}  // namespace
}  // namespace accel
