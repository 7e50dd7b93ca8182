// Sphere tree: the builders and traversals of the AABB tree with bounding spheres.
#include <gtest/gtest.h>

#include <algorithm>

#include "registry.h"
#include "structures/bvh_builders.h"
#include "structures/sphere_tree.h"
#include "structure_suite.h"
#include "test_support.h"

namespace accel {

namespace testing {
INSTANTIATE_TEST_SUITE_P(SphereTree, StructureVsReference,
                         ::testing::Values(SuiteCase{"spheretree", {"builder=median", "traversal=dfs"}},
                                           SuiteCase{"spheretree", {"builder=sah", "traversal=ordered"}},
                                           SuiteCase{"spheretree", {"builder=binned_sah", "traversal=pqueue"}},
                                           SuiteCase{"spheretree", {"builder=pca_sah", "traversal=ordered", "leaf_size=1"}},
                                           SuiteCase{"spheretree", {"builder=bottom_up", "traversal=pqueue", "leaf_size=16"}},
                                           SuiteCase{"spheretree", {"builder=insertion", "traversal=dfs"}},
                                           SuiteCase{"spheretree", {"builder=sah", "traversal=pqueue", "leaf_size=1"}},
                                           SuiteCase{"spheretree", {"builder=bottom_up", "traversal=ordered"}},
                                           SuiteCase{"spheretree", {"builder=insertion", "traversal=pqueue"}},
                                           SuiteCase{"spheretree", {"builder=sbvh", "traversal=dfs"}}),
                         suite_case_name);
}  // namespace testing

namespace {

TEST(SphereTree, EverySphereContainsItsTriangles) {
  for (const char* name : {"soup", "cornell"}) {
    const Scene scene = make_procedural_scene(name).value();
    for (const BvhBuilderInfo& row : bvh_builder_table()) {
      if (row.splits_triangles) continue;  // a sphere holds the triangle's clipped part only
      const char* builder = row.name;
      auto s = build_structure("spheretree", scene, {std::string("builder=") + builder});
      ASSERT_TRUE(s);
      const auto* tree = dynamic_cast<const SphereTree*>(s.value().get());
      ASSERT_NE(tree, nullptr);
      // Each node's sphere holds every vertex of every triangle below it (checked in double).
      const auto& nodes = tree->nodes();
      std::vector<std::vector<uint32_t>> below(nodes.size());
      for (size_t i = nodes.size(); i-- > 0;) {
        if (nodes[i].leaf()) below[i] = tree->node_prims(NodeId(i));
        else {
          below[i] = below[i + 1];
          below[i].insert(below[i].end(), below[nodes[i].index].begin(), below[nodes[i].index].end());
        }
        const BoundingSphere& sp = nodes[i].volume;
        for (uint32_t prim : below[i])
          for (int k = 0; k < 3; ++k)
            ASSERT_LE(glm::length(DVec3(scene.vertex(prim, k)) - DVec3(sp.center)), double(sp.radius))
                << name << " " << builder << " node " << i;
      }
    }
  }
}

TEST(SphereTree, AnInnerSphereIsNoLargerThanTheSphereAroundItsChildren) {
  // Nodes above SphereTree::kDirectFit triangles are fitted from their subtrees: the first
  // candidate centre is that of the smallest sphere around the two children's, and its exact
  // radius (the farthest vertex) can only be smaller; later candidates are kept only when
  // smaller still. 10,000 triangles: hundreds of such nodes.
  const Scene scene = make_procedural_scene("soup").value();
  for (const BvhBuilderInfo& row : bvh_builder_table()) {
    const char* builder = row.name;
    auto s = build_structure("spheretree", scene, {std::string("builder=") + builder});
    ASSERT_TRUE(s);
    const auto& nodes = dynamic_cast<const SphereTree&>(*s.value()).nodes();
    std::vector<size_t> below(nodes.size());
    size_t fitted_from_children = 0;
    for (size_t i = nodes.size(); i-- > 0;) {
      const auto& n = nodes[i];
      below[i] = n.leaf() ? n.count : below[i + 1] + below[n.index];
      if (n.leaf() || below[i] <= SphereTree::kDirectFit) continue;
      ++fitted_from_children;
      const BoundingSphere &a = nodes[i + 1].volume, &b = nodes[n.index].volume;
      const double d = glm::length(DVec3(a.center) - DVec3(b.center));
      const double around = std::max({double(a.radius), double(b.radius), 0.5 * (d + a.radius + b.radius)});
      EXPECT_LE(double(n.volume.radius), around * (1.0 + 1e-5)) << builder << " node " << i;
    }
    EXPECT_GT(fitted_from_children, 100u) << builder;
  }
}

TEST(SphereTree, StatsCompareSphereAndBoxVolume) {
  const Scene scene = make_procedural_scene("sphere").value();
  auto s = build_structure("spheretree", scene, {});
  ASSERT_TRUE(s);
  const BuildStats stats = s.value()->build_stats();
  bool found = false;
  for (const auto& [k, v] : stats.extra)
    if (k == "sphere_to_box_volume") {
      found = true;
      EXPECT_GT(std::stod(v), 1.0);  // a sphere around a box is always larger than the box
    }
  EXPECT_TRUE(found);
  EXPECT_TRUE(std::isfinite(stats.sah_cost));
}

}  // namespace
}  // namespace accel
